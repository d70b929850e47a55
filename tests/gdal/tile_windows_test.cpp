// `overflight tile` on a raster file reads it in windows (io/WindowedTiler.h):
// the same tiles as tiling the loaded terrain, byte for byte, on a
// projected DEM with voids, on warped ones (geographic, non-square cells)
// and on a real DEM; N = 3 parts run by GNU parallel (the README's
// example) equal to one run; a sparse mosaic equal to its samples written
// whole; a VRT 100000 samples wide tiled whole and a part of a 100000^2 one
// within a memory bound under RLIMIT_AS; one-line errors beyond the limits.
#include "RestrictedRun.h"
#include "TestCameras.h"
#include "TestSupport.h"

#include "core/Error.h"
#include "io/LoadTerrain.h"
#include "io/TileDirectory.h"
#include "core/MeshArrays.h"
#include "lod/TileSet.h"

#include <gdal.h>
#include <gtest/gtest.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

using namespace overflight;
namespace fs = std::filesystem;

namespace {

// A cols x rows Int16 GeoTIFF of smooth hills on 30 m cells of UTM 10N (or,
// geographic, on 0.0003 degree cells), each cell `aspect` times as tall as it
// is wide, no-data -32768 in `holes` squares of 9x9 samples.
void write_dem(const std::string& path, int rows, int cols, bool geographic, int holes, double aspect = 1.0) {
    GDALAllRegister();
    const char* options[] = {"COMPRESS=DEFLATE", nullptr};
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), cols, rows, 1, GDT_Int16,
                                 const_cast<char**>(options));
    ASSERT_NE(ds, nullptr);
    OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
    OSRImportFromEPSG(srs, geographic ? 4326 : 32610);
    GDALSetSpatialRef(ds, srs);
    OSRDestroySpatialReference(srs);
    double gt[6] = {500000, 30, 0, 5200000, 0, -30};
    if (geographic) {
        const double g[6] = {-121.9, 0.0003, 0, 46.9, 0, -0.0003};
        std::copy(g, g + 6, gt);
    }
    gt[5] *= aspect;
    GDALSetGeoTransform(ds, gt);
    GDALRasterBandH band = GDALGetRasterBand(ds, 1);
    GDALSetRasterNoDataValue(band, -32768);
    std::vector<std::int16_t> z(std::size_t(rows) * std::size_t(cols));
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < cols; ++j)
            z[std::size_t(i) * std::size_t(cols) + std::size_t(j)] =
                std::int16_t(800 + 300 * std::sin(i * 0.05) * std::cos(j * 0.037) + 2 * ((i * 7 + j * 13) % 11));
    for (int h = 0; h < holes; ++h) {
        const int ci = (h * 53 + 11) % rows, cj = (h * 97 + 5) % cols;
        for (int i = std::max(0, ci - 4); i <= std::min(rows - 1, ci + 4); ++i)
            for (int j = std::max(0, cj - 4); j <= std::min(cols - 1, cj + 4); ++j)
                z[std::size_t(i) * std::size_t(cols) + std::size_t(j)] = -32768;
    }
    ASSERT_EQ(GDALRasterIO(band, GF_Write, 0, 0, cols, rows, z.data(), cols, rows, GDT_Int16, 0, 0), CE_None);
    GDALClose(ds);
}

// Tiles `path` from the loaded terrain, as `tile` did before it read windows.
void tile_in_memory(const std::string& path, const std::string& dir, int tile_size) {
    TileWriteOptions o;
    o.tile_size = tile_size;
    o.measures = rottger_tile_measures();
    write_tile_directory(load_terrain(path), dir, o);
}

// index.json without its checksum line (the windowed tiler's checksum is of
// the source, the in-memory one of the loaded terrain).
std::string index_without_checksum(const std::string& dir) {
    std::string text = test::read_file_text(dir + "/index.json");
    const std::size_t at = text.find("\"checksum\"");
    return at == std::string::npos ? text : text.erase(at, text.find('\n', at) - at);
}

