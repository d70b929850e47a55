// `overflight tile`: overlapping tiles reassemble exactly to the padded
// source, existence flags, georeferencing on real DEMs, an interrupted
// tiling (and a killed tiler) that re-runs to the same result, tile-edge
// normals equal to the whole terrain's, the overview that stands in for
// a terrain larger than memory, and reduced levels that keep exact samples.
#include "TestSupport.h"

#include "core/DemoIsland.h"
#include "core/Error.h"
#include "io/LoadTerrain.h"
#include "io/RasterFile.h"
#include "io/TileDirectory.h"
#include "lod/TileSet.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <csignal>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <spawn.h>
#include <thread>

extern char** environ;

using namespace overflight;
namespace fs = std::filesystem;

namespace {

DataSet small_island() {
    DemoOptions o;
    o.size = 129;
    return make_demo_island(o);
}

// What `overflight tile` passes: Röttger's measures for the reduced levels.
TileWriteOptions tile_options(int tile_size) {
    TileWriteOptions o;
    o.tile_size = tile_size;
    o.measures = rottger_tile_measures();
    return o;
}

std::string bytes_of(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), {});
}

} // namespace

TEST(Tile, TilesReassembleToPaddedSource) {
    test::ScratchDir dir;
    const DataSet d = small_island();
    TileWriteOptions o = tile_options(33);
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
    TileWriteOptions o = tile_options(33);
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
    TileWriteOptions o = tile_options(33);
    write_tile_directory(d, ref_dir.path.string(), o);

    TileWriteOptions stop = o;
    stop.on_tile = [](int done, int) { return done < 6; };
    EXPECT_THROW(write_tile_directory(d, dir.path.string(), stop), Error);
    EXPECT_THROW(read_tile_index(dir.path.string()), Error); // incomplete: refused
    for (const auto& e : fs::directory_iterator(dir.path)) EXPECT_NE(e.path().filename().string()[0], '.');
    // A stale temporary file as a killed process would leave it.
    std::ofstream(dir.path / ".r3_c3.tif.tmp999-0") << "half";

    const TileWriteReport r = write_tile_directory(d, dir.path.string(), o);
    // Tiles are written on all cores: those in flight when it stopped finish.
    EXPECT_GE(r.skipped, 6);
    EXPECT_EQ(r.skipped + r.written, 16);
    int files = 0;
    for (const auto& e : fs::directory_iterator(ref_dir.path)) {
        ++files;
        EXPECT_EQ(bytes_of(e.path()), bytes_of(dir.path / e.path().filename())) << e.path().filename();
    }
    int files2 = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path)) ++files2;
    EXPECT_EQ(files, files2);
    EXPECT_EQ(files, 65); // 16 heights + 16 colors + 16 aprons + 16 d2 + index.json

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

