// Rasters larger than a direct render takes (DESIGN sec. 4, 6): `info` surveys
// them from metadata and a sample without reading them whole, and render,
// bench and fly read them decimated through GDAL in bounded memory. The
// rasters are made here: small ones with values worked by hand, compared
// with the full-resolution load, and large sparse GeoTIFFs (a few MB on disk
// whatever their declared size) for the memory bound and the limits.
#include "RestrictedRun.h"
#include "TestSupport.h"
#include "io/GdalRaster.h"
#include "io/RasterFile.h"

#include <gdal.h>
#include <nlohmann/json.hpp>

#include <cmath>

namespace overflight {
namespace {

using test::ScratchDir;

// A whole-metre pattern with no two samples of a 4x4 block alike, so that a
// block mean taken in the wrong place shows.
float pattern(int col, int row) { return float(100 + 7 * col + 3 * row + (col * row) % 5); }

RasterGeoreference utm10m() {
    RasterGeoreference g;
    g.geotransform = std::array<double, 6>{500000.0, 10.0, 0.0, 5000000.0, 0.0, -10.0};
    g.crs = "EPSG:32610";
    return g;
}

// Elevation in metres of sample (row, col) of a loaded terrain.
double metres(const Terrain& t, int row, int col) { return t.sample_height(row, col); }

TEST(BigRaster, DecimatedLoadIsTheBlockMeanOfTheFullLoad) {
    ScratchDir dir;
    const std::string path = dir / "dem.tif";
    Image2D<float> z(61, 47);
    for (int r = 0; r < z.height; ++r)
        for (int c = 0; c < z.width; ++c) z.at(c, r) = pattern(c, r);
    write_geotiff(path, z, utm10m());

    const DataSet full = load_gdal_raster(path);
    EXPECT_EQ(full.info.decimation, 1);
    EXPECT_EQ(load_gdal_raster(path, "", 61).terrain.cols(), 61); // at the limit: full resolution

    // 61 > 20: decimated by ceil(61 / 20) = 4 to 15x11 (the last 61 % 4 columns
    // and 47 % 4 rows left out), cells of 40 m.
    const DataSet dec = load_gdal_raster(path, "", 20);
    const Terrain& t = dec.terrain;
    ASSERT_EQ(t.cols(), 15);
    ASSERT_EQ(t.rows(), 11);
    EXPECT_EQ(t.h_scale(), 40.0f);
    EXPECT_EQ(dec.info.decimation, 4);
    EXPECT_EQ(dec.info.warnings, std::vector<std::string>{"61x47 samples is more than --max-direct-size 20; rendering "
                                                          "it decimated by 4 to 15x11 (overflight tile keeps the full "
                                                          "resolution)"});
    EXPECT_EQ(dec.info.geotransform, (std::array<double, 6>{500000.0, 40.0, 0.0, 5000000.0, 0.0, -40.0}));
    // Each sample is the mean of its 4x4 block of the full-resolution load, to
    // within half a 16-bit step of the decimated mapping.
    for (int r = 0; r < t.rows(); ++r)
        for (int c = 0; c < t.cols(); ++c) {
            double sum = 0;
            for (int i = 0; i < 4; ++i)
                for (int j = 0; j < 4; ++j) sum += metres(full.terrain, 4 * r + i, 4 * c + j);
            ASSERT_NEAR(metres(t, r, c), sum / 16, t.v_scale() / 2 + 1e-3) << r << "," << c;
        }
}

TEST(BigRaster, DecimationLeavesNoDataOutOfTheMeans) {
    ScratchDir dir;
    const std::string path = dir / "voids.tif";
    Image2D<float> z(8, 8, 50.0f);
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) z.at(c, r) = -9999.0f; // block (0, 0): no-data only
    z.at(4, 0) = -9999.0f;                                 // block (0, 1): one void among 50s
    z.at(5, 0) = 90.0f;
    RasterGeoreference g = utm10m();
    g.nodata = -9999.0;
    write_geotiff(path, z, g);
    const DataSet dec = load_gdal_raster(path, "", 2);
    const Terrain& t = dec.terrain;
    ASSERT_EQ(t.rows(), 2);
    ASSERT_EQ(t.cols(), 2);
    // (90 + 14 * 50) / 15 without the void; the void block is filled from its neighbours.
    EXPECT_NEAR(metres(t, 0, 1), (90.0 + 14 * 50.0) / 15, t.v_scale());
    EXPECT_EQ(dec.info.nodata_filled, 1);
    EXPECT_NEAR(metres(t, 0, 0), 50.0, 3.0);
}

TEST(BigRaster, DecimatedGeographicRasterIsWarpedToCoarserCells) {
    ScratchDir dir;
    const std::string path = dir / "geo.tif";
    // 120x90 samples of 3 arc-seconds near 47 N, heights rising 1 m per sample eastwards.
    Image2D<float> z(120, 90);
    for (int r = 0; r < z.height; ++r)
        for (int c = 0; c < z.width; ++c) z.at(c, r) = float(1000 + c);
    RasterGeoreference g;
    g.geotransform = std::array<double, 6>{9.0, 1.0 / 1200, 0.0, 47.0, 0.0, -1.0 / 1200};
    g.crs = "EPSG:4326";
    write_geotiff(path, z, g);

    const DataSet full = load_gdal_raster(path);
    const DataSet dec = load_gdal_raster(path, "", 40);
    const int f = dec.info.decimation;
    const int side = std::max(full.terrain.rows(), full.terrain.cols());
    EXPECT_EQ(f, (side + 39) / 40);
    EXPECT_LE(dec.terrain.cols(), 40);
    EXPECT_LE(dec.terrain.rows(), 40);
    EXPECT_EQ(dec.info.crs, full.info.crs);
    EXPECT_NEAR(dec.terrain.h_scale(), f * full.terrain.h_scale(), 1e-3);
    EXPECT_NEAR(dec.terrain.cols(), double(full.terrain.cols()) / f, 1.0);
    // The same ground: the decimated sample at the centre of each block of the
    // full grid, on a surface that is nearly a plane, within a metre.
    for (int r = 1; r + 1 < dec.terrain.rows(); ++r)
        for (int c = 1; c + 1 < dec.terrain.cols(); ++c) {
            const float x = (float(c) + 0.5f) * dec.terrain.h_scale() - 0.5f * full.terrain.h_scale();
            const float zz = (float(r) + 0.5f) * dec.terrain.h_scale() - 0.5f * full.terrain.h_scale();
            ASSERT_NEAR(metres(dec.terrain, r, c), full.terrain.height_bilinear(x, zz), 1.0) << r << "," << c;
        }
}

// The survey `info` makes of a large raster gives the figures of the full
// load, exactly where they come from the metadata, and the elevation range of
// the samples it read (all of them, for a raster this small).
TEST(BigRaster, SurveyAgreesWithTheFullLoad) {
    ScratchDir dir;
    const std::string projected = dir / "utm.tif", geographic = dir / "geo.tif";
    Image2D<float> z(70, 50);
    for (int r = 0; r < z.height; ++r)
        for (int c = 0; c < z.width; ++c) z.at(c, r) = pattern(c, r);
    write_geotiff(projected, z, utm10m());
    RasterGeoreference g;
    g.geotransform = std::array<double, 6>{-122.0, 1.0 / 1200, 0.0, 46.0, 0.0, -1.0 / 1200};
    g.crs = "EPSG:4326";
    write_geotiff(geographic, z, g);
    for (const std::string& path : {projected, geographic}) {
        const TerrainDescription exact = describe(load_gdal_raster(path));
        const TerrainDescription survey = survey_gdal_raster(path);
        EXPECT_TRUE(exact.approximation.empty());
        EXPECT_FALSE(survey.approximation.empty());
        EXPECT_EQ(survey.rows, exact.rows) << path;
        EXPECT_EQ(survey.cols, exact.cols) << path;
        EXPECT_FLOAT_EQ(survey.h_scale, exact.h_scale) << path;
        EXPECT_FLOAT_EQ(survey.extent_x, exact.extent_x) << path;
        EXPECT_FLOAT_EQ(survey.extent_z, exact.extent_z) << path;
        EXPECT_EQ(survey.info.crs, exact.info.crs) << path;
        EXPECT_EQ(survey.info.source_crs, exact.info.source_crs) << path;
        EXPECT_EQ(survey.info.reprojected, exact.info.reprojected) << path;
        EXPECT_EQ(survey.info.reprojection, exact.info.reprojection) << path;
        for (int k = 0; k < 6; ++k) EXPECT_NEAR(survey.info.geotransform[k], exact.info.geotransform[k], 1e-6) << path;
        EXPECT_EQ(survey.info.metadata, exact.info.metadata) << path;
    }
    // Projected, whole metres, no voids: the sampled range and mapping are the loaded ones.
    const TerrainDescription exact = describe(load_gdal_raster(projected));
    const TerrainDescription survey = survey_gdal_raster(projected);
    EXPECT_EQ(survey.elevation_min, exact.elevation_min);
    EXPECT_EQ(survey.elevation_max, exact.elevation_max);
    EXPECT_EQ(survey.v_scale, exact.v_scale);
    EXPECT_EQ(survey.y_offset, exact.y_offset);
    EXPECT_EQ(survey.elevation_min, 100.0f);
    EXPECT_EQ(survey.elevation_max, float(pattern(69, 49)));
}

// A tiled GeoTIFF declaring side x side Int16 samples with only its first
// block written (a 50 m bump on a field of 0 m, GDAL's value for unwritten
// blocks of a band without no-data): a few MB on disk whatever the side.
void write_sparse_dem(const std::string& path, int side) {
    GDALAllRegister();
    const char* options[] = {"SPARSE_OK=TRUE", "TILED=YES", "COMPRESS=DEFLATE", nullptr};
    GDALDatasetH ds =
        GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), side, side, 1, GDT_Int16, const_cast<char**>(options));
    ASSERT_NE(ds, nullptr);
    double gt[6] = {500000, 10, 0, 5000000, 0, -10};
    GDALSetGeoTransform(ds, gt);
    GDALSetProjection(ds, "EPSG:32610");
    std::vector<std::int16_t> bump(256 * 256, 50);
    ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, 256, 256, bump.data(), 256, 256, GDT_Int16, 0, 0),
              CE_None);
    GDALClose(ds);
    ASSERT_LT(std::filesystem::file_size(path), 4u << 20);
}

