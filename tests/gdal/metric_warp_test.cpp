// The reprojection onto metric cells (io/MetricWarp.h): PROJ on a lattice of
// every 16th grid sample, bilinear between, stays within a hundredth of a
// source pixel of PROJ on every sample (a generated geographic raster and the
// SRTM DEMs), and any window of the grid reads the same floats as the whole
// grid, voids and the wedges outside the source included.
#include "TestSupport.h"

#include "io/Gdal.h"
#include "io/GdalSource.h"
#include "io/MetricWarp.h"

#include <gdal.h>
#include <gtest/gtest.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <vector>

using namespace overflight;

namespace {

// A cols x rows Int16 GeoTIFF in EPSG:4326 on `cell`-degree cells from
// (lon, lat), hills and noise, no-data -32768 in a few 9x9 squares.
void write_geographic(const std::string& path, int rows, int cols, double lon, double lat, double cell) {
    GDALAllRegister();
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), cols, rows, 1, GDT_Int16, nullptr);
    ASSERT_NE(ds, nullptr);
    OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
    OSRImportFromEPSG(srs, 4326);
    GDALSetSpatialRef(ds, srs);
    OSRDestroySpatialReference(srs);
    double gt[6] = {lon, cell, 0, lat, 0, -cell};
    GDALSetGeoTransform(ds, gt);
    GDALRasterBandH band = GDALGetRasterBand(ds, 1);
    GDALSetRasterNoDataValue(band, -32768);
    std::vector<std::int16_t> z(std::size_t(rows) * std::size_t(cols));
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < cols; ++j)
            z[std::size_t(i) * cols + j] =
                std::int16_t(900 + 400 * std::sin(i * 0.031) * std::cos(j * 0.043) + 7 * ((i * 7 + j * 13) % 11));
    for (int h = 0; h < 5; ++h) {
        const int ci = (h * 131 + 40) % rows, cj = (h * 97 + 60) % cols;
        for (int i = std::max(0, ci - 4); i <= std::min(rows - 1, ci + 4); ++i)
            for (int j = std::max(0, cj - 4); j <= std::min(cols - 1, cj + 4); ++j) z[std::size_t(i) * cols + j] = -32768;
    }
    ASSERT_EQ(GDALRasterIO(band, GF_Write, 0, 0, cols, rows, z.data(), cols, rows, GDT_Int16, 0, 0), CE_None);
    GDALClose(ds);
}

// The UTM grid the loader warps a geographic raster onto (GDAL's suggested output).
MetricGridSpec utm_grid_of(GDALDatasetH ds) {
    double g[6];
    GDALGetGeoTransform(ds, g);
    const int cols = GDALGetRasterXSize(ds), rows = GDALGetRasterYSize(ds);
    const Srs utm = utm_for(GDALGetSpatialRef(ds), g[0] + g[1] * cols / 2, g[3] + g[5] * rows / 2);
    MetricGridSpec spec;
    spec.wkt = to_wkt(utm.get());
    const gdal::SuggestedWarpOutput out(ds, spec.wkt, "test", "no grid");
    std::copy(out.geotransform, out.geotransform + 6, spec.gt.begin());
    spec.cols = out.cols;
    spec.rows = out.rows;
    return spec;
}

// The largest distance, in source pixels, between the lattice's source
// position and PROJ's over every `step`-th sample of the grid (and the
// samples just inside its last row and column).
double max_lattice_error(const std::string& path, int step) {
    gdal::Dataset ds = gdal::open_raster(path);
    const MetricGridSpec spec = utm_grid_of(ds.get());
    const MetricWarp warp(ds.get(), spec, path);
    double worst = 0;
    long long compared = 0;
    for (int i = 0; i < spec.rows; i = (i == spec.rows - 1) ? spec.rows : std::min(i + step, spec.rows - 1))
        for (int j = 0; j < spec.cols; j = (j == spec.cols - 1) ? spec.cols : std::min(j + step, spec.cols - 1)) {
            double ex, ey, lx, ly;
            if (!warp.exact_position(j + 0.5, i + 0.5, ex, ey) || !warp.lattice_position(j + 0.5, i + 0.5, lx, ly))
                continue;
            worst = std::max(worst, std::hypot(ex - lx, ey - ly));
            ++compared;
        }
    EXPECT_GT(compared, 1000);
    std::cout << path << ": " << spec.cols << "x" << spec.rows << " grid, " << compared
              << " samples, largest lattice error " << worst << " source pixel\n";
    return worst;
}

} // namespace

TEST(MetricWarp, LatticeFollowsProjOnAGeneratedRaster) {
    test::ScratchDir scratch;
    // 1/3 arc-second cells over half a degree at the western edge of UTM
    // zone 10, at 46 N: far from the central meridian, where UTM bends most.
    const std::string path = scratch / "geo.tif";
    write_geographic(path, 5400, 5400, -125.9, 46.5, 1.0 / 10800);
    EXPECT_LT(max_lattice_error(path, 7), 0.01);
}

TEST(MetricWarp, LatticeFollowsProjOnSrtm) {
    OVERFLIGHT_SHARED_FILE(rainier, "srtm/mt_rainier_90m.tif");
    OVERFLIGHT_SHARED_FILE(fuji, "srtm/mt_fuji_90m.tif");
    OVERFLIGHT_SHARED_FILE(hgt, "srtm/N57E011.hgt");
    for (const std::string& path : {rainier, fuji, hgt}) EXPECT_LT(max_lattice_error(path, 3), 0.01) << path;
}

// Windows of many shapes and places, the ring of a widened window among
// them, read the same bits as the whole grid.
TEST(MetricWarp, AnyWindowReadsTheWholeGridsSamples) {
    test::ScratchDir scratch;
    const std::string path = scratch / "geo.tif";
    write_geographic(path, 700, 600, -121.9, 46.9, 0.0003);
    gdal::Dataset ds = gdal::open_raster(path);
    const MetricGridSpec spec = utm_grid_of(ds.get());
    const MetricWarp warp(ds.get(), spec, path);
    std::vector<float> whole(std::size_t(spec.rows) * spec.cols);
    warp.read(0, 0, spec.rows, spec.cols, whole.data());
    long long voids = 0;
    for (float v : whole) voids += v == kNoData;
    EXPECT_GT(voids, 0); // the wedges outside the source
    EXPECT_LT(voids, (long long)whole.size() / 2);
    const int windows[][4] = {{0, 0, 67, 67},     {60, 61, 67, 67},   {3, 250, 1, 300}, {100, 17, 259, 5},
                              {200, 100, 13, 211}, {spec.rows - 40, spec.cols - 30, 40, 30}, {5, 5, 300, 400}};
    for (const auto& w : windows) {
        const int r0 = w[0], c0 = w[1], h = std::min(w[2], spec.rows - r0), wd = std::min(w[3], spec.cols - c0);
        std::vector<float> part(std::size_t(h) * wd);
        warp.read(r0, c0, h, wd, part.data());
        int differ = 0;
        for (int i = 0; i < h; ++i)
            differ += std::memcmp(part.data() + std::size_t(i) * wd, whole.data() + std::size_t(r0 + i) * spec.cols + c0,
                                  sizeof(float) * wd) != 0;
        EXPECT_EQ(differ, 0) << "window at row " << r0 << ", column " << c0 << ", " << h << "x" << wd;
    }
}
