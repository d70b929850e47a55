// `overflight fly` in a real GLFW window (run under xvfb-run, Mesa llvmpipe):
// unattended scripted flights, Tab cycling the methods, record and replay, on
// the demo island. The methods themselves: fly_methods_test.cpp.
#include "ReadPng.h"
#include "TestSupport.h"
#include "io/FlightRecordFile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <vector>

using namespace overflight;
using overflight::test::Png;
using overflight::test::read_png;
using overflight::test::run_overflight;
using overflight::test::ScratchDir;

namespace {

// "method,frames,fps,triangles_per_frame" lines -> (method, frames).
std::vector<std::pair<std::string, long>> method_frames(const std::string& out) {
    std::istringstream in(out);
    std::string line;
    std::getline(in, line);
    std::vector<std::pair<std::string, long>> v;
    while (std::getline(in, line)) {
        const auto c1 = line.find(','), c2 = line.find(',', c1 + 1);
        v.emplace_back(line.substr(0, c1), std::stol(line.substr(c1 + 1, c2 - c1 - 1)));
    }
    return v;
}

// The Tab cycle `fly --help` states: "Tab cycles mesh -> voxel -> ...)".
std::vector<std::string> tab_cycle() {
    const auto r = run_overflight("fly --help");
    std::vector<std::string> names;
    const auto open = r.out.find("Tab cycles ");
    if (open == std::string::npos) return names;
    std::istringstream in(r.out.substr(open + 11, r.out.find(')', open) - open - 11));
    for (std::string name; in >> name;)
        if (name != "->") names.push_back(name);
    return names;
}

const char* kFly = "fly demo --demo-size 257 --size 320x180 ";

} // namespace

TEST(FlyWindow, UnattendedRunSavesAScreenshotThatIsNotBlank) {
    ScratchDir dir;
    const std::string shot = dir / "shot.png";
    const auto r = run_overflight(std::string(kFly) + "--frames 40 --press accelerate:0-40 left:10-20 --screenshot '" +
                                  shot + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Png p = read_png(shot);
    ASSERT_EQ(p.w, 320);
    ASSERT_EQ(p.h, 180);
    // Not blank: many distinct colors, and both sky (top rows) and ground.
    std::set<unsigned> colors;
    for (std::size_t i = 0; i < p.rgb.size(); i += 3)
        colors.insert(unsigned(p.rgb[i]) << 16 | unsigned(p.rgb[i + 1]) << 8 | p.rgb[i + 2]);
    EXPECT_GT(colors.size(), 200u);
    const auto frames = method_frames(r.out);
    ASSERT_EQ(frames.size(), 1u);
    EXPECT_EQ(frames[0].second, 40);
    // Nothing else was left in the folder.
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path), {}), 1);
}

// The demo starts with GL_EXP fog; one `f` turns the atmosphere on, which is
// where `--atmosphere` starts: the same picture, unlike the fog's.
TEST(FlyWindow, FogKeyReachesTheAtmosphereOfTheCommandLine) {
    ScratchDir dir;
    const std::string fog = dir / "fog.png", key = dir / "key.png", flag = dir / "flag.png";
    for (const auto& [args, shot] : {std::pair<std::string, std::string>{"", fog}, {"--press fog:0-1 ", key},
                                     {"--atmosphere ", flag}}) {
        const auto r = run_overflight(std::string(kFly) + "--method voxel --frames 3 " + args + "--screenshot '" + shot + "'");
        ASSERT_EQ(r.exit_code, 0) << r.err;
    }
    const Png a = read_png(fog), b = read_png(key), c = read_png(flag);
    ASSERT_FALSE(a.empty() || b.empty() || c.empty());
    EXPECT_EQ(b.rgb, c.rgb);
    EXPECT_NE(a.rgb, c.rgb);
}

TEST(FlyWindow, TabCyclesThroughTheMethodsWithTheSameCamera) {
    const std::vector<std::string> methods = tab_cycle();
    ASSERT_EQ(methods, (std::vector<std::string>{"mesh", "voxel", "roam", "quadtree"}));
    // A Tab every 5 frames while flying: the frames split 5 / 5 / 5 / 5 over
    // the methods in order, and the fifth Tab wraps around to mesh.
    ScratchDir dir;
    const auto r = run_overflight(std::string(kFly) + "--frames 25 --press accelerate:0-25 next-method:5-6 "
                                  "next-method:10-11 next-method:15-16 next-method:20-21 --record '" +
                                  (dir / "f.csv") + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::map<std::string, long> got;
    for (const auto& [m, n] : method_frames(r.out)) got[m] += n;
    const std::map<std::string, long> expected = {{"mesh", 10}, {"voxel", 5}, {"roam", 5}, {"quadtree", 5}};
    EXPECT_EQ(got, expected);
    // The camera path is continuous across the switches (same camera): no jump
    // at a switch larger than the vehicle's travel.
    const FlightRecord rec = read_flight_record(dir / "f.csv");
    ASSERT_EQ(rec.frames.size(), 25u);
    for (std::size_t i = 1; i < rec.frames.size(); ++i) {
        const glm::dvec3 d = rec.frames[i].eye - rec.frames[i - 1].eye;
        EXPECT_LT(std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z), 5.0) << "frame " << i;
    }
}

