// shadow_pixels (core/ShadowPixels.h): the pixels a screen-space shadow pass
// must cover. On flat ground seen from above, with a box and a low sun, every
// pixel whose ground point is under the box from the sun (an exact ray-box
// test) is covered, the rectangles are disjoint, and they hold few pixels
// beyond the shadow (the box's screen rectangle down to the ground held them all).
#include "TestCameras.h"
#include "core/ShadowPixels.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace overflight {
namespace {

// Whether the ray from p towards the sun meets the box (slabs).
bool under(const glm::dvec3& p, const glm::dvec3& sun, const WorldBox& box) {
    double t0 = 0, t1 = HUGE_VAL;
    for (int k = 0; k < 3; ++k) {
        if (std::abs(sun[k]) < 1e-12) {
            if (p[k] < box.lo[k] || p[k] > box.hi[k]) return false;
            continue;
        }
        double a = (box.lo[k] - p[k]) / sun[k], b = (box.hi[k] - p[k]) / sun[k];
        if (a > b) std::swap(a, b);
        t0 = std::max(t0, a);
        t1 = std::min(t1, b);
    }
    return t0 <= t1;
}

// The caster of a box: its corners.
struct BoxCaster {
    std::vector<glm::vec3> corners;
    explicit BoxCaster(const WorldBox& b) {
        for (int c = 0; c < 8; ++c) corners.emplace_back(c & 1 ? b.hi.x : b.lo.x, c & 2 ? b.hi.y : b.lo.y, c & 4 ? b.hi.z : b.lo.z);
    }
    ShadowCaster caster() const { return {corners, 0.0f}; }
};

struct Scene {
    Terrain terrain{65, 65, 1.0f}; // flat at 0
    Camera camera = test::camera_at({32, 30, 75}, 180, -35, 300, 160, 120);
    DepthImage depth;
    std::vector<glm::dvec3> ground; // per pixel; y = 1 for sky
    Scene() {
        depth.resize(camera.width, camera.height, 1.0f);
        ground.assign(std::size_t(camera.width) * std::size_t(camera.height), glm::dvec3(0, 1, 0));
        for (int row = 0; row < camera.height; ++row)
            for (int col = 0; col < camera.width; ++col) {
                const glm::dvec3 r = camera.ray(camera.u_of(col), camera.v_of(row));
                if (!(r.y < 0)) continue;
                const glm::dvec3 p = camera.eye + r * (-camera.eye.y / r.y);
                if (camera.view_depth(p) >= camera.far) continue;
                depth.at(col, row) = float(camera.window_depth(camera.view_depth(p)));
                ground[std::size_t(row) * std::size_t(camera.width) + std::size_t(col)] = p;
            }
    }
};

TEST(ShadowPixels, CoversTheShadowOfABoxOnFlatGround) {
    const Scene s;
    const WorldBox box{{30, 0, 30}, {34, 6, 34}};
    const glm::vec3 sun = glm::normalize(glm::vec3(-1.0f, 1.0f, 0.4f));
    const PixelRect all{0, 0, s.camera.width, s.camera.height};
    const BoxCaster caster(box);
    const ShadowCaster c = caster.caster();
    const std::vector<PixelRect> rects = shadow_pixels(s.depth, s.camera, {&s.terrain, 1, 1.0f}, sun, {&c, 1}, {&all, 1});
    std::vector<int> covered(s.ground.size(), 0);
    for (const PixelRect& r : rects) {
        ASSERT_FALSE(r.empty());
        ASSERT_GE(r.col0, 0);
        ASSERT_GE(r.row0, 0);
        ASSERT_LE(r.col1, s.camera.width);
        ASSERT_LE(r.row1, s.camera.height);
        for (int row = r.row0; row < r.row1; ++row)
            for (int col = r.col0; col < r.col1; ++col) ++covered[std::size_t(row) * std::size_t(s.camera.width) + std::size_t(col)];
    }
    int shadowed = 0, kept = 0;
    for (std::size_t i = 0; i < s.ground.size(); ++i) {
        ASSERT_LE(covered[i], 1) << "the rectangles overlap";
        kept += covered[i];
        const glm::dvec3& p = s.ground[i];
        if (p.y > 0 || !under(p, glm::dvec3(sun), box)) continue;
        ++shadowed;
        EXPECT_EQ(covered[i], 1) << "shadowed pixel " << i % std::size_t(s.camera.width) << ","
                                 << i / std::size_t(s.camera.width) << " left out";
    }
    EXPECT_GT(shadowed, 100) << "the test must see the shadow";
    // The box's screen rectangle down to the ground (its shadow's reach)
    // holds several times the pixels kept.
    EXPECT_LT(kept, 2 * shadowed);
}

// A cable crossing the view diagonally: the pixels under it from the sun
// (within its margin) are kept, in a thin band rather than all that lies
// under its bounding box.
TEST(ShadowPixels, ACableKeepsAThinBand) {
    const Scene s;
    const std::vector<glm::vec3> cable{{20, 5, 20}, {32, 5, 32}, {44, 5, 44}};
    const ShadowCaster c{cable, 0.5f};
    const glm::vec3 sun = glm::normalize(glm::vec3(-1.0f, 1.0f, 0.4f));
    const glm::dvec3 sd(sun);
    const PixelRect all{0, 0, s.camera.width, s.camera.height};
    std::vector<int> covered(s.ground.size(), 0);
    for (const PixelRect& r : shadow_pixels(s.depth, s.camera, {&s.terrain, 1, 1.0f}, sun, {&c, 1}, {&all, 1}))
        for (int row = r.row0; row < r.row1; ++row)
            for (int col = r.col0; col < r.col1; ++col) ++covered[std::size_t(row) * std::size_t(s.camera.width) + std::size_t(col)];
    const BoxCaster box(WorldBox{{20, 5, 20}, {44, 5, 44}});
    const ShadowCaster b{box.corners, 0.5f};
    long long under_box = 0;
    for (const PixelRect& r : shadow_pixels(s.depth, s.camera, {&s.terrain, 1, 1.0f}, sun, {&b, 1}, {&all, 1}))
        under_box += r.area();
    int shadowed = 0, kept = 0;
    for (std::size_t i = 0; i < s.ground.size(); ++i) {
        kept += covered[i];
        const glm::dvec3& p = s.ground[i];
        if (p.y > 0) continue;
        const glm::dvec3 q = p + sd * ((5.0 - p.y) / sd.y); // where its sun ray is at the cable's height
        const glm::dvec3 a(20, 5, 20), e(44, 5, 44);
        const double t = std::clamp(glm::dot(q - a, e - a) / glm::dot(e - a, e - a), 0.0, 1.0);
        if (glm::length(q - (a + t * (e - a))) > 0.5) continue;
        ++shadowed;
        EXPECT_EQ(covered[i], 1) << "pixel under the cable left out";
    }
    EXPECT_GT(shadowed, 20) << "the test must see the cable's shadow";
    EXPECT_LT(kept * 4, under_box) << "the band is not thinner than the box's shadow";
}

TEST(ShadowPixels, OnlyWithinTheGivenRectangles) {
    const Scene s;
    const WorldBox box{{30, 0, 30}, {34, 6, 34}};
    const glm::vec3 sun = glm::normalize(glm::vec3(-1.0f, 1.0f, 0.4f));
    const BoxCaster caster(box);
    const ShadowCaster c = caster.caster();
    const PixelRect none{0, 0, 0, 0};
    EXPECT_TRUE(shadow_pixels(s.depth, s.camera, {&s.terrain, 1, 1.0f}, sun, {&c, 1}, {&none, 1}).empty());
    const PixelRect left{0, 0, 20, s.camera.height};
    for (const PixelRect& r : shadow_pixels(s.depth, s.camera, {&s.terrain, 1, 1.0f}, sun, {&c, 1}, {&left, 1}))
        EXPECT_LE(r.col1, 20);
}

// The tiles' rejection passes over only pixels the per-pixel test would not
// keep: on a rough terrain (the pass moves points onto sample tops above and
// below them), a camera that sees the horizon (level rays keep their
// pixels) and casters of both kinds under a low sun, each caster within its
// own rectangle, the two give the same rectangles.
TEST(ShadowPixels, TilesKeepWhatThePixelsKeep) {
    Scene s;
    for (int r = 0; r < s.terrain.rows(); ++r)
        for (int c = 0; c < s.terrain.cols(); ++c) s.terrain.raw(r, c) = std::uint16_t((r * 7 + c * 13 + r * c) % 5);
    s.camera = test::camera_at({32, 12, 80}, 180, -8, 300, 203, 131);
    s.depth.resize(s.camera.width, s.camera.height, 1.0f);
    // A plane among the tops (heights 0..4), up to a distance: sky beyond.
    for (int row = 0; row < s.camera.height; ++row)
        for (int col = 0; col < s.camera.width; ++col) {
            const glm::dvec3 r = s.camera.ray(s.camera.u_of(col), s.camera.v_of(row));
            if (!(r.y < 0)) continue;
            const double t = (2.0 - s.camera.eye.y) / r.y; // view depth
            if (t < 150) s.depth.at(col, row) = float(s.camera.window_depth(t));
        }
    const BoxCaster house(WorldBox{{30, 0, 40}, {36, 7, 46}});
    const BoxCaster tower(WorldBox{{20, 0, 30}, {21, 25, 31}});
    const std::vector<glm::vec3> cable{{21, 24, 31}, {32, 22, 45}, {44, 24, 60}};
    const std::vector<ShadowCaster> casters{house.caster(), tower.caster(), {cable, 0.3f}};
    const std::vector<PixelRect> rects{{0, 0, s.camera.width, s.camera.height},
                                       {13, 20, 150, 131},
                                       {40, 0, 203, 90}};
    for (const glm::vec3 sun : {glm::normalize(glm::vec3(-1.0f, 0.45f, 0.4f)), glm::normalize(glm::vec3(0.3f, 0.2f, -1.0f))}) {
        const SnapGrid grid{&s.terrain, 1, 1.0f};
        const std::vector<PixelRect> tiles = shadow_pixels(s.depth, s.camera, grid, sun, casters, rects);
        const std::vector<PixelRect> pixels = shadow_pixels(s.depth, s.camera, grid, sun, casters, rects, false);
        long long kept = 0;
        for (const PixelRect& r : pixels) kept += r.area();
        EXPECT_GT(kept, 200) << "the test must keep pixels";
        ASSERT_EQ(tiles.size(), pixels.size());
        for (std::size_t i = 0; i < tiles.size(); ++i) {
            EXPECT_EQ(tiles[i].col0, pixels[i].col0);
            EXPECT_EQ(tiles[i].row0, pixels[i].row0);
            EXPECT_EQ(tiles[i].col1, pixels[i].col1);
            EXPECT_EQ(tiles[i].row1, pixels[i].row1);
        }
    }
}

} // namespace
} // namespace overflight
