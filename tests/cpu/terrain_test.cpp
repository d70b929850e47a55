// Terrain model of DESIGN sec. 1 on hand-checkable literals.
#include "core/DemoIsland.h"
#include "core/Error.h"
#include "core/Shading.h"
#include "core/Terrain.h"

#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

using namespace overflight;

namespace {

// 3x3 field, hs = 10, vs = 0.5, y0 = 100:
//   row 0:  0  2  4
//   row 1:  6  8 10
//   row 2: 12 14 16
// World height of sample (i, j) = 0.5 * H + 100, i.e. 100 + 3 i + j (metres).
Terrain ramp3() {
    Terrain t(3, 3, 10.0f, 0.5f, 100.0f);
    const std::uint16_t h[] = {0, 2, 4, 6, 8, 10, 12, 14, 16};
    std::copy(std::begin(h), std::end(h), t.heights().begin());
    return t;
}

} // namespace

TEST(Terrain, WorldCoordinatesOfSamples) {
    const Terrain t = ramp3();
    EXPECT_FLOAT_EQ(t.sample_height(0, 0), 100.0f);
    EXPECT_FLOAT_EQ(t.sample_height(1, 2), 105.0f); // 0.5 * 10 + 100
    EXPECT_FLOAT_EQ(t.sample_height(2, 1), 107.0f);
    EXPECT_FLOAT_EQ(t.width(), 20.0f);
    EXPECT_FLOAT_EQ(t.depth(), 20.0f);
    EXPECT_FLOAT_EQ(t.min_height(), 100.0f);
    EXPECT_FLOAT_EQ(t.max_height(), 108.0f);
}

TEST(Terrain, NearestAndBilinearByHand) {
    const Terrain t = ramp3();
    // (x, z) = (4, 14): nearest sample col 0, row 1 -> 103.
    EXPECT_FLOAT_EQ(t.height_nearest(4.0f, 14.0f), 103.0f);
    // (x, z) = (6, 14): nearest col 1 (0.6 rounds up), row 1 -> 104.
    EXPECT_FLOAT_EQ(t.height_nearest(6.0f, 14.0f), 104.0f);
    // The field is the plane 100 + 0.3 z + 0.1 x, so bilinear is exact:
    // (x, z) = (15, 5) -> 100 + 1.5 + 1.5 = 103.
    EXPECT_FLOAT_EQ(t.height_bilinear(15.0f, 5.0f), 103.0f);
    EXPECT_FLOAT_EQ(t.height_bilinear(2.5f, 17.5f), 105.5f);
    // Outside the grid the border value is held.
    EXPECT_FLOAT_EQ(t.height_bilinear(-5.0f, -5.0f), 100.0f);
    EXPECT_FLOAT_EQ(t.height_bilinear(25.0f, 25.0f), 108.0f);
}

TEST(Terrain, BilinearOnASaddle) {
    // 2x2 cell with corners 0 (NW), 10 (NE), 10 (SW), 0 (SE), hs 1, vs 1:
    // centre = (0 + 10 + 10 + 0) / 4 = 5; at (0.25, 0.25):
    // top = 0 + 10*0.25 = 2.5, bottom = 10 - 10*0.25 = 7.5, 2.5 + 5*0.25 = 3.75.
    Terrain t(2, 2, 1.0f);
    t.raw(0, 0) = 0; t.raw(0, 1) = 10; t.raw(1, 0) = 10; t.raw(1, 1) = 0;
    EXPECT_FLOAT_EQ(t.height_bilinear(0.5f, 0.5f), 5.0f);
    EXPECT_FLOAT_EQ(t.height_bilinear(0.25f, 0.25f), 3.75f);
}

TEST(Terrain, NormalsOfAPlane) {
    const Terrain t = ramp3();
    // Plane y = 100 + 0.1 x + 0.3 z: normal ~ (-0.1, 1, -0.3) / |.|.
    const float len = std::sqrt(0.01f + 1.0f + 0.09f);
    const glm::vec3 n = t.normal(10.0f, 10.0f);
    EXPECT_NEAR(n.x, -0.1f / len, 1e-6);
    EXPECT_NEAR(n.y, 1.0f / len, 1e-6);
    EXPECT_NEAR(n.z, -0.3f / len, 1e-6);
    const glm::vec3 corner = t.sample_normal(0, 0); // one-sided differences, same plane
    EXPECT_NEAR(corner.x, -0.1f / len, 1e-6);
    EXPECT_NEAR(corner.z, -0.3f / len, 1e-6);
}

