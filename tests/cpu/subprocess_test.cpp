// io/Subprocess.h: programs found on PATH without a shell and run with an
// argument vector, so that no character of an argument is interpreted.
#include "TestSupport.h"
#include "core/Error.h"
#include "io/Subprocess.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

using namespace overflight;
using overflight::test::ScratchDir;

TEST(Subprocess, FindsProgramsOnThePath) {
    const auto sh = find_program("sh");
    ASSERT_TRUE(sh.has_value());
    EXPECT_EQ(sh->front(), '/');
    EXPECT_FALSE(find_program("overflight-no-such-program").has_value());
    EXPECT_FALSE(find_program("").has_value());
    EXPECT_EQ(find_program(*sh), sh); // a path is taken as it is
}

TEST(Subprocess, ArgumentsAreNotInterpretedByAShell) {
    ScratchDir dir;
    const auto touch = find_program("touch");
    ASSERT_TRUE(touch.has_value());
    const std::string hostile = dir / "x'$(touch pwned)'; touch pwned2 #.mp4";
    const ProcessResult r = run_program(*touch, {hostile}, "test");
    EXPECT_TRUE(r.succeeded()) << r.describe();
    EXPECT_TRUE(std::filesystem::exists(hostile)); // the name, literally
    EXPECT_FALSE(std::filesystem::exists(dir / "pwned"));
    EXPECT_FALSE(std::filesystem::exists("pwned"));
    EXPECT_FALSE(std::filesystem::exists("pwned2"));
}

TEST(Subprocess, ReportsTheExitStatusAndTheLastLineOfStderr) {
    const auto sh = find_program("sh");
    ASSERT_TRUE(sh.has_value());
    const ProcessResult r = run_program(*sh, {"-c", "echo first >&2; echo 'the reason' >&2; echo out; exit 3"}, "t");
    EXPECT_FALSE(r.succeeded());
    EXPECT_EQ(r.exit_status, 3);
    EXPECT_EQ(r.signal, 0);
    EXPECT_EQ(r.describe(), "exit status 3: the reason");
    const ProcessResult killed = run_program(*sh, {"-c", "kill -9 $$"}, "t");
    EXPECT_EQ(killed.signal, 9);
    EXPECT_EQ(killed.describe(), "killed by signal 9");
}

TEST(Subprocess, KeepsOnlyTheEndOfALongStderr) {
    const auto sh = find_program("sh");
    ASSERT_TRUE(sh.has_value());
    const ProcessResult r =
        run_program(*sh, {"-c", "i=0; while [ $i -lt 5000 ]; do echo line $i >&2; i=$((i+1)); done"}, "t");
    EXPECT_TRUE(r.succeeded());
    EXPECT_LE(r.error_text.size(), 4096u);
    EXPECT_EQ(r.describe(), "exit status 0: line 4999");
}

TEST(Subprocess, AProgramThatCannotStartIsAnError) {
    ScratchDir dir;
    try {
        run_program(dir / "missing", {}, "--video");
        ADD_FAILURE() << "started";
    } catch (const Error& e) {
        EXPECT_EQ(e.subject(), "--video");
        EXPECT_NE(e.problem().find("no such file or directory"), std::string::npos) << e.problem();
    }
}
