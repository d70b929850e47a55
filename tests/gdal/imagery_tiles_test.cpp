// Imagery tiles (core/TiledImagery.h, io/TileDirectory.h r{R}_c{C}_img.tif):
// `overflight tile DEM --color IMAGERY` on Olinda (a 28.5 m Landsat scene
// over a 90 m DEM) writes beside each height tile the imagery's texels over
// the same ground with their mip levels, read in windows; they equal the
// whole in-memory ImageryPyramid's texels (level 0 within 1 of 255, the
// window warp using GDAL's exact transformer where the whole warp uses its
// 1/8-pixel approximation; levels 1.. the same boxes of those texels); the
// in-memory tiler writes the pyramid's texels exactly; a run in 3 parts
// equals one run byte for byte; a directory without imagery has none.
#include "TestSupport.h"

#include "core/ImageryPyramid.h"
#include "core/Error.h"
#include "core/TiledImagery.h"
#include "io/LoadTerrain.h"
#include "io/TileDirectory.h"
#include "io/WindowedTiler.h"
#include "lod/TileSet.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

using namespace overflight;
namespace fs = std::filesystem;

namespace {

struct Agreement {
    long long texels = 0, exact = 0;
    int worst = 0;
};

// Tile texels against the whole pyramid's at the same global texel, on
// every level, where the whole pyramid's box is the tile's (not the folded
// last texel of an odd side) and the texel lies on the grid.
void compare(const TileImagery& t, const ImageryPyramid& whole, const ImageryTileLayout& l, std::vector<Agreement>& by_level) {
    for (int m = 0; m <= l.levels; ++m) {
        const Image2D<Rgba8>& a = t.levels[std::size_t(m)];
        const Image2D<Rgba8>& b = whole.level(m);
        for (int i = 0; i < a.height; ++i)
            for (int j = 0; j < a.width; ++j) {
                const int gu = (t.u0 >> m) + j, gv = (t.v0 >> m) + i;
                if (gu < 0 || gv < 0 || gu >= b.width - 1 || gv >= b.height - 1) continue;
                if (((gu + 1) << m) > l.width || ((gv + 1) << m) > l.height) continue;
                const Rgba8 p = a.at(j, i), q = b.at(gu, gv);
                const int d = std::max({std::abs(p.r - q.r), std::abs(p.g - q.g), std::abs(p.b - q.b)});
                Agreement& g = by_level[std::size_t(m)];
                ++g.texels;
                g.exact += d == 0;
                g.worst = std::max(g.worst, d);
            }
    }
}

} // namespace

TEST(ImageryTiles, OlindaTilesHoldTheWholePyramidsTexels) {
    OVERFLIGHT_SHARED_FILE(dem, "paired/olinda/olinda_dem_utm25s.tif");
    OVERFLIGHT_SHARED_FILE(landsat, "paired/olinda/L7_ETMs.tif");
    test::ScratchDir scratch;
    LoadOptions lo;
    lo.color_path = landsat;
    const DataSet whole = load_terrain(dem, lo);
    ASSERT_NE(whole.terrain.imagery(), nullptr);
    const ImageryPyramid& p = *whole.terrain.imagery();

    ASSERT_TRUE(windowed_imagery_applies(dem, landsat));
    WindowedTileOptions w;
    w.tile.tile_size = 33;
    w.tile.measures = rottger_tile_measures();
    w.color_path = landsat;
    const std::string dir = scratch / "windowed";
    tile_raster_in_windows(dem, dir, w);
    const TileIndex ix = read_tile_index(dir);
    ASSERT_TRUE(ix.imagery.present());
    EXPECT_EQ(ix.imagery.width, p.level(0).width);
    EXPECT_EQ(ix.imagery.height, p.level(0).height);
    EXPECT_NEAR(std::max(ix.imagery.texel_x(), ix.imagery.texel_z()), 28.5, 0.5);
    EXPECT_EQ(ix.imagery.levels, 2); // 28.5 m x 4 = 114 m >= the 90 m cells
    EXPECT_EQ(ix.imagery.cols % 4, 0);

    std::vector<Agreement> windowed(std::size_t(ix.imagery.levels + 1)), in_memory(windowed.size());
    // The same DEM and imagery tiled from memory: the pyramid's texels.
    TileWriteOptions o;
    o.tile_size = 33;
    o.measures = rottger_tile_measures();
    const std::string mem_dir = scratch / "memory";
    write_tile_directory(whole, mem_dir, o);
    const TileIndex mix = read_tile_index(mem_dir);
    ASSERT_TRUE(mix.imagery.present());
    EXPECT_EQ(mix.imagery.cols, ix.imagery.cols);
    long long sample_colors = 0, sample_exact = 0;
    int sample_worst = 0, edge_worst = 0;
    for (int r = 0; r < ix.grid.tile_rows; ++r)
        for (int c = 0; c < ix.grid.tile_cols; ++c) {
            if (!ix.grid.present(r, c)) continue;
            const TileImagery t = read_tile_imagery(dir, ix, r, c);
            ASSERT_EQ(int(t.levels.size()), ix.imagery.levels + 1);
            ASSERT_EQ(t.levels[0].width, ix.imagery.cols);
            // The tile covers its samples' cells: every sample of it lies inside.
            const double size = ix.grid.tile_world_size();
            EXPECT_LE(ix.imagery.x_of(t.u0), c * size - 0.5 * ix.grid.h_scale);
            EXPECT_GE(ix.imagery.x_of(t.u0 + ix.imagery.cols), (c + 1) * size + 0.5 * ix.grid.h_scale);
            compare(t, p, ix.imagery, windowed);
            compare(read_tile_imagery(mem_dir, mix, r, c), p, mix.imagery, in_memory);
            // The samples' colors: the imagery's, as load_terrain gives them.
            const TileSamples s = read_tile(dir, ix, r, c, false);
            for (int i = 0; i < s.samples.rows(); ++i)
                for (int j = 0; j < s.samples.cols(); ++j) {
                    const int gi = r * ix.grid.stride() + i, gj = c * ix.grid.stride() + j;
                    if (gi >= whole.terrain.rows() || gj >= whole.terrain.cols()) continue;
                    const Rgb8 a = s.samples.color(i, j), b = whole.terrain.color(gi, gj);
                    const int d = std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
                    // The last samples read the whole pyramid's folded last texels (an odd side).
                    if (gi >= whole.terrain.rows() - 2 || gj >= whole.terrain.cols() - 2) {
                        edge_worst = std::max(edge_worst, d);
                        continue;
                    }
                    ++sample_colors;
                    sample_exact += d == 0;
                    sample_worst = std::max(sample_worst, d);
                }
        }
    for (int m = 0; m <= ix.imagery.levels; ++m) {
        const Agreement& a = windowed[std::size_t(m)];
        const Agreement& b = in_memory[std::size_t(m)];
        std::printf("  level %d: windowed %lld texels, %.2f %% exact, worst %d; from memory %lld, %.2f %% exact, worst %d\n",
                    m, a.texels, 100.0 * a.exact / std::max(1LL, a.texels), a.worst, b.texels,
                    100.0 * b.exact / std::max(1LL, b.texels), b.worst);
        EXPECT_GT(a.texels, 0);
        EXPECT_LE(a.worst, 1) << "level " << m;
        EXPECT_GE(a.exact, a.texels * 99 / 100) << "level " << m;
        EXPECT_EQ(b.worst, 0) << "level " << m;
    }
    std::printf("  sample colors: %lld, %.2f %% exact, worst %d (last two rows and columns: worst %d)\n", sample_colors,
                100.0 * sample_exact / std::max(1LL, sample_colors), sample_worst, edge_worst);
    EXPECT_LE(sample_worst, 1);
}

