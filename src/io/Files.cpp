#include "io/Files.h"

#include "core/Error.h"

#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
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

namespace {
fs::path output_folder(const fs::path& target) {
    return target.has_parent_path() ? target.parent_path() : fs::path(".");
}
} // namespace

void check_output_folder(const std::string& path) {
    const fs::path folder = output_folder(path);
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) throw Error(path, "folder " + folder.string() + " does not exist");
}

std::string errno_text(int err) {
    std::string text = std::strerror(err);
    // "No space left on device" -> "no space left on device"; "I/O error" stays.
    if (text.size() > 1 && std::isupper(static_cast<unsigned char>(text[0])) &&
        std::islower(static_cast<unsigned char>(text[1])))
        text[0] = char(std::tolower(static_cast<unsigned char>(text[0])));
    return text;
}

CheckedFile::CheckedFile(const std::string& path, const std::string& subject)
    : file_(std::fopen(path.c_str(), "wb")), subject_(subject) {
    if (!file_) throw Error(subject_, "cannot create: " + errno_text(errno));
}

CheckedFile::~CheckedFile() {
    if (file_) std::fclose(file_); // only after a failure: close() was not reached
}

void CheckedFile::write(const void* data, std::size_t size) {
    if (error_ != 0 || size == 0) return;
    if (std::fwrite(data, 1, size, file_) != size) error_ = errno != 0 ? errno : EIO;
}

void CheckedFile::close(FileSync sync) {
    std::FILE* f = file_;
    file_ = nullptr;
    if (error_ == 0 && std::fflush(f) != 0) error_ = errno;
    if (error_ == 0 && sync == FileSync::Now && ::fsync(::fileno(f)) != 0) error_ = errno;
    if (std::fclose(f) != 0 && error_ == 0) error_ = errno;
    if (error_ != 0) throw Error(subject_, "cannot write: " + errno_text(error_));
}

void write_file_atomically(const std::string& path, const std::function<void(CheckedFile&)>& write) {
    write_atomically(path, [&](const std::string& temp) {
        CheckedFile file(temp, path);
        write(file);
        file.close();
    });
}

void write_atomically(const std::string& path, const std::function<void(const std::string&)>& write) {
    static std::atomic<unsigned> counter{0};
    const fs::path target(path);
    const fs::path folder = output_folder(target);
    check_output_folder(path);
    std::error_code ec;
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

void write_file_atomically(const std::string& path, const void* data, std::size_t size, FileSync sync) {
    write_atomically(path, [&](const std::string& temp) {
        CheckedFile file(temp, path);
        file.write(data, size);
        file.close(sync);
    });
}

FolderSync::FolderSync(const std::string& folder)
    : fd_(::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)), folder_(folder) {
    if (fd_ < 0) throw Error(folder, "cannot open: " + errno_text(errno));
}

FolderSync::~FolderSync() { ::close(fd_); }

void FolderSync::sync() {
    if (::syncfs(fd_) != 0) throw Error(folder_, "cannot write: " + errno_text(errno));
}

} // namespace overflight
