// `overflight tile`: overlapping tiles reassemble exactly to the padded
// source, existence flags, georeferencing, and an interrupted tiling that
// re-runs to the same result.
#include "TestSupport.h"

#include "core/DemoIsland.h"
#include "core/Error.h"
#include "io/TileDirectory.h"
#include "lod/TileSet.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

using namespace overflight;
namespace fs = std::filesystem;

namespace {

DataSet small_island() {
    DemoOptions o;
    o.size = 129;
    return make_demo_island(o);
}

std::string bytes_of(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), {});
}

} // namespace

TEST(Tile, TilesReassembleToPaddedSource) {
    test::ScratchDir dir;
    const DataSet d = small_island();
    TileWriteOptions o;
    o.tile_size = 33;
    const TileWriteReport r = write_tile_directory(d, dir.path.string(), o);
    EXPECT_EQ(r.index.grid.tile_rows, 4);
    EXPECT_EQ(r.written, 16);
    const TileIndex ix = read_tile_index(dir.path.string());
    EXPECT_TRUE(ix.complete);
    EXPECT_EQ(ix.checksum, terrain_checksum(d.terrain));
    // Neighbours share their edge samples; every tile is the padded source window.
    const Terrain padded = pad_to_pow2_plus1(d.terrain);
    for (int tr = 0; tr < 4; ++tr)
        for (int tc = 0; tc < 4; ++tc) {
            const TileSamples t = read_tile(dir.path.string(), ix, tr, tc);
            for (int i = 0; i < 33; ++i)
                for (int j = 0; j < 33; ++j) {
                    ASSERT_EQ(t.samples.raw(i, j), padded.raw(tr * 32 + i, tc * 32 + j));
                    ASSERT_EQ(t.samples.color(i, j), padded.color(tr * 32 + i, tc * 32 + j));
                }
        }
    const DataSet back = load_tile_directory(dir.path.string());
    EXPECT_EQ(back.terrain.heights(), d.terrain.heights());
    EXPECT_EQ(back.terrain.colors(), d.terrain.colors());
    EXPECT_EQ(back.terrain.h_scale(), d.terrain.h_scale());
    EXPECT_EQ(back.info.kind, "tiles");
    EXPECT_TRUE(is_tile_directory(dir.path.string()));
    // Geotransform of tile (1, 2): the local frame shifted by (2*32, 1*32) pixels.
    std::array<double, 6> gt{};
    std::string wkt;
    int rows = 0, cols = 0;
    ASSERT_TRUE(read_georeferencing(dir / "r1_c2.tif", gt, wkt, rows, cols));
    const double hs = d.terrain.h_scale();
    EXPECT_DOUBLE_EQ(gt[0], -0.5 * hs + 64 * hs);
    EXPECT_DOUBLE_EQ(gt[3], 0.5 * hs - 32 * hs);
    EXPECT_DOUBLE_EQ(gt[1], hs);
    EXPECT_EQ(rows, 33);
}

// 70 x 100 samples pad to 129 x 129; with 33-sample tiles, tile row 3 starts
// at row 96 >= 70: no source data, flagged 0 and not written.
TEST(Tile, ExistenceFlagsOnEmptyTiles) {
    test::ScratchDir dir;
    DataSet d;
    d.terrain = Terrain(70, 100, 5.0f, 0.5f, -10.0f);
    for (int i = 0; i < 70; ++i)
        for (int j = 0; j < 100; ++j) d.terrain.raw(i, j) = std::uint16_t(i * 100 + j);
    TileWriteOptions o;
    o.tile_size = 33;
    const TileWriteReport r = write_tile_directory(d, dir.path.string(), o);
    EXPECT_EQ(r.written, 12);
    EXPECT_EQ(r.empty, 4);
    const TileIndex ix = read_tile_index(dir.path.string());
    for (int tc = 0; tc < 4; ++tc) {
        EXPECT_TRUE(ix.grid.present(2, tc));
        EXPECT_FALSE(ix.grid.present(3, tc));
        EXPECT_FALSE(fs::exists(dir / ("r3_c" + std::to_string(tc) + ".tif")));
        EXPECT_TRUE(fs::exists(dir / ("r2_c" + std::to_string(tc) + ".tif")));
    }
    EXPECT_FLOAT_EQ(ix.grid.v_scale, 0.5f);
    EXPECT_FLOAT_EQ(ix.grid.y_offset, -10.0f);
    // Height range of tile (0,0): raw 0 .. 32*100+32 -> world -10 .. 0.5*3232 - 10.
    EXPECT_FLOAT_EQ(ix.grid.min_height[0], -10.0f);
    EXPECT_FLOAT_EQ(ix.grid.max_height[0], 0.5f * 3232 - 10);
    EXPECT_THROW(read_tile(dir.path.string(), ix, 3, 0), Error);
    const DataSet back = load_tile_directory(dir.path.string());
    EXPECT_EQ(back.terrain.heights(), d.terrain.heights());
}

