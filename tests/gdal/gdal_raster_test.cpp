// Rasters through GDAL (DESIGN sec. 4; Zamri, sec. 3): every file of
// ../shared/data with the size and elevation range its README gives, small
// DEMs made here (feet, float, negative, no-data) with values worked by hand,
// and the writers.
#include "TestSupport.h"
#include "core/Error.h"
#include "io/GdalRaster.h"
#include "io/ImageWriters.h"
#include "io/LoadTerrain.h"
#include "io/RasterFile.h"

#include <cmath>
#include <fstream>
#include <set>

namespace overflight {
namespace {

using test::ScratchDir;

std::string metadata(const DataSet& d, const std::string& key) {
    for (const auto& [k, v] : d.info.metadata)
        if (k == key) return v;
    return "<absent>";
}

// A projected georeference with square cells of `cell` metres.
RasterGeoreference utm(double cell) {
    RasterGeoreference g;
    g.geotransform = std::array<double, 6>{500000.0, cell, 0.0, 5000000.0, 0.0, -cell};
    g.crs = "EPSG:32610";
    return g;
}

Image2D<float> grid(int w, int h, std::initializer_list<float> values) {
    Image2D<float> img(w, h);
    img.pixels.assign(values.begin(), values.end());
    return img;
}

// ---- the shared data (README table) -------------------------------------

TEST(SharedData, SainteHelensUsgsDem) {
    OVERFLIGHT_SHARED_FILE(path, "usgs-dem/SainteHelens.dem");
    const DataSet d = load_terrain(path);
    // gdalinfo: "Size is 327, 468" = 327 columns (the DEM's profiles), 468 rows.
    EXPECT_EQ(d.terrain.cols(), 327);
    EXPECT_EQ(d.terrain.rows(), 468);
    EXPECT_EQ(d.terrain.h_scale(), 30.0f);
    // Whole metres stay exact: v_scale 1, y0 0, range exactly 682..2543.
    EXPECT_EQ(d.terrain.v_scale(), 1.0f);
    EXPECT_EQ(d.terrain.min_height(), 682.0f);
    EXPECT_EQ(d.terrain.max_height(), 2543.0f);
    EXPECT_GT(d.info.nodata_filled, 0); // the -32767 collar around the quadrangle
    EXPECT_FALSE(d.info.reprojected);
    EXPECT_NE(d.info.crs.find("UTM zone 10N"), std::string::npos) << d.info.crs;
    EXPECT_EQ(d.info.driver, "USGSDEM");
    // Record A (Zamri, sec. 3).
    EXPECT_EQ(metadata(d, "USGS_PROFILES"), "327");
    EXPECT_EQ(metadata(d, "USGS_MIN_ELEVATION"), "682");
    EXPECT_EQ(metadata(d, "USGS_MAX_ELEVATION"), "2543");
    EXPECT_EQ(metadata(d, "USGS_ZONE"), "10");
    EXPECT_EQ(metadata(d, "USGS_ELEVATION_UNITS"), "2 (metres)");
    EXPECT_EQ(metadata(d, "USGS_RESOLUTION"), "30, 30, 1");
}

// SRTM tiles are reprojected from degrees to UTM by bilinear resampling at
// about the native spacing; a one-sample peak or pit is then averaged with its
// neighbours, so the extremes move by up to 0.5 % of the relief (Fuji's summit
// is a single 3" sample). Size: the sample count stays within 10 % of native.
DataSet expect_srtm(const std::string& path, float lo, float hi, const std::string& zone) {
    DataSet d = load_terrain(path);
    const float tolerance = std::max(5.0f, 0.005f * (hi - lo));
    EXPECT_NEAR(d.terrain.min_height(), lo, tolerance);
    EXPECT_NEAR(d.terrain.max_height(), hi, tolerance);
    EXPECT_TRUE(d.info.reprojected);
    EXPECT_NE(d.info.crs.find("UTM zone " + zone), std::string::npos) << d.info.crs;
    const double samples = double(d.terrain.rows()) * d.terrain.cols();
    EXPECT_NEAR(samples / (1201.0 * 1201.0), 1.0, 0.10);
    // Square cells in metres near the 3" spacing (92 m north-south, less east-west).
    EXPECT_GT(d.terrain.h_scale(), 55.0f);
    EXPECT_LT(d.terrain.h_scale(), 95.0f);
    // Cells outside the tile's footprint after reprojection were filled, not left as spikes.
    EXPECT_GT(d.info.nodata_filled, 0);
    // The quantisation error is at most half a step over the whole relief.
    EXPECT_LE(d.terrain.v_scale(), (hi - lo + 2 * tolerance) / 65535.0f * 1.001f);
    return d;
}

TEST(SharedData, MtRainierSrtmGeoTiff) {
    OVERFLIGHT_SHARED_FILE(path, "srtm/mt_rainier_90m.tif");
    expect_srtm(path, 263, 4371, "10N");
}

TEST(SharedData, MtFujiSrtmNegativeElevations) {
    OVERFLIGHT_SHARED_FILE(path, "srtm/mt_fuji_90m.tif");
    expect_srtm(path, -16, 3742, "54N");
}

TEST(SharedData, N57E011Hgt) {
    OVERFLIGHT_SHARED_FILE(path, "srtm/N57E011.hgt");
    EXPECT_EQ(expect_srtm(path, -6, 163, "32N").info.driver, "SRTMHGT");
}

TEST(SharedData, CraterLakeFloatBt) {
    OVERFLIGHT_SHARED_FILE(path, "bt/crater_0513.bt");
    const DataSet d = load_terrain(path);
    // Its cells are 20.14 x 27.25 m: resampled to square 20.14 m cells, so the
    // 513 columns stay and the 513 rows become 27.25/20.14 * 512 + 1 = 694.
    EXPECT_EQ(d.terrain.cols(), 513);
    EXPECT_NEAR(d.terrain.rows(), 694, 1);
    EXPECT_NEAR(d.terrain.h_scale(), 20.1429f, 1e-3f);
    EXPECT_TRUE(d.info.reprojected);
    EXPECT_NEAR(d.terrain.min_height(), 1524.0f, 5.0f);
    EXPECT_NEAR(d.terrain.max_height(), 2478.0f, 5.0f);
    EXPECT_LT(d.terrain.v_scale(), 0.02f); // float mapping, not 1 m steps
}

TEST(SharedData, OlindaDemWithLandsatColor) {
    OVERFLIGHT_SHARED_FILE(dem, "paired/olinda/olinda_dem_utm25s.tif");
    OVERFLIGHT_SHARED_FILE(landsat, "paired/olinda/L7_ETMs.tif");
    LoadOptions options;
    options.color_path = landsat;
    const DataSet d = load_terrain(dem, options);
    EXPECT_EQ(d.terrain.rows(), 111);
    EXPECT_EQ(d.terrain.cols(), 111);
    EXPECT_NEAR(d.terrain.h_scale(), 89.994f, 1e-3f);
    EXPECT_EQ(d.terrain.min_height(), -1.0f);
    EXPECT_EQ(d.terrain.max_height(), 88.0f);
    EXPECT_EQ(d.terrain.colors().size(), 111u * 111u);
    std::set<std::uint32_t> distinct;
    for (const Rgb8& c : d.terrain.colors()) distinct.insert(std::uint32_t(c.r) << 16 | c.g << 8 | c.b);
    EXPECT_GT(distinct.size(), 100u) << "the Landsat colors must vary over the DEM";
    EXPECT_NE(d.info.color_source.find("bands 3,2,1"), std::string::npos) << d.info.color_source;
}

TEST(SharedData, GamePngHeightMapWithJpegColor) {
    OVERFLIGHT_SHARED_FILE(height, "game/arizonachase_h.png");
    OVERFLIGHT_SHARED_FILE(color, "game/arizonachase_c.jpg");
    LoadOptions options;
    options.color_path = color;
    const DataSet d = load_terrain(height, options);
    EXPECT_EQ(d.terrain.rows(), 1024);
    EXPECT_EQ(d.terrain.cols(), 1024);
    EXPECT_EQ(d.terrain.h_scale(), 1.0f); // no CRS, no geotransform
    EXPECT_EQ(d.terrain.min_height(), 4.0f);
    EXPECT_EQ(d.terrain.max_height(), 255.0f);
    EXPECT_TRUE(d.info.crs.empty());
    EXPECT_FALSE(d.info.reprojected);
    EXPECT_NE(d.terrain.color(0, 0), d.terrain.color(512, 512));
}

// ---- small DEMs made here ------------------------------------------------

TEST(GdalRaster, FeetAreConvertedToMetres) {
    ScratchDir dir;
    RasterGeoreference g = utm(10.0);
    g.unit = "ft";
    write_geotiff(dir / "feet.tif", grid(3, 2, {0, 100, 1000, 10, 20, 30}), g);
    const DataSet d = load_terrain(dir / "feet.tif");
    EXPECT_EQ(d.info.vertical_units, "foot");
    // 1000 ft = 304.8 m, 10 ft = 3.048 m: not whole metres, so a float mapping over 0..304.8 m.
    const float half_step = d.terrain.v_scale() / 2 + 1e-4f;
    EXPECT_NEAR(d.terrain.sample_height(0, 2), 304.8f, half_step);
    EXPECT_NEAR(d.terrain.sample_height(1, 0), 3.048f, half_step);
    EXPECT_NEAR(d.terrain.max_height(), 304.8f, half_step);
}

TEST(GdalRaster, UsSurveyFeetAreConvertedToMetres) {
    ScratchDir dir;
    RasterGeoreference g = utm(10.0);
    g.unit = "US survey foot";
    write_geotiff(dir / "usft.tif", grid(2, 2, {0, 3937, 0, 0}), g);
    const DataSet d = load_terrain(dir / "usft.tif");
    // 3937 US survey feet are exactly 1200 m.
    EXPECT_EQ(d.terrain.max_height(), 1200.0f);
    EXPECT_EQ(d.terrain.v_scale(), 1.0f);
}

TEST(GdalRaster, FloatNegativeDemKeepsHeightsWithinHalfAStep) {
    ScratchDir dir;
    const Image2D<float> z = grid(4, 3, {-12.25f, -3.5f, 0.0f, 0.125f, 7.75f, 100.5f, 250.0f, 999.875f, -0.001f, 42.42f,
                                         512.3f, 1.0f});
    write_geotiff(dir / "float.tif", z, utm(2.0));
    const DataSet d = load_terrain(dir / "float.tif");
    // v_scale = (999.875 + 12.25) / 65535 = 0.015444 m, y0 = -12.25.
    EXPECT_NEAR(d.terrain.v_scale(), (999.875 + 12.25) / 65535.0, 1e-7);
    EXPECT_EQ(d.terrain.y_offset(), -12.25f);
    EXPECT_EQ(d.terrain.h_scale(), 2.0f);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j)
            EXPECT_NEAR(d.terrain.sample_height(i, j), z.at(j, i), d.terrain.v_scale() / 2 + 1e-4f) << i << "," << j;
}

TEST(GdalRaster, NegativeIntegersKeepOneMetreSteps) {
    ScratchDir dir;
    write_geotiff(dir / "int.tif", grid(2, 2, {-16, 0, 3742, 5}), utm(90.0));
    const DataSet d = load_terrain(dir / "int.tif");
    EXPECT_EQ(d.terrain.v_scale(), 1.0f);
    EXPECT_EQ(d.terrain.y_offset(), -16.0f);
    EXPECT_EQ(d.terrain.sample_height(1, 0), 3742.0f);
    EXPECT_EQ(d.terrain.raw(0, 0), 0);
}

TEST(GdalRaster, BandScaleAndOffsetApply) {
    ScratchDir dir;
    RasterGeoreference g = utm(1.0);
    g.scale = 0.5;
    g.offset = 100;
    write_geotiff(dir / "scaled.tif", grid(2, 2, {0, 2, 4, 6}), g);
    const DataSet d = load_terrain(dir / "scaled.tif");
    EXPECT_EQ(d.terrain.sample_height(1, 1), 103.0f); // 6 * 0.5 + 100
}

TEST(GdalRaster, NoDataHoleInAFlatFieldTakesItsHeight) {
    ScratchDir dir;
    RasterGeoreference g = utm(1.0);
    g.nodata = -9999;
    write_geotiff(dir / "flat.tif", grid(4, 4, {7, 7, 7, 7, 7, -9999, -9999, 7, 7, -9999, -9999, 7, 7, 7, 7, 7}), g);
    const DataSet d = load_terrain(dir / "flat.tif");
    EXPECT_EQ(d.info.nodata_filled, 4);
    EXPECT_FALSE(d.info.nodata_method.empty());
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) EXPECT_EQ(d.terrain.sample_height(i, j), 7.0f);
}

