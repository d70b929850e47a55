// The tile folder's own TIFF encoder (io/TiffEncoder.h through
// io/TileRasters.h write_geotiff) against GDAL's GTiff driver: what GDAL
// reads from our file equals what it reads from one it wrote itself with
// the same contents (samples of every level, georeferencing, CRS, band
// scale, offset, unit and color interpretation); a truncated file fails on
// its full-resolution samples.
#include "TestSupport.h"
#include "core/TileGrid.h"
#include "io/Gdal.h"
#include "io/TileRasters.h"

#include <cpl_conv.h>
#include <gtest/gtest.h>
#include <ogr_srs_api.h>

#include <fstream>
#include <iterator>

using namespace overflight;
using overflight::test::ScratchDir;

namespace {

std::string utm_wkt() {
    OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
    OSRImportFromEPSG(srs, 32610);
    char* wkt = nullptr;
    OSRExportToWkt(srs, &wkt);
    std::string out = wkt;
    CPLFree(wkt);
    OSRDestroySpatialReference(srs);
    return out;
}

// `spec` written by GDAL itself: overviews allocated, then every 2^m-th
// sample (or the given box levels) written into them.
void write_with_gdal(const std::string& path, const RasterSpec& spec) {
    gdal::Dataset ds(GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), spec.cols, spec.rows, spec.bands, spec.type, nullptr));
    ASSERT_TRUE(ds);
    if (spec.gt) {
        double g[6];
        std::copy(spec.gt->begin(), spec.gt->end(), g);
        GDALSetGeoTransform(ds.get(), g);
        if (!spec.wkt.empty()) GDALSetProjection(ds.get(), spec.wkt.c_str());
    }
    const int bytes = GDALGetDataTypeSizeBytes(spec.type);
    const std::size_t plane = std::size_t(spec.cols) * spec.rows * bytes;
    std::vector<int> factors;
    for (int m = 1; m <= spec.levels; ++m) factors.push_back(1 << m);
    if (!factors.empty()) {
        ASSERT_EQ(GDALBuildOverviews(ds.get(), "NONE", int(factors.size()), factors.data(), 0, nullptr, nullptr, nullptr), CE_None);
    }
    for (int b = 0; b < spec.bands; ++b) {
        GDALRasterBandH h = GDALGetRasterBand(ds.get(), b + 1);
        if (spec.rgb) GDALSetRasterColorInterpretation(h, GDALColorInterp(GCI_RedBand + b));
        if (spec.height_mapping) {
            GDALSetRasterScale(h, spec.height_mapping->v_scale);
            GDALSetRasterOffset(h, spec.height_mapping->y_offset);
            GDALSetRasterUnitType(h, "metre");
        }
        auto* p = const_cast<unsigned char*>(static_cast<const unsigned char*>(spec.data)) + b * plane;
        ASSERT_EQ(GDALRasterIO(h, GF_Write, 0, 0, spec.cols, spec.rows, p, spec.cols, spec.rows, spec.type, 0, 0), CE_None);
        for (int m = 1; m <= spec.levels; ++m) {
            const int f = 1 << m, cols = (spec.cols - 1) / f + 1, rows = (spec.rows - 1) / f + 1;
            std::vector<unsigned char> level(std::size_t(cols) * rows * bytes);
            if (spec.box_levels) {
                const auto* q = static_cast<const unsigned char*>((*spec.box_levels)[std::size_t(m - 1)]);
                std::copy_n(q + b * level.size(), level.size(), level.data());
            } else {
                for (int i = 0; i < rows; ++i)
                    for (int j = 0; j < cols; ++j)
                        std::copy_n(p + (std::size_t(i) * f * spec.cols + std::size_t(j) * f) * bytes, bytes,
                                    level.data() + (std::size_t(i) * cols + j) * bytes);
            }
            GDALRasterBandH ov = GDALGetOverview(h, m - 1);
            ASSERT_EQ(GDALGetRasterBandXSize(ov), cols);
            ASSERT_EQ(GDALRasterIO(ov, GF_Write, 0, 0, cols, rows, level.data(), cols, rows, spec.type, 0, 0), CE_None);
        }
    }
}

std::vector<unsigned char> samples(GDALRasterBandH band) {
    const int cols = GDALGetRasterBandXSize(band), rows = GDALGetRasterBandYSize(band);
    const GDALDataType t = GDALGetRasterDataType(band);
    std::vector<unsigned char> out(std::size_t(cols) * rows * GDALGetDataTypeSizeBytes(t));
    EXPECT_EQ(GDALRasterIO(band, GF_Read, 0, 0, cols, rows, out.data(), cols, rows, t, 0, 0), CE_None);
    return out;
}

