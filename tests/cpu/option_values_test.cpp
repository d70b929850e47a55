// Option values of every command (apps/OptionValues.h): integers are decimal,
// never silently clamped, never octal or hexadecimal; empty file names are
// refused; each with one line naming the option. Command-line errors CLI11
// finds (missing or unknown options) are one line and exit 1 as well.
#include "TestSupport.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

using overflight::test::line_count;
using overflight::test::run_overflight;
using overflight::test::ScratchDir;

TEST(OptionValues, EveryIntegerOptionRefusesWhatIsNotADecimalInRange) {
    ScratchDir dir;
    const std::string out = dir / "o";
    struct Case { std::string command, option, type_range; };
    const std::string int_range = "(-2147483648..2147483647)";
    const std::string ll_range = "(-9223372036854775808..9223372036854775807)";
    for (const Case& c : {Case{"sim demo --demo-size 33", "--steps", ll_range},
                          Case{"sim demo --steps 5", "--demo-size", int_range},
                          Case{"render demo --demo-size 33 -o '" + out + ".png'", "--triangles", int_range},
                          Case{"render demo --demo-size 33 -o '" + out + ".png'", "--cache-mib", int_range},
                          Case{"tile demo --demo-size 33 -o '" + out + "'", "--tile-size", int_range},
                          Case{"bench demo --demo-size 33", "--frames", int_range},
                          Case{"bench demo --demo-size 33", "--threads", int_range},
                          Case{"fly demo --demo-size 33", "--frames", ll_range},
                          Case{"fly demo --demo-size 33 --frames 1", "--cache-mib", int_range}}) {
        for (const std::string value : {"99999999999999999999", "0x10", "12abc"}) {
            SCOPED_TRACE(c.command + " " + c.option + " " + value);
            const auto r = run_overflight(c.command + " " + c.option + " " + value);
            EXPECT_EQ(r.exit_code, 1);
            const std::string expected =
                value[0] == '9' ? "overflight: " + c.option + ": '" + value + "' is out of range " + c.type_range + "\n"
                                : "overflight: " + c.option + ": '" + value + "' is not a whole decimal number\n";
            EXPECT_EQ(r.err, expected);
            EXPECT_TRUE(r.out.empty()) << r.out;
        }
    }
    EXPECT_FALSE(std::filesystem::exists(out));
    EXPECT_FALSE(std::filesystem::exists(out + ".png"));
}

TEST(OptionValues, LeadingZerosAreDecimal) {
    ScratchDir dir;
    // 017 tiles of 17 samples (octal would be 15, not 2^k+1, and refused).
    const auto r = run_overflight("tile demo --demo-size 033 --tile-size 017 -o '" + (dir / "t") + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("2x2 tiles of 17 samples"), std::string::npos) << r.out;
}

TEST(OptionValues, CommandLineErrorsAreOneLineAndExitOne) {
    struct Case { const char* args; const char* err; };
    for (const Case c : {Case{"sim demo", "overflight: --steps is required\n"},
                         Case{"sim demo --steps", "overflight: --steps: 1 required INT missing\n"},
                         Case{"sim demo --steps 5 --warp 3",
                              "overflight: The following arguments were not expected: 3 --warp\n"},
                         Case{"", "overflight: A subcommand is required\n"},
                         Case{"tile demo --demo-size 33 -o ''", "overflight: -o: the file name is empty\n"}}) {
        SCOPED_TRACE(c.args);
        const auto r = run_overflight(c.args);
        EXPECT_EQ(r.exit_code, 1);
        EXPECT_EQ(line_count(r.err), 1) << r.err;
        EXPECT_EQ(r.err, c.err);
    }
    // --help still prints the usage, on stdout, exit 0.
    const auto help = run_overflight("sim --help");
    EXPECT_EQ(help.exit_code, 0);
    EXPECT_NE(help.out.find("--steps"), std::string::npos);
}
