// Writers that check every write and the close (io/Files.h CheckedFile): the
// PNG, the depth TIFF and the flight record onto a full file system fail with
// one line naming the file and "no space left on device", leave no temporary
// file and keep the previous file as it was. Label gdal: the TIFF goes
// through GDAL. The file systems are small tmpfs mounts (tests/SmallFilesystem.h).
// Files synced later, with their folder (FolderSync), are whole at once.
#include "SmallFilesystem.h"
#include "TestSupport.h"
#include "core/Error.h"
#include "io/Files.h"
#include "io/FlightRecordFile.h"
#include "io/ImageWriters.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <set>

using namespace overflight;
using overflight::test::file_names_in;
using overflight::test::read_file_text;
using overflight::test::ScratchDir;

namespace {

// Pictures that do not compress to almost nothing: each pixel from a linear
// congruential generator (Numerical Recipes' constants).
template <class T, class Make>
Image2D<T> noise(int w, int h, Make make) {
    Image2D<T> img(w, h);
    std::uint32_t s = 12345;
    for (T& p : img.pixels) {
        s = s * 1664525u + 1013904223u;
        p = make(s);
    }
    return img;
}

ColorImage noisy_image(int w, int h) {
    return noise<Rgb8>(w, h, [](std::uint32_t s) {
        return Rgb8{std::uint8_t(s >> 24), std::uint8_t(s >> 16), std::uint8_t(s >> 8)};
    });
}

DepthImage noisy_depth(int w, int h) {
    return noise<float>(w, h, [](std::uint32_t s) { return float(s >> 8) / float(1u << 24); });
}

FlightRecord long_record(int frames) {
    FlightRecord r;
    for (int i = 0; i < frames; ++i) {
        FlightFrame f;
        f.frame = i;
        f.time = i / 60.0;
        f.eye = {100.0 + i * 0.123456789, 50.5, 200.0 - i * 0.987654321};
        f.heading = i * 0.7;
        f.pitch = -10.25;
        f.x = f.eye.x;
        f.z = f.eye.z;
        r.frames.push_back(f);
    }
    return r;
}

// `write` onto the full file system `fs` over an existing file `name`: throws
// Error(path, "cannot write: no space left on device"), the previous content
// stays, and no other file appears.
void expect_full_disk_error(const test::SmallFilesystem& fs, const std::string& name,
                            const std::function<void(const std::string&)>& write) {
    const std::string path = fs / name;
    {
        std::ofstream(path) << "previous";
    }
    fs.fill();
    const std::set<std::string> before = file_names_in(fs.path());
    try {
        write(path);
        ADD_FAILURE() << "no error for " << path;
    } catch (const Error& e) {
        EXPECT_EQ(e.subject(), path);
        EXPECT_EQ(e.problem(), "cannot write: no space left on device");
    }
    EXPECT_EQ(read_file_text(path), "previous");
    EXPECT_EQ(file_names_in(fs.path()), before);
    fs.free_space();
}

} // namespace

TEST(CheckedWrites, PngOnAFullDiskFailsAndKeepsThePreviousFile) {
    OVERFLIGHT_SMALL_FILESYSTEM(fs, 256 * 1024);
    const ColorImage img = noisy_image(64, 64); // about 12 KiB of PNG
    expect_full_disk_error(fs, "out.png", [&](const std::string& p) { write_png(p, img); });
    // With room again the same call writes a complete PNG (IEND last).
    write_png(fs / "out.png", img);
    const std::string png = read_file_text(fs / "out.png");
    ASSERT_GT(png.size(), 64u * 64u * 3u / 2u);
    EXPECT_EQ(png.substr(png.size() - 8, 4), "IEND");
}

TEST(CheckedWrites, DepthTiffOnAFullDiskFailsAndKeepsThePreviousFile) {
    OVERFLIGHT_SMALL_FILESYSTEM(fs, 256 * 1024);
    const DepthImage depth = noisy_depth(64, 64);
    expect_full_disk_error(fs, "depth.tif", [&](const std::string& p) { write_depth_tiff(p, depth); });
    write_depth_tiff(fs / "depth.tif", depth);
    EXPECT_GT(std::filesystem::file_size(fs / "depth.tif"), 64u * 64u); // float noise hardly compresses
}

TEST(CheckedWrites, FlightRecordOnAFullDiskFailsAndKeepsThePreviousFile) {
    OVERFLIGHT_SMALL_FILESYSTEM(fs, 256 * 1024);
    const FlightRecord record = long_record(500); // about 50 KiB of CSV
    expect_full_disk_error(fs, "flight.csv", [&](const std::string& p) { write_flight_record(p, record); });
    write_flight_record(fs / "flight.csv", record);
    EXPECT_EQ(read_flight_record(fs / "flight.csv"), record);
}

TEST(CheckedWrites, MissingFolderNamesTheFile) {
    ScratchDir dir;
    const std::string path = dir / "no/such/out.png";
    try {
        write_png(path, noisy_image(4, 4));
        ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.subject(), path);
        EXPECT_NE(e.problem().find("does not exist"), std::string::npos) << e.problem();
    }
    EXPECT_TRUE(file_names_in(dir.path).empty());
}

// Files written with FileSync::Later (the tiles of a tile folder) are whole
// at once under their final names; the folder's one sync then succeeds, and
// a folder that cannot be opened is named before anything is written.
TEST(CheckedWrites, FilesSyncedLaterWithTheirFolder) {
    ScratchDir dir;
    FolderSync later(dir.path);
    const std::string text(100000, 'x');
    for (int i = 0; i < 3; ++i)
        write_file_atomically(dir / ("f" + std::to_string(i)), text.data(), text.size(), FileSync::Later);
    later.sync();
    EXPECT_EQ(file_names_in(dir.path), (std::set<std::string>{"f0", "f1", "f2"}));
    EXPECT_EQ(read_file_text(dir / "f2"), text);
    const std::string missing = dir / "no-such-folder";
    try {
        FolderSync bad(missing);
        ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.subject(), missing);
        EXPECT_NE(e.problem().find("no such file or directory"), std::string::npos) << e.problem();
    }
}

TEST(CheckedWrites, ErrnoTextIsALowercasePhrase) {
    EXPECT_EQ(errno_text(ENOSPC), "no space left on device");
    EXPECT_EQ(errno_text(EIO), "input/output error");
}
