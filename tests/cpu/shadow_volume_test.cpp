// append_shadow_volume (core/ShadowVolume.h): the closed convex volume a box
// shades, checked on literal boxes and suns by its enclosed volume (the
// divergence theorem over the triangles: positive and exact only when the
// surface is closed and turned outwards) and by which points it holds.
#include "core/ShadowVolume.h"
#include "core/SunLight.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace overflight {
namespace {

// Sum over the triangles of a . (b x c) / 6.
double enclosed(const std::vector<glm::vec3>& t) {
    double v = 0;
    for (std::size_t i = 0; i + 2 < t.size(); i += 3)
        v += glm::dot(glm::dvec3(t[i]), glm::cross(glm::dvec3(t[i + 1]), glm::dvec3(t[i + 2]))) / 6.0;
    return v;
}

// Inside (or on) every triangle's plane.
bool holds(const std::vector<glm::vec3>& t, const glm::vec3& p) {
    for (std::size_t i = 0; i + 2 < t.size(); i += 3) {
        const glm::vec3 n = glm::cross(t[i + 1] - t[i], t[i + 2] - t[i]);
        if (glm::dot(n, n) == 0.0f) continue;
        if (glm::dot(glm::normalize(n), p - t[i]) > 1e-3f) return false;
    }
    return true;
}

// The box swept by d encloses the box's volume plus |d| times the box's area
// seen along d: |d.x| A_yz + |d.y| A_xz + |d.z| A_xy.
double swept_volume(const WorldBox& b, const glm::vec3& d) {
    const glm::dvec3 s(b.hi - b.lo);
    return s.x * s.y * s.z + std::abs(d.x) * s.y * s.z + std::abs(d.y) * s.x * s.z + std::abs(d.z) * s.x * s.y;
}

const WorldBox kBox{{20, 0, 28}, {28, 8, 36}};

TEST(ShadowVolume, WesternSunAt45DegreesOnALiteral) {
    // Sun in the west at 45 degrees: the sweep down to floor -2 is 10 units
    // east and 10 down; the top's far edge lands at X = 38, Y = -2.
    const glm::vec3 sun = sun_direction(270.0, 45.0);
    std::vector<glm::vec3> t;
    append_shadow_volume(kBox, sun, -2.0f, t);
    ASSERT_EQ(t.size() % 3, 0u);
    EXPECT_LE(t.size(), 24u * 3);
    EXPECT_NEAR(enclosed(t), 8 * 8 * 8 + 10 * 8 * 8 + 10 * 8 * 8, 1e-2);
    EXPECT_TRUE(holds(t, {32, 0, 32}));   // the shadow on the ground east of the box
    EXPECT_TRUE(holds(t, {37.9f, -1.9f, 30}));
    EXPECT_TRUE(holds(t, {24, 4, 32}));   // the box itself
    EXPECT_FALSE(holds(t, {18, 0, 32}));  // west of it, in the sun
    EXPECT_FALSE(holds(t, {32, 0, 37}));  // beside the shadow
    EXPECT_FALSE(holds(t, {30, 9, 32}));  // above the box
}

TEST(ShadowVolume, ClosedAndOutwardForSunsAlongAndBetweenTheAxes) {
    for (double azimuth : {0.0, 45.0, 90.0, 135.0, 180.0, 200.0, 270.0, 333.0})
        for (double elevation : {10.0, 25.0, 60.0, 90.0}) {
            const glm::vec3 sun = sun_direction(azimuth, elevation);
            std::vector<glm::vec3> t;
            append_shadow_volume(kBox, sun, -3.0f, t);
            const glm::vec3 d = -sun * ((kBox.hi.y + 3.0f) / sun.y);
            EXPECT_NEAR(enclosed(t), swept_volume(kBox, d), 1e-3 * swept_volume(kBox, d))
                << azimuth << "," << elevation;
        }
}

TEST(ShadowVolume, HoldsEveryPointWhoseRayToTheSunMeetsTheBox) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int trial = 0; trial < 200; ++trial) {
        const glm::vec3 sun = sun_direction(360.0 * u(rng), 5.0 + 85.0 * u(rng));
        const float floor = -10.0f * u(rng);
        std::vector<glm::vec3> t;
        append_shadow_volume(kBox, sun, floor, t);
        const glm::vec3 b = kBox.lo + (kBox.hi - kBox.lo) * glm::vec3(u(rng), u(rng), u(rng));
        const float reach = (b.y - floor) / sun.y; // down to the floor
        const glm::vec3 p = b - sun * (reach * u(rng));
        EXPECT_TRUE(holds(t, p)) << trial;
    }
}

TEST(ShadowVolume, NothingForASunAtTheHorizon) {
    std::vector<glm::vec3> t;
    append_shadow_volume(kBox, {1, 0, 0}, 0.0f, t);
    EXPECT_TRUE(t.empty());
}

} // namespace
} // namespace overflight