TEST(GdalRaster, NoDataHoleIsFilledBetweenItsNeighbours) {
    ScratchDir dir;
    RasterGeoreference g = utm(1.0);
    g.nodata = -9999;
    // A ramp rising 10 m per column with a hole at the centre: inverse-distance
    // weighting is a convex combination of valid samples around it, so the
    // fill lies between the nearest columns' 10 and 30 m (GDALFillNodata's
    // quadrant search breaks ties unevenly, so not exactly at 20).
    write_geotiff(dir / "hole.tif",
                  grid(5, 5, {0, 10, 20, 30, 40, 0, 10, 20, 30, 40, 0, 10, -9999, 30, 40, 0, 10, 20, 30, 40, 0, 10, 20, 30, 40}),
                  g);
    const DataSet d = load_terrain(dir / "hole.tif");
    EXPECT_EQ(d.info.nodata_filled, 1);
    EXPECT_GE(d.terrain.sample_height(2, 2), 10.0f);
    EXPECT_LE(d.terrain.sample_height(2, 2), 30.0f);
    EXPECT_EQ(d.terrain.min_height(), 0.0f);
    EXPECT_EQ(d.terrain.max_height(), 40.0f);
}

TEST(GdalRaster, GeotransformWithoutCrsSetsTheCellSize) {
    ScratchDir dir;
    RasterGeoreference g;
    g.geotransform = std::array<double, 6>{0, 5, 0, 0, 0, -5};
    write_geotiff(dir / "nocrs.tif", grid(2, 2, {1, 2, 3, 4}), g);
    const DataSet d = load_terrain(dir / "nocrs.tif");
    EXPECT_EQ(d.terrain.h_scale(), 5.0f);
    EXPECT_TRUE(d.info.crs.empty());
}

