#pragma once
// Running `overflight` in a child under restrictions a user may have: a cap
// on its address space (ulimit -v), or an unprivileged user (tests run as
// root in CI, where file permissions deny nothing).
#include "TestSupport.h"

#include <fcntl.h>
#include <grp.h>
#include <pwd.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdint>
#include <fstream>
#include <sstream>

namespace overflight::test {

// AddressSanitizer reserves terabytes of address space for its shadow
// memory, so a program built with it (the sanitizer build of the tests and of
// `overflight`) cannot even start under RLIMIT_AS.
// Tests that need the limit exist only in builds without it (the Release run
// holds them; CI fails on a skipped test, so they are left out, not skipped).
#if defined(__SANITIZE_ADDRESS__)
#define OVERFLIGHT_ADDRESS_SPACE_CAN_BE_LIMITED 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define OVERFLIGHT_ADDRESS_SPACE_CAN_BE_LIMITED 0
#endif
#endif
#ifndef OVERFLIGHT_ADDRESS_SPACE_CAN_BE_LIMITED
#define OVERFLIGHT_ADDRESS_SPACE_CAN_BE_LIMITED 1
#endif
inline constexpr bool kAddressSpaceCanBeLimited = OVERFLIGHT_ADDRESS_SPACE_CAN_BE_LIMITED;

struct Restrictions {
    // RLIMIT_AS of the child; 0, or !kAddressSpaceCanBeLimited: unlimited.
    std::uint64_t address_space_bytes = 0;
    bool unprivileged = false; // as user `nobody` when running as root
};

inline std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// As run_overflight, in a forked child that applies `limits` before exec. The
// exit code of a child killed by a signal is 128 + the signal.
// `exe`: the program to run (default the build's `overflight`; as `nobody`,
// a copy in a folder that user can enter, since the build tree may not be).
inline RunResult run_overflight_restricted(const std::string& args, const Restrictions& limits,
                                           const std::string& exe = OVERFLIGHT_EXE) {
    const auto dir = std::filesystem::temp_directory_path();
    const std::string out_file = dir / ("overflight-rr-out-" + std::to_string(::getpid()));
    const std::string err_file = dir / ("overflight-rr-err-" + std::to_string(::getpid()));
    const int out = ::open(out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    const int err = ::open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    const std::string cmd = "exec '" + exe + "' " + args;
    const passwd* nobody = limits.unprivileged && ::geteuid() == 0 ? ::getpwnam("nobody") : nullptr;
    RunResult r;
    const pid_t pid = ::fork();
    if (pid == 0) {
        // Only async-signal-safe calls from here to exec.
        ::dup2(out, 1);
        ::dup2(err, 2);
        if (limits.address_space_bytes && kAddressSpaceCanBeLimited) {
            const rlimit cap{limits.address_space_bytes, limits.address_space_bytes};
            if (::setrlimit(RLIMIT_AS, &cap) != 0) ::_exit(126);
        }
        if (nobody && (::setgroups(0, nullptr) != 0 || ::setgid(nobody->pw_gid) != 0 || ::setuid(nobody->pw_uid) != 0))
            ::_exit(126);
        ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
        ::_exit(127);
    }
    ::close(out);
    ::close(err);
    int status = 0;
    if (pid > 0 && ::waitpid(pid, &status, 0) == pid)
        r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.out = slurp(out_file);
    r.err = slurp(err_file);
    std::filesystem::remove(out_file);
    std::filesystem::remove(err_file);
    return r;
}

} // namespace overflight::test
