// `info` in map terms (DESIGN sec. 6.1): `--at POSITION` prints the terrain
// height there, equal to the raster value GDAL reads at that point; the extent
// is given in the grid's CRS and in longitude/latitude.
#include "TestSupport.h"

#include <gdal.h>
#include <nlohmann/json.hpp>
#include <ogr_spatialref.h>

namespace overflight {
namespace {

using test::run_overflight;

struct RasterPoint {
    double easting = 0, northing = 0, lon = 0, lat = 0;
    double value = 0; // band 1 at the pixel
};

// Centre of pixel (col, row) of `path`, its value and its lon/lat, by GDAL and OGR.
RasterPoint raster_point(const std::string& path, int col, int row) {
    RasterPoint p;
    GDALAllRegister();
    GDALDatasetH ds = GDALOpen(path.c_str(), GA_ReadOnly);
    EXPECT_NE(ds, nullptr);
    double gt[6];
    GDALGetGeoTransform(ds, gt);
    GDALApplyGeoTransform(gt, col + 0.5, row + 0.5, &p.easting, &p.northing);
    EXPECT_EQ(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Read, col, row, 1, 1, &p.value, 1, 1, GDT_Float64, 0, 0), CE_None);
    OGRSpatialReference crs(GDALGetProjectionRef(ds)), wgs84;
    crs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    wgs84.importFromEPSG(4326);
    OGRCoordinateTransformation* ct = OGRCreateCoordinateTransformation(&crs, &wgs84);
    p.lon = p.easting;
    p.lat = p.northing;
    EXPECT_TRUE(ct && ct->Transform(1, &p.lon, &p.lat));
    OGRCoordinateTransformation::DestroyCT(ct);
    GDALClose(ds);
    return p;
}

nlohmann::json info_at(const std::string& path, const std::string& position) {
    const test::RunResult r = run_overflight("info --json '" + path + "' --at " + position);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return nlohmann::json::parse(r.out);
}

TEST(InfoMap, HeightAtMatchesGdalsRasterValue) {
    // A projected DEM with square 30 m cells is not resampled: the terrain's
    // samples are the raster's pixels, so the heights agree exactly (Int16 metres).
    OVERFLIGHT_SHARED_FILE(path, "usgs-dem/SainteHelens.dem");
    for (const auto& [col, row] : {std::pair{150, 200}, std::pair{40, 300}, std::pair{250, 90}}) {
        const RasterPoint p = raster_point(path, col, row);
        ASSERT_GT(p.value, 600.0); // not no-data
        char crs[96], lonlat[96];
        std::snprintf(crs, sizeof crs, "crs:%.3f,%.3f", p.easting, p.northing);
        std::snprintf(lonlat, sizeof lonlat, "lonlat:%.9f,%.9f", p.lon, p.lat);
        for (const std::string& position : {std::string(crs), std::string(lonlat)}) {
            const nlohmann::json j = info_at(path, position);
            EXPECT_NEAR(j["at"]["height"].get<double>(), p.value, 1e-3) << position;
            EXPECT_NEAR(j["at"]["x"].get<double>(), 30.0 * col, 0.01) << position;
            EXPECT_NEAR(j["at"]["z"].get<double>(), 30.0 * row, 0.01) << position;
        }
    }
}

TEST(InfoMap, HeightAtOnAReprojectedSrtmTile) {
    // Rainier's tile is warped from degrees to UTM (bilinear), so the height
    // at Paradise is an interpolation of the source's pixels; on Paradise's
    // gentle meadows it stays within 10 m of GDAL's value of the pixel there
    // (gdallocationinfo -wgs84 gives 1651).
    OVERFLIGHT_SHARED_FILE(path, "srtm/mt_rainier_90m.tif");
    GDALAllRegister();
    GDALDatasetH ds = GDALOpen(path.c_str(), GA_ReadOnly);
    ASSERT_NE(ds, nullptr);
    double gt[6], inv[6];
    GDALGetGeoTransform(ds, gt);
    ASSERT_TRUE(GDALInvGeoTransform(gt, inv));
    double col = 0, row = 0;
    GDALApplyGeoTransform(inv, -121.7353, 46.7860, &col, &row);
    double value = 0;
    ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Read, int(col), int(row), 1, 1, &value, 1, 1, GDT_Float64, 0, 0),
              CE_None);
    GDALClose(ds);
    const nlohmann::json j = info_at(path, "lonlat:-121.7353,46.7860");
    EXPECT_NEAR(j["at"]["height"].get<double>(), value, 10.0);
    // The extent in lon/lat covers the source tile (1 degree from 46 N, 122 W).
    EXPECT_LT(j["lonlat_extent"]["lon_min"].get<double>(), -121.99);
    EXPECT_GT(j["lonlat_extent"]["lat_max"].get<double>(), 46.99);
    EXPECT_EQ(j["map_extent"]["crs"], "EPSG:32610");
    EXPECT_NEAR(j["default_camera"]["map"]["eye_lonlat"][1].get<double>(), 46.0, 0.1);
}

TEST(InfoMap, AtErrorsAreOneLine) {
    OVERFLIGHT_SHARED_FILE(path, "usgs-dem/SainteHelens.dem");
    for (const std::string& args : {"info '" + path + "' --at lonlat:0,0", std::string("info demo --demo-size 33 --at lonlat:1,2"),
                                    "info '" + path + "' --at 1,2,3"}) {
        const test::RunResult r = run_overflight(args);
        EXPECT_EQ(r.exit_code, 1) << args;
        EXPECT_EQ(test::line_count(r.err), 1) << r.err;
        EXPECT_EQ(r.err.rfind("overflight: --at: ", 0), 0u) << r.err;
    }
}

} // namespace
} // namespace overflight
