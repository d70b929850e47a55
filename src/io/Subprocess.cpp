#include "io/Subprocess.h"

#include "core/Error.h"
#include "io/Files.h"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace overflight {

namespace {

bool is_executable_file(const std::string& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(path.c_str(), X_OK) == 0;
}

// Closes a file descriptor when it goes out of scope.
struct Fd {
    int fd = -1;
    ~Fd() {
        if (fd >= 0) ::close(fd);
    }
};

} // namespace

std::optional<std::string> find_program(const std::string& name) {
    if (name.empty()) return std::nullopt;
    if (name.find('/') != std::string::npos) return is_executable_file(name) ? std::optional(name) : std::nullopt;
    const char* path = std::getenv("PATH");
    const std::string dirs = path ? path : "/usr/local/bin:/usr/bin:/bin";
    std::size_t start = 0;
    while (start <= dirs.size()) {
        const std::size_t colon = std::min(dirs.find(':', start), dirs.size());
        const std::string dir = dirs.substr(start, colon - start);
        const std::string candidate = (dir.empty() ? std::string(".") : dir) + "/" + name;
        if (is_executable_file(candidate)) return candidate;
        start = colon + 1;
    }
    return std::nullopt;
}

std::string ProcessResult::describe() const {
    std::string text = signal != 0 ? "killed by signal " + std::to_string(signal)
                                   : "exit status " + std::to_string(exit_status);
    // The last non-empty line: tools print their conclusion last.
    std::size_t end = error_text.find_last_not_of("\r\n \t");
    if (end != std::string::npos) {
        const std::size_t begin = error_text.find_last_of('\n', end);
        text += ": " + error_text.substr(begin == std::string::npos ? 0 : begin + 1,
                                         end + 1 - (begin == std::string::npos ? 0 : begin + 1));
    }
    return text;
}

ProcessResult run_program(const std::string& program, const std::vector<std::string>& args,
                          const std::string& subject) {
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) throw Error(subject, "cannot run " + program + ": " + errno_text(errno));
    Fd read_end{fds[0]}, write_end{fds[1]};

    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(program.c_str()));
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);

    // The child: stdin and stdout on /dev/null, stderr into the pipe (dup2
    // clears close-on-exec on fd 2 only; both pipe ends close at exec).
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_adddup2(&actions, write_end.fd, 2);
    pid_t pid = -1;
    const int spawned = ::posix_spawn(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) throw Error(subject, "cannot run " + program + ": " + errno_text(spawned));
    ::close(write_end.fd);
    write_end.fd = -1;

    ProcessResult result;
    constexpr std::size_t kKeep = 4096;
    char buf[4096];
    while (true) {
        const ssize_t n = ::read(read_end.fd, buf, sizeof buf);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        result.error_text.append(buf, std::size_t(n));
        if (result.error_text.size() > 2 * kKeep) result.error_text.erase(0, result.error_text.size() - kKeep);
    }
    if (result.error_text.size() > kKeep) result.error_text.erase(0, result.error_text.size() - kKeep);

    int status = 0;
    while (::waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) throw Error(subject, "lost track of " + program + ": " + errno_text(errno));
    }
    if (WIFEXITED(status)) result.exit_status = WEXITSTATUS(status);
    else if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
    return result;
}

} // namespace overflight
