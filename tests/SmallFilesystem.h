#pragma once
// A small filesystem for full-disk tests: a tmpfs of a given size mounted on a
// fresh scratch folder, unmounted and removed when it goes out of scope.
// Mounting needs root (CI and the development machines run as root); where it
// is refused the calling test is skipped, which CTest reports as such.
#include "TestSupport.h"

#include <sys/mount.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>

namespace overflight::test {

class SmallFilesystem {
public:
    // Mounts `bytes` of tmpfs (rounded up to whole pages by the kernel).
    explicit SmallFilesystem(std::size_t bytes) {
        const std::string options = "size=" + std::to_string(bytes) + ",mode=0777";
        mounted_ = ::mount("tmpfs", scratch_.path.c_str(), "tmpfs", 0, options.c_str()) == 0;
        if (!mounted_) error_ = std::strerror(errno);
    }
    ~SmallFilesystem() {
        if (mounted_) ::umount2(scratch_.path.c_str(), MNT_DETACH);
    }
    SmallFilesystem(const SmallFilesystem&) = delete;
    SmallFilesystem& operator=(const SmallFilesystem&) = delete;

    bool mounted() const { return mounted_; }
    const std::string& error() const { return error_; } // why mount failed
    const std::filesystem::path& path() const { return scratch_.path; }
    std::string operator/(const std::string& name) const { return scratch_ / name; }

    // Fills the filesystem up to `leave` free bytes with a file called `name`.
    void fill(std::size_t leave = 0, const std::string& name = "filler") const {
        const std::filesystem::space_info s = std::filesystem::space(scratch_.path);
        if (s.available <= leave) return;
        std::FILE* f = std::fopen((scratch_ / name).c_str(), "wb");
        if (!f) return;
        static const char zeros[4096] = {};
        std::size_t left = s.available - leave;
        while (left > 0) {
            const std::size_t n = left < sizeof zeros ? left : sizeof zeros;
            if (std::fwrite(zeros, 1, n, f) != n) break;
            left -= n;
        }
        std::fclose(f);
    }
    // Removes what fill() wrote.
    void free_space(const std::string& name = "filler") const { std::filesystem::remove(scratch_ / name); }

private:
    ScratchDir scratch_;
    bool mounted_ = false;
    std::string error_;
};

// Mounts a SmallFilesystem called `var` of `bytes`, or skips the calling test.
#define OVERFLIGHT_SMALL_FILESYSTEM(var, bytes)                                                  \
    ::overflight::test::SmallFilesystem var(bytes);                                              \
    if (!var.mounted()) GTEST_SKIP() << "cannot mount a tmpfs (needs root): " << var.error()

} // namespace overflight::test
