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

// When a file written through write_file_atomically reaches the device:
// Now, before it is renamed into place (fsync); Later, with the rest of the
// folder through a FolderSync, for a writer of thousands of files (a tile
// directory), for which one fsync each costs more than making them (every
// fsync waits for the device).
enum class FileSync { Now, Later };

// A file being written in which every write and the close are checked. The
// first failure (disk full, I/O error) is kept, later writes are skipped, and
// close() reports it; so a producer that cannot report errors itself (stb's
// write callback) still cannot lose data silently. close() also flushes the
// data to the device (fsync, unless FileSync::Later) before the caller
// renames the file into place: some file systems only report a full disk or
// an I/O error then, and a rename over the previous file must not be able to
// outlive the data it points to.
class CheckedFile {
public:
    // Creates `path`; errors name `subject` (the file the user asked for).
    CheckedFile(const std::string& path, const std::string& subject);
    ~CheckedFile();
    CheckedFile(const CheckedFile&) = delete;
    CheckedFile& operator=(const CheckedFile&) = delete;

    void write(const void* data, std::size_t size);
    // Flushes, syncs (with FileSync::Now) and closes; throws Error(subject,
    // "cannot write: ...") for the first failure of any write or of the close.
    void close(FileSync sync = FileSync::Now);

private:
    std::FILE* file_ = nullptr;
    std::string subject_;
    int error_ = 0; // errno of the first failure
};

// Writes `size` bytes to `path` through write_atomically, checking every
// write, the flush and the close (a full disk often shows only there):
// Error(path, "cannot write: no space left on device") and the like. With
// FileSync::Later the caller makes it durable with a FolderSync before it
// writes anything that says the file is complete.
void write_file_atomically(const std::string& path, const void* data, std::size_t size,
                           FileSync sync = FileSync::Now);

// write_atomically with the temporary file opened as a CheckedFile: calls
// write(file), closes it checked, then renames it to `path`.
void write_file_atomically(const std::string& path, const std::function<void(CheckedFile& file)>& write);

// The files a run writes into one folder with FileSync::Later, made durable
// at once: sync() is one syncfs(2) of the folder's file system (one wait for
// the device instead of one per file). Created before the first such write:
// the kernel reports to syncfs the write-back failures (an I/O error, a full
// disk found late) that happen after the folder was opened.
class FolderSync {
public:
    // Error(folder, "cannot open: ...") when the folder cannot be opened.
    explicit FolderSync(const std::string& folder);
    ~FolderSync();
    FolderSync(const FolderSync&) = delete;
    FolderSync& operator=(const FolderSync&) = delete;

    // Every file written into the file system so far on the device;
    // Error(folder, "cannot write: ...") for a failure of any of them.
    void sync();

private:
    int fd_ = -1;
    std::string folder_;
};

} // namespace overflight
