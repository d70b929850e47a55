// `overflight info` on GDAL rasters (DESIGN sec. 4, 6): the JSON report of a
// USGS DEM and an SRTM tile, and the one-line errors of bad rasters.
#include "TestSupport.h"
#include "io/RasterFile.h"

#include <nlohmann/json.hpp>

#include <fstream>

namespace overflight {
namespace {

using test::line_count;
using test::run_overflight;
using test::ScratchDir;

void expect_one_line_error(const std::string& args, const std::string& file, const std::string& words) {
    const test::RunResult r = run_overflight(args);
    EXPECT_NE(r.exit_code, 0) << args;
    EXPECT_EQ(line_count(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("overflight: " + file + ": ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(words), std::string::npos) << r.err;
}

TEST(InfoGdalCli, UsgsDemJson) {
    OVERFLIGHT_SHARED_FILE(path, "usgs-dem/SainteHelens.dem");
    const test::RunResult r = run_overflight("info --json '" + path + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(r.err.empty()) << "GDAL chatter must be silenced: " << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["rows"], 468);
    EXPECT_EQ(j["cols"], 327);
    EXPECT_EQ(j["h_scale"], 30.0);
    EXPECT_EQ(j["v_scale"], 1.0);
    EXPECT_EQ(j["y_offset"], 0.0);
    EXPECT_EQ(j["elevation_min"], 682.0);
    EXPECT_EQ(j["elevation_max"], 2543.0);
    EXPECT_EQ(j["extent_x"], 30.0 * 326);
    EXPECT_EQ(j["extent_z"], 30.0 * 467);
    EXPECT_GT(j["nodata_filled"].get<long long>(), 0);
    EXPECT_EQ(j["reprojected"], false);
    EXPECT_EQ(j["color_source"], "elevation ramp + hillshade");
    EXPECT_EQ(j["metadata"]["USGS_PROFILES"], "327");
    EXPECT_NE(j["crs"].get<std::string>().find("UTM zone 10N"), std::string::npos);
}

TEST(InfoGdalCli, SrtmReportsTheReprojection) {
    OVERFLIGHT_SHARED_FILE(path, "srtm/N57E011.hgt");
    const test::RunResult r = run_overflight("info --json '" + path + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["reprojected"], true);
    EXPECT_NE(j["source_crs"].get<std::string>().find("WGS 84"), std::string::npos);
    EXPECT_NE(j["crs"].get<std::string>().find("UTM zone 32N"), std::string::npos);
    EXPECT_FALSE(j["reprojection"].get<std::string>().empty());
}

TEST(InfoGdalCliErrors, GarbageRaster) {
    ScratchDir dir;
    std::ofstream(dir / "garbage.dem") << "\x01\x02 not a DEM \xff";
    expect_one_line_error("info '" + dir / "garbage.dem" + "'", dir / "garbage.dem", "not a raster");
}

TEST(InfoGdalCliErrors, TruncatedGeoTiff) {
    OVERFLIGHT_SHARED_FILE(src, "srtm/mt_rainier_90m.tif");
    ScratchDir dir;
    std::ifstream in(src, std::ios::binary);
    std::string head(4096, '\0');
    in.read(head.data(), std::streamsize(head.size()));
    std::ofstream(dir / "cut.tif", std::ios::binary) << head;
    const test::RunResult r = run_overflight("info '" + dir / "cut.tif" + "'");
    EXPECT_NE(r.exit_code, 0);
    EXPECT_EQ(line_count(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("overflight: " + dir / "cut.tif" + ": ", 0), 0u) << r.err;
}

TEST(InfoGdalCliErrors, EntirelyNoData) {
    ScratchDir dir;
    Image2D<float> z(3, 3, -9999.0f);
    RasterGeoreference g;
    g.nodata = -9999;
    write_geotiff(dir / "void.tif", z, g);
    expect_one_line_error("info '" + dir / "void.tif" + "'", dir / "void.tif", "entirely no-data");
}

TEST(InfoGdalCliErrors, MissingColorRaster) {
    OVERFLIGHT_SHARED_FILE(dem, "paired/olinda/olinda_dem_utm25s.tif");
    ScratchDir dir;
    expect_one_line_error("info '" + dem + "' --color '" + dir / "none.tif" + "'", dir / "none.tif", "no such file");
}

} // namespace
} // namespace overflight
