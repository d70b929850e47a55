// The four terrain methods of `overflight fly` (mesh, voxel, roam, quadtree)
// in a real GLFW window under xvfb-run: they share one camera, every one of
// them draws a frame, and the objects are composited by depth over each of
// them (Szenberg et al. 1997 sec. 5: "a building must not move in the terrain").
//
// Most checks use a data set written here, small enough to reason about by
// hand: a flat plane 10 m high, 129 x 129 samples 1 m apart, brown checker
// colors, no fog; the vehicle at (64, 100) facing north (heading 180), so the
// chase camera (12 m behind, 4 m above) looks north over the plane and sees
// sky above the horizon and ground below it.
#include "ReadPng.h"
#include "TestSupport.h"
#include "core/Camera.h"
#include "io/FlightRecordFile.h"
#include "io/HovercraftDataSet.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace overflight;
using overflight::test::Png;
using overflight::test::read_png;
using overflight::test::run_overflight;
using overflight::test::ScratchDir;

namespace {

// Sky (blue gradient) against the brown ground and the objects, which are
// all redder than they are blue.
bool is_sky(const unsigned char* c) { return c[2] > c[0]; }
// The test box's magenta, whatever its lighting: red and blue well above green.
bool is_magenta(const unsigned char* c) { return c[0] > 2 * c[1] + 30 && c[2] > 2 * c[1] + 30; }

long count(const Png& p, bool (*pred)(const unsigned char*)) {
    long n = 0;
    for (int y = 0; y < p.h; ++y)
        for (int x = 0; x < p.w; ++x) n += pred(p.at(x, y));
    return n;
}

constexpr double kGround = 10.0;  // world height of the plane
constexpr double kBoxX = 64, kBoxZ = 85, kBoxSize = 4; // 15 m ahead of the vehicle

// Writes the flat data set to `dir`; `scene` is appended to its map as is.
void write_flat_data_set(const std::string& dir, const Scene& scene) {
    DataSet d;
    d.terrain = Terrain(129, 129, 1.0f, 0.1f);
    for (int r = 0; r < 129; ++r)
        for (int c = 0; c < 129; ++c) {
            d.terrain.raw(r, c) = std::uint16_t(kGround / 0.1);
            d.terrain.color(r, c) = ((r / 8 + c / 8) % 2) ? Rgb8{200, 120, 60} : Rgb8{140, 85, 45};
        }
    d.environment.fog_density = 0; // the fog toggle starts off
    d.start = VehicleStart{true, 64.0, 100.0, 180.0};
    d.scene = scene;
    save_hovercraft(dir, d);
}

SceneObject magenta_box(double base_y) {
    SceneObject box;
    box.kind = ObjectKind::Box;
    box.x = kBoxX;
    box.z = kBoxZ;
    box.y = base_y;
    box.width = box.height = box.depth = kBoxSize;
    box.color = Rgb8{255, 0, 255};
    return box;
}

// The window's camera of frame `i` of a record (fly's fov 60, the test's size).
Camera recorded_camera(const FlightRecord& r, std::size_t i, int w, int h) {
    Camera c;
    c.eye = r.frames[i].eye;
    c.heading = r.frames[i].heading;
    c.pitch = r.frames[i].pitch;
    c.width = w;
    c.height = h;
    c.near = 0.5;
    c.far = 1000;
    return c;
}

const std::vector<std::string> kMethods = {"mesh", "voxel", "roam", "quadtree"};

// "method,frames,..." lines -> method -> (frames, triangles per frame).
std::map<std::string, std::pair<long, long>> method_rows(const std::string& out) {
    std::istringstream in(out);
    std::string line;
    std::getline(in, line);
    std::map<std::string, std::pair<long, long>> rows;
    while (std::getline(in, line)) {
        std::vector<std::string> f;
        std::istringstream cols(line);
        for (std::string col; std::getline(cols, col, ',');) f.push_back(col);
        if (f.size() >= 4) rows[f[0]] = {std::stol(f[1]), std::stol(f[3])};
    }
    return rows;
}

} // namespace

