// Tile folders that lie, break or cannot be written: declared sizes are
// checked before anything is allocated from them (under a 512 MiB address
// space limit), corrupt index values and tile files are reported per file,
// a full disk fails with one line and leaves no index claiming missing tiles,
// a re-run rewrites broken tiles and ends byte-identical to an uninterrupted
// run, and a 2x2 raster tiles.
#include "SmallFilesystem.h"
#include "TestSupport.h"

#include "core/Error.h"
#include "io/TileDirectory.h"
#include "lod/TileSet.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <fstream>
#include <functional>
#include <iterator>
#include <sys/resource.h>
#include <unistd.h>

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define OVERFLIGHT_CLANG_ASAN 1
#endif
#endif
#ifndef OVERFLIGHT_CLANG_ASAN
#define OVERFLIGHT_CLANG_ASAN 0
#endif

using namespace overflight;
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

std::string bytes_of(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), {});
}

void write_bytes(const fs::path& p, const std::string& bytes) { std::ofstream(p, std::ios::binary) << bytes; }

void edit_index(const std::string& dir, const std::function<void(json&)>& edit) {
    json j = json::parse(bytes_of(fs::path(dir) / "index.json"));
    edit(j);
    write_bytes(fs::path(dir) / "index.json", j.dump(1) + "\n");
}

// Every file of `dir` is byte-identical to the same file of `ref`, and both
// hold the same number of files.
void expect_same_files(const std::string& dir, const std::string& ref) {
    int files = 0, ref_files = 0;
    for (const auto& e : fs::directory_iterator(dir)) {
        ++files;
        EXPECT_EQ(bytes_of(e.path()), bytes_of(fs::path(ref) / e.path().filename())) << e.path().filename();
    }
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(ref)) ++ref_files;
    EXPECT_EQ(files, ref_files);
}

void expect_no_temporaries(const std::string& dir) {
    for (const auto& e : fs::directory_iterator(dir)) EXPECT_NE(e.path().filename().string()[0], '.') << e.path();
}

// `overflight ARGS...` in a child whose address space is limited to `bytes`
// (setrlimit(RLIMIT_AS) between fork and exec).
test::RunResult run_limited(const std::vector<std::string>& args, rlim_t bytes, const test::ScratchDir& scratch) {
    const std::string out_path = scratch / "limited.out", err_path = scratch / "limited.err";
    std::vector<std::string> argv_s = {OVERFLIGHT_EXE};
    argv_s.insert(argv_s.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : argv_s) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t pid = fork();
    if (pid == 0) {
        const rlimit limit{bytes, bytes};
        const int out = ::open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int err = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (setrlimit(RLIMIT_AS, &limit) != 0 || out < 0 || err < 0 || dup2(out, 1) < 0 || dup2(err, 2) < 0) _exit(127);
        execv(OVERFLIGHT_EXE, argv.data());
        _exit(127);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    test::RunResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.out = bytes_of(out_path);
    r.err = bytes_of(err_path);
    return r;
}

// 70 x 100 samples, raw = 100 i + j, world = 0.5 raw - 10, in 33-sample
// tiles: 4x4 tiles, row 3 padding only (flag 0). Tile (0, 0) spans raw
// 0 .. 3232 (world -10 .. 1606), tile (1, 1) raw 3232 .. 6464 (1606 .. 3222),
// tile (1, 2) raw 3264 .. 6496 (1622 .. 3238).
void write_ramp_tiles(const std::string& dir) {
    DataSet d;
    d.terrain = Terrain(70, 100, 5.0f, 0.5f, -10.0f);
    for (int i = 0; i < 70; ++i)
        for (int j = 0; j < 100; ++j) d.terrain.raw(i, j) = std::uint16_t(i * 100 + j);
    TileWriteOptions o;
    o.tile_size = 33;
    o.measures = rottger_tile_measures();
    write_tile_directory(d, dir, o);
}

std::string info_error(const std::string& dir) {
    const auto r = test::run_overflight("info '" + dir + "'");
    EXPECT_EQ(r.exit_code, 1) << r.out;
    EXPECT_EQ(test::line_count(r.err), 1) << r.err;
    return r.err;
}

} // namespace