TEST(BigRaster, SurveyReadsAnOverviewWhenTheRasterHasOne) {
    ScratchDir dir;
    const std::string path = dir / "ov.tif";
    write_sparse_dem(path, 5000);
    {
        GDALDatasetH ds = GDALOpen(path.c_str(), GA_Update);
        ASSERT_NE(ds, nullptr);
        int levels[] = {2, 4};
        ASSERT_EQ(GDALBuildOverviews(ds, "AVERAGE", 2, levels, 0, nullptr, nullptr, nullptr), CE_None);
        GDALClose(ds);
    }
    // 2500x2500 is the smallest overview holding the 4194304 samples a survey reads.
    const TerrainDescription d = survey_gdal_raster(path);
    EXPECT_NE(d.approximation.find("(overview 2500x2500)"), std::string::npos) << d.approximation;
    EXPECT_EQ(d.elevation_min, 0.0f);
    EXPECT_EQ(d.elevation_max, 50.0f);
    EXPECT_EQ(d.rows, 5000);
}

// Needs an address-space limit, which an AddressSanitizer build cannot run under.
#if OVERFLIGHT_ADDRESS_SPACE_CAN_BE_LIMITED
TEST(BigRasterCli, InfoOnALargeRasterSurveysItInBoundedMemory) {
    // 20000^2 samples: a full load needs about 6 GiB; the survey reads a sample.
    ScratchDir dir;
    const std::string path = dir / "big.tif";
    write_sparse_dem(path, 20000);
    const test::Restrictions half_gib{512ull << 20, false};
    test::RunResult r = test::run_overflight_restricted("info --json '" + path + "'", half_gib);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["rows"], 20000);
    EXPECT_EQ(j["cols"], 20000);
    EXPECT_EQ(j["h_scale"], 10.0);
    EXPECT_EQ(j["extent_x"], 199990.0);
    EXPECT_EQ(j["approximate"], true);
    EXPECT_EQ(j["elevation_min"], 0.0);
    EXPECT_NE(j["approximation"].get<std::string>().find("blocks of 256x256"), std::string::npos) << j;
    EXPECT_NE(j["crs"].get<std::string>().find("UTM zone 10N"), std::string::npos);
    r = test::run_overflight_restricted("info '" + path + "'", half_gib);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("\nelevation_min: 0.0 (approximate)\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\nrows: 20000\n"), std::string::npos) << r.out;
}