TEST(GdalRaster, GeographicDemIsReprojectedToUtm) {
    ScratchDir dir;
    // 21x21 samples of 0.001 degrees at 46.5 N, 121.5 W, a plane rising 1 m per row.
    RasterGeoreference g;
    g.geotransform = std::array<double, 6>{-121.5, 0.001, 0, 46.5, 0, -0.001};
    g.crs = "EPSG:4326";
    Image2D<float> z(21, 21);
    for (int i = 0; i < 21; ++i)
        for (int j = 0; j < 21; ++j) z.at(j, i) = float(100 + i);
    write_geotiff(dir / "geo.tif", z, g);
    const DataSet d = load_terrain(dir / "geo.tif");
    EXPECT_TRUE(d.info.reprojected);
    EXPECT_NE(d.info.crs.find("UTM zone 10N"), std::string::npos) << d.info.crs;
    // 0.001 degrees: 111 m north-south, 76.6 m east-west at 46.5 N.
    EXPECT_GT(d.terrain.h_scale(), 70.0f);
    EXPECT_LT(d.terrain.h_scale(), 112.0f);
    EXPECT_NEAR(d.terrain.min_height(), 100.0f, 0.5f);
    EXPECT_NEAR(d.terrain.max_height(), 120.0f, 0.5f);
}

