// Rasters that declare more than they hold, hold values no terrain has, or
// are not what the user meant: `overflight` must stop (or warn) with one line
// naming the file (DESIGN sec. 6), within a 512 MiB address space (except in
// the AddressSanitizer build, see RestrictedRun.h), without being killed.
// Inputs are made here with GDAL's API; each test also runs the nearest good
// input, so it can fail.
#include "RestrictedRun.h"
#include "TestSupport.h"
#include "io/RasterFile.h"

#include <gdal.h>
#include <ogr_srs_api.h>

#include <nlohmann/json.hpp>

#include <fstream>
#include <sys/stat.h>

namespace overflight {
namespace {

using test::Restrictions;
using test::run_overflight;
using test::run_overflight_restricted;
using test::ScratchDir;

constexpr Restrictions kHalfGiB{512ull << 20, false};

// A tiled GeoTIFF declaring cols x rows Int16 samples without writing any
// block: a few MB on disk, however large the declared raster.
void write_sparse_geotiff(const std::string& path, int cols, int rows) {
    GDALAllRegister();
    const char* options[] = {"SPARSE_OK=TRUE", "TILED=YES", "COMPRESS=DEFLATE", nullptr};
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), cols, rows, 1, GDT_Int16,
                                 const_cast<char**>(options));
    ASSERT_NE(ds, nullptr);
    GDALClose(ds);
    ASSERT_LT(std::filesystem::file_size(path), 4u << 20);
}

// A 4-profile USGS ASCII DEM in UTM zone 10N written by GDAL's USGSDEM driver.
void write_usgs_dem(const std::string& path) {
    GDALAllRegister();
    GDALDatasetH mem = GDALCreate(GDALGetDriverByName("MEM"), "", 4, 5, 1, GDT_Int16, nullptr);
    ASSERT_NE(mem, nullptr);
    double gt[6] = {500000, 30, 0, 5000150, 0, -30};
    GDALSetGeoTransform(mem, gt);
    OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
    OSRImportFromEPSG(srs, 32610);
    GDALSetSpatialRef(mem, srs);
    OSRDestroySpatialReference(srs);
    GDALFillRaster(GDALGetRasterBand(mem, 1), 100, 0);
    GDALDatasetH dem = GDALCreateCopy(GDALGetDriverByName("USGSDEM"), path.c_str(), mem, FALSE, nullptr, nullptr, nullptr);
    ASSERT_NE(dem, nullptr);
    GDALClose(dem);
    GDALClose(mem);
}

// Overwrites Record A element 16's column count (columns 859-864: the profiles).
void set_profile_count(const std::string& path, const char* six_digits) {
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(858);
    f.write(six_digits, 6);
}

test::RunResult info_in_half_a_gib(const std::string& path) {
    return run_overflight_restricted("info '" + path + "'", kHalfGiB);
}

TEST(UntrustedRaster, SparseGeoTiffLargerThanATerrainIsRefusedBeforeReading) {
    ScratchDir dir;
    const std::string path = dir / "huge.tif";
    write_sparse_geotiff(path, 100000, 100000);
    const test::RunResult r = info_in_half_a_gib(path);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err, "overflight: " + path + ": raster is 100000x100000, more than 65537 samples per side\n");
    const std::string small = dir / "small.tif";
    write_sparse_geotiff(small, 300, 200);
    EXPECT_EQ(info_in_half_a_gib(small).exit_code, 0);
}

// Needs a 512 MiB address-space limit, which an AddressSanitizer build cannot run under.
#if OVERFLIGHT_ADDRESS_SPACE_CAN_BE_LIMITED
TEST(UntrustedRaster, SparseGeoTiffBeyondMemoryFailsCleanly) {
    // Loaded at full resolution (sim; render, bench and fly decimate it, info
    // surveys it): 3.6e9 samples need more than most machines' memory (checked
    // before reading); 4e8 samples fit a machine but not the 512 MiB the child
    // may use (the allocation fails and is reported).
    for (const int side : {60000, 20000}) {
        ScratchDir dir;
        const std::string path = dir / "big.tif";
        write_sparse_geotiff(path, side, side);
        const test::RunResult r = run_overflight_restricted("sim '" + path + "' --steps 1", kHalfGiB);
        EXPECT_EQ(r.exit_code, 1);
        EXPECT_EQ(test::line_count(r.err), 1) << r.err;
        EXPECT_EQ(r.err.rfind("overflight: " + path + ": ", 0), 0u) << r.err;
        EXPECT_NE(r.err.find(std::to_string(side) + "x" + std::to_string(side)), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("memory"), std::string::npos) << r.err;
    }
}
#endif

