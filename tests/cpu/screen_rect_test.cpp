// screen_rect (core/ScreenRect.h): the pixels world boxes can cover, for the
// compositor's partial depth load. Each outcome on hand-placed boxes, and
// random points inside random boxes always project inside their rectangle.
#include "TestCameras.h"
#include "core/ScreenRect.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace overflight {
namespace {

// Looking south (+Z) from the origin, 200x100, shear pitch -10.
Camera camera() {
    Camera c = test::camera_at({0, 0, 0}, 0, -10, 1000, 200, 100);
    c.near = 1;
    return c;
}

TEST(ScreenRect, NoBoxesIsEmpty) { EXPECT_TRUE(screen_rect({}, camera()).empty()); }

TEST(ScreenRect, BoxAheadBoundsItsCorners) {
    const Camera c = camera();
    const std::vector<WorldBox> boxes{{{-5, -10, 95}, {5, 0, 105}}};
    const PixelRect r = screen_rect(boxes, c);
    ASSERT_FALSE(r.empty());
    EXPECT_LT(r.area(), 200LL * 100 / 4);
    for (int k = 0; k < 8; ++k) {
        const auto& b = boxes[0];
        const Camera::Projected p =
            c.project({(k & 1) ? b.hi.x : b.lo.x, (k & 2) ? b.hi.y : b.lo.y, (k & 4) ? b.hi.z : b.lo.z});
        EXPECT_GE(p.col, r.col0 + 1.0);
        EXPECT_LE(p.col, r.col1 - 1.0);
        EXPECT_GE(p.row, r.row0 + 1.0);
        EXPECT_LE(p.row, r.row1 - 1.0);
    }
}

TEST(ScreenRect, BoxBehindTheEyeIsSkipped) {
    const std::vector<WorldBox> boxes{{{-5, -10, -105}, {5, 0, -95}}};
    EXPECT_TRUE(screen_rect(boxes, camera()).empty());
}

TEST(ScreenRect, BoxCutByTheNearPlaneIsBoundedInFront) {
    // Around the eye: what lies in front of the near plane covers the image.
    const std::vector<WorldBox> around{{{-5, -10, 95}, {5, 0, 105}}, {{-1, -1, -1}, {1, 1, 3}}};
    const PixelRect r = screen_rect(around, camera());
    EXPECT_EQ(r.col0, 0);
    EXPECT_EQ(r.row0, 0);
    EXPECT_EQ(r.col1, 200);
    EXPECT_EQ(r.row1, 100);
    // From behind the eye to far ahead on +X (the image's left, looking south): only that side.
    const std::vector<WorldBox> right{{{20, -10, -5}, {30, 0, 300}}};
    const PixelRect q = screen_rect(right, camera());
    ASSERT_FALSE(q.empty());
    EXPECT_EQ(q.col0, 0);
    EXPECT_LT(q.col1, 100);
}

TEST(ScreenRect, RandomPointsInFrontOfTheNearPlaneProjectInside) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1, 1);
    const Camera c = camera();
    for (int i = 0; i < 200; ++i) {
        const glm::vec3 centre{60 * u(rng), 20 * u(rng), 20 * u(rng)};
        const glm::vec3 half{1 + 30 * std::abs(u(rng)), 1 + 20 * std::abs(u(rng)), 1 + 40 * std::abs(u(rng))};
        const std::vector<WorldBox> boxes{{centre - half, centre + half}};
        const PixelRect r = screen_rect(boxes, c);
        for (int k = 0; k < 50; ++k) {
            const glm::dvec3 p = centre + half * glm::vec3(u(rng), u(rng), u(rng));
            if (!(c.view_depth(p) > c.near)) continue;
            const Camera::Projected q = c.project(p);
            if (q.col < 0 || q.col >= c.width || q.row < 0 || q.row >= c.height) continue;
            EXPECT_GE(q.col, r.col0);
            EXPECT_LT(q.col, r.col1);
            EXPECT_GE(q.row, r.row0);
            EXPECT_LT(q.row, r.row1);
        }
    }
}