TEST(Tile, InterruptedRunResumesToTheSameResult) {
    test::ScratchDir scratch;
    struct {
        fs::path path;
    } ref_dir{scratch.path / "ref"}, dir{scratch.path / "resumed"};
    const DataSet d = small_island();
    TileWriteOptions o;
    o.tile_size = 33;
    write_tile_directory(d, ref_dir.path.string(), o);

    TileWriteOptions stop = o;
    stop.on_tile = [](int done, int) { return done < 6; };
    EXPECT_THROW(write_tile_directory(d, dir.path.string(), stop), Error);
    EXPECT_THROW(read_tile_index(dir.path.string()), Error); // incomplete: refused
    for (const auto& e : fs::directory_iterator(dir.path)) EXPECT_NE(e.path().filename().string()[0], '.');
    // A stale temporary file as a killed process would leave it.
    std::ofstream(dir.path / ".r3_c3.tif.tmp999-0") << "half";

    const TileWriteReport r = write_tile_directory(d, dir.path.string(), o);
    EXPECT_EQ(r.skipped, 6);
    EXPECT_EQ(r.written, 10);
    int files = 0;
    for (const auto& e : fs::directory_iterator(ref_dir.path)) {
        ++files;
        EXPECT_EQ(bytes_of(e.path()), bytes_of(dir.path / e.path().filename())) << e.path().filename();
    }
    int files2 = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path)) ++files2;
    EXPECT_EQ(files, files2);
    EXPECT_EQ(files, 33); // 16 heights + 16 colors + index.json

    // A different source does not resume: everything is rewritten.
    DataSet other = d;
    other.terrain.raw(5, 5) ^= 1;
    EXPECT_EQ(write_tile_directory(other, dir.path.string(), o).written, 16);
}

TEST(Tile, CommandLine) {
    test::ScratchDir dir;
    const auto ok = test::run_overflight("tile demo --demo-size 129 -o '" + (dir / "t") + "' --tile-size 65");
    ASSERT_EQ(ok.exit_code, 0) << ok.err;
    EXPECT_TRUE(fs::exists(dir.path / "t" / "index.json"));
    EXPECT_TRUE(fs::exists(dir.path / "t" / "r1_c1.tif"));
    const auto again = test::run_overflight("tile demo --demo-size 129 -o '" + (dir / "t") + "' --tile-size 65");
    EXPECT_NE(again.out.find("4 already done"), std::string::npos) << again.out;
    const auto bad = test::run_overflight("tile demo --demo-size 129 -o '" + (dir / "u") + "' --tile-size 64");
    EXPECT_EQ(bad.exit_code, 1);
    EXPECT_EQ(test::line_count(bad.err), 1);
    EXPECT_NE(bad.err.find("--tile-size"), std::string::npos) << bad.err;
}

TEST(Tile, RejectsBrokenIndex) {
    test::ScratchDir dir;
    std::ofstream(dir / "index.json") << "{\"format\": \"overflight-tiles\", \"version\": 1";
    EXPECT_THROW(read_tile_index(dir.path.string()), Error);
    std::ofstream(dir / "index.json") << "{\"format\": \"something\"}";
    EXPECT_THROW(read_tile_index(dir.path.string()), Error);
    EXPECT_THROW(read_tile_index((dir / "missing")), Error);
}

// A real DEM: Mount St. Helens (327 x 468 USGS DEM) keeps its UTM
// georeferencing; its padded 513^2 square leaves tile column 3 empty.
TEST(Tile, RealDemKeepsGeoreferencing) {
    OVERFLIGHT_SHARED_FILE(path, "usgs-dem/SainteHelens.dem");
    std::array<double, 6> gt{};
    std::string wkt;
    int rows = 0, cols = 0;
    ASSERT_TRUE(read_georeferencing(path, gt, wkt, rows, cols));
    test::ScratchDir dir;
    const auto r = test::run_overflight("tile '" + path + "' -o '" + (dir / "t") + "' --tile-size 129");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const TileIndex ix = read_tile_index(dir / "t");
    EXPECT_TRUE(ix.georeferenced);
    EXPECT_FALSE(ix.crs_wkt.empty());
    EXPECT_EQ(ix.geotransform, gt);
    std::array<double, 6> tgt{};
    std::string twkt;
    ASSERT_TRUE(read_georeferencing(dir / "t/r1_c1.tif", tgt, twkt, rows, cols));
    EXPECT_NEAR(tgt[0], gt[0] + 128 * gt[1], 1e-6);
    EXPECT_NEAR(tgt[3], gt[3] + 128 * gt[5], 1e-6);
}