TEST(UntrustedRaster, UsgsDemRecordAClaimingTooManyProfiles) {
    ScratchDir dir;
    const std::string path = dir / "quad.dem";
    write_usgs_dem(path);
    ASSERT_EQ(info_in_half_a_gib(path).exit_code, 0);
    const auto bytes = std::filesystem::file_size(path);

    set_profile_count(path, "999999");
    test::RunResult r = info_in_half_a_gib(path);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err, "overflight: " + path + ": Record A declares 999999 profiles, more than 65537\n");

    // `tile` reads a raster in windows, with no side limit but its grid's:
    // it refuses the file by its size.
    r = test::run_overflight("tile '" + path + "' -o '" + (dir / "tiles") + "'");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err, "overflight: " + path + ": Record A declares 999999 profiles but the file holds only " +
                         std::to_string(bytes) + " bytes (at least 144 per profile)\n");

    set_profile_count(path, " 60000");
    for (const std::string command : {"info", "tile"}) {
        r = command == "info" ? info_in_half_a_gib(path)
                              : test::run_overflight("tile '" + path + "' -o '" + (dir / "tiles") + "'");
        EXPECT_EQ(r.exit_code, 1);
        EXPECT_EQ(r.err, "overflight: " + path + ": Record A declares 60000 profiles but the file holds only " +
                             std::to_string(bytes) + " bytes (at least 144 per profile)\n");
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "tiles"));
}

TEST(UntrustedRaster, ElevationNearFloatMaxIsRefusedAtLoad) {
    ScratchDir dir;
    Image2D<float> heights(3, 3, 100.0f);
    heights.at(2, 1) = 3.0e38f;
    const std::string path = dir / "float.tif";
    write_geotiff(path, heights);
    for (const char* command : {"info", "info --json"}) {
        const test::RunResult r = run_overflight(std::string(command) + " '" + path + "'");
        EXPECT_EQ(r.exit_code, 1);
        EXPECT_EQ(r.err, "overflight: " + path +
                             ": row 1, column 2: elevation 3e+38 is beyond +-16777216 (2^24), where float world "
                             "coordinates no longer hold whole units (not a terrain height; is the no-data value set?)\n");
        EXPECT_TRUE(r.out.empty());
    }
    // The same value declared as no-data is a void, filled from its neighbours.
    write_geotiff(path, heights, RasterGeoreference{std::nullopt, "", 3.0e38f, "", 1.0, 0.0});
    const test::RunResult r = run_overflight("info --json '" + path + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(r.out)["elevation_max"], 100.0);
}

TEST(UntrustedRaster, RgbImageGivenAsDemIsReported) {
    ScratchDir dir;
    const std::string path = dir / "photo.tif";
    {
        GDALAllRegister();
        const char* options[] = {"PHOTOMETRIC=RGB", nullptr};
        GDALDatasetH ds =
            GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), 4, 4, 3, GDT_Byte, const_cast<char**>(options));
        ASSERT_NE(ds, nullptr);
        for (int b = 1; b <= 3; ++b) GDALFillRaster(GDALGetRasterBand(ds, b), 40.0 * b, 0);
        GDALClose(ds);
    }
    const std::string warning = "has 3 bands; band 1 (red) is taken as heights (an RGB image? give heights as "
                                "TERRAIN and the image as --color)";
    test::RunResult r = run_overflight("info '" + path + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("\nwarning: " + warning + "\n"), std::string::npos) << r.out;
    EXPECT_TRUE(r.err.empty()) << r.err;
    r = run_overflight("info --json '" + path + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(r.out)["warnings"], nlohmann::json::array({warning}));
    r = run_overflight("sim '" + path + "' --steps 1");
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_EQ(r.err, "overflight: " + path + ": warning: " + warning + "\n");
    // `tile` reads it in windows, and warns the same.
    r = run_overflight("tile '" + path + "' -o '" + (dir / "tiles") + "' --tile-size 33");
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_EQ(r.err, "overflight: " + path + ": warning: " + warning + "\n");

    // A one-band DEM says nothing.
    const std::string dem = dir / "dem.tif";
    write_geotiff(dem, Image2D<float>(4, 4, 40.0f));
    r = run_overflight("info --json '" + dem + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(r.out)["warnings"], nlohmann::json::array());
    r = run_overflight("sim '" + dem + "' --steps 1");
    EXPECT_TRUE(r.err.empty()) << r.err;
    r = run_overflight("tile '" + dem + "' -o '" + (dir / "dem_tiles") + "' --tile-size 33");
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST(UntrustedRaster, UnreadableFileIsPermissionDenied) {
    // Root reads a mode-000 file anyway: the child runs as `nobody` then.
    if (::geteuid() == 0 && !::getpwnam("nobody")) GTEST_SKIP() << "running as root without a `nobody` user";
    ScratchDir dir;
    std::filesystem::permissions(dir.path, std::filesystem::perms(0755));
    const std::string locked = dir / "locked.tif", open = dir / "open.tif";
    write_geotiff(locked, Image2D<float>(3, 3, 5.0f));
    write_geotiff(open, Image2D<float>(3, 3, 5.0f));
    ::chmod(locked.c_str(), 0);
    ::chmod(open.c_str(), 0644);
    // `nobody` may not enter the build tree (a clone under a 0700 folder): run a copy from here.
    const std::string exe = dir / "overflight";
    std::filesystem::copy_file(OVERFLIGHT_EXE, exe);
    const Restrictions as_user{0, true};
    const test::RunResult r = run_overflight_restricted("info '" + locked + "'", as_user, exe);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err, "overflight: " + locked + ": permission denied\n");
    const test::RunResult ok = run_overflight_restricted("info '" + open + "'", as_user, exe);
    EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

} // namespace
} // namespace overflight