namespace {

// The tiler stopped by signal `sig` in mid-run (not the cooperative stop
// above): no file under a final name is partial (each is byte-identical to
// the same file of an uninterrupted run), the directory is refused until
// finished, and a re-run skips the finished tiles and ends identical to the
// uninterrupted run. SIGINT and SIGTERM let the tiler finish its tile and
// exit with one line (no temporary file left); SIGKILL leaves temporaries
// that the re-run removes.
void stop_and_resume(int sig) {
    test::ScratchDir scratch;
    const std::string ref = scratch / "ref", dir = scratch / "killed";
    const std::string args = "tile demo --demo-size 257 --tile-size 9 -o "; // 32x32 tiles
    const auto done = test::run_overflight(args + "'" + ref + "'");
    ASSERT_EQ(done.exit_code, 0) << done.err;

    // Heights files (r{R}_c{C}.tif) under their final names: finished tiles.
    auto finished_tiles = [&] {
        int n = 0;
        std::error_code ec;
        for (const auto& e : fs::directory_iterator(dir, ec)) {
            const std::string name = e.path().filename().string();
            n += name[0] == 'r' && name.size() > 4 && name.compare(name.size() - 4, 4, ".tif") == 0 &&
                 name.find("_rgb") == std::string::npos && name.find("_apron") == std::string::npos &&
                 name.find("_d2") == std::string::npos;
        }
        return n;
    };
    std::vector<std::string> argv_s = {OVERFLIGHT_EXE, "tile", "demo", "--demo-size", "257", "--tile-size", "9", "-o", dir};
    std::vector<char*> argv;
    for (auto& a : argv_s) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t quiet;
    posix_spawn_file_actions_init(&quiet);
    posix_spawn_file_actions_addopen(&quiet, 1, "/dev/null", O_WRONLY, 0);
    const std::string err_path = scratch / "stderr";
    posix_spawn_file_actions_addopen(&quiet, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid = 0;
    ASSERT_EQ(posix_spawn(&pid, OVERFLIGHT_EXE, &quiet, nullptr, argv.data(), environ), 0);
    posix_spawn_file_actions_destroy(&quiet);
    // Kill it once a few dozen of the 1024 tiles are finished.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    int status = 0;
    bool exited = false;
    while (finished_tiles() < 40 && std::chrono::steady_clock::now() < deadline) {
        if (waitpid(pid, &status, WNOHANG) == pid) {
            exited = true;
            break;
        }
        std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
    ASSERT_FALSE(exited) << "the tiler ended before it could be stopped";
    kill(pid, sig);
    waitpid(pid, &status, 0);
    if (sig == SIGKILL) {
        ASSERT_TRUE(WIFSIGNALED(status));
    } else {
        ASSERT_TRUE(WIFEXITED(status));
        EXPECT_EQ(WEXITSTATUS(status), 1);
        EXPECT_EQ(bytes_of(err_path), "overflight: " + dir + ": interrupted\n");
        for (const auto& e : fs::directory_iterator(dir)) EXPECT_NE(e.path().filename().string()[0], '.') << e.path();
    }

    const int finished = finished_tiles();
    EXPECT_GE(finished, 40);
    EXPECT_LT(finished, 1024);
    EXPECT_THROW(read_tile_index(dir), Error); // incomplete: refused
    for (const auto& e : fs::directory_iterator(dir)) {
        const std::string name = e.path().filename().string();
        if (name[0] == '.' || name == "index.json") continue; // temporaries and the incomplete index
        EXPECT_EQ(bytes_of(e.path()), bytes_of(fs::path(ref) / name)) << name << " is partial";
    }

    const auto again = test::run_overflight(args + "'" + dir + "'");
    ASSERT_EQ(again.exit_code, 0) << again.err;
    EXPECT_NE(again.out.find(std::to_string(finished) + " already done"), std::string::npos) << again.out;
    int files = 0;
    for (const auto& e : fs::directory_iterator(dir)) {
        ++files;
        EXPECT_EQ(bytes_of(e.path()), bytes_of(fs::path(ref) / e.path().filename())) << e.path().filename();
    }
    EXPECT_EQ(files, 4 * 1024 + 1);
    EXPECT_EQ(read_tile_index(dir).checksum, read_tile_index(ref).checksum);
}

} // namespace

TEST(Tile, KilledTilerLeavesNoBrokenTileAndResumes) { stop_and_resume(SIGKILL); }

TEST(Tile, InterruptedTilerStopsCleanlyAndResumes) { stop_and_resume(SIGINT); }

// Normals read from a tile directory equal the whole terrain's at every
// sample, so the two tiles of a seam light it identically (the apron files).
TEST(Tile, TileEdgeNormalsMatchTheWholeTerrain) {
    test::ScratchDir dir;
    const DataSet d = small_island();
    TileWriteOptions o = tile_options(33);
    write_tile_directory(d, dir.path.string(), o);
    const TileIndex ix = read_tile_index(dir.path.string());
    EXPECT_TRUE(ix.apron);
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) {
            const TileSamples t = read_tile(dir.path.string(), ix, r, c);
            ASSERT_EQ(t.normals.size(), 33u * 33u);
            for (int i = 0; i < 33; ++i)
                for (int j = 0; j < 33; ++j)
                    ASSERT_EQ(t.normals[t.samples.index(i, j)], d.terrain.sample_normal(r * 32 + i, c * 32 + j))
                        << "tile " << r << "," << c << " sample " << i << "," << j;
        }
    // The shared column of tiles (1,1) and (1,2): the same normals from both.
    const TileSamples a = read_tile(dir.path.string(), ix, 1, 1), b = read_tile(dir.path.string(), ix, 1, 2);
    for (int i = 0; i < 33; ++i) EXPECT_EQ(a.normals[a.samples.index(i, 32)], b.normals[b.samples.index(i, 0)]);
    // A directory of an older tiler (no aprons) still loads; normals are then left to TileSet.
    TileIndex old = ix;
    old.apron = false;
    EXPECT_TRUE(read_tile(dir.path.string(), old, 1, 1).normals.empty());
}

// A 70 x 100 terrain (h_scale 5) standing in for a large one: every f-th
// sample, f the power of two that fits max_side, over the same extent (the
// last row/column clamped to the source's, darkened as padding), from the
// stored overview.tif, from it decimated further, or from the tiles.
TEST(Tile, OverviewStandsInForTheTerrain) {
    test::ScratchDir dir;
    DataSet d;
    d.terrain = Terrain(70, 100, 5.0f, 0.5f, -10.0f);
    for (int i = 0; i < 70; ++i)
        for (int j = 0; j < 100; ++j) {
            d.terrain.raw(i, j) = std::uint16_t(i * 100 + j);
            d.terrain.color(i, j) = Rgb8{std::uint8_t(2 * i), std::uint8_t(2 * j), 200};
        }
    EXPECT_EQ(overview_stride(70, 100, 30), 4);  // (100 - 2) / 4 + 2 = 26 <= 30 < (100 - 2) / 2 + 2
    EXPECT_EQ(overview_stride(70, 100, 100), 1);
    EXPECT_EQ(overview_stride(16385, 16385, 2049), 8);
    EXPECT_THROW(overview_stride(70, 100, 1), Error);
    TileWriteOptions o = tile_options(33);
    o.overview_max_side = 30;
    write_tile_directory(d, dir.path.string(), o);
    const TileIndex ix = read_tile_index(dir.path.string());
    EXPECT_EQ(ix.overview_stride, 4);
    EXPECT_EQ(ix.overview_rows, 19); // (70 - 2) / 4 + 2
    EXPECT_EQ(ix.overview_cols, 26);
    ASSERT_TRUE(fs::exists(dir.path / "overview.tif"));
    std::array<double, 6> gt{};
    std::string wkt;
    int rows = 0, cols = 0;
    ASSERT_TRUE(read_georeferencing(dir / "overview.tif", gt, wkt, rows, cols));
    EXPECT_EQ(rows, 19);
    EXPECT_DOUBLE_EQ(gt[1], 4 * ix.geotransform[1]);
    EXPECT_DOUBLE_EQ(gt[0], ix.geotransform[0]);

    auto check = [&](const DataSet& ov, int f) {
        SCOPED_TRACE("stride " + std::to_string(f));
        ASSERT_EQ(ov.terrain.rows(), (70 - 2) / f + 2);
        ASSERT_EQ(ov.terrain.cols(), (100 - 2) / f + 2);
        EXPECT_FLOAT_EQ(ov.terrain.h_scale(), 5.0f * float(f));
        EXPECT_GE(ov.terrain.width(), d.terrain.width());
        EXPECT_LT(ov.terrain.width(), d.terrain.width() + 5.0f * float(f));
        EXPECT_EQ(ov.terrain.v_scale(), 0.5f);
        EXPECT_EQ(ov.info.source_rows, 70);
        EXPECT_EQ(ov.info.source_cols, 100);
        for (int i = 0; i < ov.terrain.rows(); ++i)
            for (int j = 0; j < ov.terrain.cols(); ++j) {
                const int si = std::min(i * f, 69), sj = std::min(j * f, 99);
                ASSERT_EQ(ov.terrain.raw(i, j), d.terrain.raw(si, sj)) << i << "," << j;
                Rgb8 want = d.terrain.color(si, sj);
                if (si != i * f || sj != j * f) want = Rgb8{std::uint8_t(want.r / 2), std::uint8_t(want.g / 2), 100};
                ASSERT_EQ(ov.terrain.color(i, j), want) << i << "," << j;
            }
    };
    check(load_tile_directory_overview(dir.path.string(), 30), 4); // overview.tif as stored
    check(load_tile_directory_overview(dir.path.string(), 15), 8); // stored, decimated by 2
    check(load_tile_directory_overview(dir.path.string(), 60), 2); // finer than stored: from the tiles
    const DataSet full = load_tile_directory_overview(dir.path.string(), 100);
    EXPECT_EQ(full.terrain.heights(), d.terrain.heights());
    // A terrain that fits needs no overview files.
    test::ScratchDir small;
    write_tile_directory(d, small.path.string(), tile_options(33));
    EXPECT_FALSE(fs::exists(small.path / "overview.tif"));
    EXPECT_EQ(read_tile_index(small.path.string()).overview_stride, 0);
}

// A float DEM on its own square UTM grid (Olinda, 111 x 111 Float32, 90 m):
// each tile carries the source CRS, a geotransform on the source grid (tile
// (r, c) origin = source origin + (c (s-1) dx, r (s-1) dy)), and GDAL
// scale/offset so that a tile's scaled value is the source's elevation
// within half a v_scale step (its elevations are whole metres from -1 m: the
// mapping is raw * 1 - 1).
TEST(Tile, FloatDemTilesReadAsMetresOnTheSourceGrid) {
    OVERFLIGHT_SHARED_FILE(path, "paired/olinda/olinda_dem_utm25s.tif");
    std::array<double, 6> src_gt{};
    std::string src_wkt;
    int rows = 0, cols = 0;
    ASSERT_TRUE(read_georeferencing(path, src_gt, src_wkt, rows, cols));
    const Image2D<float> src = read_raster_band(path);
    const DataSet d = load_terrain(path);
    ASSERT_FALSE(d.info.reprojected);
    ASSERT_EQ(d.terrain.rows(), 111);
    test::ScratchDir dir;
    TileWriteOptions o = tile_options(33);
    write_tile_directory(d, dir.path.string(), o);
    const TileIndex ix = read_tile_index(dir.path.string());
    EXPECT_TRUE(ix.georeferenced);
    EXPECT_EQ(ix.geotransform, src_gt);
    const float step = ix.grid.v_scale;
    int checked = 0;
    for (const auto& [r, c] : {std::pair{0, 0}, std::pair{1, 2}, std::pair{3, 3}}) {
        const std::string tile = dir / ("r" + std::to_string(r) + "_c" + std::to_string(c) + ".tif");
        std::array<double, 6> gt{};
        std::string wkt;
        ASSERT_TRUE(read_georeferencing(tile, gt, wkt, rows, cols));
        EXPECT_EQ(wkt, src_wkt);
        EXPECT_NEAR(gt[0], src_gt[0] + c * 32 * src_gt[1], 1e-6);
        EXPECT_NEAR(gt[3], src_gt[3] + r * 32 * src_gt[5], 1e-6);
        EXPECT_EQ(gt[1], src_gt[1]);
        EXPECT_EQ(gt[5], src_gt[5]);
        const BandMapping m = read_band_mapping(tile);
        EXPECT_EQ(m.unit, "metre");
        EXPECT_EQ(m.scale, step);
        EXPECT_EQ(m.offset, ix.grid.y_offset);
        const Image2D<float> raw = read_raster_band(tile);
        for (int i = 0; i < 33 && r * 32 + i < 111; i += 4)
            for (int j = 0; j < 33 && c * 32 + j < 111; j += 4) {
                const double metres = raw.at(j, i) * m.scale + m.offset;
                EXPECT_NEAR(metres, src.at(c * 32 + j, r * 32 + i), 0.5 * step + 1e-6)
                    << "tile " << r << "," << c << " sample " << i << "," << j;
                ++checked;
            }
    }
    EXPECT_EQ(checked, 81 + 81 + 16);
}

// SRTM .hgt (WGS84 degrees) is reprojected to square UTM cells when loaded;
// its tiles carry that UTM grid and CRS, and read back as the loaded metres.
TEST(Tile, SrtmTilesCarryTheReprojectedGrid) {
    OVERFLIGHT_SHARED_FILE(path, "srtm/N57E011.hgt");
    const DataSet d = load_terrain(path);
    ASSERT_TRUE(d.info.reprojected);
    ASSERT_TRUE(d.info.georeferenced);
    test::ScratchDir dir;
    TileWriteOptions o = tile_options(513);
    write_tile_directory(d, dir.path.string(), o);
    const TileIndex ix = read_tile_index(dir.path.string());
    EXPECT_EQ(ix.geotransform, d.info.geotransform);
    EXPECT_NE(ix.crs_wkt.find("UTM zone 32N"), std::string::npos) << ix.crs_wkt.substr(0, 80);
    const double dx = d.info.geotransform[1], dy = d.info.geotransform[5];
    EXPECT_NEAR(dx, d.terrain.h_scale(), 1e-3);
    EXPECT_NEAR(dy, -dx, 1e-9); // square cells, north up
    int checked = 0;
    for (int r = 0; r < ix.grid.tile_rows; ++r)
        for (int c = 0; c < ix.grid.tile_cols; ++c) {
            if (!ix.grid.present(r, c)) continue;
            const std::string tile = dir / ("r" + std::to_string(r) + "_c" + std::to_string(c) + ".tif");
            std::array<double, 6> gt{};
            std::string wkt;
            int rows = 0, cols = 0;
            ASSERT_TRUE(read_georeferencing(tile, gt, wkt, rows, cols));
            EXPECT_EQ(wkt, ix.crs_wkt);
            EXPECT_NEAR(gt[0], d.info.geotransform[0] + c * 512 * dx, 1e-6);
            EXPECT_NEAR(gt[3], d.info.geotransform[3] + r * 512 * dy, 1e-6);
            const BandMapping m = read_band_mapping(tile);
            const Image2D<float> raw = read_raster_band(tile);
            for (int i = 0; i < 513 && r * 512 + i < d.terrain.rows(); i += 37)
                for (int j = 0; j < 513 && c * 512 + j < d.terrain.cols(); j += 37) {
                    EXPECT_NEAR(raw.at(j, i) * m.scale + m.offset, d.terrain.sample_height(r * 512 + i, c * 512 + j),
                                0.5 * d.terrain.v_scale() + 1e-3);
                    ++checked;
                }
        }
    EXPECT_GT(checked, 300);
}

// Each tile file holds levels of every 2^m-th sample, exactly the samples
// (not resampled), so that reduced neighbours share their edge samples, and
// the full tile's d2 at them; the index carries each tile's roughness. A directory of an older tiler
// (no levels) still renders, at full resolution.
TEST(Tile, ReducedLevelsKeepExactSamples) {
    test::ScratchDir dir;
    const DataSet d = small_island();
    TileWriteOptions o = tile_options(33);
    write_tile_directory(d, dir.path.string(), o);
    const TileIndex ix = read_tile_index(dir.path.string());
    ASSERT_EQ(ix.levels, 4); // 17, 9, 5, 3 samples
    EXPECT_EQ(ix.grid.max_level, 4);
    EXPECT_EQ(ix.grid.d2_min_resolution, 4.0);
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) {
            const TileSamples full = read_tile(dir.path.string(), ix, r, c);
            EXPECT_EQ(ix.grid.roughness[ix.grid.index(r, c)], rottger_roughness(full.samples));
            const std::vector<float> d2 = rottger_d2(full.samples, 4.0);
            for (int m = 1; m <= 4; ++m) {
                const TileSamples red = read_tile(dir.path.string(), ix, r, c, true, m);
                const int n = 32 / (1 << m) + 1;
                ASSERT_EQ(red.samples.rows(), n);
                EXPECT_EQ(red.samples.h_scale(), d.terrain.h_scale() * float(1 << m));
                EXPECT_TRUE(red.normals.empty());
                for (int i = 0; i < n; ++i)
                    for (int j = 0; j < n; ++j) {
                        ASSERT_EQ(red.samples.raw(i, j), full.samples.raw(i << m, j << m)) << r << "," << c << " level " << m;
                        ASSERT_EQ(red.samples.color(i, j), full.samples.color(i << m, j << m));
                        ASSERT_EQ(red.d2[red.samples.index(i, j)], d2[full.samples.index(i << m, j << m)]);
                    }
            }
        }
    EXPECT_THROW(read_tile(dir.path.string(), ix, 1, 1, true, 5), Error);

    // An older tiler's index: no levels, no roughness.
    const fs::path index = dir.path / "index.json";
    nlohmann::json j = nlohmann::json::parse(bytes_of(index));
    j.erase("levels");
    j.erase("roughness");
    j.erase("d2_min_resolution");
    std::ofstream(index) << j.dump();
    const TileIndex old = read_tile_index(dir.path.string());
    EXPECT_EQ(old.levels, 0);
    EXPECT_EQ(old.grid.max_level, 0);
    TileSet set(old.grid, tile_directory_loader(dir.path.string(), old), std::size_t(1) << 30);
    Camera cam;
    cam.eye = {-3000, 2000, -3000};
    cam.heading = 45;
    cam.pitch = -20;
    cam.far = 20000;
    MeshArrays m;
    const TileFrameStats s = set.build_mesh(cam, 1.0, m);
    EXPECT_GT(s.visible, 0);
    EXPECT_EQ(s.per_level[0], s.visible);
}