TEST(Terrain, PadsToPow2Plus1ByZamrisRule) {
    EXPECT_EQ(next_pow2_plus1(2), 2);
    EXPECT_EQ(next_pow2_plus1(3), 3);
    EXPECT_EQ(next_pow2_plus1(4), 5);
    EXPECT_EQ(next_pow2_plus1(468), 513);
    EXPECT_EQ(next_pow2_plus1(1201), 2049);
    EXPECT_TRUE(is_pow2_plus1(1025));
    EXPECT_FALSE(is_pow2_plus1(1024));

    Terrain t(3, 4, 2.0f); // 3 rows x 4 cols -> 5x5
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) t.raw(i, j) = std::uint16_t(10 * i + j);
    const Terrain p = pad_to_pow2_plus1(t);
    ASSERT_EQ(p.rows(), 5);
    ASSERT_EQ(p.cols(), 5);
    EXPECT_EQ(p.raw(2, 3), 23); // source kept in place
    EXPECT_EQ(p.raw(4, 1), 21); // below: repeats the last row
    EXPECT_EQ(p.raw(0, 4), 3);  // right: repeats the last column
    EXPECT_EQ(p.raw(4, 4), 23);
    EXPECT_FLOAT_EQ(p.h_scale(), 2.0f);
}

TEST(Terrain, RejectsBadSizes) {
    EXPECT_THROW(Terrain(1, 5, 1.0f), Error);
    EXPECT_THROW(Terrain(5, 70000, 1.0f), Error);
    EXPECT_THROW(Terrain(5, 5, 0.0f), Error);
}

TEST(Shading, HillshadeLightsSlopesFacingTheSun) {
    // Sun from the north-west (azimuth 315). A slope rising to the east faces
    // west and is lit more than one rising to the west (facing east).
    Terrain east(3, 3, 1.0f), west(3, 3, 1.0f), flat(3, 3, 1.0f);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            east.raw(i, j) = std::uint16_t(j);
            west.raw(i, j) = std::uint16_t(2 - j);
        }
    const float lit = hillshade(east, 1, 1), dark = hillshade(west, 1, 1), level = hillshade(flat, 1, 1);
    EXPECT_GT(lit, level);
    EXPECT_LT(dark, level);
    EXPECT_NEAR(level, std::cos(45.0f * 3.14159265f / 180.0f), 1e-6); // cos(zenith) on flat ground
}

TEST(Shading, RampGoesFromWaterToSnow) {
    const Rgb8 water = elevation_ramp(-10, -50, 1000, 0);
    const Rgb8 snow = elevation_ramp(1000, -50, 1000, 0);
    EXPECT_GT(water.b, water.r);
    EXPECT_GT(snow.r, 240);
    EXPECT_GT(snow.b, 240);
}

// The row shader (each height converted once) gives every sample exactly
// shaded_color's color, edges included.
TEST(Shading, RowsEqualShadedColorPerSample) {
    Terrain t(13, 17, 7.5f, 0.37f, -20.0f);
    std::uint32_t s = 12345;
    for (std::uint16_t& h : t.heights()) {
        s = s * 1664525u + 1013904223u;
        h = std::uint16_t(s >> 20);
    }
    shade_by_elevation(t, 50.0f, -20.0f, 1500.0f);
    for (int i = 0; i < t.rows(); ++i)
        for (int j = 0; j < t.cols(); ++j) {
            const Rgb8 want = shaded_color(t, i, j, -20.0f, 1500.0f, 50.0f), got = t.color(i, j);
            EXPECT_EQ(std::tie(got.r, got.g, got.b), std::tie(want.r, want.g, want.b)) << i << "," << j;
        }
}

TEST(DemoIsland, IsDeterministicAndAnIsland) {
    const DataSet a = make_demo_island({.size = 129});
    const DataSet b = make_demo_island({.size = 129});
    EXPECT_EQ(a.terrain.heights(), b.terrain.heights());
    EXPECT_EQ(a.terrain.colors(), b.terrain.colors());
    const DataSet c = make_demo_island({.size = 129, .seed = 42});
    EXPECT_NE(a.terrain.heights(), c.terrain.heights());
    // Sea at the corners, land in the middle.
    const Terrain& t = a.terrain;
    EXPECT_FLOAT_EQ(t.sample_height(0, 0), 0.0f);
    EXPECT_FLOAT_EQ(t.sample_height(128, 128), 0.0f);
    EXPECT_GT(t.max_height(), 300.0f);
    EXPECT_FLOAT_EQ(t.min_height(), 0.0f);
    // Objects and a start on the terrain.
    EXPECT_TRUE(a.start.given);
    EXPECT_TRUE(t.contains(float(a.start.x), float(a.start.z)));
    EXPECT_GT(t.height_bilinear(float(a.start.x), float(a.start.z)), 0.0f);
    EXPECT_GE(a.scene.objects.size(), 3u);
    ASSERT_EQ(a.scene.lines.size(), 1u);
    EXPECT_GE(a.scene.lines[0].points.size(), 2u);
}

TEST(DemoIsland, RejectsSizesThatAreNot2nPlus1) {
    EXPECT_THROW(make_demo_island({.size = 1000}), Error);
    EXPECT_THROW(make_demo_island({.size = 17}), Error);
}
