#pragma once
// The file primitives every io module uses: reading a whole file into
// memory, and writing a file so that a failure never leaves a half-written
// result behind (write a temporary file in the same folder, then rename it
// over the destination: rename is atomic within one file system).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace overflight {

// The bytes of `path`. Throws Error(path, ...) when it is missing, a directory
// or unreadable.
std::vector<std::uint8_t> read_file_bytes(const std::string& path);

// Calls write(temp_path) with a fresh temporary name in the folder of `path`,
// then renames it to `path`. If write throws, or the rename fails, the
// temporary file is removed and the error (Error(path, ...)) propagates; an
// existing file at `path` is untouched.
void write_atomically(const std::string& path, const std::function<void(const std::string& temp_path)>& write);

// Throws Error(path, "folder F does not exist") unless the folder `path` would
// be written into exists, so that a command can refuse a bad output name
// before it does any work.
void check_output_folder(const std::string& path);

// The reason for the errno value `err` as a lowercase phrase, for messages
// such as "cannot write: no space left on device".
std::string errno_text(int err);

// A file being written in which every write and the close are checked. The
// first failure (disk full, I/O error) is kept, later writes are skipped, and
// close() reports it; so a producer that cannot report errors itself (stb's
// write callback) still cannot lose data silently. close() also flushes the
// data to the device (fsync) before the caller renames the file into place:
// some file systems only report a full disk or an I/O error then, and a rename
// over the previous file must not be able to outlive the data it points to.
class CheckedFile {
public:
    // Creates `path`; errors name `subject` (the file the user asked for).
    CheckedFile(const std::string& path, const std::string& subject);
    ~CheckedFile();
    CheckedFile(const CheckedFile&) = delete;
    CheckedFile& operator=(const CheckedFile&) = delete;

    void write(const void* data, std::size_t size);
    // Flushes, syncs and closes; throws Error(subject, "cannot write: ...")
    // for the first failure of any write or of the close.
    void close();

private:
    std::FILE* file_ = nullptr;
    std::string subject_;
    int error_ = 0; // errno of the first failure
};

// Writes `size` bytes to `path` through write_atomically, checking every
// write, the flush and the close (a full disk often shows only there):
// Error(path, "cannot write: no space left on device") and the like.
void write_file_atomically(const std::string& path, const void* data, std::size_t size);

// write_atomically with the temporary file opened as a CheckedFile: calls
// write(file), closes it checked, then renames it to `path`.
void write_file_atomically(const std::string& path, const std::function<void(CheckedFile& file)>& write);

} // namespace overflight