// Every file of `ref` is in `dir` with the same bytes (index.json: but its
// checksum when `checksums` is false); `dir` holds nothing else but hidden
// part records.
void expect_same_files(const std::string& dir, const std::string& ref, bool checksums) {
    int files = 0;
    for (const auto& e : fs::directory_iterator(ref)) {
        const std::string name = e.path().filename().string();
        ++files;
        if (name == "index.json" && !checksums)
            EXPECT_EQ(index_without_checksum(dir), index_without_checksum(ref));
        else
            EXPECT_EQ(test::read_file_text(dir + "/" + name), test::read_file_text(e.path().string())) << name;
    }
    EXPECT_GT(files, 4);
    for (const auto& e : fs::directory_iterator(dir)) {
        const std::string name = e.path().filename().string();
        EXPECT_TRUE(fs::exists(fs::path(ref) / name) || name.rfind(".part-", 0) == 0) << name;
    }
}

} // namespace

TEST(TileWindows, ProjectedDemWithVoidsGivesTheSameTiles) {
    test::ScratchDir scratch;
    const std::string dem = scratch / "dem.tif";
    write_dem(dem, 300, 200, false, 12);
    for (const int size : {33, 129}) {
        const std::string ref = scratch / ("ref" + std::to_string(size)), dir = scratch / ("win" + std::to_string(size));
        tile_in_memory(dem, ref, size);
        const auto r = test::run_overflight("tile '" + dem + "' -o '" + dir + "' --tile-size " + std::to_string(size));
        ASSERT_EQ(r.exit_code, 0) << r.err;
        expect_same_files(dir, ref, false);
    }
}

// A re-run keeps the finished tiles and rewrites a broken one, ending
// byte-identical; a stop while tiling leaves an index readers refuse.
TEST(TileWindows, ReRunResumes) {
    test::ScratchDir scratch;
    const std::string dem = scratch / "dem.tif", ref = scratch / "ref", dir = scratch / "t";
    write_dem(dem, 200, 150, false, 4);
    const std::string args = "tile '" + dem + "' --tile-size 65 -o ";
    ASSERT_EQ(test::run_overflight(args + "'" + ref + "'").exit_code, 0);
    fs::copy(ref, dir);
    std::ofstream(dir + "/r1_c1.tif", std::ios::trunc) << "garbage";
    const auto again = test::run_overflight(args + "'" + dir + "'");
    ASSERT_EQ(again.exit_code, 0) << again.err;
    EXPECT_NE(again.out.find("1 written, 11 already done, 4 without data"), std::string::npos) << again.out;
    expect_same_files(dir, ref, true);
}

TEST(TileWindows, RealDemGivesTheSameTiles) {
    OVERFLIGHT_SHARED_FILE(path, "usgs-dem/SainteHelens.dem");
    test::ScratchDir scratch;
    tile_in_memory(path, scratch / "ref", 65);
    const auto r = test::run_overflight("tile '" + path + "' -o '" + (scratch / "win") + "' --tile-size 65");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    expect_same_files(scratch / "win", scratch / "ref", false);
}

// Warped per window rather than whole (io/MetricWarp.h), with the source's
// range as the height mapping: the same tiles as the loaded terrain's, for a
// geographic raster and for one on non-square cells.
TEST(TileWindows, WarpedDemsGiveTheSameTiles) {
    test::ScratchDir scratch;
    for (const bool geographic : {true, false}) {
        const std::string dem = scratch / (geographic ? "geo.tif" : "oblong.tif");
        const std::string ref = scratch / (geographic ? "geo_ref" : "oblong_ref");
        const std::string dir = scratch / (geographic ? "geo_win" : "oblong_win");
        write_dem(dem, 240, 260, geographic, 3, geographic ? 1.0 : 0.6);
        tile_in_memory(dem, ref, 65);
        const auto r = test::run_overflight("tile '" + dem + "' -o '" + dir + "' --tile-size 65");
        ASSERT_EQ(r.exit_code, 0) << r.err;
        expect_same_files(dir, ref, false);
    }
}

