// What `render` and `fly --replay` write, and what they print when they
// cannot (DESIGN sec. 6: one line naming the file or option, exit 1, nothing
// half-written left behind): full disks (tests/SmallFilesystem.h), missing
// folders, empty names, a recorded camera the renderers refuse, and file
// names a shell would interpret, which must reach ffmpeg verbatim. Label gl:
// both commands render through headless OpenGL.
#include "SmallFilesystem.h"
#include "TestSupport.h"
#include "core/DemoIsland.h"
#include "io/FlightRecordFile.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>

using namespace overflight;
using overflight::test::file_names_in;
using overflight::test::line_count;
using overflight::test::read_file_text;
using overflight::test::run_overflight;
using overflight::test::ScratchDir;

namespace {

// `s` as one shell word.
std::string quoted(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

// A short recorded flight over the 65-sample demo island: the camera above
// the centre, looking slightly down, turning.
FlightRecord demo_flight(int frames) {
    const DataSet ds = make_demo_island({.size = 65});
    FlightRecord r;
    for (int i = 0; i < frames; ++i) {
        FlightFrame f;
        f.frame = i;
        f.time = i / 60.0;
        f.x = ds.terrain.width() * 0.5;
        f.z = ds.terrain.depth() * 0.5;
        f.eye = {f.x, ds.terrain.max_height() + 40.0, f.z - 100.0};
        f.heading = 10.0 * i;
        f.pitch = -10.0;
        r.frames.push_back(f);
    }
    return r;
}

const std::string kReplay = "fly demo --demo-size 65 --size 64x48 --replay ";
const std::string kRender = "render demo --demo-size 65 --size 64x40 ";

} // namespace

TEST(ReplayOutput, HostileNamesReachFfmpegVerbatim) {
    if (!std::filesystem::exists("/usr/bin/ffmpeg") && !std::filesystem::exists("/usr/local/bin/ffmpeg"))
        GTEST_SKIP() << "ffmpeg is not installed (scripts/setup.sh installs it)";
    ScratchDir dir;
    const std::string csv = dir / "flight.csv";
    write_flight_record(csv, demo_flight(3));
    // Quotes and $(...) for a shell, '%' for ffmpeg's frame pattern, ':' for
    // ffmpeg's protocols.
    const std::string frames = dir / "frames %d 'x'$(touch pwned)'";
    const std::string video = dir / "file:x'$(touch pwned)'.mp4";
    const auto r = run_overflight(kReplay + quoted(csv) + " --out " + quoted(frames) + " --video " + quoted(video));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;
    EXPECT_EQ(line_count(r.out), 2) << r.out; // the stats header and one method
    EXPECT_FALSE(std::filesystem::exists(dir / "pwned"));
    EXPECT_FALSE(std::filesystem::exists("pwned"));
    EXPECT_EQ(file_names_in(frames),
              (std::set<std::string>{"frame_00000.png", "frame_00001.png", "frame_00002.png"}));
    // An MP4 (its first box is "ftyp") and no temporary beside it.
    const std::string mp4 = read_file_text(video);
    ASSERT_GT(mp4.size(), 8u);
    EXPECT_EQ(mp4.substr(4, 4), "ftyp");
    EXPECT_EQ(file_names_in(dir.path),
              (std::set<std::string>{"flight.csv", std::filesystem::path(frames).filename(),
                                     std::filesystem::path(video).filename()}));
}

TEST(ReplayOutput, BadOutputsFailBeforeAnyFrame) {
    ScratchDir dir;
    const std::string csv = dir / "flight.csv", frames = dir / "frames";
    write_flight_record(csv, demo_flight(2));
    struct Case { std::string args, err; };
    const std::string missing = dir / "missing";
    for (const Case& c : {Case{" --video " + quoted(missing + "/v.mp4"),
                               "overflight: " + missing + "/v.mp4: folder " + missing + " does not exist\n"},
                          Case{" --record " + quoted(missing + "/r.csv"),
                               "overflight: " + missing + "/r.csv: folder " + missing + " does not exist\n"},
                          Case{" --video ''", "overflight: --video: the file name is empty\n"},
                          Case{" --record ''", "overflight: --record: the file name is empty\n"}}) {
        SCOPED_TRACE(c.args);
        const auto r = run_overflight(kReplay + quoted(csv) + " --out " + quoted(frames) + c.args);
        EXPECT_EQ(r.exit_code, 1);
        EXPECT_EQ(r.err, c.err);
        EXPECT_TRUE(r.out.empty()) << r.out;
        EXPECT_EQ(file_names_in(dir.path), std::set<std::string>{"flight.csv"}); // no frames folder
    }
}

TEST(ReplayOutput, MissingFfmpegIsOneLine) {
    ScratchDir dir;
    const std::string csv = dir / "flight.csv";
    write_flight_record(csv, demo_flight(2));
    const char* path = std::getenv("PATH");
    const std::string saved = path ? path : "";
    ::setenv("PATH", dir.path.c_str(), 1); // overflight is started by its full path
    const auto r = run_overflight(kReplay + quoted(csv) + " --out " + quoted(dir / "f") + " --video " +
                                  quoted(dir / "v.mp4"));
    ::setenv("PATH", saved.c_str(), 1);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err, "overflight: --video: ffmpeg is not installed (not found on PATH)\n");
    EXPECT_EQ(file_names_in(dir.path), std::set<std::string>{"flight.csv"});
}