// The index claims one tile of 16385^2 samples (a 16385^2 source); the tile
// file holds 129^2. Reading it would need 1.3 GB (info) and far more
// (render); the file's raster size is checked first.
TEST(TileFolderRobustness, DeclaredSizesAreCheckedBeforeAllocating) {
    test::ScratchDir scratch;
    const std::string dir = scratch / "t";
    ASSERT_EQ(test::run_overflight("tile demo --demo-size 129 --tile-size 129 -o '" + dir + "'").exit_code, 0);
    // AddressSanitizer reserves terabytes of address space for its shadow
    // memory, so a sanitizer build runs the same commands without the limit.
#if defined(__SANITIZE_ADDRESS__) || OVERFLIGHT_CLANG_ASAN
    constexpr rlim_t kLimit = RLIM_INFINITY;
#else
    constexpr rlim_t kLimit = 512u << 20;
#endif
    const auto honest = run_limited({"info", dir}, kLimit, scratch);
    ASSERT_EQ(honest.exit_code, 0) << honest.err; // the limit leaves room for a real run
    edit_index(dir, [](json& j) {
        j["tile_size"] = 16385;
        j["padded_size"] = 16385;
        j["source_rows"] = 16385;
        j["source_cols"] = 16385;
        j["levels"] = 0;
        j["roughness"] = nullptr;
    });
    const std::string expected = "overflight: " + dir +
                                 "/r0_c0.tif: holds 1 band(s) of 129x129 UInt16 samples, the tile index expects 1 of "
                                 "16385x16385 UInt16\n";
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"info", dir}, {"render", dir, "-o", scratch / "a.png"},
          {"render", dir, "--method", "quadtree", "-o", scratch / "b.png"}}) {
        const auto r = run_limited(args, kLimit, scratch);
        EXPECT_EQ(r.exit_code, 1) << args[0] << " " << args[args.size() - 1];
        EXPECT_EQ(r.err, expected);
    }
    EXPECT_FALSE(fs::exists(scratch / "a.png"));
    EXPECT_FALSE(fs::exists(scratch / "b.png"));
}

TEST(TileFolderRobustness, CorruptIndexValuesNameTheIndex) {
    test::ScratchDir scratch;
    const std::string dir = scratch / "t";
    write_ramp_tiles(dir);
    const std::string original = bytes_of(fs::path(dir) / "index.json");
    const std::string mapping = " is not within the height mapping's -10 .. 32757.5";
    const std::vector<std::pair<std::function<void(json&)>, std::string>> cases = {
        {[](json& j) { j["tile_size"] = (1 << 30) + 1; }, "tile size 1073741825 is not 2^k+1 in 3 .. 32769"},
        {[](json& j) { j["tile_size"] = 65; },
         "tile grid 4x4 of 65-sample tiles does not cut the 129^2 square padding a source of 70x100 samples"},
        {[](json& j) { j["tile_rows"] = 1000000000; }, "exists does not match tile_rows x tile_cols"},
        {[](json& j) { j["source_rows"] = 65537; },
         "source of 65537x100 samples does not fit the tile grid 4x4 of 33-sample tiles"},
        {[](json& j) { j["padded_size"] = 257; }, "padded_size does not match the tile grid"},
        {[](json& j) { j["min_height"][0][0] = -1e30; }, "height range -1e+30 .. 1606 of tile r0_c0" + mapping},
        {[](json& j) { j["min_height"][0][0] = 2000; }, "height range 2000 .. 1606 of tile r0_c0" + mapping},
        {[](json& j) { j["max_height"][0][0] = 1e39; }, "max_height of tile r0_c0 is beyond the range of a float"},
        {[](json& j) { j["min_height"][0][0] = -1e39; }, "min_height of tile r0_c0 is beyond the range of a float"},
        {[](json& j) { j["exists"][3][0] = 1; }, "tile r3_c0 is flagged 1 but lies wholly in the padding"},
        {[](json& j) { j["exists"][1][2] = 0; }, "tile r1_c2 is flagged 0 but holds source samples"},
        {[](json& j) { j["exists"][0][0] = 2; }, "exists of tile r0_c0 is neither 0 nor 1"},
        {[](json& j) { j["levels"] = 40; }, "levels 40 is outside 0 .. 4 for tiles of 33 samples"},
        {[](json& j) { j["roughness"][0][0][0] = -1; }, "tile roughness -1 is not a finite number >= 0"},
        {[](json& j) { j["h_scale"] = 0; }, "horizontal scale 0 is not a positive number with a finite extent"},
        {[](json& j) { j["height_mapping"]["v_scale"] = 1e38; }, "height mapping 1e+38 * raw + -10 is not finite"},
        {[](json& j) { j["d2_min_resolution"] = 0.5; }, "d2_min_resolution 0.5 is neither 0 nor a number above 1"},
        {[](json& j) { j["version"] = "1"; }, "version is not an integer"},
        {[](json& j) { j["tile_cols"] = 4.5; }, "tile_cols is not an integer"},
    };
    for (const auto& [edit, problem] : cases) {
        edit_index(dir, edit);
        EXPECT_EQ(info_error(dir), "overflight: " + dir + "/index.json: " + problem + "\n");
        write_bytes(fs::path(dir) / "index.json", original);
    }
    // A source one row smaller still fits the grid and its flags, but tile
    // row 2 then holds data where the padding should be.
    edit_index(dir, [](json& j) { j["source_rows"] = 69; });
    EXPECT_EQ(info_error(dir),
              "overflight: " + dir + "/r2_c0.tif: samples beyond the 69x100 source index.json gives are not its padding\n");
    write_bytes(fs::path(dir) / "index.json", original.substr(0, original.size() / 2));
    EXPECT_EQ(info_error(dir).rfind("overflight: " + dir + "/index.json: malformed JSON: ", 0), 0u);
    write_bytes(fs::path(dir) / "index.json", original);
    EXPECT_EQ(test::run_overflight("info '" + dir + "'").exit_code, 0);
}

