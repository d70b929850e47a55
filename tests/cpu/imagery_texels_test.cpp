// The ray casters' tiled copy of the imagery (ImageryTexels.h) holds the
// pyramid's texels: every texel of every level read through the tiled layout
// is the row-major one, and the layout's index worked by hand.
#include "core/ImageryPyramid.h"
#include "raycast/ImageryTexels.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

using namespace overflight;

// Pages of 32 x 32 texels, lines of 4 x 4 within a page, texels row-major in a line.
TEST(ImageryTexels, TiledIndexWorkedByHand) {
    // Page 0; line (row 1, column 1) of the page is line 9 (16 texels each);
    // texel (row 2, column 1) of the line is its 9th: 144 + 9.
    EXPECT_EQ(ImageryTexels::tiled_index(5, 6, 3), 153u);
    // Page (row 1, column 1) of 3 per row is page 4 (1024 texels each); in it
    // texel (column 1, row 8): line 16 (row 2, column 0) at 256, texel 1 of it.
    EXPECT_EQ(ImageryTexels::tiled_index(33, 40, 3), 4096u + 256u + 1u);
    EXPECT_EQ(ImageryTexels::tiled_index(31, 31, 1), 1023u);
}

// A 70 x 37 image (pages cut at neither side, odd levels down to 1 x 1).
TEST(ImageryTexels, TiledLevelsHoldTheRowMajorTexels) {
    std::mt19937 rng(11);
    std::uniform_int_distribution<int> byte(0, 255);
    Image2D<Rgba8> img(70, 37);
    for (Rgba8& t : img.pixels)
        t = Rgba8{std::uint8_t(byte(rng)), std::uint8_t(byte(rng)), std::uint8_t(byte(rng)), std::uint8_t(byte(rng))};
    const ImageryPyramid pyramid(std::move(img), -3.0, 2.0, 140.0, 74.0);
    ImageryTexels texels;
    texels.bind(&pyramid);
    ASSERT_EQ(pyramid.levels(), 7);
    for (int l = 0; l < pyramid.levels(); ++l) {
        const Image2D<Rgba8>& level = pyramid.level(l);
        for (int row = 0; row < level.height; ++row)
            for (int col = 0; col < level.width; ++col) {
                // The texel's centre, in world units.
                const double x = pyramid.x0() + (col + 0.5) * pyramid.texel_x(l);
                const double z = pyramid.z0() + (row + 0.5) * pyramid.texel_z(l);
                ASSERT_EQ(texels.at(float(x), float(z), l), level.at(col, row))
                    << "level " << l << " column " << col << " row " << row;
            }
        // Outside the imagery: the edge texels.
        EXPECT_EQ(texels.at(-100.0f, -100.0f, l), level.at(0, 0));
        EXPECT_EQ(texels.at(1000.0f, 1000.0f, l), level.at(level.width - 1, level.height - 1));
    }
}

// Every row's level starts give level(k, j) for every slice: rows down,
// level, up and grazing, in an order that moves the boundaries both ways
// from one row to the next, and slices far enough for the last level.
TEST(ImageryTexels, LevelStartsCountTheLevelOfEverySlice) {
    Image2D<Rgba8> img(200, 120);
    const ImageryPyramid pyramid(std::move(img), 0.0, 0.0, 200.0, 120.0);
    ImageryTexels texels;
    texels.bind(&pyramid);
    ASSERT_TRUE(texels.lane_tables());
    ASSERT_EQ(texels.last_level(), 7);
    const int slices = 3000, rows = 120;
    std::vector<float> slice_d(slices), row_m(rows);
    for (int k = 0; k < slices; ++k) slice_d[std::size_t(k)] = 0.25f + 0.5f * float(k);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> slope(-1.5f, 0.3f);
    for (int j = 0; j < rows; ++j)
        row_m[std::size_t(j)] = j < 40 ? -1.2f + 0.03f * float(j) : j < 45 ? -1e-5f : slope(rng);
    auto check = [&] {
        for (int j = 0; j < rows; ++j) {
            const ImageryTexels::LevelStarts& starts = texels.level_starts(j);
            EXPECT_EQ(starts.k[0], 0);
            for (int k = 0; k < slices; ++k) {
                int level = 0;
                for (int l = 1; l < ImageryTexels::LevelLanes::kLevels; ++l) level += starts.k[l] <= k;
                ASSERT_EQ(level, texels.level(k, j)) << "row " << j << " slice " << k;
            }
        }
    };
    texels.prepare_slices(slice_d.data(), slices, 30.0);
    texels.prepare_rows(row_m.data(), rows);
    check();
    // The same rows again keep their starts; other rows or slices get new ones.
    texels.prepare_rows(row_m.data(), rows);
    check();
    std::reverse(row_m.begin(), row_m.end());
    texels.prepare_rows(row_m.data(), rows);
    check();
    texels.prepare_slices(slice_d.data(), slices, 3.0);
    texels.prepare_rows(row_m.data(), rows);
    check();
}
