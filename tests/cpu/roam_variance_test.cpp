// ROAM variance tree (CMSC 23700 project 2a sec. 5) and view wedge (sec. 5.1) on
// hand-checkable literals.
#include "core/Error.h"
#include "core/Terrain.h"
#include "lod/RoamMesh.h"
#include "lod/RoamVarianceTree.h"
#include "lod/RoamViewWedge.h"

#include <gtest/gtest.h>

#include <vector>

using namespace overflight;

namespace {

Terrain field(int size, const std::vector<std::uint16_t>& h, float vs = 1.0f) {
    Terrain t(size, size, 1.0f, vs);
    t.heights() = h;
    return t;
}

} // namespace

// 5x5 field (row, col), zero except the centre (2,2) = 5 and (1,3) = 8:
//   0 0 0 0 0
//   0 0 0 8 0
//   0 0 5 0 0
//   0 0 0 0 0
//   0 0 0 0 0
// Nodes (heap index: hypotenuse midpoint m between v0 and v1; local error
// ceil|H[m] - (H[v0] + H[v1]) / 2|):
//   level 0: 2 = (NE; NW-SE), m (2,2): |5 - 0| = 5;  3 = (SW; SE-NW): 5.
//   level 1: 4 (hyp (0,4)-(0,0), m (0,2)), 5 ((4,4)-(0,4), m (2,4)), 6 ((4,0)-(4,4), m (4,2)),
//            7 ((0,0)-(4,0), m (2,0)): all midpoints on the border are 0 between 0s -> 0.
//   level 2: 8 ((2,2)-(0,4), m (1,3)): |8 - 2.5| = 5.5 -> 6;  9 ((0,0)-(2,2), m (1,1)): |0 - 2.5| -> 3;
//            10 ((2,2)-(4,4), m (3,3)) -> 3;  11 ((0,4)-(2,2), m (1,3)) -> 6;
//            12 ((2,2)-(4,0), m (3,1)) -> 3;  13 ((4,4)-(2,2)) -> 3;  14 ((2,2)-(0,0)) -> 3;  15 ((4,0)-(2,2)) -> 3.
//   level 3: hypotenuses of length 2 ending at the centre have error |0 - 2.5| -> 3:
//            16 ((0,2)-(2,2)), 19 ((2,2)-(0,2)), 20 ((2,4)-(2,2)), 23 ((2,2)-(2,4)),
//            24 ((4,2)-(2,2)), 27, 28 ((2,0)-(2,2)), 31; the others (17, 18, 21, 22, 25,
//            26, 29, 30) lie on the border between zeros -> 0.
// Variance = max over the subtree:
//   level 2: 8 = max(6, 3, 0) = 6, 9 = max(3, 0, 3) = 3, 10 = 3, 11 = max(6, 0, 3) = 6, 12..15 = 3
//   level 1: 4 = max(0, 6, 3) = 6, 5 = max(0, 3, 6) = 6, 6 = 3, 7 = 3
//   level 0: 2 = max(5, 6, 6) = 6 (the north-east half holds the 8), 3 = max(5, 3, 3) = 5.
TEST(RoamVarianceTree, FiveByFiveByHand) {
    // clang-format off
    const Terrain t = field(5, {0, 0, 0, 0, 0,
                                0, 0, 0, 8, 0,
                                0, 0, 5, 0, 0,
                                0, 0, 0, 0, 0,
                                0, 0, 0, 0, 0}, 2.0f);
    // clang-format on
    const RoamVarianceTree v(t);
    EXPECT_EQ(v.grid_log2(), 2);
    EXPECT_EQ(v.finest_level(), 4);
    EXPECT_EQ(v.stored_depth(), 3);
    const std::uint16_t expected[32] = {0, 0,                       // unused
                                        6, 5,                       // level 0
                                        6, 6, 3, 3,                 // level 1
                                        6, 3, 3, 6, 3, 3, 3, 3,     // level 2
                                        3, 0, 0, 3, 3, 0, 0, 3,     // level 3
                                        3, 0, 0, 3, 3, 0, 0, 3};
    for (std::uint32_t k = 2; k < 32; ++k) EXPECT_EQ(v.raw(k), expected[k]) << "node " << k;
    // World units: v_scale 2.
    EXPECT_FLOAT_EQ(v.world(2), 12.0f);
    EXPECT_FLOAT_EQ(v.world(3), 10.0f);
}

