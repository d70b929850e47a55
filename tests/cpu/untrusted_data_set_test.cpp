// Hovercraft data sets and camera options whose values are valid TOML and
// numbers but no terrain: each must stop with one line naming the map file or
// the option at fault (DESIGN sec. 6), never blame something else or render
// garbage. Each test also runs the nearest good input, so it can fail.
#include "RestrictedRun.h"
#include "TestSupport.h"
#include "core/Shading.h"
#include "io/Pnm.h"

#include <cmath>
#include <fstream>
#include <limits>

namespace overflight {
namespace {

using test::run_overflight;
using test::ScratchDir;

// A data set of 3x3 samples, all `sample` high but the centre one, under the given map text.
std::string data_set(const ScratchDir& dir, const std::string& map, std::uint16_t sample = 100,
                     std::uint16_t centre = 100) {
    const std::string set = dir / "set";
    std::filesystem::create_directories(set);
    std::ofstream(set + "/map", std::ios::binary) << map;
    Image2D<std::uint16_t> hf(3, 3);
    for (auto& h : hf.pixels) h = sample;
    hf.at(1, 1) = centre;
    write_pgm(set + "/hf.pgm", hf, 65535);
    return set;
}

void expect_error(const std::string& args, const std::string& line) {
    const test::RunResult r = run_overflight(args);
    EXPECT_EQ(r.exit_code, 1) << args;
    EXPECT_EQ(r.err, line) << args;
    EXPECT_TRUE(r.out.empty()) << r.out;
}

void expect_success(const std::string& args) {
    const test::RunResult r = run_overflight(args);
    EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
}

TEST(UntrustedDataSet, HorizontalScaleBeyondFloatWorld) {
    ScratchDir dir;
    const std::string set = data_set(dir, "h_scale = 1e300\nv_scale = 1\n");
    expect_error("info '" + set + "'",
                 "overflight: " + set + "/map: h_scale = 1e+300 for a 3x3 hf.pgm: horizontal scale 1e+300 makes the "
                 "terrain 2e+300 units across, beyond the 16777216 (2^24) that float world coordinates hold\n");
    const std::string tiny = data_set(dir, "h_scale = 1e-50\nv_scale = 1\n");
    expect_error("info '" + tiny + "'", "overflight: " + tiny + "/map: h_scale = 1e-50 is beyond float range\n");
    expect_success("info '" + data_set(dir, "h_scale = 1e6\nv_scale = 1\n") + "'");
}

TEST(UntrustedDataSet, VerticalScaleBeyondFloatRange) {
    ScratchDir dir;
    const std::string set = data_set(dir, "h_scale = 1\nv_scale = 1e300\n");
    expect_error("info '" + set + "'", "overflight: " + set + "/map: v_scale = 1e+300 is beyond float range\n");
}

TEST(UntrustedDataSet, ElevationsBeyondFloatWorld) {
    ScratchDir dir;
    const std::string set = data_set(dir, "h_scale = 1\nv_scale = 1000\n", 60000, 60000);
    expect_error("info '" + set + "'",
                 "overflight: " + set + "/map: v_scale = 1000, y_offset = 0: for sample 60000 of hf.pgm, elevation "
                 "60000000 is beyond +-16777216 (2^24), where float world coordinates no longer hold whole units\n");
    expect_success("info '" + data_set(dir, "h_scale = 1\nv_scale = 100\n", 60000, 60000) + "'");
}

TEST(UntrustedDataSet, VehicleStartOutsideTheTerrainBlamesTheMap) {
    ScratchDir dir;
    const std::string set = data_set(dir, "h_scale = 10\nv_scale = 1\n[vehicle]\nx = 1000\nz = 5\n");
    // sim has no --at here: the start comes from the map, which is named.
    expect_error("sim '" + set + "' --steps 1",
                 "overflight: " + set + "/map: [vehicle] start x = 1000, z = 5 is outside the terrain (x 0..20, z 0..20)\n");
    expect_success("sim '" + data_set(dir, "h_scale = 10\nv_scale = 1\n[vehicle]\nx = 20\nz = 5\n") + "' --steps 1");
}

// Needs a 512 MiB address-space limit, which an AddressSanitizer build cannot run under.
#if OVERFLIGHT_ADDRESS_SPACE_CAN_BE_LIMITED
TEST(OutOfMemory, LastResortNamesWhatWasBeingLoaded) {
    // The demo generator sizes nothing from a file, so nothing checks its
    // memory beforehand: a 16385^2 island (1.3 GB) under 512 MiB reaches main.
    const test::Restrictions half_gib{512ull << 20, false};
    const test::RunResult r = test::run_overflight_restricted("info demo --demo-size 16385", half_gib);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err, "overflight: demo: not enough memory to load it\n");
    EXPECT_EQ(test::run_overflight_restricted("info demo --demo-size 65", half_gib).exit_code, 0);
}
#endif

TEST(UntrustedCamera, EyeUnderTheSurfaceIsRefused) {
    ScratchDir dir;
    const std::string set = data_set(dir, "h_scale = 10\nv_scale = 1\n");
    const std::string out = dir / "out.png";
    expect_error("render '" + set + "' -o '" + out + "' --size 16x16 --eye 10,97,10",
                 "overflight: --eye: eye 10,97,10 is 3 below the terrain surface (ground at 100 there)\n");
    EXPECT_FALSE(std::filesystem::exists(out));
    expect_success("render '" + set + "' -o '" + out + "' --size 16x16 --eye 10,103,10");
    EXPECT_TRUE(std::filesystem::exists(out));
}

TEST(UntrustedCamera, EyeInsideTheNearestSampleBlockIsRefused) {
    // At (8, 8) the bilinear ground is 100 + 20 * 0.8 * 0.8 = 112.8 but the
    // nearest sample, the block the voxel renderer draws there, is 120 high.
    ScratchDir dir;
    const std::string set = data_set(dir, "h_scale = 10\nv_scale = 1\n", 100, 120);
    const std::string out = dir / "out.png";
    expect_error("render '" + set + "' -o '" + out + "' --size 16x16 --at 8,8 --agl 2",
                 "overflight: --agl: eye 8,114.8,8 is 5.2 below the terrain surface (ground at 120 there)\n");
    EXPECT_FALSE(std::filesystem::exists(out));
    expect_success("render '" + set + "' -o '" + out + "' --size 16x16 --at 8,8 --agl 8");
}

TEST(Shading, NotANumberHeightGetsADefinedColor) {
    // A NaN converted to uint8_t is undefined; the ramp takes it as its lowest land color.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(elevation_ramp(nan, 0.0f, 100.0f, 0.0f), elevation_ramp(0.0f, 0.0f, 100.0f, 0.0f));
    EXPECT_EQ(elevation_ramp(10.0f, 0.0f, nan, 0.0f), elevation_ramp(0.0f, 0.0f, 100.0f, 0.0f));
}

} // namespace
} // namespace overflight