// A band scale and offset and a vertical unit in feet (GDAL's GetScale,
// GetOffset, GetUnitType) are applied before any warp, as the loader applies
// them: the tiles are the loaded terrain's, byte for byte, on the source's
// own grid and warped (geographic, non-square cells), and read back as the
// quadtree reads them every sample is the loaded terrain's, in metres.
TEST(TileWindows, ScaledFootDemsGiveTheLoadersHeights) {
    test::ScratchDir scratch;
    const double scale = 0.25, offset = -12.5, foot = 0.3048;
    for (const char* kind : {"projected", "geographic", "oblong"}) {
        const std::string name = kind;
        const std::string dem = scratch / (name + ".tif"), ref = scratch / (name + "_ref"), dir = scratch / (name + "_win");
        write_dem(dem, 150, 170, name == "geographic", 3, name == "oblong" ? 0.6 : 1.0);
        GDALDatasetH ds = GDALOpen(dem.c_str(), GA_Update);
        ASSERT_NE(ds, nullptr);
        GDALRasterBandH band = GDALGetRasterBand(ds, 1);
        GDALSetRasterScale(band, scale);
        GDALSetRasterOffset(band, offset);
        GDALSetRasterUnitType(band, "ft");
        GDALClose(ds);

        tile_in_memory(dem, ref, 65);
        const auto r = test::run_overflight("tile '" + dem + "' -o '" + dir + "' --tile-size 65");
        ASSERT_EQ(r.exit_code, 0) << r.err;
        expect_same_files(dir, ref, false);

        const DataSet loaded = load_terrain(dem);
        const Terrain& t = loaded.terrain;
        if (name == "projected") {
            // Row 0, column 0 is no void: 800 + 2 * 0 raw, in feet, scaled.
            EXPECT_NEAR(t.sample_height(0, 0), (800 * scale + offset) * foot, t.v_scale() / 2);
        }
        const TileIndex ix = read_tile_index(dir);
        const TileGrid& g = ix.grid;
        EXPECT_EQ(g.v_scale, t.v_scale()) << kind;
        EXPECT_EQ(g.y_offset, t.y_offset()) << kind;
        ASSERT_EQ(g.source_rows, t.rows());
        ASSERT_EQ(g.source_cols, t.cols());
        long long compared = 0, differing = 0;
        for (int tr = 0; tr < g.tile_rows; ++tr)
            for (int tc = 0; tc < g.tile_cols; ++tc) {
                if (!g.present(tr, tc)) continue;
                const TileSamples tile = read_tile(dir, ix, tr, tc, false, 0);
                const int S = g.stride();
                for (int i = 0; i < g.tile_size && tr * S + i < t.rows(); ++i)
                    for (int j = 0; j < g.tile_size && tc * S + j < t.cols(); ++j) {
                        ++compared;
                        differing += tile.samples.raw(i, j) != t.raw(tr * S + i, tc * S + j);
                    }
            }
        EXPECT_GE(compared, (long long)(t.rows()) * t.cols()) << kind; // shared edges counted twice
        EXPECT_EQ(differing, 0) << kind;
    }
}

