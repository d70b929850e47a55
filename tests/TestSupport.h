#pragma once
// Helpers shared by the tests: where the real data lives, scratch folders,
// and running the `overflight` program as a user would.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace overflight::test {

// Path of a file under ../shared/data; the calling test is skipped when it is absent.
#define OVERFLIGHT_SHARED_FILE(var, rel)                                                      \
    const std::string var = std::string(OVERFLIGHT_SHARED_DATA) + "/" + (rel);                \
    if (!std::filesystem::exists(var)) GTEST_SKIP() << "shared data not present: " << var

// A fresh empty folder for one test, removed when it goes out of scope.
struct ScratchDir {
    std::filesystem::path path;
    ScratchDir() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        path = std::filesystem::temp_directory_path() /
               ("overflight-" + std::string(info ? info->test_suite_name() : "t") + "-" +
                std::string(info ? info->name() : "x") + "-" + std::to_string(::getpid()));
        std::filesystem::remove_all(path);
        std::filesystem::create_directories(path);
    }
    ~ScratchDir() { std::filesystem::remove_all(path); }
    std::string operator/(const std::string& name) const { return (path / name).string(); }
};

struct RunResult {
    int exit_code = -1;
    std::string out; // stdout
    std::string err; // stderr
};

// Runs `overflight ARGS` (ARGS is shell-quoted by the caller) and captures its output.
inline RunResult run_overflight(const std::string& args) {
    const std::string err_file = std::filesystem::temp_directory_path() /
                                 ("overflight-stderr-" + std::to_string(::getpid()));
    const std::string cmd = std::string("'") + OVERFLIGHT_EXE + "' " + args + " 2>'" + err_file + "'";
    RunResult r;
    FILE* p = ::popen(cmd.c_str(), "r");
    if (!p) return r;
    std::array<char, 4096> buf{};
    std::size_t n;
    while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
    const int status = ::pclose(p);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128;
    if (FILE* e = std::fopen(err_file.c_str(), "r")) {
        while ((n = std::fread(buf.data(), 1, buf.size(), e)) > 0) r.err.append(buf.data(), n);
        std::fclose(e);
    }
    std::filesystem::remove(err_file);
    return r;
}

// Number of lines in s (a final line without newline counts).
inline int line_count(const std::string& s) {
    int n = 0;
    for (char c : s) n += c == '\n';
    return n + (!s.empty() && s.back() != '\n');
}

// The names of the entries of a folder (not recursive).
inline std::set<std::string> file_names_in(const std::filesystem::path& dir) {
    std::set<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir)) names.insert(e.path().filename().string());
    return names;
}

// The whole content of a file ("" when it cannot be read).
inline std::string read_file_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

} // namespace overflight::test
