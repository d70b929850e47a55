#include "io/Files.h"

#include "core/Error.h"

#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <unistd.h>

namespace overflight {

namespace fs = std::filesystem;

namespace {

// strerror() as the tail of a one-line message: "no space left on device".
std::string errno_text(int err) {
    std::string s = std::strerror(err);
    if (!s.empty()) s[0] = char(std::tolower(static_cast<unsigned char>(s[0])));
    return s;
}

} // namespace

std::vector<std::uint8_t> read_file_bytes(const std::string& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw Error(path, "no such file");
    if (fs::is_directory(path, ec)) throw Error(path, "is a directory, expected a file");
    FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) throw Error(path, std::string("cannot open: ") + std::strerror(errno));
    std::vector<std::uint8_t> bytes;
    std::uint8_t buf[1 << 16];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) bytes.insert(bytes.end(), buf, buf + n);
    const bool failed = std::ferror(f) != 0;
    std::fclose(f);
    if (failed) throw Error(path, "read error");
    return bytes;
}

void write_atomically(const std::string& path, const std::function<void(const std::string&)>& write) {
    static std::atomic<unsigned> counter{0};
    const fs::path target(path);
    const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) throw Error(path, "folder " + folder.string() + " does not exist");
    // Hidden, unique per process and call, in the destination folder so that
    // the final rename stays within one file system.
    const std::string temp = (folder / ("." + target.filename().string() + ".tmp" + std::to_string(::getpid()) +
                                        "-" + std::to_string(counter++))).string();
    try {
        write(temp);
    } catch (...) {
        fs::remove(temp, ec);
        throw;
    }
    fs::rename(temp, target, ec);
    if (ec) {
        std::error_code ignored;
        fs::remove(temp, ignored);
        throw Error(path, "cannot write: " + ec.message());
    }
}

void write_file_atomically(const std::string& path, const void* data, std::size_t size) {
    write_atomically(path, [&](const std::string& temp) {
        FILE* f = std::fopen(temp.c_str(), "wb");
        if (!f) throw Error(path, "cannot write: " + errno_text(errno));
        errno = 0;
        const bool written = std::fwrite(data, 1, size, f) == size && std::fflush(f) == 0;
        const int write_errno = errno;
        const bool closed = std::fclose(f) == 0;
        if (!written || !closed) throw Error(path, "cannot write: " + errno_text(!written ? write_errno : errno));
    });
}

} // namespace overflight