// The README's example: GNU parallel runs three parts; the directory equals
// one run's, byte for byte, and `--merge` finds nothing left to do.
TEST(TileWindows, ThreePartsUnderGnuParallelEqualOneRun) {
    if (std::system("command -v parallel >/dev/null 2>&1") != 0) GTEST_SKIP() << "GNU parallel is not installed";
    test::ScratchDir scratch;
    const std::string dem = scratch / "dem.tif", one = scratch / "one", parts = scratch / "parts";
    write_dem(dem, 700, 900, false, 30);
    const auto r = test::run_overflight("tile '" + dem + "' -o '" + one + "' --tile-size 65");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string cmd = "parallel --halt now,fail=1 '" + std::string(OVERFLIGHT_EXE) + "' tile '" + dem + "' -o '" +
                            parts + "' --tile-size 65 --part {}/3 ::: 1 2 3 >/dev/null";
    ASSERT_EQ(std::system(cmd.c_str()), 0);
    expect_same_files(parts, one, true);
    const auto merged = test::run_overflight("tile --merge '" + parts + "'");
    ASSERT_EQ(merged.exit_code, 0) << merged.err;
    expect_same_files(parts, one, true);

    // A part missing: no index readers accept, and --merge names it.
    const std::string two = scratch / "two";
    for (const char* k : {"1", "3"})
        ASSERT_EQ(test::run_overflight("tile '" + dem + "' -o '" + two + "' --tile-size 65 --part " + k + "/3").exit_code, 0);
    EXPECT_THROW(read_tile_index(two), Error);
    const auto missing = test::run_overflight("tile --merge '" + two + "'");
    EXPECT_EQ(missing.exit_code, 1);
    EXPECT_EQ(missing.err, "overflight: " + two + ": 1 of 3 parts not finished (2); run them with --part K/3\n");
    ASSERT_EQ(test::run_overflight("tile '" + dem + "' -o '" + two + "' --tile-size 65 --part 2/3").exit_code, 0);
    expect_same_files(two, one, true);
}

namespace {

// Writes `block`, a 256^2 Int16 GeoTIFF of hills (100 + i + j m).
void write_hills_block(const std::string& block) {
    GDALAllRegister();
    const char* options[] = {"COMPRESS=DEFLATE", nullptr};
    GDALDatasetH ds =
        GDALCreate(GDALGetDriverByName("GTiff"), block.c_str(), 256, 256, 1, GDT_Int16, const_cast<char**>(options));
    ASSERT_NE(ds, nullptr);
    std::vector<std::int16_t> z(256 * 256);
    for (int i = 0; i < 256; ++i)
        for (int j = 0; j < 256; ++j) z[std::size_t(i) * 256 + std::size_t(j)] = std::int16_t(100 + i + j);
    ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, 256, 256, z.data(), 256, 256, GDT_Int16, 0, 0),
              CE_None);
    GDALClose(ds);
}

// A VRT source placing all of `block` (256^2) over `cols` x `rows` samples
// from (`row`, `col`).
std::string block_source(const std::string& block, int row, int col, int rows, int cols) {
    return "<SimpleSource><SourceFilename relativeToVRT=\"0\">" + block +
           "</SourceFilename><SourceBand>1</SourceBand><SrcRect xOff=\"0\" yOff=\"0\" xSize=\"256\" "
           "ySize=\"256\"/><DstRect xOff=\"" + std::to_string(col) + "\" yOff=\"" + std::to_string(row) +
           "\" xSize=\"" + std::to_string(cols) + "\" ySize=\"" + std::to_string(rows) + "\"/></SimpleSource>";
}

// Writes `vrt`, a virtual raster 100000 columns wide (beyond the 65537 a
// terrain may have per side) and `rows` tall, no-data -32768, from the
// hills of write_hills_block (`vrt` + ".block.tif") stretched over columns
// 0..98999 and 99100..99999 (columns 99000..99099 a void, filled when
// tiled), and on top of that placed sample for sample at rows 0..255,
// columns 512..767.
void write_block_vrt(const std::string& vrt, int rows) {
    const std::string block = vrt + ".block.tif";
    ASSERT_NO_FATAL_FAILURE(write_hills_block(block));
    const auto source = [&](int col, int row, int cols, int rows_) { return block_source(block, row, col, rows_, cols); };
    std::ofstream(vrt) << "<VRTDataset rasterXSize=\"100000\" rasterYSize=\"" << rows
                       << "\"><VRTRasterBand dataType=\"Int16\" band=\"1\"><NoDataValue>-32768</NoDataValue>"
                       << source(0, 0, 99000, rows) << source(99100, 0, 900, rows) << source(512, 0, 256, 256)
                       << "</VRTRasterBand></VRTDataset>\n";
}