TEST(DisjointCover, CoversTheUnionOnceEachPixel) {
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> u(0, 40);
    for (int trial = 0; trial < 100; ++trial) {
        std::vector<PixelRect> rects;
        for (int i = 0; i < 1 + trial % 6; ++i) {
            const int c0 = u(rng), r0 = u(rng);
            rects.push_back({c0, r0, c0 + u(rng) / 2, r0 + u(rng) / 2});
        }
        const std::vector<PixelRect> cover = disjoint_cover(rects);
        for (int row = 0; row < 64; ++row)
            for (int col = 0; col < 64; ++col) {
                int in = 0, covered = 0;
                for (const PixelRect& r : rects) in |= r.col0 <= col && col < r.col1 && r.row0 <= row && row < r.row1;
                for (const PixelRect& r : cover) covered += r.col0 <= col && col < r.col1 && r.row0 <= row && row < r.row1;
                ASSERT_EQ(covered, in) << "trial " << trial << " pixel " << col << "," << row;
            }
    }
    // Two far apart stay two; one inside another is one.
    const std::vector<PixelRect> apart{{0, 0, 10, 10}, {100, 50, 110, 60}};
    EXPECT_EQ(disjoint_cover(apart).size(), 2u);
    const std::vector<PixelRect> nested{{0, 0, 10, 10}, {2, 2, 5, 5}};
    ASSERT_EQ(disjoint_cover(nested).size(), 1u);
    EXPECT_EQ(disjoint_cover(nested)[0].area(), 100);
}

TEST(ScreenRect, BoxBesideTheViewClipsToNothing) {
    // Far to the camera's side: its rectangle lies wholly left or right of the image.
    const std::vector<WorldBox> boxes{{{500, -10, 95}, {510, 0, 105}}};
    EXPECT_TRUE(screen_rect(boxes, camera()).empty());
}

TEST(ScreenRect, RandomPointsInRandomBoxesProjectInside) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1, 1);
    for (Projection proj : {Projection::Shear, Projection::Tilt}) {
        Camera c = camera();
        c.projection = proj;
        for (int i = 0; i < 200; ++i) {
            const glm::vec3 centre{300 * u(rng), 50 * u(rng), 150 + 140 * u(rng)};
            const glm::vec3 half{1 + 20 * std::abs(u(rng)), 1 + 20 * std::abs(u(rng)), 1 + 20 * std::abs(u(rng))};
            const std::vector<WorldBox> boxes{{centre - half, centre + half}};
            const PixelRect r = screen_rect(boxes, c);
            for (int k = 0; k < 20; ++k) {
                const glm::dvec3 p = centre + half * glm::vec3(u(rng), u(rng), u(rng));
                const Camera::Projected q = c.project(p);
                if (q.col < 0 || q.col >= c.width || q.row < 0 || q.row >= c.height) continue;
                EXPECT_TRUE(q.col >= r.col0 && q.col < r.col1 && q.row >= r.row0 && q.row < r.row1)
                    << "box " << i << " point " << k;
            }
        }
    }
}

TEST(ScreenRect, BoundingUnionHoldsBothAndIgnoresEmpty) {
    const PixelRect a{10, 20, 30, 40}, b{25, 5, 50, 35}, none{7, 7, 7, 9};
    const PixelRect u = bounding_union(a, b);
    EXPECT_EQ(u.col0, 10);
    EXPECT_EQ(u.row0, 5);
    EXPECT_EQ(u.col1, 50);
    EXPECT_EQ(u.row1, 40);
    const PixelRect ua = bounding_union(a, none), ub = bounding_union(none, b);
    EXPECT_EQ(ua.col0, a.col0);
    EXPECT_EQ(ua.row1, a.row1);
    EXPECT_EQ(ub.col1, b.col1);
    EXPECT_EQ(ub.row0, b.row0);
    EXPECT_TRUE(bounding_union(none, PixelRect{}).empty());
}

} // namespace
} // namespace overflight