TEST(BigRasterCli, RenderDecimatesALargeRasterInBoundedMemory) {
    ScratchDir dir;
    const std::string path = dir / "big.tif";
    write_sparse_dem(path, 20000);
    // Decimated by 20 to 1000x1000: a few MB of terrain, where a full load would need 6 GiB.
    const test::RunResult r = test::run_overflight_restricted(
        "render '" + path + "' --max-direct-size 1000 --size 64x48 -o '" + dir / "out.png" + "'", {3ull << 30, false});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "overflight: " + path +
                         ": warning: 20000x20000 samples is more than --max-direct-size 1000; rendering it decimated "
                         "by 20 to 1000x1000 (overflight tile keeps the full resolution)\n");
    EXPECT_TRUE(std::filesystem::exists(dir / "out.png"));
}
#endif

TEST(BigRasterCli, RasterBeyondTheTerrainLimitIsOneLine) {
    ScratchDir dir;
    const std::string path = dir / "huge.tif";
    write_sparse_dem(path, 70000);
    for (const std::string& command : std::vector<std::string>{"info", "render -o '" + dir / "out.png" + "'"}) {
        const test::RunResult r = test::run_overflight(command + " '" + path + "'");
        EXPECT_EQ(r.exit_code, 1);
        EXPECT_EQ(r.err, "overflight: " + path + ": raster is 70000x70000, more than 65537 samples per side\n");
    }
}

TEST(BigRasterCli, MaxDirectSizeOutOfRangeIsOneLine) {
    const test::RunResult r = test::run_overflight("render demo --demo-size 33 --max-direct-size 1 -o /dev/null");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err, "overflight: --max-direct-size: 1 is not a side in 2..65537 samples\n");
}

} // namespace
} // namespace overflight