TEST(ReplayOutput, ACameraTheRenderersRefuseNamesFileAndLine) {
    ScratchDir dir;
    FlightRecord rec = demo_flight(3);
    rec.frames[1].pitch = 90.0; // line 3: after the header and frame 0
    const std::string csv = dir / "flight.csv";
    write_flight_record(csv, rec);
    const auto r = run_overflight(kReplay + quoted(csv) + " --out " + quoted(dir / "frames"));
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err, "overflight: " + csv + ": line 3: pitch 90.000000 is outside (-89, 89) degrees\n");
    EXPECT_EQ(file_names_in(dir.path), std::set<std::string>{"flight.csv"});
}

TEST(ReplayOutput, FramesOntoAFullDiskLeaveNothing) {
    OVERFLIGHT_SMALL_FILESYSTEM(fs, 256 * 1024);
    const std::string csv = fs / "flight.csv";
    write_flight_record(csv, demo_flight(20));
    fs.fill(6000); // room for a frame or two, not for twenty
    const auto r = run_overflight(kReplay + quoted(csv) + " --out " + quoted(fs / "frames"));
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(line_count(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("overflight: " + fs / "frames/frame_000", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(".png: cannot write: no space left on device\n"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    // The frames written before the disk filled are gone, and so is the folder.
    EXPECT_EQ(file_names_in(fs.path()), (std::set<std::string>{"filler", "flight.csv"}));
}

TEST(RenderOutput, FullDiskKeepsThePreviousPictureAndDepth) {
    OVERFLIGHT_SMALL_FILESYSTEM(fs, 256 * 1024);
    const std::string png = fs / "out.png", tif = fs / "depth.tif";
    std::ofstream(png) << "previous png";
    std::ofstream(tif) << "previous tif";
    fs.fill();
    auto r = run_overflight(kRender + "-o " + quoted(png));
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err, "overflight: " + png + ": cannot write: no space left on device\n");
    r = run_overflight(kRender + "-o " + quoted(png) + " --depth " + quoted(tif));
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err, "overflight: " + tif + ": cannot write: no space left on device\n");
    EXPECT_EQ(read_file_text(png), "previous png");
    EXPECT_EQ(read_file_text(tif), "previous tif");
    EXPECT_EQ(file_names_in(fs.path()), (std::set<std::string>{"filler", "out.png", "depth.tif"}));
    // With room again both are written.
    fs.free_space();
    r = run_overflight(kRender + "-o " + quoted(png) + " --depth " + quoted(tif));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(read_file_text(png).substr(1, 3), "PNG");
    EXPECT_EQ(read_file_text(tif).substr(0, 2), "II");
}

TEST(RenderOutput, EmptyAndMissingNamesAreOneLine) {
    ScratchDir dir;
    struct Case { std::string args, err; };
    for (const Case& c : {Case{"-o ''", "overflight: -o: the file name is empty\n"},
                          Case{"-o " + quoted(dir / "a.png") + " --depth ''",
                               "overflight: --depth: the file name is empty\n"},
                          Case{"-o " + quoted(dir / "no/a.png"),
                               "overflight: " + dir / "no/a.png" + ": folder " + dir / "no" + " does not exist\n"},
                          Case{"-o " + quoted(dir / "a.png") + " --depth " + quoted(dir / "no/d.tif"),
                               "overflight: " + dir / "no/d.tif" + ": folder " + dir / "no" + " does not exist\n"}}) {
        SCOPED_TRACE(c.args);
        const auto r = run_overflight(kRender + c.args);
        EXPECT_EQ(r.exit_code, 1);
        EXPECT_EQ(r.err, c.err);
        EXPECT_TRUE(file_names_in(dir.path).empty());
    }
}
