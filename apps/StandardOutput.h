#pragma once
// Checked writes to standard output. A command whose output cannot be written
// (`> /dev/full`, a closed stdout, a full disk behind a redirection) must not
// exit 0 as if it had: every write is checked, and so is the final flush.
#include <string_view>

namespace overflight::app {

// Writes `text` to stdout; throws Error("stdout", "cannot write: ...").
void write_stdout(std::string_view text);

// Flushes stdout and checks that no earlier write to it (printf included)
// failed; throws Error("stdout", ...). main calls it after every command.
void finish_stdout();

} // namespace overflight::app