// 9x9 field H[i][j] = i * j. On a hypotenuse from (r0, c0) to (r1, c1) the
// midpoint error of the bilinear function r * c is |dr * dc| / 4:
// axis-aligned hypotenuses (odd levels) have error 0; diagonal ones with
// legs d (levels 0, 2, 4: d = 8, 4, 2) have error d^2 / 4 = 16, 4, 1.
// Subtree maxima by level: 0: 16, 1: 4, 2: 4, 3: 1, 4: 1, 5: 0.
TEST(RoamVarianceTree, NineByNineBilinearByHand) {
    std::vector<std::uint16_t> h(81);
    for (int i = 0; i < 9; ++i)
        for (int j = 0; j < 9; ++j) h[std::size_t(i * 9 + j)] = std::uint16_t(i * j);
    const Terrain t = field(9, h);
    const RoamVarianceTree v(t);
    EXPECT_EQ(v.finest_level(), 6);
    ASSERT_EQ(v.stored_depth(), 5);
    const std::uint16_t by_level[6] = {16, 4, 4, 1, 1, 0};
    for (int level = 0; level <= 5; ++level)
        for (std::uint32_t k = 1u << (level + 1); k < (2u << (level + 1)); ++k)
            EXPECT_EQ(v.raw(k), by_level[level]) << "level " << level << " node " << k;

    // Limited depth: levels below 2 share the bound of their level-2 ancestor,
    // which is never smaller than their own.
    const RoamVarianceTree shallow(t, 2);
    EXPECT_EQ(shallow.stored_depth(), 2);
    EXPECT_EQ(shallow.memory_bytes(), 16u * sizeof(std::uint16_t));
    for (int level = 3; level <= 5; ++level)
        for (std::uint32_t k = 1u << (level + 1); k < (2u << (level + 1)); ++k) {
            const std::uint32_t s = shallow.stored_node(k, level);
            EXPECT_EQ(s, k >> (level - 2));
            EXPECT_GE(shallow.raw(s), v.raw(k));
        }
}

// A plane is reproduced exactly by linear interpolation: every bound is 0.
TEST(RoamVarianceTree, PlaneHasNoError) {
    std::vector<std::uint16_t> h(81);
    for (int i = 0; i < 9; ++i)
        for (int j = 0; j < 9; ++j) h[std::size_t(i * 9 + j)] = std::uint16_t(100 + 3 * i + 2 * j);
    const RoamVarianceTree v(field(9, h));
    for (std::uint32_t k = 2; k < 64; ++k) EXPECT_EQ(v.raw(k), 0) << k;
}

TEST(RoamVarianceTree, RejectsBadInput) {
    EXPECT_THROW(RoamVarianceTree(Terrain(5, 6, 1.0f)), Error);
    EXPECT_THROW(RoamVarianceTree(Terrain(6, 6, 1.0f)), Error);
    EXPECT_THROW(RoamVarianceTree(Terrain(5, 5, 1.0f), -1), Error);
    EXPECT_THROW(RoamMesh(Terrain(2, 2, 1.0f)), Error);
}

