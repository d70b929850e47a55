#include "io/Files.h"

#include "core/Error.h"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <unistd.h>

namespace overflight {

namespace fs = std::filesystem;

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

} // namespace overflight