TEST(GdalRaster, EntirelyNoDataIsAnError) {
    ScratchDir dir;
    RasterGeoreference g = utm(1.0);
    g.nodata = -1;
    write_geotiff(dir / "empty.tif", grid(2, 2, {-1, -1, -1, -1}), g);
    try {
        load_terrain(dir / "empty.tif");
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.subject(), dir / "empty.tif");
        EXPECT_NE(e.problem().find("entirely no-data"), std::string::npos);
    }
}

TEST(GdalRaster, GarbageIsAnError) {
    ScratchDir dir;
    std::ofstream(dir / "garbage.tif") << "this is not a raster at all";
    try {
        load_terrain(dir / "garbage.tif");
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.subject(), dir / "garbage.tif");
        EXPECT_NE(e.problem().find("not a raster"), std::string::npos);
    }
}

TEST(GdalRaster, ColorRasterThatIsMissing) {
    ScratchDir dir;
    write_geotiff(dir / "dem.tif", grid(2, 2, {1, 2, 3, 4}), utm(1.0));
    LoadOptions options;
    options.color_path = dir / "nope.tif";
    try {
        load_terrain(dir / "dem.tif", options);
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.subject(), dir / "nope.tif");
    }
}

TEST(GdalRaster, SingleBandColorIsGreyOnTheDemGrid) {
    ScratchDir dir;
    write_geotiff(dir / "dem.tif", grid(2, 2, {1, 2, 3, 4}), utm(10.0));
    // A Float32 color band over the same 20 x 20 m: rescaled min..max -> 0..255.
    write_geotiff(dir / "grey.tif", grid(2, 2, {0, 1, 2, 3}), utm(10.0));
    LoadOptions options;
    options.color_path = dir / "grey.tif";
    const DataSet d = load_terrain(dir / "dem.tif", options);
    EXPECT_EQ(d.terrain.color(0, 0), (Rgb8{0, 0, 0}));
    EXPECT_EQ(d.terrain.color(1, 1), (Rgb8{255, 255, 255}));
    const Rgb8 mid = d.terrain.color(0, 1);
    EXPECT_EQ(mid.r, mid.g);
    EXPECT_NEAR(mid.r, 85, 1); // 1/3 of the way
}