// Shear camera at (50, 10, 50) facing south (+Z), fov 90: the side lines are
// x - 50 = +-(z - 50).
TEST(RoamViewWedge, ShearSideLinesByHand) {
    Camera cam;
    cam.eye = {50, 10, 50};
    cam.heading = 0;
    cam.fov = 90;
    cam.width = 200;
    cam.height = 100;
    cam.far = 100;
    const RoamViewWedge w = RoamViewWedge::from_camera(cam, 0, 20);
    ASSERT_TRUE(w.enabled);
    // Straight ahead.
    EXPECT_FALSE(w.outside({49, 60}, {51, 60}, {50, 62}));
    // Behind the eye.
    EXPECT_TRUE(w.outside({49, 40}, {51, 40}, {50, 42}));
    // East of the line x - 50 = z - 50 (45 degrees to the left of heading 0,
    // since R = F x Y = (-1, 0, 0) points west).
    EXPECT_TRUE(w.outside({70, 60}, {75, 60}, {75, 65}));
    EXPECT_TRUE(w.outside({30, 60}, {25, 60}, {25, 65}));
    // Straddling a side line: visible.
    EXPECT_FALSE(w.outside({58, 60}, {62, 60}, {62, 64}));
    // Straddling the eye's left and right lines far behind: caught by the
    // behind-the-eye line.
    EXPECT_TRUE(w.outside({0, 0}, {100, 0}, {50, 20}));
    // Beyond far = 100 along the heading.
    EXPECT_TRUE(w.outside({49, 151}, {51, 151}, {50, 160}));
    EXPECT_FALSE(w.outside({49, 149}, {51, 151}, {50, 160}));
}

// A tilted camera looking steeply down sees behind its own XZ position: no wedge.
TEST(RoamViewWedge, SteepTiltDisablesTheWedge) {
    Camera cam;
    cam.eye = {50, 100, 50};
    cam.pitch = -80;
    cam.fov = 60;
    cam.projection = Projection::Tilt;
    const RoamViewWedge w = RoamViewWedge::from_camera(cam, 0, 20);
    EXPECT_FALSE(w.enabled);
    EXPECT_FALSE(w.outside({49, 40}, {51, 40}, {50, 42}));
    cam.pitch = -10; // a mild tilt widens the wedge a little beyond fov/2
    const RoamViewWedge m = RoamViewWedge::from_camera(cam, 0, 20);
    ASSERT_TRUE(m.enabled);
    cam.projection = Projection::Shear;
    const RoamViewWedge s = RoamViewWedge::from_camera(cam, 0, 20);
    // A point just outside the shear wedge (30 degrees) at 31 degrees is inside the tilt wedge.
    const double a = 31.0 * 3.14159265358979 / 180.0;
    const glm::dvec2 p{50 - 40 * std::sin(a), 50 + 40 * std::cos(a)};
    EXPECT_TRUE(s.outside(p, p, p));
    EXPECT_FALSE(m.outside(p, p, p));
}

TEST(RoamBuckets, MonotoneWithFineSteps) {
    EXPECT_EQ(roam_bucket(0.0f), 1);
    EXPECT_EQ(roam_bucket(1.0f / 2048), 1);
    int prev = 1;
    for (float e = 1.0f / 1000; e < 1e7f; e *= 1.01f) {
        const int b = roam_bucket(e);
        EXPECT_GE(b, prev);
        EXPECT_LE(b, kRoamBuckets - 2);
        prev = b;
    }
    // 128 buckets per octave.
    EXPECT_EQ(roam_bucket(2.0f) - roam_bucket(1.0f), 128);
    EXPECT_GT(roam_bucket(1.0f + 1.0f / 64), roam_bucket(1.0f));
}

TEST(RoamBudget, SqrtTwoLadder) {
    EXPECT_EQ(roam_scale_budget(65536, 1), 92682);  // 2^16.5
    EXPECT_EQ(roam_scale_budget(65536, -1), 46341); // 2^15.5
    EXPECT_EQ(roam_scale_budget(65536, 2), 131072);
    EXPECT_EQ(roam_scale_budget(roam_scale_budget(65536, 1), -1), 65536);
    EXPECT_EQ(roam_scale_budget(roam_scale_budget(30000, 3), -3), roam_scale_budget(30000, 0));
    EXPECT_EQ(roam_scale_budget(64, -5), 64);
    EXPECT_EQ(roam_scale_budget(1 << 22, 4), 1 << 22);
}
