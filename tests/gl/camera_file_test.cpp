// Camera files (DESIGN sec. 6.1): a view saved with --save-camera renders
// again from --camera to the same bytes, with the voxel renderer and the mesh
// renderer; options beside --camera override its fields; a bad file is one
// line naming it.
#include "TestSupport.h"
#include "io/Files.h"
#include "sim/FlightRecord.h"

#include <nlohmann/json.hpp>

namespace overflight {
namespace {

using test::run_overflight;
using test::ScratchDir;

bool same_bytes(const std::string& a, const std::string& b) { return read_file_bytes(a) == read_file_bytes(b); }

TEST(CameraFile, RoundTripGivesTheSameImages) {
    ScratchDir dir;
    const std::string demo = "render demo --demo-size 257 ";
    for (const char* method : {"voxel", "mesh"}) {
        const std::string m = method;
        const std::string saved = dir / (m + ".json");
        // An eye, heading and pitch no default would give, and a tilted camera.
        test::RunResult r = run_overflight(demo + "--method " + m + " -o '" + dir / (m + "_a.png") + "' --depth '" +
                                           dir / (m + "_a.tif") + "' --size 96x64 --at 1300,1900 --agl 37.5 "
                                           "--heading 33.3 --pitch -7.25 --fov 55 --projection tilt --save-camera '" +
                                           saved + "'");
        ASSERT_EQ(r.exit_code, 0) << r.err;
        r = run_overflight(demo + "--method " + m + " -o '" + dir / (m + "_b.png") + "' --depth '" + dir / (m + "_b.tif") +
                           "' --camera '" + saved + "'");
        ASSERT_EQ(r.exit_code, 0) << r.err;
        EXPECT_TRUE(same_bytes(dir / (m + "_a.png"), dir / (m + "_b.png"))) << m;
        EXPECT_TRUE(same_bytes(dir / (m + "_a.tif"), dir / (m + "_b.tif"))) << m;
        // Saved again from the file, the camera is the same text.
        r = run_overflight(demo + "--method " + m + " -o '" + dir / (m + "_c.png") + "' --camera '" + saved +
                           "' --save-camera '" + dir / (m + "_again.json") + "'");
        ASSERT_EQ(r.exit_code, 0) << r.err;
        EXPECT_EQ(test::read_file_text(saved), test::read_file_text(dir / (m + "_again.json")));
    }
    // The demo has no georeferencing: no map part.
    EXPECT_FALSE(nlohmann::json::parse(test::read_file_text(dir / "voxel.json")).contains("map"));
}

TEST(CameraFile, OptionsOverrideFieldsAndAnotherSizeKeepsTheFov) {
    ScratchDir dir;
    const std::string saved = dir / "view.json", again = dir / "again.json";
    ASSERT_EQ(run_overflight("render demo --demo-size 129 -o '" + dir / "a.png" + "' --size 64x48 --fov 40 --save-camera '" +
                             saved + "'").exit_code, 0);
    const test::RunResult r = run_overflight("render demo --demo-size 129 -o '" + dir / "b.png" + "' --camera '" + saved +
                                             "' --size 200x50 --pitch 3 --save-camera '" + again + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto a = nlohmann::json::parse(test::read_file_text(saved));
    const auto b = nlohmann::json::parse(test::read_file_text(again));
    EXPECT_EQ(b["width"], 200);
    EXPECT_EQ(b["height"], 50);
    EXPECT_EQ(b["fov"], 40.0);
    EXPECT_EQ(b["pitch"], 3.0);
    EXPECT_EQ(b["eye"], a["eye"]);
    EXPECT_EQ(b["heading"], a["heading"]);
}

TEST(CameraFile, BadFilesAreOneLineErrors) {
    ScratchDir dir;
    const std::pair<std::string, std::string> cases[] = {
        {"{not json", "not a camera file (not JSON)"},
        {"[1, 2]", "not a camera file (not a JSON object)"},
        {"{\"heading\": 3}", "no eye"},
        {"{\"eye\": [1, 2]}", "eye is not an array of three numbers"},
        {"{\"eye\": [1, 2, 3], \"fov\": \"wide\"}", "fov is not a number"},
        {"{\"eye\": [1, 2, 3], \"fov\": 200}", "fov 200"},
        {"{\"eye\": [1, 2, 3], \"width\": 0}", "width is not a whole number of pixels"},
        {"{\"eye\": [1, 2, 3], \"projection\": \"fisheye\"}", "projection is not"},
    };
    const std::string file = dir / "bad.json";
    for (const auto& [text, words] : cases) {
        std::ofstream(file) << text;
        const test::RunResult r = run_overflight("render demo --demo-size 65 -o '" + dir / "x.png" + "' --camera '" + file + "'");
        EXPECT_EQ(r.exit_code, 1) << text;
        EXPECT_EQ(test::line_count(r.err), 1) << r.err;
        EXPECT_EQ(r.err.rfind("overflight: " + file + ": ", 0), 0u) << r.err;
        EXPECT_NE(r.err.find(words), std::string::npos) << text << " -> " << r.err;
    }
    const test::RunResult r = run_overflight("render demo --demo-size 65 -o '" + dir / "x.png" + "' --camera '" + dir / "none.json" + "'");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err.rfind("overflight: " + dir / "none.json" + ": ", 0), 0u) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

TEST(CameraFile, FlightReplayWritesEachFramesCamera) {
    ScratchDir dir;
    FlightRecord record;
    for (int k = 0; k < 2; ++k) {
        FlightFrame f;
        f.frame = k;
        f.time = 0.01 * k;
        f.eye = {600.0 + 10.0 * k, 1500.0, 700.0};
        f.heading = 30.0 + k;
        f.pitch = -10.0;
        record.frames.push_back(f);
    }
    std::ofstream(dir / "rec.csv") << format_flight_record(record);
    const test::RunResult r = run_overflight("fly demo --demo-size 129 --replay '" + dir / "rec.csv" + "' --out '" +
                                             dir / "frames" + "' --size 64x48 --fov 50 --save-cameras");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (int k = 0; k < 2; ++k) {
        const std::string json = dir / ("frames/frame_0000" + std::to_string(k) + ".json");
        const auto j = nlohmann::json::parse(test::read_file_text(json));
        EXPECT_EQ(j["eye"], nlohmann::json::array({600.0 + 10.0 * k, 1500.0, 700.0}));
        EXPECT_EQ(j["heading"], 30.0 + k);
        EXPECT_EQ(j["pitch"], -10.0);
        EXPECT_EQ(j["fov"], 50.0);
        EXPECT_EQ(j["width"], 64);
        // The camera file renders (the view without the hovercraft).
        EXPECT_EQ(run_overflight("render demo --demo-size 129 --method mesh -o '" + dir / "r.png" + "' --camera '" + json + "'")
                      .exit_code, 0);
    }
}

} // namespace
} // namespace overflight
