// `overflight render` and `overflight bench` as a user runs them (DESIGN
// sec. 6): every method writes its PNG, depth and --stats JSON; objects of
// --scene appear; bad input gives one-line errors with nothing left behind.
// Label gl: `voxel` composites the demo's objects through OpenGL.
#include "ReadPng.h"
#include "TestSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

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
        {"--sun 10", "--sun"},
        {"--sun 400,10", "--sun"},
        {"--sun 10,95", "--sun"},
        {"--sun east,10", "--sun"},
        {"--time 25:00", "--time"},
        {"--time 9", "--time"},
        {"--time 12:60", "--time"},
        {"--time 12:00 --sun 180,60", "--time"},
        {"--lighting flat", "--lighting"},
        {"--water-level 99999", "--water-level"},
        {"--water-level deep", "--water-level"},
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

// A sun below the horizon is night, not an error: one warning line, an image
// in ambient light.
TEST(RenderVoxelCli, SunBelowTheHorizonIsAmbientLight) {
    ScratchDir dir;
    const std::string out = dir / "night.png";
    const RunResult r = run_overflight("render demo --demo-size 33 -o '" + out + "' --size 16x8 --sun 90,-5 --shadows");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "overflight: --sun: warning: elevation -5 is at or below the horizon: ambient light only\n");
    EXPECT_TRUE(std::filesystem::exists(out));
}