// ---- writers ---------------------------------------------------------------

TEST(ImageWriters, DepthTiffRoundTrip) {
    ScratchDir dir;
    DepthImage depth(3, 2);
    depth.pixels = {0.0f, 0.5f, 1.0f, 0.25f, 0.999f, 1.0f};
    write_depth_tiff(dir / "depth.tif", depth);
    const Image2D<float> back = read_raster_band(dir / "depth.tif");
    EXPECT_EQ(back.width, 3);
    EXPECT_EQ(back.height, 2);
    EXPECT_EQ(back.pixels, depth.pixels);
}

TEST(ImageWriters, PngRoundTrip) {
    ScratchDir dir;
    ColorImage img(2, 2);
    img.pixels = {Rgb8{255, 0, 0}, Rgb8{0, 255, 0}, Rgb8{0, 0, 255}, Rgb8{10, 20, 30}};
    write_png(dir / "out.png", img);
    // Bands 1..3 are R, G, B; row 0 is the top.
    const Image2D<float> r = read_raster_band(dir / "out.png", 1), b = read_raster_band(dir / "out.png", 3);
    EXPECT_EQ(r.pixels, (ImagePixels<float>{255, 0, 0, 10}));
    EXPECT_EQ(b.pixels, (ImagePixels<float>{0, 0, 255, 30}));
}

TEST(ImageWriters, FailureLeavesNothingBehind) {
    ScratchDir dir;
    ColorImage img(2, 2);
    EXPECT_THROW(write_png(dir / "no/such/folder/out.png", img), Error);
    EXPECT_THROW(write_png(dir / "empty.png", ColorImage()), Error);
    EXPECT_THROW(write_depth_tiff(dir / "no/such/folder/d.tif", DepthImage(2, 2)), Error);
    EXPECT_TRUE(std::filesystem::is_empty(dir.path));
}

TEST(ImageWriters, ExistingFileIsReplacedWhole) {
    ScratchDir dir;
    write_png(dir / "out.png", ColorImage(4, 4, Rgb8{1, 1, 1}));
    write_png(dir / "out.png", ColorImage(2, 3, Rgb8{9, 9, 9}));
    const Image2D<float> r = read_raster_band(dir / "out.png", 1);
    EXPECT_EQ(r.width, 2);
    EXPECT_EQ(r.height, 3);
    // Only the result is left: no temporary file.
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path), std::filesystem::directory_iterator()), 1);
}

} // namespace
} // namespace overflight
