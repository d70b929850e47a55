// The tiling model's limits (core/TileGrid.h): sizes computed in 64-bit, so
// that a declared tile size or grid from a file can neither hang nor wrap
// around; a terrain of 2x2 samples still makes a valid grid; validate()
// refuses grids terrain_tile_grid() would not make.
#include "core/Error.h"
#include "core/TileGrid.h"

#include <gtest/gtest.h>

#include <climits>

using namespace overflight;

namespace {

// A grid as an index would declare it, with consistent flags and ranges.
TileGrid declared(int tile_size, int tiles, int source) {
    TileGrid g;
    g.tile_size = tile_size;
    g.tile_rows = g.tile_cols = tiles;
    g.source_rows = g.source_cols = source;
    const std::size_t n = std::size_t(tiles) * std::size_t(tiles);
    g.exists.assign(n, 1);
    g.min_height.assign(n, 0.0f);
    g.max_height.assign(n, 0.0f);
    return g;
}

std::string problem(const TileGrid& g) {
    try {
        g.validate("index.json");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST(TileGrid, CoarsestLevelOfHugeStridesDoesNotOverflow) {
    TileGrid g;
    g.tile_size = 3;
    EXPECT_EQ(g.coarsest_level(), 0);
    g.tile_size = 257;
    EXPECT_EQ(g.coarsest_level(), 7);
    g.tile_size = (1 << 30) + 1; // shifting a 32-bit 1 by 31 and 32 hung here
    EXPECT_EQ(g.coarsest_level(), 29);
    g.tile_size = INT_MAX;
    EXPECT_EQ(g.coarsest_level(), 29);
    g.tile_size = 2;
    EXPECT_EQ(g.coarsest_level(), -1);
}

TEST(TileGrid, PaddedSizesAre64Bit) {
    TileGrid g;
    g.tile_size = 32769;
    g.tile_rows = g.tile_cols = 65536;
    EXPECT_EQ(g.padded_rows(), 65536LL * 32768 + 1);
    EXPECT_TRUE(is_pow2_plus1((1 << 30) + 1));
    EXPECT_FALSE(is_pow2_plus1(INT_MAX)); // doubled past INT_MAX before
}

TEST(TileGrid, DeclaredSizesOutsideTheLimits) {
    EXPECT_EQ(problem(declared((1 << 30) + 1, 1, (1 << 30) + 1)),
              "index.json: tile size 1073741825 is not 2^k+1 in 3 .. 32769");
    EXPECT_EQ(problem(declared(INT_MAX, 1, 3)), "index.json: tile size 2147483647 is not 2^k+1 in 3 .. 32769");
    TileGrid huge; // sizes are checked before the per-tile vectors
    huge.tile_size = 32769;
    huge.tile_rows = huge.tile_cols = 65536;
    huge.source_rows = huge.source_cols = 3;
    EXPECT_EQ(problem(huge),
              "index.json: tile grid 65536x65536 of 32769-sample tiles is empty or larger than 1048577 samples per side");
    EXPECT_EQ(problem(declared(129, 4, 129)),
              "index.json: tile grid 4x4 of 129-sample tiles does not cut the 129^2 square padding a source of 129x129 "
              "samples");
    EXPECT_EQ(problem(declared(129, 1, 129)), "");
}

TEST(TileGrid, FlagsAndRangesMustFollowTheSource) {
    TileGrid g = declared(33, 4, 100);
    g.source_rows = 70; // tile row 3 starts at 96: padding only
    EXPECT_EQ(problem(g), "index.json: tile r3_c0 is flagged 1 but lies wholly in the padding");
    for (int c = 0; c < 4; ++c) g.exists[g.index(3, c)] = 0;
    EXPECT_EQ(problem(g), "");
    g.exists[g.index(1, 2)] = 0;
    EXPECT_EQ(problem(g), "index.json: tile r1_c2 is flagged 0 but holds source samples");
    g.exists[g.index(1, 2)] = 1;
    g.min_height[g.index(0, 1)] = -1e30f;
    EXPECT_EQ(problem(g), "index.json: height range -1e+30 .. 0 of tile r0_c1 is not within the height mapping's 0 .. 65535");
    g.min_height[g.index(0, 1)] = 5.0f; // min > max
    EXPECT_EQ(problem(g), "index.json: height range 5 .. 0 of tile r0_c1 is not within the height mapping's 0 .. 65535");
}

// A 2x2 raster used to pad to 2x2, make tiles of stride 1 and level -1.
TEST(TileGrid, TwoByTwoTerrainMakesOneTile) {
    Terrain t(2, 2, 1.0f);
    t.raw(1, 1) = 7;
    const TileGrid g = terrain_tile_grid(t, 257);
    EXPECT_EQ(g.tile_size, 3);
    EXPECT_EQ(g.tile_rows, 1);
    EXPECT_EQ(g.coarsest_level(), 0);
    EXPECT_NO_THROW(g.validate("grid"));
    const TileSamples s = cut_tile(t, g, 0, 0, false);
    EXPECT_EQ(s.samples.raw(1, 1), 7);
    EXPECT_EQ(s.samples.raw(2, 2), 7); // padding repeats the edge
}