// Everything GDAL reads from `ours` equals what it reads from `theirs`.
void expect_same_raster(const std::string& ours, const std::string& theirs) {
    gdal::Dataset a = gdal::open_raster(ours), b = gdal::open_raster(theirs);
    ASSERT_EQ(GDALGetRasterXSize(a.get()), GDALGetRasterXSize(b.get()));
    ASSERT_EQ(GDALGetRasterYSize(a.get()), GDALGetRasterYSize(b.get()));
    ASSERT_EQ(GDALGetRasterCount(a.get()), GDALGetRasterCount(b.get()));
    double ga[6], gb[6];
    const CPLErr ea = GDALGetGeoTransform(a.get(), ga), eb = GDALGetGeoTransform(b.get(), gb);
    EXPECT_EQ(ea, eb);
    if (ea == CE_None && eb == CE_None) {
        for (int k = 0; k < 6; ++k) EXPECT_EQ(ga[k], gb[k]) << k;
    }
    EXPECT_STREQ(GDALGetProjectionRef(a.get()), GDALGetProjectionRef(b.get()));
    for (int k = 1; k <= GDALGetRasterCount(a.get()); ++k) {
        GDALRasterBandH x = GDALGetRasterBand(a.get(), k), y = GDALGetRasterBand(b.get(), k);
        EXPECT_EQ(GDALGetRasterDataType(x), GDALGetRasterDataType(y));
        EXPECT_EQ(GDALGetRasterColorInterpretation(x), GDALGetRasterColorInterpretation(y)) << "band " << k;
        int has = 0;
        EXPECT_EQ(GDALGetRasterScale(x, &has), GDALGetRasterScale(y, &has));
        EXPECT_EQ(GDALGetRasterOffset(x, &has), GDALGetRasterOffset(y, &has));
        EXPECT_STREQ(GDALGetRasterUnitType(x), GDALGetRasterUnitType(y));
        EXPECT_EQ(samples(x), samples(y)) << "band " << k;
        ASSERT_EQ(GDALGetOverviewCount(x), GDALGetOverviewCount(y));
        for (int o = 0; o < GDALGetOverviewCount(x); ++o) {
            GDALRasterBandH ox = GDALGetOverview(x, o), oy = GDALGetOverview(y, o);
            EXPECT_EQ(GDALGetRasterBandXSize(ox), GDALGetRasterBandXSize(oy));
            EXPECT_EQ(samples(ox), samples(oy)) << "band " << k << " level " << o + 1;
        }
    }
}

void check(const std::string& dir, const std::string& name, const RasterSpec& spec) {
    SCOPED_TRACE(name);
    const std::string ours = dir + "/" + name + ".tif", theirs = dir + "/" + name + "_gdal.tif";
    write_geotiff(ours, spec);
    write_with_gdal(theirs, spec);
    expect_same_raster(ours, theirs);
    EXPECT_TRUE(geotiff_matches(ours, spec));
}

} // namespace

TEST(TiffEncoder, ReadsAsGdalsOwnGeoTiff) {
    gdal::ensure_initialised();
    ScratchDir scratch;
    const std::string dir = scratch.path.string();
    const int n = 33;
    std::vector<std::uint16_t> heights(std::size_t(n) * n);
    for (std::size_t k = 0; k < heights.size(); ++k) heights[k] = std::uint16_t(1000 + (k * 7919) % 3001);
    std::vector<std::uint8_t> rgb(3 * std::size_t(n) * n);
    for (std::size_t k = 0; k < rgb.size(); ++k) rgb[k] = std::uint8_t(k * 31 % 251);
    std::vector<float> d2(std::size_t(17) * 17);
    for (std::size_t k = 0; k < d2.size(); ++k) d2[k] = 0.001f * float(k % 97);
    TileGrid mapping;
    mapping.v_scale = 0.25f;
    mapping.y_offset = -12.5f;
    const std::array<double, 6> gt{500600.0, 10.0, 0.0, 4999400.0, 0.0, -10.0};
    const std::array<double, 6> south_up{-2.5, 5.0, 0.0, 2.5, 0.0, 5.0};
    const std::string wkt = utm_wkt();

    check(dir, "heights", RasterSpec{n, n, 1, GDT_UInt16, heights.data(), &gt, wkt, &mapping, false, 5});
    check(dir, "colors", RasterSpec{n, n, 3, GDT_Byte, rgb.data(), &gt, wkt, nullptr, true, 5});
    check(dir, "plain", RasterSpec{n, n, 1, GDT_UInt16, heights.data(), &south_up, "", nullptr, false, 0});
    check(dir, "apron", RasterSpec{n, 4, 1, GDT_UInt16, heights.data(), nullptr, "", nullptr, false, 0});
    check(dir, "d2", RasterSpec{17, 17, 1, GDT_Float32, d2.data(), nullptr, "", nullptr, false, 3});
    // An imagery tile: RGBA with its own box-filtered levels.
    std::vector<std::uint8_t> rgba(4 * 16 * 16), half(4 * 8 * 8);
    for (std::size_t k = 0; k < rgba.size(); ++k) rgba[k] = std::uint8_t(k * 13 % 256);
    for (std::size_t k = 0; k < half.size(); ++k) half[k] = std::uint8_t(k * 5 % 256);
    const std::vector<const void*> box{half.data()};
    check(dir, "imagery", RasterSpec{16, 16, 4, GDT_Byte, rgba.data(), &gt, wkt, nullptr, true, 1, &box});
}

TEST(TiffEncoder, TruncatedFileFailsOnItsFullImage) {
    gdal::ensure_initialised();
    ScratchDir scratch;
    const int n = 65;
    std::vector<std::uint16_t> heights(std::size_t(n) * n);
    for (std::size_t k = 0; k < heights.size(); ++k) heights[k] = std::uint16_t((k * 7919) % 65521);
    const std::string path = scratch / "t.tif";
    write_geotiff(path, RasterSpec{n, n, 1, GDT_UInt16, heights.data(), nullptr, "", nullptr, false, 4});
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    in.close();
    std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), std::streamsize(bytes.size() - bytes.size() / 4));
    CPLPushErrorHandler(CPLQuietErrorHandler);
    gdal::Dataset ds(GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr));
    std::vector<std::uint16_t> got(heights.size());
    const bool read = ds && GDALRasterIO(GDALGetRasterBand(ds.get(), 1), GF_Read, 0, 0, n, n, got.data(), n, n,
                                         GDT_UInt16, 0, 0) == CE_None;
    CPLPopErrorHandler();
    EXPECT_FALSE(read);
}
