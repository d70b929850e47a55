#pragma once
// The two file primitives every io module uses: reading a whole file into
// memory, and writing a file so that a failure never leaves a half-written
// result behind (write a temporary file in the same folder, then rename it
// over the destination: rename is atomic within one file system).
#include <cstdint>
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

// Writes `size` bytes to `path` through write_atomically, checking every
// write, the flush and the close (a full disk often shows only there):
// Error(path, "cannot write: no space left on device") and the like.
void write_file_atomically(const std::string& path, const void* data, std::size_t size);

} // namespace overflight