// Writes `vrt`, a sparse mosaic: a virtual raster of `rows` x `cols`,
// no-data -32768, holding only the hills of write_hills_block (`vrt` +
// ".block.tif") sample for sample at (`row`, `col`); the rest has no source
// (GDALGetDataCoverageStatus: empty).
void write_sparse_vrt(const std::string& vrt, int rows, int cols, int row, int col) {
    const std::string block = vrt + ".block.tif";
    ASSERT_NO_FATAL_FAILURE(write_hills_block(block));
    std::ofstream(vrt) << "<VRTDataset rasterXSize=\"" << cols << "\" rasterYSize=\"" << rows
                       << "\"><VRTRasterBand dataType=\"Int16\" band=\"1\"><NoDataValue>-32768</NoDataValue>"
                       << block_source(block, row, col, 256, 256) << "</VRTRasterBand></VRTDataset>\n";
}

// Whether GDAL reports no data in rows `row`.. `row + rows` - 1 and the
// columns likewise of `path`.
bool reported_empty(const std::string& path, int row, int col, int rows, int cols) {
    GDALDatasetH ds = GDALOpen(path.c_str(), GA_ReadOnly);
    if (!ds) return false;
    const int status = GDALGetDataCoverageStatus(GDALGetRasterBand(ds, 1), col, row, cols, rows, 0, nullptr);
    GDALClose(ds);
    return status == GDAL_DATA_COVERAGE_STATUS_EMPTY;
}

} // namespace

// Where a sparse mosaic has no source nothing is read: the survey of the
// elevation range passes over it, and a tile without data within the fill's
// reach is the lowest elevation throughout, not filled. Its tiles are those
// of the same samples written whole to a GeoTIFF (every block present, read
// and filled as any raster), byte for byte.
TEST(TileWindows, SparseMosaicGivesTheSameTilesAsTheRasterWrittenWhole) {
    test::ScratchDir scratch;
    const std::string vrt = scratch / "sparse.vrt", whole = scratch / "whole.tif";
    ASSERT_NO_FATAL_FAILURE(write_sparse_vrt(vrt, 700, 800, 0, 544));
    GDALDatasetH src = GDALOpen(vrt.c_str(), GA_ReadOnly);
    ASSERT_NE(src, nullptr);
    GDALDatasetH copy = GDALCreateCopy(GDALGetDriverByName("GTiff"), whole.c_str(), src, FALSE, nullptr, nullptr, nullptr);
    GDALClose(src);
    ASSERT_NE(copy, nullptr);
    GDALClose(copy);
    // The lower left corner, beyond the fill's reach of the hills (tiles
    // r4_c0, r5_c0 and r5_c1 and their windows): empty in the mosaic only.
    ASSERT_TRUE(reported_empty(vrt, 383, 0, 317, 514));
    ASSERT_FALSE(reported_empty(whole, 383, 0, 317, 514));
    const std::string ref = scratch / "whole_tiles", dir = scratch / "sparse_tiles";
    ASSERT_EQ(test::run_overflight("tile '" + whole + "' -o '" + ref + "' --tile-size 129").exit_code, 0);
    const auto r = test::run_overflight("tile '" + vrt + "' -o '" + dir + "' --tile-size 129");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    int files = 0;
    for (const auto& e : fs::directory_iterator(ref)) {
        const std::string name = e.path().filename().string();
        ++files;
        std::string a = test::read_file_text(dir + "/" + name), b = test::read_file_text(e.path().string());
        if (name == "index.json") // the source's name apart
            for (std::string* text : {&a, &b})
                if (const std::size_t at = text->find("\"source\""); at != std::string::npos)
                    text->erase(at, text->find('\n', at) - at);
        EXPECT_EQ(a, b) << name;
    }
    EXPECT_GT(files, 4 * 42);
}

