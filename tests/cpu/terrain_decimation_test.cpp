// core/TerrainDecimation.h: every f-th sample, box-filtered colors, the
// factor for a side limit, and the grids that cannot be decimated.
#include "core/Error.h"
#include "core/TerrainDecimation.h"

#include <gtest/gtest.h>

using namespace overflight;

TEST(TerrainDecimation, FactorIsTheSmallestThatFits) {
    EXPECT_EQ(decimation_factor(65, 65, 65), 1);
    EXPECT_EQ(decimation_factor(65, 65, 33), 2);
    EXPECT_EQ(decimation_factor(257, 100, 65), 4);
    EXPECT_EQ(decimation_factor(66, 10, 65), 2);  // 65 samples would not reach the 66th
    EXPECT_EQ(decimation_factor(8193, 8193, 4097), 2);
    EXPECT_EQ(decimation_factor(20001, 5, 4097), 5); // (20001 - 1) / 5 + 1 = 4001
}

TEST(TerrainDecimation, KeepsEveryFthSampleAndAveragesColors) {
    // 5x5 heights h = 10 row + col, colors r = 4 (5 row + col) (green, blue 0).
    Terrain t(5, 5, 2.0f, 0.5f, -3.0f);
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j) {
            t.raw(i, j) = std::uint16_t(10 * i + j);
            t.color(i, j) = Rgb8{std::uint8_t(4 * (5 * i + j)), 0, 0};
        }
    const Terrain d = decimate_terrain(t, 2);
    ASSERT_EQ(d.rows(), 3);
    ASSERT_EQ(d.cols(), 3);
    EXPECT_FLOAT_EQ(d.h_scale(), 4.0f);
    EXPECT_FLOAT_EQ(d.v_scale(), 0.5f);
    EXPECT_FLOAT_EQ(d.y_offset(), -3.0f);
    const std::uint16_t heights[9] = {0, 2, 4, 20, 22, 24, 40, 42, 44};
    for (int k = 0; k < 9; ++k) EXPECT_EQ(d.heights()[std::size_t(k)], heights[k]) << k;
    // f = 2: the block of kept sample k is source samples 2k-1 .. 2k (clamped).
    // (0,0): just sample (0,0) -> 0. (1,1): samples (1..2, 1..2): r = 4 (6, 7, 11, 12) -> mean 36.
    // (2,2): samples (3..4, 3..4): 4 (18, 19, 23, 24) -> 84.
    EXPECT_EQ(d.color(0, 0).r, 0);
    EXPECT_EQ(d.color(1, 1).r, 36);
    EXPECT_EQ(d.color(2, 2).r, 84);
    // A kept sample keeps its world position and height.
    EXPECT_FLOAT_EQ(d.sample_height(1, 2), t.sample_height(2, 4));
    EXPECT_FLOAT_EQ(d.width(), t.width());
}

TEST(TerrainDecimation, DropsTheSamplesBetweenTheLastKeptAndTheEdge) {
    Terrain t(6, 7, 1.0f);
    const Terrain d = decimate_terrain(t, 2);
    EXPECT_EQ(d.rows(), 3); // rows 0, 2, 4 of 0..5
    EXPECT_EQ(d.cols(), 4); // cols 0, 2, 4, 6
    EXPECT_FLOAT_EQ(d.depth(), 4.0f);
}

TEST(TerrainDecimation, RefusesAShorterSideThatWouldKeepOneSample) {
    EXPECT_EQ(decimation_problem(3, 1000, 2), "");
    EXPECT_NE(decimation_problem(3, 1000, 3), "");
    EXPECT_THROW(decimate_terrain(Terrain(3, 100, 1.0f), 3), Error);
}

TEST(TerrainDecimation, FactorOneIsACopy) {
    Terrain t(3, 3, 1.0f);
    t.raw(1, 1) = 7;
    const Terrain d = decimate_terrain(t, 1);
    EXPECT_EQ(d.heights(), t.heights());
    EXPECT_EQ(d.h_scale(), t.h_scale());
}