TEST(TileFolderRobustness, CorruptTileFilesNameTheFile) {
    test::ScratchDir scratch;
    const std::string dir = scratch / "t";
    write_ramp_tiles(dir);
    const fs::path tile = fs::path(dir) / "r1_c2.tif", colors = fs::path(dir) / "r1_c2_rgb.tif";
    const std::string tile_bytes = bytes_of(tile), color_bytes = bytes_of(colors);
    const std::string prefix = "overflight: " + tile.string() + ": ";

    fs::remove(tile);
    EXPECT_EQ(info_error(dir), prefix + "no such file\n");
    write_bytes(tile, "not a GeoTIFF at all");
    EXPECT_EQ(info_error(dir).rfind(prefix + "not a raster GDAL can read", 0), 0u);
    write_bytes(tile, tile_bytes.substr(0, tile_bytes.size() / 2)); // truncated
    EXPECT_EQ(info_error(dir).rfind(prefix, 0), 0u);
    // A valid tile of the same size from elsewhere in the grid.
    write_bytes(tile, bytes_of(fs::path(dir) / "r1_c1.tif"));
    EXPECT_EQ(info_error(dir), prefix + "heights 1606 .. 3222 differ from the range 1622 .. 3238 index.json gives the tile\n");
    write_bytes(tile, tile_bytes);
    write_bytes(colors, bytes_of(fs::path(dir) / "r1_c2_apron.tif"));
    EXPECT_EQ(info_error(dir), "overflight: " + colors.string() +
                                   ": holds 1 band(s) of 33x4 UInt16 samples, the tile index expects 3 of 33x33 Byte\n");
    write_bytes(colors, color_bytes);
    EXPECT_EQ(test::run_overflight("info '" + dir + "'").exit_code, 0);
}

// A re-run keeps only tiles whose files read back exactly what it would
// write: a garbage heights file and truncated color and d2 files are
// rewritten, and the folder ends byte-identical to an uninterrupted run.
TEST(TileFolderRobustness, ResumeRewritesBrokenTiles) {
    test::ScratchDir scratch;
    const std::string ref = scratch / "ref", dir = scratch / "t";
    const std::string args = "tile demo --demo-size 129 --tile-size 33 -o ";
    ASSERT_EQ(test::run_overflight(args + "'" + ref + "'").exit_code, 0);
    fs::copy(ref, dir);
    write_bytes(fs::path(dir) / "r0_c0.tif", "garbage");
    const std::string rgb = bytes_of(fs::path(dir) / "r1_c1_rgb.tif"), d2 = bytes_of(fs::path(dir) / "r2_c3_d2.tif");
    write_bytes(fs::path(dir) / "r1_c1_rgb.tif", rgb.substr(0, rgb.size() - 100));
    write_bytes(fs::path(dir) / "r2_c3_d2.tif", d2.substr(0, d2.size() / 2));
    const auto r = test::run_overflight(args + "'" + dir + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("3 written, 13 already done"), std::string::npos) << r.out;
    expect_same_files(dir, ref);
}