TEST(FlyMethods, TabShowsAllFourMethodsFromTheSameCamera) {
    ScratchDir dir;
    write_flat_data_set(dir / "flat", Scene{});
    // P on the last frame of each method, Tab after it: frames 0-4 mesh,
    // 5-9 voxel, 10-14 roam, 15-19 quadtree. The vehicle stays at rest, so
    // every frame has the same camera.
    const auto r = run_overflight("fly '" + (dir / "flat") + "' --size 320x180 --frames 20 --no-hud "
                                  "--press screenshot:4-5 next-method:5-6 screenshot:9-10 next-method:10-11 "
                                  "screenshot:14-15 next-method:15-16 screenshot:19-20 "
                                  "--screenshot '" + (dir / "tab.png") + "' --record '" + (dir / "f.csv") + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto rows = method_rows(r.out);
    ASSERT_EQ(rows.size(), 4u) << r.out;
    for (const std::string& m : kMethods) {
        ASSERT_TRUE(rows.count(m)) << m << "\n" << r.out;
        EXPECT_EQ(rows.at(m).first, 5) << m;
        // The mesh methods report triangles; the ray caster none.
        if (m == "voxel") EXPECT_EQ(rows.at(m).second, 0);
        else EXPECT_GE(rows.at(m).second, 2) << m;
    }
    const FlightRecord rec = read_flight_record(dir / "f.csv");
    ASSERT_EQ(rec.frames.size(), 20u);
    for (const FlightFrame& f : rec.frames) {
        EXPECT_EQ(f.eye, rec.frames[0].eye);
        EXPECT_EQ(f.pitch, rec.frames[0].pitch);
    }
    // P also saved each frame's camera file.
    for (int k = 0; k < 4; ++k) {
        const auto cam = nlohmann::json::parse(test::read_file_text(dir / ("tab-00" + std::to_string(k) + ".json")));
        EXPECT_EQ(cam["eye"], nlohmann::json::array({rec.frames[0].eye.x, rec.frames[0].eye.y, rec.frames[0].eye.z}));
        EXPECT_EQ(cam["pitch"], rec.frames[0].pitch);
        EXPECT_EQ(cam["width"], 320);
    }

    // Each method's frame has sky above the horizon and ground below it, and
    // all four put the horizon and the plane's far edge on the same pixels.
    std::vector<Png> shots;
    for (int k = 0; k < 4; ++k) {
        shots.push_back(read_png(dir / ("tab-00" + std::to_string(k) + ".png")));
        ASSERT_EQ(shots.back().w, 320) << kMethods[std::size_t(k)];
        ASSERT_EQ(shots.back().h, 180);
    }
    const long pixels = 320 * 180;
    for (int k = 0; k < 4; ++k) {
        SCOPED_TRACE(kMethods[std::size_t(k)]);
        const Png& p = shots[std::size_t(k)];
        EXPECT_TRUE(is_sky(p.at(160, 0)));
        EXPECT_FALSE(is_sky(p.at(160, 179)));
        const long sky = count(p, is_sky);
        EXPECT_GT(sky, pixels / 10);
        EXPECT_LT(sky, pixels * 9 / 10);
        long disagree = 0;
        for (int y = 0; y < 180; ++y)
            for (int x = 0; x < 320; ++x) disagree += is_sky(p.at(x, y)) != is_sky(shots[0].at(x, y));
        EXPECT_LT(double(disagree) / double(pixels), 0.01);
    }
}

TEST(FlyMethods, ObjectsAreCompositedByDepthOverEveryMethod) {
    ScratchDir dir;
    // A magenta box standing on the plane 15 m ahead of the vehicle...
    Scene standing;
    standing.objects.push_back(magenta_box(kGround));
    write_flat_data_set(dir / "standing", standing);
    // ...and the same box sunk under the plane (top 2 m below the ground):
    // in view, but behind the terrain's depth.
    Scene sunk;
    sunk.objects.push_back(magenta_box(kGround - 2 - kBoxSize));
    write_flat_data_set(dir / "sunk", sunk);

    // Every method of the table can be shown in fly (--method), not only the
    // Tab cycle: the brute-force ray marcher composites the same box.
    std::vector<std::string> methods = kMethods;
    methods.push_back("raymarch");
    for (const std::string& m : methods) {
        SCOPED_TRACE(m);
        const std::string common = " --size 320x180 --frames 2 --no-hud --method " + m;
        auto r = run_overflight("fly '" + (dir / "standing") + "'" + common + " --screenshot '" + (dir / "a.png") +
                                "' --record '" + (dir / "a.csv") + "'");
        ASSERT_EQ(r.exit_code, 0) << r.err;
        const Png a = read_png(dir / "a.png");
        ASSERT_FALSE(a.empty());
        // The box is drawn over the terrain where it projects: the centre of
        // its top and the foot of its face towards the camera lie on magenta
        // pixels (a 4 m box 25 m from the eye spans about 40 pixels).
        const Camera cam = recorded_camera(read_flight_record(dir / "a.csv"), 1, 320, 180);
        const Camera::Projected base = cam.project({kBoxX, kGround + 0.5, kBoxZ + kBoxSize / 2});
        const Camera::Projected top = cam.project({kBoxX, kGround + kBoxSize, kBoxZ});
        ASSERT_TRUE(base.in_front && top.in_front);
        for (const Camera::Projected& p : {base, top}) {
            ASSERT_TRUE(p.col > 0 && p.col < 320 && p.row > 0 && p.row < 180);
            EXPECT_TRUE(is_magenta(a.at(int(p.col), int(p.row)))) << p.col << "," << p.row;
        }
        EXPECT_GT(count(a, is_magenta), 400);

        r = run_overflight("fly '" + (dir / "sunk") + "'" + common + " --screenshot '" + (dir / "b.png") + "'");
        ASSERT_EQ(r.exit_code, 0) << r.err;
        const Png b = read_png(dir / "b.png");
        ASSERT_FALSE(b.empty());
        // Its top face projects inside the image, below the standing box's base...
        const Camera::Projected sunk_top = cam.project({kBoxX, kGround - 2, kBoxZ});
        ASSERT_TRUE(sunk_top.in_front && sunk_top.row > base.row && sunk_top.row < 180);
        // ...but the terrain's depth hides every pixel of it.
        EXPECT_EQ(count(b, is_magenta), 0);
    }
}

TEST(FlyMethods, VoxelReplayMatchesTheWindow) {
    ScratchDir dir;
    Scene standing;
    standing.objects.push_back(magenta_box(kGround));
    write_flat_data_set(dir / "flat", standing);
    const std::string data = "'" + (dir / "flat") + "' --size 320x180 --method voxel ";
    auto r = run_overflight("fly " + data + "--frames 20 --no-hud --press accelerate:0-20 left:5-15 --record '" +
                            (dir / "f.csv") + "' --screenshot '" + (dir / "last.png") + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = run_overflight("fly " + data + "--replay '" + (dir / "f.csv") + "' --out '" + (dir / "frames") + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto rows = method_rows(r.out);
    ASSERT_TRUE(rows.count("voxel")) << r.out;
    EXPECT_EQ(rows.at("voxel").first, 20);
    // Same camera, same ray caster, same objects, and the same composite (the
    // window's is drawn offscreen like the headless one and blitted): the
    // window's last frame and the headless replay are the same pixels, though
    // the window cast it one frame ahead of drawing it.
    const Png a = read_png(dir / "last.png"), b = read_png(dir / "frames/frame_00019.png");
    ASSERT_EQ(a.rgb.size(), b.rgb.size());
    ASSERT_FALSE(a.empty());
    long differing = 0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) differing += a.rgb[i] != b.rgb[i];
    EXPECT_EQ(differing, 0);
    EXPECT_GT(count(b, is_magenta), 100);
}

TEST(FlyMethods, DetailKeysScaleTheRoamBudgetAndTheQuadtreeError) {
    // On the demo island's relief (513^2, whose start looks across the
    // island to mountains kilometres away): `_` at frame 0 takes ROAM's
    // budget from 65536 one sqrt 2 step down, to round(2^15.5) = 46341
    // triangles, which split-only ROAM fills to within one triangle; the
    // quadtree's error grows by sqrt 2 (fewer triangles) with `_` and shrinks
    // with `+` (more).
    const std::string fly = "fly demo --demo-size 513 --size 320x180 --frames 2 --no-hud --method ";
    auto triangles = [&](const std::string& method, const std::string& press) {
        const auto r = run_overflight(fly + method + (press.empty() ? "" : " --press " + press));
        EXPECT_EQ(r.exit_code, 0) << r.err;
        const auto rows = method_rows(r.out);
        return rows.count(method) ? rows.at(method).second : -1L;
    };
    const long roam_down = triangles("roam", "detail-down:0-1");
    EXPECT_GE(roam_down, 46340);
    EXPECT_LE(roam_down, 46341);
    const long quad = triangles("quadtree", "");
    EXPECT_LT(triangles("quadtree", "detail-down:0-1"), quad);
    EXPECT_GT(triangles("quadtree", "detail-up:0-1"), quad);
}
