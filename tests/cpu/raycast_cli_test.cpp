// `overflight render --method voxel` and `overflight bench` as a user runs
// them (DESIGN sec. 6): outputs, --stats JSON, and one-line errors for bad
// camera input with nothing left behind.
#include "TestSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>

using namespace overflight::test;

TEST(RenderVoxelCli, WritesPngDepthAndStats) {
    ScratchDir dir;
    const RunResult r = run_overflight("render demo --demo-size 65 -o '" + dir / "out.png" + "' --depth '" +
                                       dir / "depth.tif" + "' --stats --size 64x40 --pitch -10");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "out.png"));
    EXPECT_TRUE(std::filesystem::exists(dir / "depth.tif"));
    EXPECT_EQ(line_count(r.out), 1);
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["method"], "voxel");
    EXPECT_EQ(j["width"], 64);
    EXPECT_EQ(j["height"], 40);
    EXPECT_EQ(j["columns"], 64);
    EXPECT_GT(j["samples"].get<long long>(), 0);
    EXPECT_TRUE(j["ms"].contains("cast"));
    EXPECT_TRUE(j["ms"].contains("write"));
}

TEST(RenderVoxelCli, EveryCameraOption) {
    ScratchDir dir;
    const RunResult r = run_overflight("render demo --demo-size 65 -o '" + dir / "a.png" +
                                       "' --at 300,300 --agl 50 --heading 45 --pitch 5 --projection tilt --fov 70 "
                                       "--size 48x32 --near 0.5 --far 900 --surface bilinear --tilt-method guedes --stats");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["projection"], "tilt");
    EXPECT_EQ(j["tilt_method"], "guedes");
    EXPECT_EQ(j["surface"], "bilinear");
    const RunResult e = run_overflight("render demo --demo-size 65 -o '" + dir / "b.png" +
                                       "' --eye 320,400,-50 --lod --size 48x32");
    EXPECT_EQ(e.exit_code, 0) << e.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "b.png"));
}

TEST(RenderVoxelCli, BadCameraInputIsOneLineAndLeavesNothing) {
    ScratchDir dir;
    const std::string out = dir / "bad.png";
    const struct {
        const char* args;
        const char* subject;
    } cases[] = {
        {"--near 10 --far 5", "--far"},
        {"--far 0", "--far"},
        {"--fov 0", "--fov"},
        {"--fov 180", "--fov"},
        {"--pitch 89", "--pitch"},
        {"--pitch -95", "--pitch"},
        {"--size 0x100", "--size"},
        {"--size 20000x10", "--size"},
        {"--size banana", "--size"},
        {"--eye 1e9,100,0", "--eye"},
        {"--eye 1,2", "--eye"},
        {"--at 99999,5", "--at"},
        {"--projection fisheye", "--projection"},
        {"--surface voxels", "--surface"},
        {"--tilt-method fast", "--tilt-method"},
        {"--method nope", "--method"},
    };
    for (const auto& c : cases) {
        const std::string size = std::string(c.args).find("--size") == std::string::npos ? " --size 16x8 " : " ";
        const RunResult r = run_overflight("render demo --demo-size 33 -o '" + out + "'" + size + c.args);
        EXPECT_NE(r.exit_code, 0) << c.args;
        EXPECT_EQ(line_count(r.err), 1) << c.args << ": " << r.err;
        EXPECT_EQ(r.err.rfind(std::string("overflight: ") + c.subject + ":", 0), 0u) << c.args << ": " << r.err;
        EXPECT_FALSE(std::filesystem::exists(out)) << c.args;
    }
}

TEST(RenderVoxelCli, LiteralNeedsShear) {
    ScratchDir dir;
    const RunResult r = run_overflight("render demo --demo-size 33 -o '" + dir / "x.png" +
                                       "' --size 16x8 --method voxel-literal --projection tilt");
    EXPECT_NE(r.exit_code, 0);
    EXPECT_EQ(r.err.rfind("overflight: --projection:", 0), 0u) << r.err;
}

TEST(BenchCli, JsonListsVoxelAndLiteral) {
    const RunResult r = run_overflight("bench demo --demo-size 65 --json --size 40x24 --frames 2");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    ASSERT_EQ(j["runs"].size(), 2u);
    EXPECT_EQ(j["runs"][0]["method"], "voxel");
    EXPECT_EQ(j["runs"][1]["method"], "voxel-literal");
    for (const auto& run : j["runs"]) {
        EXPECT_EQ(run["width"], 40);
        EXPECT_EQ(run["height"], 24);
        EXPECT_EQ(run["frames"], 2);
        EXPECT_GT(run["ms_median"].get<double>(), 0.0);
        EXPECT_GT(run["samples"].get<long long>(), 0);
    }
    // Both methods cast the same columns x slices.
    EXPECT_EQ(j["runs"][0]["samples"], j["runs"][1]["samples"]);
}

TEST(BenchCli, MarkdownTable) {
    const RunResult r = run_overflight("bench demo --demo-size 33 --markdown --size 16x8 --frames 1 --methods voxel");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("| voxel |"), std::string::npos) << r.out;
    const RunResult bad = run_overflight("bench demo --demo-size 33 --frames 0");
    EXPECT_NE(bad.exit_code, 0);
    EXPECT_EQ(bad.err.rfind("overflight: --frames:", 0), 0u) << bad.err;
}