// The disk fills while tiles are written: one line naming the file, no
// temporary file, an index readers refuse; with space again a re-run ends
// byte-identical to a run that never failed.
TEST(TileFolderRobustness, FullDiskFailsWithOneLineAndResumes) {
    OVERFLIGHT_SMALL_FILESYSTEM(disk, 4u << 20);
    const std::string ref = disk / "ref", dir = disk / "t";
    const std::string args = "tile demo --demo-size 129 --tile-size 33 -o ";
    ASSERT_EQ(test::run_overflight(args + "'" + ref + "'").exit_code, 0);
    std::size_t ref_bytes = 0;
    for (const auto& e : fs::directory_iterator(ref)) ref_bytes += fs::file_size(e.path());

    disk.fill(ref_bytes / 2);
    const auto full = test::run_overflight(args + "'" + dir + "'");
    EXPECT_EQ(full.exit_code, 1);
    EXPECT_EQ(test::line_count(full.err), 1) << full.err;
    EXPECT_EQ(full.err.rfind("overflight: " + dir + "/", 0), 0u) << full.err;
    const std::string tail = ": cannot write: no space left on device\n";
    ASSERT_GE(full.err.size(), tail.size());
    EXPECT_EQ(full.err.substr(full.err.size() - tail.size()), tail);
    expect_no_temporaries(dir);
    EXPECT_THROW(read_tile_index(dir), Error);

    disk.free_space();
    const auto again = test::run_overflight(args + "'" + dir + "'");
    ASSERT_EQ(again.exit_code, 0) << again.err;
    expect_same_files(dir, ref);
}

// The disk fills just before the final index is written (an index of a few
// hundred bytes fails only when it is closed): the run fails naming
// index.json, which stays the unfinished one readers refuse.
TEST(TileFolderRobustness, FullDiskAtTheFinalIndex) {
    OVERFLIGHT_SMALL_FILESYSTEM(disk, 1u << 20);
    DataSet d;
    d.terrain = Terrain(33, 33, 1.0f);
    for (std::size_t i = 0; i < d.terrain.heights().size(); ++i) d.terrain.heights()[i] = std::uint16_t(i * 7 % 251);
    TileWriteOptions o;
    o.tile_size = 33;
    o.measures = rottger_tile_measures();
    write_tile_directory(d, disk / "ref", o);

    const std::string dir = disk / "t";
    TileWriteOptions filling = o;
    filling.on_tile = [&](int done, int total) {
        if (done == total) disk.fill();
        return true;
    };
    try {
        write_tile_directory(d, dir, filling);
        ADD_FAILURE() << "the full disk went unnoticed";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), dir + "/index.json: cannot write: no space left on device");
    }
    expect_no_temporaries(dir);
    try {
        read_tile_index(dir);
        ADD_FAILURE() << "an index claims tiles of an unfinished run";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("tiling did not finish"), std::string::npos) << e.what();
    }
    disk.free_space();
    write_tile_directory(d, dir, o);
    expect_same_files(dir, disk / "ref");
}

// A 2x2 raster pads to one 3x3 tile (it used to end in an internal error
// and an index with levels = -1).
TEST(TileFolderRobustness, TinyRastersTile) {
    test::ScratchDir scratch;
    for (const auto& [rows, cols] : {std::pair{2, 2}, std::pair{2, 5}, std::pair{3, 2}}) {
        const std::string pgm = scratch / "tiny.pgm", dir = scratch / ("t" + std::to_string(rows) + std::to_string(cols));
        std::string bytes = "P5\n" + std::to_string(cols) + " " + std::to_string(rows) + "\n255\n";
        for (int k = 0; k < rows * cols; ++k) bytes += char(10 + 20 * k);
        write_bytes(pgm, bytes);
        const auto r = test::run_overflight("tile '" + pgm + "' -o '" + dir + "'");
        ASSERT_EQ(r.exit_code, 0) << r.err;
        EXPECT_EQ(test::run_overflight("info '" + dir + "'").exit_code, 0);
        const DataSet back = load_tile_directory(dir);
        ASSERT_EQ(back.terrain.rows(), rows);
        ASSERT_EQ(back.terrain.cols(), cols);
        for (int k = 0; k < rows * cols; ++k) EXPECT_EQ(back.terrain.heights()[std::size_t(k)], 10 + 20 * k);
    }
}
