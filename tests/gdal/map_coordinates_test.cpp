// Positions in map coordinates (DESIGN sec. 6.1) on Mount Rainier's SRTM tile,
// which is loaded warped from WGS 84 degrees to UTM 10N: `--at lonlat:`,
// `crs:` and `--crs EPSG:4326` land where GDAL's own transform of the same
// point says (within 0.5 m), and `--look-at` puts the summit on the image
// centre with the depth there its distance (within 1 %). Expected positions
// are computed here with OGR and GDAL's geotransform functions directly.
#include "TestSupport.h"
#include "core/Camera.h"
#include "io/LoadTerrain.h"

#include <gdal.h>
#include <nlohmann/json.hpp>
#include <ogr_spatialref.h>

#include <cmath>

namespace overflight {
namespace {

using test::run_overflight;
using test::ScratchDir;

constexpr const char* kRainier = "srtm/mt_rainier_90m.tif";
// Paradise (the visitor centre on the south slope) and the summit (Columbia Crest).
constexpr double kParadiseLon = -121.7353, kParadiseLat = 46.7860;
constexpr double kSummitLon = -121.7603, kSummitLat = 46.8529;

// UTM easting, northing of lon/lat in `data`'s CRS, by OGR.
glm::dvec2 utm_of_lonlat(const DataSet& data, double lon, double lat) {
    OGRSpatialReference wgs84, utm;
    wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    utm.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    wgs84.importFromEPSG(4326);
    utm.importFromWkt(data.info.crs_wkt.c_str());
    OGRCoordinateTransformation* ct = OGRCreateCoordinateTransformation(&wgs84, &utm);
    double x = lon, y = lat;
    EXPECT_TRUE(ct && ct->Transform(1, &x, &y));
    OGRCoordinateTransformation::DestroyCT(ct);
    return {x, y};
}

// World X, Z of lon/lat on `data`'s grid, by OGR and GDAL's inverse geotransform.
glm::dvec2 gdal_world_of_lonlat(const DataSet& data, double lon, double lat) {
    const glm::dvec2 utm = utm_of_lonlat(data, lon, lat);
    double inv[6];
    EXPECT_TRUE(GDALInvGeoTransform(const_cast<double*>(data.info.geotransform.data()), inv));
    double col = 0, row = 0;
    GDALApplyGeoTransform(inv, utm.x, utm.y, &col, &row);
    // The sample of pixel (row, col) stands at its centre (DESIGN sec. 4).
    const double hs = data.terrain.h_scale();
    return {(col - 0.5) * hs, (row - 0.5) * hs};
}

// The camera file written for `position_args` on Rainier (32x24 unless they give --size).
nlohmann::json saved_camera(const std::string& path, const std::string& position_args, const ScratchDir& dir) {
    const std::string cam = dir / "cam.json";
    const std::string size = position_args.find("--size") == std::string::npos ? " --size 32x24 " : " ";
    const test::RunResult r = run_overflight("render '" + path + "' -o '" + dir / "v.png" + "'" + size +
                                             position_args + " --save-camera '" + cam + "'");
    EXPECT_EQ(r.exit_code, 0) << position_args << ": " << r.err;
    return nlohmann::json::parse(test::read_file_text(cam));
}

TEST(MapCoordinates, LonLatCrsAndEpsgAgreeWithGdal) {
    OVERFLIGHT_SHARED_FILE(path, kRainier);
    ScratchDir dir;
    const DataSet data = load_terrain(path);
    ASSERT_TRUE(data.info.georeferenced);
    const glm::dvec2 expected = gdal_world_of_lonlat(data, kParadiseLon, kParadiseLat);
    const glm::dvec2 utm = utm_of_lonlat(data, kParadiseLon, kParadiseLat);
    char lonlat[64], en[64];
    std::snprintf(lonlat, sizeof lonlat, "%.7f,%.7f", kParadiseLon, kParadiseLat);
    std::snprintf(en, sizeof en, "%.4f,%.4f", utm.x, utm.y);
    for (const std::string& args : {"--at lonlat:" + std::string(lonlat) + " --agl 2",
                                    "--at crs:" + std::string(en) + " --agl 2",
                                    "--crs EPSG:4326 --at " + std::string(lonlat) + " --agl 2",
                                    "--eye lonlat:" + std::string(lonlat) + " --agl 2"}) {
        const nlohmann::json j = saved_camera(path, args, dir);
        EXPECT_NEAR(j["eye"][0].get<double>(), expected.x, 0.5) << args;
        EXPECT_NEAR(j["eye"][2].get<double>(), expected.y, 0.5) << args;
        // The camera file's map eye is the same point back in both map terms.
        EXPECT_NEAR(j["map"]["eye"][0].get<double>(), utm.x, 0.5) << args;
        EXPECT_NEAR(j["map"]["eye"][1].get<double>(), utm.y, 0.5) << args;
        EXPECT_NEAR(j["map"]["eye_lonlat"][0].get<double>(), kParadiseLon, 1e-5) << args;
        EXPECT_NEAR(j["map"]["eye_lonlat"][1].get<double>(), kParadiseLat, 1e-5) << args;
        EXPECT_EQ(j["map"]["crs"], "EPSG:32610") << args;
    }
    // An eye with its elevation: Y is H.
    const nlohmann::json j = saved_camera(path, "--eye lonlat:" + std::string(lonlat) + ",2500", dir);
    EXPECT_EQ(j["eye"][1].get<double>(), 2500.0);
    EXPECT_NEAR(j["eye"][0].get<double>(), expected.x, 0.5);
}

TEST(MapCoordinates, LookAtPutsTheSummitOnTheImageCentre) {
    OVERFLIGHT_SHARED_FILE(path, kRainier);
    ScratchDir dir;
    const DataSet data = load_terrain(path);
    char args[256];
    std::snprintf(args, sizeof args, "--eye lonlat:%.7f,%.7f,7000 --look-at lonlat:%.7f,%.7f --size 201x151",
                  kParadiseLon, kParadiseLat, kSummitLon, kSummitLat);
    const std::string depth = dir / "depth.tif";
    const nlohmann::json j = saved_camera(path, std::string(args) + " --depth '" + depth + "'", dir);
    Camera cam;
    cam.eye = {j["eye"][0], j["eye"][1], j["eye"][2]};
    cam.heading = j["heading"];
    cam.pitch = j["pitch"];
    cam.fov = j["fov"];
    cam.near = j["near"];
    cam.far = j["far"];
    cam.width = j["width"];
    cam.height = j["height"];
    const glm::dvec2 summit = gdal_world_of_lonlat(data, kSummitLon, kSummitLat);
    const glm::dvec3 target{summit.x, data.terrain.height_bilinear(float(summit.x), float(summit.y)), summit.y};
    const Camera::Projected p = cam.project(target);
    EXPECT_NEAR(p.col, 100.5, 1.0);
    EXPECT_NEAR(p.row, 75.5, 1.0);
    // The centre pixel sees the summit: its depth is the summit's distance
    // along the (horizontal, shear) view axis. The eye is 7000 m above
    // Paradise, so the ray comes down onto the summit at about 19 degrees
    // rather than grazing the dome (seen from Paradise's ground a grazing
    // ray meets the 90 m blocks of the dome's near side first).
    GDALAllRegister();
    GDALDatasetH ds = GDALOpen(depth.c_str(), GA_ReadOnly);
    ASSERT_NE(ds, nullptr);
    float wd = 0;
    ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Read, 100, 75, 1, 1, &wd, 1, 1, GDT_Float32, 0, 0), CE_None);
    GDALClose(ds);
    const double expected = cam.view_depth(target);
    EXPECT_GT(expected, 5000.0); // the summit is about 7.7 km from Paradise
    EXPECT_NEAR(cam.view_depth_of_window(wd), expected, 0.01 * expected);
}

