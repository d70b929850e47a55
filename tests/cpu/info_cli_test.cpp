// Hovercraft data sets (CMSC 23700 project 2a, sec. 6) through the library and through
// `overflight info`, and the one-line error of each bad data set (DESIGN sec. 6).
#include "TestSupport.h"
#include "core/Error.h"
#include "io/HovercraftDataSet.h"
#include "io/LoadTerrain.h"
#include "io/Pnm.h"

#include <nlohmann/json.hpp>

#include <fstream>

namespace overflight {
namespace {

using test::line_count;
using test::run_overflight;
using test::ScratchDir;

// A 3x3 data set worked by hand: heights 0..8 (raw), h_scale 2, v_scale 0.5,
// so world Y = 0.5 * raw: min 0, max 4; extent 4 x 4.
DataSet tiny_data_set() {
    DataSet d;
    d.terrain = Terrain(3, 3, 2.0f, 0.5f, 0.0f);
    for (int i = 0; i < 9; ++i) d.terrain.heights()[std::size_t(i)] = std::uint16_t(i);
    for (int i = 0; i < 9; ++i) d.terrain.colors()[std::size_t(i)] = Rgb8{std::uint8_t(40 * i), 10, 20};
    d.environment.fog_density = 0.01f;
    d.start = VehicleStart{true, 1.0, 2.0, 90.0};
    SceneObject house;
    house.kind = ObjectKind::House;
    house.x = 2;
    house.z = 2;
    d.scene.objects.push_back(house);
    return d;
}

void write_text(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// A valid data set on disk, to be broken by each test.
std::string make_data_set(const ScratchDir& dir) {
    const std::string set = dir / "set";
    save_hovercraft(set, tiny_data_set());
    return set;
}

void expect_one_line_error(const std::string& args, const std::string& file, const std::string& words) {
    const test::RunResult r = run_overflight(args);
    EXPECT_NE(r.exit_code, 0) << args;
    EXPECT_EQ(line_count(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("overflight: " + file + ": ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(words), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
}

TEST(HovercraftDataSet, CellColorsAverageToSamples) {
    // 2x2 cells -> 3x3 samples: a corner takes its one cell, an edge sample
    // the mean of two, the centre the mean of all four (rounded).
    ColorImage cells(2, 2);
    cells.pixels = {Rgb8{0, 0, 0}, Rgb8{100, 0, 0}, Rgb8{0, 200, 0}, Rgb8{1, 0, 0}};
    const ColorImage s = cell_colors_to_samples(cells);
    ASSERT_EQ(s.width, 3);
    ASSERT_EQ(s.height, 3);
    EXPECT_EQ(s.at(0, 0), (Rgb8{0, 0, 0}));
    EXPECT_EQ(s.at(2, 0), (Rgb8{100, 0, 0}));
    EXPECT_EQ(s.at(1, 0), (Rgb8{50, 0, 0}));  // (0 + 100) / 2
    EXPECT_EQ(s.at(0, 1), (Rgb8{0, 100, 0})); // (0 + 200) / 2
    EXPECT_EQ(s.at(1, 1), (Rgb8{25, 50, 0})); // (0 + 100 + 0 + 1) / 4 = 25.25, 200 / 4
    EXPECT_EQ(s.at(2, 2), (Rgb8{1, 0, 0}));
}

TEST(HovercraftDataSet, SaveAndLoadRoundTrip) {
    ScratchDir dir;
    const std::string set = make_data_set(dir);
    EXPECT_TRUE(std::filesystem::exists(set + "/map"));
    // color.ppm holds one pixel per cell: 2x2 for a 3x3 height field.
    const ColorImage cells = read_ppm(set + "/color.ppm");
    EXPECT_EQ(cells.width, 2);
    EXPECT_EQ(cells.height, 2);
    const DataSet d = load_terrain(set);
    EXPECT_EQ(d.info.kind, "hovercraft");
    EXPECT_EQ(d.terrain.rows(), 3);
    EXPECT_EQ(d.terrain.h_scale(), 2.0f);
    EXPECT_EQ(d.terrain.v_scale(), 0.5f);
    EXPECT_EQ(d.terrain.heights(), tiny_data_set().terrain.heights());
    EXPECT_FLOAT_EQ(d.terrain.max_height(), 4.0f);
    EXPECT_EQ(d.environment.fog_density, 0.01f);
    EXPECT_TRUE(d.start.given);
    EXPECT_EQ(d.start.heading, 90.0);
    ASSERT_EQ(d.scene.objects.size(), 1u);
    EXPECT_EQ(d.scene.objects[0].kind, ObjectKind::House);
}

TEST(HovercraftDataSet, PerSampleColorsAreAccepted) {
    ScratchDir dir;
    const std::string set = make_data_set(dir);
    ColorImage per_sample(3, 3, Rgb8{7, 8, 9});
    write_ppm(set + "/color.ppm", per_sample);
    const DataSet d = load_hovercraft(set);
    EXPECT_EQ(d.terrain.color(2, 2), (Rgb8{7, 8, 9}));
}

TEST(HovercraftDataSet, DemoSurvivesTheRoundTrip) {
    ScratchDir dir;
    LoadOptions options;
    options.demo_size = 33;
    const DataSet demo = load_terrain("demo", options);
    save_hovercraft(dir / "island", demo);
    const DataSet back = load_terrain(dir / "island");
    EXPECT_EQ(back.terrain.heights(), demo.terrain.heights());
    EXPECT_EQ(back.terrain.v_scale(), demo.terrain.v_scale());
    EXPECT_EQ(back.terrain.y_offset(), demo.terrain.y_offset());
    EXPECT_EQ(back.scene.objects.size(), demo.scene.objects.size());
    EXPECT_EQ(back.scene.lines.size(), demo.scene.lines.size());
}

TEST(InfoCli, JsonDescribesAHovercraftDataSet) {
    ScratchDir dir;
    const std::string set = make_data_set(dir);
    const test::RunResult r = run_overflight("info '" + set + "' --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(line_count(r.out), 1);
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["rows"], 3);
    EXPECT_EQ(j["cols"], 3);
    EXPECT_EQ(j["h_scale"], 2.0);
    EXPECT_EQ(j["v_scale"], 0.5);
    EXPECT_EQ(j["y_offset"], 0.0);
    EXPECT_EQ(j["elevation_min"], 0.0);
    EXPECT_EQ(j["elevation_max"], 4.0);
    EXPECT_EQ(j["extent_x"], 4.0);
    EXPECT_EQ(j["extent_z"], 4.0);
    EXPECT_EQ(j["nodata_filled"], 0);
    EXPECT_EQ(j["reprojected"], false);
    EXPECT_EQ(j["kind"], "hovercraft");
    EXPECT_NE(j["color_source"].get<std::string>().find("color.ppm"), std::string::npos);
    EXPECT_TRUE(j["metadata"].is_object());
}

TEST(InfoCli, TextDescribesTheDemo) {
    const test::RunResult r = run_overflight("info demo --demo-size 33");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("rows: 33\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("kind: demo\n"), std::string::npos) << r.out;
}

TEST(InfoCliErrors, MissingFile) {
    ScratchDir dir;
    expect_one_line_error("info '" + dir / "nope.tif" + "'", dir / "nope.tif", "no such file");
}

TEST(InfoCliErrors, DirectoryWithoutMap) {
    ScratchDir dir;
    expect_one_line_error("info '" + dir.path.string() + "'", dir.path.string(), "without a `map`");
}

// A valid data set broken one way: the file that breaks (relative to the set),
// how, and the words its one-line error must hold.
struct BrokenDataSet {
    const char* name;
    const char* file;
    void (*breaks)(const std::string& path);
    const char* words;
};

const BrokenDataSet kBrokenDataSets[] = {
    {"MapSyntaxError", "map", [](const std::string& f) { write_text(f, "h_scale = 1\nv_scale = [1,\n"); }, "line "},
    {"MapMissingKey", "map", [](const std::string& f) { write_text(f, "h_scale = 1\n"); }, "missing key v_scale"},
    {"MapWrongTypedKey", "map", [](const std::string& f) { write_text(f, "h_scale = 1\nv_scale = \"x\"\n"); },
     "line 2: v_scale must be a number"},
    {"PgmMissing", "hf.pgm", [](const std::string& f) { std::filesystem::remove(f); }, "no such file"},
    {"PgmTruncated", "hf.pgm",
     [](const std::string& f) { std::filesystem::resize_file(f, std::filesystem::file_size(f) - 3); }, "truncated"},
    {"PgmWrongMagic", "hf.pgm", [](const std::string& f) { write_text(f, "P2\n3 3\n255\n0 1 2 3 4 5 6 7 8\n"); },
     "magic"},
    {"PgmMaxvalZero", "hf.pgm",
     [](const std::string& f) { write_text(f, std::string("P5\n3 3\n0\n") + std::string(9, '\0')); }, "maxval 0"},
    {"PgmMaxvalTooLarge", "hf.pgm",
     [](const std::string& f) { write_text(f, std::string("P5\n3 3\n70000\n") + std::string(18, '\0')); },
     "maxval 70000"},
    {"PgmZeroSize", "hf.pgm", [](const std::string& f) { write_text(f, "P5\n0 0\n255\n"); }, "size 0x0"},
    {"PgmAbsurdSize", "hf.pgm", [](const std::string& f) { write_text(f, "P5\n100000 3\n65535\n"); },
     "size 100000x3"},
    // Wider than the grid but shorter: neither per cell, per sample, nor imagery over the grid.
    {"PpmSizeNotMatchingPgm", "color.ppm", [](const std::string& f) { write_ppm(f, ColorImage(5, 1)); },
     "matches neither"},
};

void PrintTo(const BrokenDataSet& b, std::ostream* os) { *os << b.name; }

class InfoCliBrokenDataSet : public testing::TestWithParam<BrokenDataSet> {};

TEST_P(InfoCliBrokenDataSet, FailsWithOneLineNamingTheFile) {
    ScratchDir dir;
    const std::string set = make_data_set(dir);
    const std::string file = set + "/" + GetParam().file;
    GetParam().breaks(file);
    expect_one_line_error("info '" + set + "'", file, GetParam().words);
}

INSTANTIATE_TEST_SUITE_P(InfoCliErrors, InfoCliBrokenDataSet, testing::ValuesIn(kBrokenDataSets),
                         [](const testing::TestParamInfo<BrokenDataSet>& p) { return p.param.name; });

TEST(InfoCliErrors, BadDemoSize) {
    const test::RunResult r = run_overflight("info demo --demo-size 100");
    EXPECT_NE(r.exit_code, 0);
    EXPECT_EQ(line_count(r.err), 1) << r.err;
}

TEST(InfoCli, AColorPpmLargerThanTheGridIsImageryAtItsOwnResolution) {
    ScratchDir dir;
    const std::string set = make_data_set(dir);
    write_ppm(set + "/color.ppm", ColorImage(8, 8, Rgb8{10, 20, 30}));
    const test::RunResult r = run_overflight("info '" + set + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    // 8x8 texels over the 3x3 grid's 4x4 world units of cells: 0.5 per texel, all covered.
    EXPECT_NE(r.out.find("imagery_size: 8x8\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("imagery_resolution: 0.5\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("imagery_coverage: 1.0\n"), std::string::npos) << r.out;
}

} // namespace
} // namespace overflight