TEST(FlyWindow, RecordedFlightReplaysToTheSameCameraPath) {
    ScratchDir dir;
    const std::string rec = dir / "flight.csv", shot = dir / "last.png";
    auto r = run_overflight(std::string(kFly) + "--frames 30 --press accelerate:0-30 right:5-25 --record '" + rec +
                            "' --screenshot '" + shot + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const FlightRecord flown = read_flight_record(rec);
    ASSERT_EQ(flown.frames.size(), 30u);
    EXPECT_GT(flown.frames.back().velocity, 0.5);
    EXPECT_NE(flown.frames.back().vehicle_heading, flown.frames.front().vehicle_heading); // it turned
    // The same scripted flight again gives the same record: time is simulated.
    const std::string rec2 = dir / "again.csv";
    r = run_overflight(std::string(kFly) + "--frames 30 --press accelerate:0-30 right:5-25 --record '" + rec2 + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(read_flight_record(rec2), flown);
    // Headless replay renders every recorded camera and reports the path it rendered.
    const std::string out = dir / "frames", replayed = dir / "replayed.csv";
    r = run_overflight(std::string(kFly) + "--replay '" + rec + "' --out '" + out + "' --record '" + replayed + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(read_flight_record(replayed), flown);
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(out), {}), 30);
    // The last replayed frame is the window's last frame (same camera, same
    // renderer; window and headless contexts may round a few pixels apart).
    const Png a = read_png(shot), b = read_png(out + "/frame_00029.png");
    ASSERT_EQ(a.rgb.size(), b.rgb.size());
    ASSERT_FALSE(a.rgb.empty());
    long over = 0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) over += std::abs(int(a.rgb[i]) - int(b.rgb[i])) > 8;
    EXPECT_LT(double(over) / double(a.rgb.size()), 0.01);
}

TEST(FlyWindow, BadOptionsAreOneLineErrors) {
    ScratchDir dir;
    struct Case { std::string args, subject; };
    for (const Case& c : {Case{"--frames 5 --method warp", "--method"},
                          Case{"--frames 5 --press jump:0-3", "--press"},
                          Case{"--screenshot x.png", "--screenshot"},
                          Case{"--replay '" + (dir / "missing.csv") + "' --out '" + (dir / "o") + "'",
                               dir / "missing.csv"},
                          Case{"--frames 5 --fov 60 --size 10", "--size"},
                          Case{"--frames 5 --cache-mib 0", "--cache-mib"}}) {
        SCOPED_TRACE(c.args);
        std::string args = std::string(kFly) + c.args;
        if (c.subject == "--size") args = "fly demo --demo-size 33 " + c.args; // kFly sets a size already
        const auto r = run_overflight(args);
        EXPECT_EQ(r.exit_code, 1);
        EXPECT_EQ(overflight::test::line_count(r.err), 1) << r.err;
        EXPECT_EQ(r.err.rfind("overflight: " + c.subject + ":", 0), 0u) << r.err;
    }
}

// A tile directory flies like any terrain: the quadtree reads its tiles
// lazily within --cache-mib (a 1 MiB bound streams them and draws the same
// image), the other methods and the vehicle use its overview (here the whole
// terrain); a broken index fails before the window opens.
TEST(FlyWindow, TileDirectoryFliesTheQuadtreeOverLazilyReadTiles) {
    ScratchDir dir;
    const std::string tiles = dir / "t";
    ASSERT_EQ(run_overflight("tile demo --demo-size 257 --tile-size 33 -o '" + tiles + "'").exit_code, 0);
    const std::string fly = "fly '" + tiles + "' --size 320x180 --frames 20 --press accelerate:0-20 ";
    auto shot = [&](const std::string& args, const std::string& name) {
        const auto r = run_overflight(fly + args + " --screenshot '" + (dir / name) + "'");
        EXPECT_EQ(r.exit_code, 0) << r.err;
        return std::make_pair(read_png(dir / name), r.out);
    };
    const auto [streamed, streamed_out] = shot("--method quadtree --cache-mib 1", "q1.png");
    const auto [cached, cached_out] = shot("--method quadtree", "q.png");
    const auto [mesh, mesh_out] = shot("--method mesh", "m.png");
    ASSERT_FALSE(streamed.rgb.empty());
    EXPECT_EQ(streamed.rgb, cached.rgb);
    // Fewer triangles than the full mesh (17642 against 131072 on 257^2).
    const auto triangles = [](const std::string& out) {
        const std::string row = out.substr(out.find('\n') + 1);
        std::size_t at = 0;
        for (int i = 0; i < 3; ++i) at = row.find(',', at) + 1;
        return std::stol(row.substr(at));
    };
    EXPECT_LT(triangles(cached_out) * 4, triangles(mesh_out));
    // At 1 px the quadtree's frame is the full mesh's but for shading along
    // coarser triangles.
    ASSERT_EQ(mesh.rgb.size(), cached.rgb.size());
    long close = 0;
    for (std::size_t i = 0; i < mesh.rgb.size(); ++i) close += std::abs(int(mesh.rgb[i]) - int(cached.rgb[i])) <= 24;
    EXPECT_GT(double(close) / double(mesh.rgb.size()), 0.95);

    std::filesystem::create_directories(dir / "bad");
    std::ofstream(dir / "bad/index.json") << "{";
    const auto bad = run_overflight("fly '" + (dir / "bad") + "' --method quadtree --frames 2");
    EXPECT_EQ(bad.exit_code, 1);
    EXPECT_EQ(overflight::test::line_count(bad.err), 1) << bad.err;
    EXPECT_NE(bad.err.find("index.json"), std::string::npos) << bad.err;
}