// One tile of 8193^2 samples does not fit 64 MiB: one line naming the option,
// before the source is read.
TEST(TileWindows, TileBeyondTheMemoryBoundIsRefused) {
    test::ScratchDir scratch;
    const std::string big = scratch / "big.vrt";
    ASSERT_NO_FATAL_FAILURE(write_block_vrt(big, 100000));
    const auto small = test::run_overflight("tile '" + big + "' -o '" + (scratch / "u") + "' --tile-size 8193 --memory-mib 64");
    EXPECT_EQ(small.exit_code, 1);
    EXPECT_EQ(test::line_count(small.err), 1) << small.err;
    EXPECT_EQ(small.err.rfind("overflight: --memory-mib: ", 0), 0u) << small.err;
}

#if OVERFLIGHT_ADDRESS_SPACE_CAN_BE_LIMITED
// The whole of a VRT 100000 samples wide (a 131073^2 tile grid, beyond the
// 65537 of a terrain held at once) tiled in one run under a 1 GiB address
// space with --memory-mib 256: every tile holding source samples written,
// the index complete, the placed block's samples exact and the void filled
// within the source's range. (AddressSanitizer builds cannot start under
// RLIMIT_AS: tests/RestrictedRun.h.)
TEST(TileWindows, LargeRasterIsTiledWithinTheMemoryBound) {
    test::ScratchDir scratch;
    const std::string big = scratch / "big.vrt", dir = scratch / "t";
    ASSERT_NO_FATAL_FAILURE(write_block_vrt(big, 256));
    test::Restrictions limits;
    limits.address_space_bytes = std::uint64_t(1) << 30;
    const auto r =
        test::run_overflight_restricted("tile '" + big + "' -o '" + dir + "' --tile-size 257 --memory-mib 256", limits);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("512x512 tiles of 257 samples, 391 written, 0 already done, 261753 without data"),
              std::string::npos)
        << r.out;
    const std::string text = test::read_file_text(dir + "/index.json");
    EXPECT_NE(text.find("\"padded_size\": 131073"), std::string::npos);
    EXPECT_NE(text.find("\"complete\": true"), std::string::npos);
    const TileIndex ix = read_tile_index(dir);
    EXPECT_EQ(ix.grid.source_cols, 100000);
    EXPECT_EQ(ix.grid.source_rows, 256);
    // Tile r0_c2 (columns 512..768) holds the placed block, sample for sample.
    const Terrain block = read_tile(dir, ix, 0, 2, false, 0).samples;
    long long differing = 0;
    for (int i = 0; i < 256; ++i)
        for (int j = 0; j < 256; ++j) differing += block.sample_height(i, j) != float(100 + i + j);
    EXPECT_EQ(differing, 0);
    // Tile r0_c387 (columns 99072..99328) holds the void's last 28 columns,
    // filled from both sides: on row 0 between 355 m (column 98999) and
    // 100 m (column 99100), not the lowest elevation.
    const Terrain filled = read_tile(dir, ix, 0, 387, false, 0).samples;
    EXPECT_GT(filled.sample_height(0, 0), 100.0f);
    EXPECT_LT(filled.sample_height(0, 0), 355.0f);
    for (int i = 0; i < 256; i += 15)
        for (int j = 0; j < 28; ++j) {
            EXPECT_GE(filled.sample_height(i, j), 100.0f) << i << ", " << j;
            EXPECT_LE(filled.sample_height(i, j), 610.0f) << i << ", " << j;
        }
}