TEST(ImageryTiles, PartsAndMergeEqualOneRunByteForByte) {
    OVERFLIGHT_SHARED_FILE(dem, "paired/olinda/olinda_dem_utm25s.tif");
    OVERFLIGHT_SHARED_FILE(landsat, "paired/olinda/L7_ETMs.tif");
    test::ScratchDir scratch;
    const std::string one = scratch / "one", parts = scratch / "parts";
    const auto r = test::run_overflight("tile '" + dem + "' --color '" + landsat + "' -o '" + one + "' --tile-size 33");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("imagery"), std::string::npos) << r.out;
    for (const char* k : {"3", "1", "2"}) {
        const auto p = test::run_overflight("tile '" + dem + "' --color '" + landsat + "' -o '" + parts +
                                            "' --tile-size 33 --part " + k + "/3");
        ASSERT_EQ(p.exit_code, 0) << p.err;
    }
    ASSERT_EQ(test::run_overflight("tile --merge '" + parts + "'").exit_code, 0);
    int images = 0, files = 0;
    for (const auto& e : fs::directory_iterator(one)) {
        const std::string name = e.path().filename().string();
        ++files;
        images += name.find("_img.tif") != std::string::npos;
        EXPECT_EQ(test::read_file_text(parts + "/" + name), test::read_file_text(e.path().string())) << name;
    }
    for (const auto& e : fs::directory_iterator(parts)) {
        const std::string name = e.path().filename().string();
        EXPECT_TRUE(fs::exists(fs::path(one) / name) || name.rfind(".part-", 0) == 0) << name;
    }
    EXPECT_EQ(images, 16); // 4 x 4 tiles of 33 samples over 111 x 111
    EXPECT_GT(files, 5 * images);
    EXPECT_NE(test::read_file_text(one + "/index.json").find("\"imagery\": {"), std::string::npos);
}

TEST(ImageryTiles, ADirectoryWithoutImageryHasNoImageryTiles) {
    OVERFLIGHT_SHARED_FILE(dem, "paired/olinda/olinda_dem_utm25s.tif");
    test::ScratchDir scratch;
    const std::string dir = scratch / "plain";
    ASSERT_EQ(test::run_overflight("tile '" + dem + "' -o '" + dir + "' --tile-size 33").exit_code, 0);
    const TileIndex ix = read_tile_index(dir);
    EXPECT_FALSE(ix.imagery.present());
    EXPECT_FALSE(fs::exists(dir + "/r0_c0_img.tif"));
    EXPECT_NE(test::read_file_text(dir + "/index.json").find("\"imagery\": null"), std::string::npos);
    EXPECT_THROW(read_tile_imagery(dir, ix, 0, 0), Error);
}