TEST(MapCoordinates, OneLineErrors) {
    OVERFLIGHT_SHARED_FILE(path, kRainier);
    ScratchDir dir;
    const std::string out = " -o '" + dir / "v.png" + "' --size 16x16 ";
    const std::pair<std::string, std::string> cases[] = {
        {"render demo" + out + "--at lonlat:-121.7,46.8", "overflight: --at: the terrain demo has no georeferencing"},
        {"render '" + path + "'" + out + "--at lonlat:10,50", "overflight: --at: point "},
        {"render '" + path + "'" + out + "--look-at crs:1,2", "overflight: --look-at: point "},
        {"render '" + path + "'" + out + "--crs EPSG:999999 --at 1,2", "overflight: --at: 'EPSG:999999' is not a CRS"},
        {"render '" + path + "'" + out + "--at lonlat:1,2,3", "overflight: --at: 'lonlat:1,2,3' gives a height"},
        {"render '" + path + "'" + out + "--at lonlat:x,2", "overflight: --at: 'x,2' is not E,N[,H]"},
    };
    for (const auto& [args, start] : cases) {
        const test::RunResult r = run_overflight(args);
        EXPECT_EQ(r.exit_code, 1) << args;
        EXPECT_EQ(test::line_count(r.err), 1) << r.err;
        EXPECT_EQ(r.err.rfind(start, 0), 0u) << args << "\n" << r.err;
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "v.png"));
}

} // namespace
} // namespace overflight