// The first of 512 parts of a 100000^2 sparse mosaic (the hills at rows
// 0..255, columns 512..767, no other source) under the same bound: the
// survey reads only where the mosaic has data, the tiles beyond the fill's
// reach are not filled. Its row of 391 tiles written, the index not yet
// complete, the hills sample for sample (metres as stored: the range is
// 100..610) and the void beyond the fill's reach the lowest elevation.
TEST(TileWindows, PartOfALargeSparseMosaicIsTiledWithinTheMemoryBound) {
    test::ScratchDir scratch;
    const std::string big = scratch / "big.vrt", dir = scratch / "t";
    ASSERT_NO_FATAL_FAILURE(write_sparse_vrt(big, 100000, 100000, 0, 512));
    test::Restrictions limits;
    limits.address_space_bytes = std::uint64_t(1) << 30;
    const auto r = test::run_overflight_restricted(
        "tile '" + big + "' -o '" + dir + "' --tile-size 257 --memory-mib 256 --part 1/512", limits);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("512x512 tiles of 257 samples, 391 written, 0 already done, 121 without data"),
              std::string::npos)
        << r.out;
    const std::string text = test::read_file_text(dir + "/index.json");
    EXPECT_NE(text.find("\"padded_size\": 131073"), std::string::npos);
    EXPECT_NE(text.find("\"complete\": false"), std::string::npos);
    const auto heights = [&](int c) {
        std::vector<std::uint16_t> z(257 * 257, 0);
        GDALDatasetH tile = GDALOpen((dir + "/r0_c" + std::to_string(c) + ".tif").c_str(), GA_ReadOnly);
        EXPECT_NE(tile, nullptr) << c;
        if (tile) {
            EXPECT_EQ(GDALRasterIO(GDALGetRasterBand(tile, 1), GF_Read, 0, 0, 257, 257, z.data(), 257, 257, GDT_UInt16,
                                   0, 0),
                      CE_None);
            GDALClose(tile);
        }
        return z;
    };
    const std::vector<std::uint16_t> hills = heights(2), far = heights(300);
    long long differing = 0;
    for (int i = 0; i < 256; ++i)
        for (int j = 0; j < 256; ++j) differing += hills[std::size_t(i) * 257 + std::size_t(j)] != 100 + i + j;
    EXPECT_EQ(differing, 0);
    EXPECT_EQ(std::count(far.begin(), far.end(), std::uint16_t(100)), 257 * 257);
}
#endif

// A 70000 x 200 raster (one row of tiles) pads to 131073^2, beyond the
// 65537 of a terrain held at once: its directory opens through the overview
// (at most 2049 per side) and the quadtree over the tiles draws it.
TEST(TileWindows, DirectoryBeyondOneTerrainOpensLazily) {
    test::ScratchDir scratch;
    const std::string dem = scratch / "long.tif", dir = scratch / "t";
    write_dem(dem, 200, 70000, false, 0);
    const auto r = test::run_overflight("tile '" + dem + "' -o '" + dir + "' --tile-size 257");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const TileIndex ix = read_tile_index(dir);
    EXPECT_EQ(ix.padded_size, 131073);
    const DataSet overview = load_tile_directory_overview(dir);
    EXPECT_LE(overview.terrain.cols(), 2049);
    EXPECT_EQ(test::run_overflight("info '" + dir + "'").exit_code, 0);
    TileSet tiles(ix.grid, tile_directory_loader(dir, ix), std::size_t(256) << 20);
    const glm::dvec3 eye(35000 * 30.0, 2500.0, 150 * 30.0);
    MeshArrays mesh;
    const TileFrameStats stats = tiles.build_mesh(test::camera_at(eye, 90, -20, 40000, 320, 200), 1.0, mesh);
    EXPECT_GT(stats.triangles, 1000u);
    EXPECT_FALSE(tiles.visible_tiles().empty());
}

TEST(TileWindows, RasterBeyondTheTileGridIsRefused) {
    test::ScratchDir scratch;
    const std::string wide = scratch / "wide.tif";
    GDALAllRegister();
    const char* options[] = {"SPARSE_OK=TRUE", "TILED=YES", nullptr};
    GDALDatasetH ds =
        GDALCreate(GDALGetDriverByName("GTiff"), wide.c_str(), 1100000, 2, 1, GDT_Int16, const_cast<char**>(options));
    ASSERT_NE(ds, nullptr);
    GDALClose(ds);
    const auto r = test::run_overflight("tile '" + wide + "' -o '" + (scratch / "t") + "'");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err, "overflight: " + wide + ": 1100000x2 samples pad to more than 1048577 per side, the largest tile grid\n");
}
