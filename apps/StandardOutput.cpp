#include "StandardOutput.h"

#include "core/Error.h"
#include "io/Files.h"

#include <cerrno>
#include <cstdio>

namespace overflight::app {

void write_stdout(std::string_view text) {
    if (std::fwrite(text.data(), 1, text.size(), stdout) != text.size())
        throw Error("stdout", "cannot write: " + errno_text(errno));
}

void finish_stdout() {
    errno = 0;
    if (std::fflush(stdout) != 0) throw Error("stdout", "cannot write: " + errno_text(errno));
    // A failed printf earlier leaves the error flag set, its errno long gone.
    if (std::ferror(stdout)) throw Error("stdout", "cannot write: a write failed");
}

} // namespace overflight::app
