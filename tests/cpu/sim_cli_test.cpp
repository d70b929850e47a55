// `overflight sim` (DESIGN sec. 6): CSV of the hovercraft physics, no GL.
#include "TestSupport.h"
#include "core/DemoIsland.h"
#include "sim/Hovercraft.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>
#include <vector>

using namespace overflight;
using overflight::test::line_count;
using overflight::test::run_overflight;

namespace {
std::vector<std::vector<double>> parse_rows(const std::string& csv) {
    std::istringstream in(csv);
    std::string line;
    std::getline(in, line); // header
    std::vector<std::vector<double>> rows;
    while (std::getline(in, line)) {
        std::vector<double> r;
        std::istringstream fields(line);
        std::string f;
        while (std::getline(fields, f, ',')) r.push_back(std::stod(f));
        rows.push_back(r);
    }
    return rows;
}
} // namespace

TEST(SimCli, PrintsOneRowPerStepMatchingTheLibrary) {
    const auto r = run_overflight("sim demo --demo-size 257 --steps 300 --press accelerate:0-200 left:50-80 "
                                  "brake:250-300");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out.substr(0, r.out.find('\n')), "step,x,z,y,velocity,heading");
    EXPECT_EQ(line_count(r.out), 301);
    const auto rows = parse_rows(r.out);
    // The same flight through the library: from the demo's vehicle start.
    const DataSet ds = make_demo_island({.size = 257});
    Hovercraft hc(ds.terrain, ds.start.x, ds.start.z, ds.start.heading);
    for (int k = 0; k < 300; ++k) {
        hc.step(Controls{k < 200, k >= 250, k >= 50 && k < 80, false});
        const auto& row = rows[std::size_t(k)];
        ASSERT_EQ(row.size(), 6u);
        EXPECT_EQ(row[0], k);
        EXPECT_NEAR(row[1], hc.state().x, 1e-6);
        EXPECT_NEAR(row[2], hc.state().z, 1e-6);
        EXPECT_NEAR(row[3], hc.state().y, 1e-6);
        EXPECT_NEAR(row[4], hc.state().velocity, 1e-6);
        EXPECT_NEAR(row[5], hc.state().heading, 1e-6);
    }
    // Braking at the end slowed it down.
    EXPECT_LT(rows[299][4], rows[249][4]);
}

TEST(SimCli, AtAndHeadingSetTheStart) {
    // 1000,1200 facing east (90), accelerating: x grows, z stays.
    const auto r = run_overflight("sim demo --demo-size 257 --steps 20 --at 1000,1200 --heading 90 "
                                  "--press accelerate:0-20");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto rows = parse_rows(r.out);
    ASSERT_EQ(rows.size(), 20u);
    EXPECT_GT(rows[19][1], 1000.0);
    EXPECT_NEAR(rows[19][2], 1200.0, 1e-6);
    EXPECT_NEAR(rows[19][5], 90.0, 1e-9);
}

TEST(SimCli, BadInputIsOneLineNamingTheOption) {
    struct Case { const char* args; const char* subject; };
    for (const Case c : {Case{"sim demo --demo-size 257 --steps 0", "--steps"},
                         Case{"sim demo --demo-size 257 --steps 5 --at 5000,10", "--at"},
                         Case{"sim demo --demo-size 257 --steps 5 --at ten,10", "--at"},
                         Case{"sim demo --demo-size 257 --steps 5 --press warp:0-5", "--press"},
                         Case{"sim demo --demo-size 257 --steps 5 --press accelerate:5-1", "--press"},
                         Case{"sim demo --demo-size 257 --steps 5 --press fog:0-5", "--press"},
                         Case{"sim demo --demo-size 257 --steps 5 --slope sideways", "--slope"},
                         Case{"sim /nonexistent/terrain --steps 5", "/nonexistent/terrain"}}) {
        SCOPED_TRACE(c.args);
        const auto r = run_overflight(c.args);
        EXPECT_EQ(r.exit_code, 1);
        EXPECT_EQ(line_count(r.err), 1) << r.err;
        EXPECT_EQ(r.err.rfind(std::string("overflight: ") + c.subject + ":", 0), 0u) << r.err;
        EXPECT_TRUE(r.out.empty()) << r.out;
    }
}

// Whole numbers are decimal: 010 is ten steps (CLI11 alone reads it as octal
// 8), and a count too large for the step counter is refused rather than clamped.
TEST(SimCli, StepsAreDecimalAndNeverClamped) {
    const auto r = run_overflight("sim demo --demo-size 33 --steps 010");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(line_count(r.out), 11);
    struct Case { const char* steps; const char* err; };
    for (const Case c :
         {Case{"99999999999999999999", "overflight: --steps: '99999999999999999999' is out of range "
                                       "(-9223372036854775808..9223372036854775807)\n"},
          Case{"0x10", "overflight: --steps: '0x10' is not a whole decimal number\n"},
          Case{"1e3", "overflight: --steps: '1e3' is not a whole decimal number\n"},
          Case{"' 5'", "overflight: --steps: ' 5' is not a whole decimal number\n"}}) {
        SCOPED_TRACE(c.steps);
        const auto bad = run_overflight(std::string("sim demo --demo-size 33 --steps ") + c.steps);
        EXPECT_EQ(bad.exit_code, 1);
        EXPECT_EQ(bad.err, c.err);
        EXPECT_TRUE(bad.out.empty()) << bad.out;
    }
}

// Output that cannot be written is an error, whether the device is full
// (every write fails) or stdout is closed; the run stops at the first failure.
TEST(SimCli, UnwritableStandardOutputIsAnError) {
    const auto full = run_overflight("sim demo --demo-size 33 --steps 100000 >/dev/full");
    EXPECT_EQ(full.exit_code, 1);
    EXPECT_EQ(full.err, "overflight: stdout: cannot write: no space left on device\n");
    const auto closed = run_overflight("sim demo --demo-size 33 --steps 5 >&-");
    EXPECT_EQ(closed.exit_code, 1);
    EXPECT_EQ(closed.err, "overflight: stdout: cannot write: bad file descriptor\n");
    // The same command writing to a pipe succeeds: the failure is the output's.
    EXPECT_EQ(run_overflight("sim demo --demo-size 33 --steps 5").exit_code, 0);
}
