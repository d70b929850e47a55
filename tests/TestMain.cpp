// The main of every test executable (in place of GTest::gtest_main). A test
// that calls GTEST_SKIP (shared data absent, no tmpfs) still lets a plain
// GoogleTest run exit 0, which CTest would count as Passed. This main exits
// with OVERFLIGHT_TEST_SKIP_CODE when some test was skipped and none failed;
// tests/CMakeLists.txt gives CTest the same code as SKIP_RETURN_CODE, so such
// an executable is reported as Skipped and scripts/test.sh can refuse it.
#include <gtest/gtest.h>

int main(int argc, char** argv) {
    ::testing::InitGoogleTest(&argc, argv);
    const int failed = RUN_ALL_TESTS();
    if (failed != 0) return failed;
    return ::testing::UnitTest::GetInstance()->skipped_test_count() > 0 ? OVERFLIGHT_TEST_SKIP_CODE : 0;
}