// --time HH:MM puts the sun where fly's time-of-day keys do: at noon due
// south at 60 degrees, the same picture as --sun 180,60; another hour another.
TEST(RenderVoxelCli, TimeOfDaySetsTheSun) {
    ScratchDir dir;
    const std::string base = "render demo --demo-size 33 --size 32x16 --shadows -o '";
    const auto bytes = [](const std::string& path) {
        std::ifstream in(path, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    };
    ASSERT_EQ(run_overflight(base + dir / "noon.png" + "' --time 12:00").exit_code, 0);
    ASSERT_EQ(run_overflight(base + dir / "sun.png" + "' --sun 180,60").exit_code, 0);
    ASSERT_EQ(run_overflight(base + dir / "morning.png" + "' --time 07:30").exit_code, 0);
    EXPECT_EQ(bytes(dir / "noon.png"), bytes(dir / "sun.png"));
    EXPECT_NE(bytes(dir / "noon.png"), bytes(dir / "morning.png"));
    const RunResult night = run_overflight(base + dir / "night.png" + "' --time 22:15");
    EXPECT_EQ(night.exit_code, 0) << night.err;
    EXPECT_EQ(night.err, "overflight: --time: warning: the sun is at or below the horizon at 22:15: ambient light only\n");
}

// The method's lighting, its water and the compositor's shadow ceiling share
// one horizon sweep for the run's sun, as in `fly`.
TEST(RenderCli, OneSunSweepPerRender) {
    ScratchDir dir;
    for (const char* method : {"voxel", "mesh"}) {
        const std::string base = std::string("render demo --demo-size 65 --size 32x16 --stats --method ") + method +
                                 " -o '" + dir / (std::string(method) + ".png") + "'";
        const RunResult lit = run_overflight(base + " --shadows --water --sun 250,25");
        ASSERT_EQ(lit.exit_code, 0) << lit.err;
        EXPECT_EQ(nlohmann::json::parse(lit.out)["sun_sweeps"], 1) << method;
        const RunResult plain = run_overflight(base);
        ASSERT_EQ(plain.exit_code, 0) << plain.err;
        EXPECT_EQ(nlohmann::json::parse(plain.out)["sun_sweeps"], 0) << method;
    }
}

TEST(RenderVoxelCli, LiteralNeedsShear) {
    ScratchDir dir;
    const RunResult r = run_overflight("render demo --demo-size 33 -o '" + dir / "x.png" +
                                       "' --size 16x8 --method voxel-literal --projection tilt");
    EXPECT_NE(r.exit_code, 0);
    EXPECT_EQ(r.err.rfind("overflight: --projection:", 0), 0u) << r.err;
}

// --atmosphere changes the picture of an image method and of a mesh method
// (sky and terrain), and nothing else about the run.
TEST(RenderCli, AtmosphereReachesEveryKindOfMethod) {
    ScratchDir dir;
    for (const char* method : {"voxel", "mesh"}) {
        Png with_air, without;
        for (bool air : {false, true}) {
            const std::string out = dir / (std::string(method) + (air ? "_air.png" : ".png"));
            const RunResult r = run_overflight("render demo --demo-size 65 --size 48x32 --pitch 5 --method " +
                                               std::string(method) + " -o '" + out + "'" + (air ? " --atmosphere" : ""));
            ASSERT_EQ(r.exit_code, 0) << r.err;
            (air ? with_air : without) = read_png(out);
        }
        ASSERT_EQ(with_air.rgb.size(), without.rgb.size());
        EXPECT_NE(with_air.rgb, without.rgb) << method;
        // The top row is sky in both: the atmosphere's sky is another color.
        EXPECT_NE(std::vector<unsigned char>(with_air.at(0, 0), with_air.at(0, 0) + 3),
                  std::vector<unsigned char>(without.at(0, 0), without.at(0, 0) + 3))
            << method;
    }
}

// bench --atmosphere times each method without and with it in one run.
TEST(BenchCli, AtmosphereIsTimedBesideThePlainRun) {
    const RunResult r =
        run_overflight("bench demo --demo-size 65 --json --size 40x24 --frames 2 --methods voxel,mesh --atmosphere");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    ASSERT_EQ(j["runs"].size(), 4u);
    EXPECT_EQ(j["runs"][0]["method"], "voxel");
    EXPECT_EQ(j["runs"][1]["method"], "voxel+looks");
    EXPECT_EQ(j["runs"][3]["method"], "mesh+looks");
    EXPECT_GT(j["runs"][1]["x_without_looks"].get<double>(), 0.0);
}

TEST(BenchCli, JsonListsVoxelAndLiteral) {
    const RunResult r =
        run_overflight("bench demo --demo-size 65 --json --size 40x24 --frames 2 --methods voxel,voxel-literal");
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

// bench --lod measures the distance LOD's outline against the exact cast at 1080p.
TEST(BenchCli, LodReportsItsOutlineAgainstTheExactCast) {
    const RunResult r = run_overflight("bench demo --demo-size 65 --json --size 40x24 --frames 1 --methods voxel --lod");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    ASSERT_EQ(j["runs"].size(), 1u);
    const auto& a = j["runs"][0]["lod_accuracy"];
    EXPECT_EQ(a["width"], 1920);
    EXPECT_EQ(a["height"], 1080);
    for (const char* share : {"sky_mask_agreement", "silhouette_within_1px"}) {
        EXPECT_GT(a[share].get<double>(), 0.9) << share;
        EXPECT_LE(a[share].get<double>(), 1.0) << share;
    }
    // Without --lod there is nothing to compare.
    const RunResult exact = run_overflight("bench demo --demo-size 65 --json --size 40x24 --frames 1 --methods voxel");
    ASSERT_EQ(exact.exit_code, 0) << exact.err;
    EXPECT_FALSE(nlohmann::json::parse(exact.out)["runs"][0].contains("lod_accuracy"));
}

TEST(BenchCli, DefaultRunsEveryMethodWithStepsAndAccuracy) {
    const RunResult r = run_overflight("bench demo --demo-size 65 --json --size 64x36 --frames 1");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    std::set<std::string> methods;
    for (const auto& run : j["runs"]) methods.insert(run["method"].get<std::string>());
    for (const char* m : {"voxel", "voxel+present", "voxel+objects", "voxel-literal", "mesh", "points", "top-faces",
                          "front-faces", "segments", "blocks", "roam", "quadtree"})
        EXPECT_TRUE(methods.count(m)) << m;
    for (const auto& run : j["runs"]) {
        const std::string m = run["method"];
        if (m == "voxel+objects") {
            for (const char* step : {"raycast", "color_upload", "depth_upload", "objects", "present"})
                EXPECT_TRUE(run["steps_ms"].contains(step)) << step;
        }
        if (m == "roam") {
            EXPECT_GT(run["triangles_per_s"].get<double>(), 0.0);
            EXPECT_GT(run["ms_tessellate_100000"].get<double>(), 0.0);
            EXPECT_EQ(run["error_curve"].size(), 7u); // 4k .. 256k
        }
        if (m == "roam" || m == "quadtree") {
            EXPECT_GT(run["depth_within_3pct"].get<double>(), 0.5) << m;
            EXPECT_GT(run["triangles"].get<long long>(), 0) << m;
        }
    }
    const RunResult md = run_overflight("bench demo --demo-size 65 --markdown --size 64x36 --frames 1 "
                                        "--methods voxel,voxel+present,voxel+objects,blocks");
    ASSERT_EQ(md.exit_code, 0) << md.err;
    EXPECT_NE(md.out.find("Szenberg Table 1"), std::string::npos) << md.out;
    EXPECT_NE(md.out.find("Szenberg Table 2"), std::string::npos) << md.out;
}

TEST(RenderCli, EveryMethodWritesImageDepthAndStats) {
    ScratchDir dir;
    for (const char* m : {"voxel", "voxel-literal", "raymarch", "mesh", "points", "top-faces", "front-faces",
                          "segments", "blocks", "roam", "quadtree"}) {
        const std::string png = dir / (std::string(m) + ".png"), tif = dir / (std::string(m) + ".tif");
        const RunResult r = run_overflight("render demo --demo-size 129 --size 64x36 --method " + std::string(m) +
                                           " -o '" + png + "' --depth '" + tif + "' --stats --triangles 5000 --error 2");
        ASSERT_EQ(r.exit_code, 0) << m << ": " << r.err;
        EXPECT_TRUE(std::filesystem::exists(png)) << m;
        EXPECT_TRUE(std::filesystem::exists(tif)) << m;
        const auto j = nlohmann::json::parse(r.out);
        EXPECT_EQ(j["method"], m);
        EXPECT_TRUE(j["ms"].contains("render")) << m;
        if (std::string(m) == "roam") {
            EXPECT_LE(j["triangles"].get<long long>(), 5000);
            EXPECT_GE(j["triangles"].get<long long>(), 4998);
            for (const char* k : {"tessellate", "upload", "terrain"}) EXPECT_TRUE(j["ms"].contains(k)) << k;
            EXPECT_TRUE(j.contains("max_error_px") && j.contains("mean_error_px"));
        }
        if (std::string(m) == "quadtree") {
            EXPECT_EQ(j["error_px"], 2.0);
            for (const char* k : {"tiles_visible", "tiles_culled", "tiles_loaded", "tiles_streamed", "tiles_per_level",
                                  "bound_mib"})
                EXPECT_TRUE(j.contains(k)) << k;
        }
    }
    const RunResult bad = run_overflight("render demo --demo-size 65 -o '" + dir / "x.png" + "' --method roam --triangles 1");
    EXPECT_NE(bad.exit_code, 0);
    EXPECT_EQ(bad.err.rfind("overflight: --triangles:", 0), 0u) << bad.err;
    const RunResult bad_bound =
        run_overflight("render demo --demo-size 65 -o '" + dir / "x.png" + "' --method quadtree --cache-mib 0");
    EXPECT_EQ(bad_bound.err.rfind("overflight: --cache-mib:", 0), 0u) << bad_bound.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

// A big red box placed by --scene in front of the camera shows in the
// composite and in the mesh image alike.
TEST(RenderCli, SceneObjectsAppearOverEveryMethod) {
    ScratchDir dir;
    {
        std::ofstream f(dir / "scene.toml");
        f << "[[object]]\nkind = \"box\"\nx = 1280.0\nz = 1300.0\nwidth = 120.0\nheight = 2500.0\n"
             "depth = 120.0\ncolor = [255, 0, 0]\n";
    }
    // The box's pixels: lit and fogged red, far from any terrain color.
    auto red_mask = [](const Png& img) {
        std::vector<bool> mask(img.rgb.size() / 3);
        for (std::size_t i = 0; i < mask.size(); ++i) {
            const unsigned char* p = &img.rgb[3 * i];
            mask[i] = p[0] >= p[1] + 35 && p[0] >= p[2] + 30;
        }
        return mask;
    };
    std::vector<bool> voxel_mask;
    for (const char* m : {"voxel", "mesh", "roam", "quadtree"}) {
        const std::string png = dir / (std::string(m) + ".png");
        const RunResult r = run_overflight("render demo --demo-size 257 --size 96x54 --method " + std::string(m) +
                                           " -o '" + png + "' --eye 1280,1700,2100 --heading 180 --pitch -30 --scene '" +
                                           dir / "scene.toml" + "' --stats");
        ASSERT_EQ(r.exit_code, 0) << m << ": " << r.err;
        EXPECT_GE(nlohmann::json::parse(r.out)["object_triangles"].get<long long>(), 12) << m;
        const std::vector<bool> mask = red_mask(read_png(png));
        const long long red = std::count(mask.begin(), mask.end(), true);
        EXPECT_GT(red, 40) << m;
        if (voxel_mask.empty()) {
            voxel_mask = mask;
            continue;
        }
        long long both = 0, either = 0;
        for (std::size_t i = 0; i < mask.size(); ++i) {
            both += mask[i] && voxel_mask[i];
            either += mask[i] || voxel_mask[i];
        }
        EXPECT_GE(double(both) / double(either), 0.9) << m << " vs voxel: " << both << " of " << either;
    }
    const RunResult bad = run_overflight("render demo --demo-size 65 -o '" + dir / "y.png" + "' --scene '" +
                                         dir / "missing.toml" + "'");
    EXPECT_NE(bad.exit_code, 0);
    EXPECT_NE(bad.err.find("missing.toml"), std::string::npos) << bad.err;
    EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1);
    EXPECT_FALSE(std::filesystem::exists(dir / "y.png"));
}

TEST(BenchCli, MarkdownTable) {
    const RunResult r = run_overflight("bench demo --demo-size 33 --markdown --size 16x8 --frames 1 --methods voxel");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("| voxel |"), std::string::npos) << r.out;
    const RunResult bad = run_overflight("bench demo --demo-size 33 --frames 0");
    EXPECT_NE(bad.exit_code, 0);
    EXPECT_EQ(bad.err.rfind("overflight: --frames:", 0), 0u) << bad.err;
}
