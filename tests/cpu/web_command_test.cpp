// `overflight web TERRAIN -o SITE` (DESIGN sec. 6.1): the folder it writes,
// the decimation notice, and its one-line refusals (SITE not empty, a bad
// terrain, a bad --max-size, no WebAssembly engine), none of which leaves
// anything behind. The engine is stood in for by two small files
// (OVERFLIGHT_WEB_ENGINE_DIR): the site writer only copies it; tests/web
// runs the real one in a browser.
#include "TestSupport.h"
#include "core/WebTerrainFormat.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

using overflight::test::file_names_in;
using overflight::test::line_count;
using overflight::test::read_file_text;
using overflight::test::run_overflight;
using overflight::test::ScratchDir;
namespace fs = std::filesystem;

namespace {

// A stand-in engine folder, named to the command through the environment.
struct FakeEngine {
    explicit FakeEngine(const ScratchDir& dir) {
        const fs::path engine = dir.path / "engine";
        fs::create_directories(engine);
        for (const char* name : {"overflight_engine", "overflight_engine_scalar"}) {
            std::ofstream(engine / (std::string(name) + ".js")) << "var OverflightEngine;\n";
            std::ofstream(engine / (std::string(name) + ".wasm")) << "wasm";
        }
        ::setenv("OVERFLIGHT_WEB_ENGINE_DIR", engine.c_str(), 1);
    }
    ~FakeEngine() { ::unsetenv("OVERFLIGHT_WEB_ENGINE_DIR"); }
};

const std::set<std::string> kSiteFiles = {"atmosphere.glsl",
                                          "index.html",
                                          "objects.bin",
                                          "overflight.js",
                                          "overflight_engine.js",
                                          "overflight_engine.wasm",
                                          "overflight_engine_scalar.js",
                                          "overflight_engine_scalar.wasm",
                                          "site.json",
                                          "terrain.bin",
                                          "vehicle.bin"};

} // namespace

TEST(WebCommand, WritesTheSite) {
    ScratchDir dir;
    FakeEngine engine(dir);
    const auto r = run_overflight("web demo --demo-size 65 -o '" + dir / "site/'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(line_count(r.out), 1) << r.out;
    EXPECT_EQ(file_names_in(dir / "site"), kSiteFiles);
    // Nothing beside it: the temporary folder became the site.
    EXPECT_EQ(file_names_in(dir.path), (std::set<std::string>{"engine", "site"}));
    const auto site = nlohmann::json::parse(read_file_text(dir / "site/site.json"));
    EXPECT_EQ(site["terrain"]["rows"], 65);
    EXPECT_EQ(site["terrain"]["decimation"], 1);
    const std::string terrain = read_file_text(dir / "site/terrain.bin");
    EXPECT_EQ(terrain.size(), overflight::web_terrain_bytes(65, 65));
    EXPECT_EQ(terrain.substr(0, 8), "OFTERR01");
    EXPECT_EQ(site["terrain"]["bytes"], terrain.size());
    // The demo's houses, vehicle and water tower, and its transmission line.
    const std::string objects = read_file_text(dir / "site/objects.bin");
    EXPECT_EQ(objects.substr(0, 8), std::string("OFOBJ01\0", 8));
    EXPECT_EQ(site["objects"]["bytes"], objects.size());
    EXPECT_GT(site["objects"]["triangles"].get<int>(), 50);
    EXPECT_GT(site["objects"]["line_points"].get<int>(), 100);
    // The arrays, then one box per object, tower and cable span.
    const auto layout_bytes = [](const std::string& file, std::uint32_t (&counts)[4]) {
        std::memcpy(counts, file.data() + 8, sizeof counts);
        const auto pad4 = [](std::size_t n) { return (n + 3) / 4 * 4; };
        const std::size_t v = counts[0], i = counts[1], l = counts[2], b = counts[3];
        return 24 + 24 * v + pad4(3 * v) + 4 * i + 12 * l + pad4(3 * l) + 24 * b;
    };
    std::uint32_t counts[4];
    EXPECT_EQ(layout_bytes(objects, counts), objects.size());
    EXPECT_GT(counts[3], 5u);
    // The player's hovercraft in its own frame: triangles, no lines, its box.
    const std::string vehicle = read_file_text(dir / "site/vehicle.bin");
    EXPECT_EQ(vehicle.substr(0, 8), std::string("OFOBJ01\0", 8));
    EXPECT_EQ(site["vehicle"]["bytes"], vehicle.size());
    EXPECT_EQ(layout_bytes(vehicle, counts), vehicle.size());
    EXPECT_GT(counts[1], 0u);
    EXPECT_EQ(counts[2], 0u);
    EXPECT_EQ(counts[3], 1u);
    EXPECT_EQ(read_file_text(dir / "site/overflight.js"),
              read_file_text(std::string(OVERFLIGHT_SOURCE_DIR) + "/web/shell/overflight.js"));
}

TEST(WebCommand, DecimatesALargerTerrainWithOneLine) {
    ScratchDir dir;
    FakeEngine engine(dir);
    fs::create_directories(dir / "empty");
    const auto r = run_overflight("web demo --demo-size 257 --max-size 65 -o '" + dir / "empty" + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(line_count(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("257x257 samples decimated by 4 to 65x65"), std::string::npos) << r.err;
    const auto site = nlohmann::json::parse(read_file_text(dir / "empty/site.json"));
    EXPECT_EQ(site["terrain"]["rows"], 65);
    EXPECT_EQ(site["terrain"]["decimation"], 4);
    EXPECT_FLOAT_EQ(site["terrain"]["h_scale"].get<float>(), 40.0f);
}

TEST(WebCommand, RefusesWithOneLineAndLeavesNothingBehind) {
    ScratchDir dir;
    FakeEngine engine(dir);
    fs::create_directories(dir / "full");
    std::ofstream(dir / "full/keep.txt") << "mine";
    std::ofstream(dir / "bad.tif") << "not a raster at all";
    const struct {
        std::string args, names;
    } cases[] = {
        {"demo --demo-size 65 -o '" + dir / "full" + "'", "exists and is not empty"},
        {"demo --demo-size 65 -o '" + dir / "bad.tif" + "'", "exists and is not a folder"},
        {"'" + dir / "missing.tif" + "' -o '" + dir / "site" + "'", "missing.tif"},
        {"'" + dir / "bad.tif" + "' -o '" + dir / "site" + "'", "bad.tif"},
        {"demo --demo-size 65 --max-size 10 -o '" + dir / "site" + "'", "--max-size"},
        {"demo --demo-size 65 -o '" + dir / "no/such/site" + "'", "does not exist"},
    };
    for (const auto& c : cases) {
        const auto r = run_overflight("web " + c.args);
        EXPECT_EQ(r.exit_code, 1) << c.args;
        EXPECT_EQ(line_count(r.err), 1) << c.args << ": " << r.err;
        EXPECT_NE(r.err.find(c.names), std::string::npos) << c.args << ": " << r.err;
    }
    EXPECT_EQ(read_file_text(dir / "full/keep.txt"), "mine");
    EXPECT_EQ(file_names_in(dir.path), (std::set<std::string>{"bad.tif", "engine", "full"}));
}

TEST(WebCommand, SaysHowToBuildAMissingEngine) {
    ScratchDir dir;
    FakeEngine engine(dir);
    ::setenv("OVERFLIGHT_WEB_ENGINE_DIR", (dir / "nothing").c_str(), 1);
    const auto r = run_overflight("web demo --demo-size 65 -o '" + dir / "site" + "'");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(line_count(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("/nothing/overflight_engine"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("scripts/build_web.sh"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "site"));
}
