#pragma once
// Running another program (ffmpeg for `fly --replay --video`) without a
// shell: the arguments go to posix_spawn as a vector, so no character of a
// user's file name (quotes, `$(...)`, `;`) is ever interpreted.
#include <optional>
#include <string>
#include <vector>

namespace overflight {

// The first executable regular file called `name` in the folders of $PATH,
// searched as execvp does (an empty entry is the current folder); nullopt
// when there is none. A `name` containing '/' is returned as is if executable.
std::optional<std::string> find_program(const std::string& name);

struct ProcessResult {
    int exit_status = -1;   // exit status when the program exited, else -1
    int signal = 0;         // the signal that ended it, else 0
    std::string error_text; // what it wrote on stderr (the last 4 KiB)
    bool succeeded() const { return exit_status == 0; }
    // "exit status N" or "killed by signal N", then the last non-empty line of
    // stderr after ": ", for a one-line message.
    std::string describe() const;
};

// Runs `program` (a path, e.g. from find_program) with `args` (argv[1]...),
// stdin from /dev/null, stdout discarded, stderr captured; waits for it.
// Throws Error(subject, ...) when it cannot be started.
ProcessResult run_program(const std::string& program, const std::vector<std::string>& args,
                          const std::string& subject);

} // namespace overflight
