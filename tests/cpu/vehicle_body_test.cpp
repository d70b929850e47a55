// The hovercraft body's frame on the terrain (sim/VehicleBody.h), which the
// native compositor and the web page's engine both place the vehicle with.
#include "sim/VehicleBody.h"

#include "sim/Hovercraft.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <cmath>

using namespace overflight;

namespace {

// 65x65 samples 10 m apart rising 1 m per metre eastward (+X) from 100 m.
Terrain east_slope() {
    Terrain t(65, 65, 10.0f);
    for (int r = 0; r < 65; ++r)
        for (int c = 0; c < 65; ++c) t.raw(r, c) = std::uint16_t(100 + 10 * c);
    return t;
}

} // namespace

TEST(VehicleBody, OnFlatGroundItHoversUprightFacingItsHeading) {
    Terrain t(33, 33, 10.0f);
    for (auto& h : t.heights()) h = 50;
    const BodyFrame f = vehicle_frame(t, 160, 160, 90); // heading 90: facing +X
    EXPECT_NEAR(f.origin.y, ground_height(t, 160, 160) + VehicleBody::kHover, 1e-9);
    EXPECT_NEAR(f.az.x, 1, 1e-12);
    EXPECT_NEAR(f.ay.y, 1, 1e-12);
    EXPECT_NEAR(f.ax.z, -1, 1e-12); // right of +X is -Z (DESIGN sec. 1)
}

TEST(VehicleBody, TiltsToTheSlopeWithOrthonormalAxes) {
    const Terrain t = east_slope();
    const BodyFrame f = vehicle_frame(t, 320, 320, 90); // uphill
    EXPECT_NEAR(glm::length(f.ax), 1, 1e-12);
    EXPECT_NEAR(glm::length(f.ay), 1, 1e-12);
    EXPECT_NEAR(glm::length(f.az), 1, 1e-12);
    EXPECT_NEAR(glm::dot(f.ax, f.ay), 0, 1e-12);
    EXPECT_NEAR(glm::dot(f.ay, f.az), 0, 1e-12);
    EXPECT_NEAR(f.az.y, std::sqrt(0.5), 1e-9); // 45 degrees up the 1:1 slope
    EXPECT_NEAR(f.ax.y, 0, 1e-9);              // level across it
}

TEST(VehicleBody, PlacedBoxHoldsEveryPlacedCorner) {
    const Terrain t = east_slope();
    const BodyFrame f = vehicle_frame(t, 300, 200, 33);
    const WorldBox local = vehicle_local_box();
    const WorldBox box = placed_box(f, local, 0.5);
    for (int k = 0; k < 8; ++k) {
        const glm::dvec3 p = f.place({(k & 1) ? local.hi.x : local.lo.x, (k & 2) ? local.hi.y : local.lo.y,
                                      (k & 4) ? local.hi.z : local.lo.z});
        for (int c = 0; c < 3; ++c) {
            EXPECT_GE(p[c], box.lo[c] + 0.49);
            EXPECT_LE(p[c], box.hi[c] - 0.49);
        }
    }
}
