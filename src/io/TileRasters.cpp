#include "io/TileRasters.h"

#include "core/Error.h"
#include "io/Files.h"
#include "io/TiffEncoder.h"

#include <algorithm>
#include <filesystem>
#include <vector>

namespace overflight {

namespace {

const char* type_name(GDALDataType t) { return GDALGetDataTypeName(t); }

std::size_t plane_bytes(const RasterSpec& spec) {
    return std::size_t(spec.cols) * std::size_t(spec.rows) * std::size_t(GDALGetDataTypeSizeBytes(spec.type));
}

// Every f-th sample of band b of `spec` in both directions (f = 1: the band),
// or band b of the box-filtered level of factor f when the spec has them.
std::vector<unsigned char> level_plane(const RasterSpec& spec, int b, int f) {
    const std::size_t bytes = std::size_t(GDALGetDataTypeSizeBytes(spec.type));
    if (spec.box_levels && f > 1) {
        int m = 0;
        while ((1 << m) < f) ++m;
        const std::size_t plane = std::size_t(spec.cols / f) * std::size_t(spec.rows / f) * bytes;
        const auto* p = static_cast<const unsigned char*>((*spec.box_levels)[std::size_t(m - 1)]) + std::size_t(b) * plane;
        return std::vector<unsigned char>(p, p + plane);
    }
    const auto* src = static_cast<const unsigned char*>(spec.data) + std::size_t(b) * plane_bytes(spec);
    const int cols = (spec.cols - 1) / f + 1, rows = (spec.rows - 1) / f + 1;
    std::vector<unsigned char> out(std::size_t(cols) * std::size_t(rows) * bytes);
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < cols; ++j)
            std::copy_n(src + (std::size_t(i) * std::size_t(f) * std::size_t(spec.cols) + std::size_t(j) * std::size_t(f)) *
                                  bytes,
                        bytes, out.data() + (std::size_t(i) * std::size_t(cols) + std::size_t(j)) * bytes);
    return out;
}

// The overview of `band` of exactly cols x rows samples, or null.
GDALRasterBandH level_band(GDALRasterBandH band, int cols, int rows) {
    for (int o = 0; o < GDALGetOverviewCount(band); ++o) {
        GDALRasterBandH cand = GDALGetOverview(band, o);
        if (GDALGetRasterBandXSize(cand) == cols && GDALGetRasterBandYSize(cand) == rows) return cand;
    }
    return nullptr;
}

// The GeoTIFF bytes of `spec` (io/TiffEncoder.h). Its reduced levels keep
// every 2^m-th sample, m = 1 .. levels, not a resampling: the samples at
// multiples of 2^m, so that the edge samples neighbouring tiles share stay
// identical (averaging would open cracks); imagery tiles give their own
// box-filtered levels. Measured on 400 tiles of a 5000^2 DEM: made through
// GDAL (create, overviews, close in /vsimem) the directories and GDAL's
// bookkeeping took more CPU than DEFLATE. Level 1 DEFLATE (libdeflate's
// fastest) with horizontal differencing for integers; the floating-point
// predictor makes the d2 matrices larger, so floats go undifferenced. Any
// DEFLATE reader reads every level and predictor, so folders written by
// GDAL with other settings stay readable and resumable (a re-run compares
// samples, not bytes).
std::vector<std::uint8_t> encode_geotiff(const std::string& path, const RasterSpec& spec) {
    const int bytes = GDALGetDataTypeSizeBytes(spec.type);
    std::vector<std::vector<unsigned char>> planes(std::size_t(spec.levels));
    std::vector<TiffImage> images{{spec.cols, spec.rows, spec.bands, bytes, spec.type == GDT_Float32, spec.data}};
    for (int m = 1; m <= spec.levels; ++m) {
        const int f = 1 << m;
        std::vector<unsigned char>& level = planes[std::size_t(m - 1)];
        for (int b = 0; b < spec.bands; ++b) {
            const std::vector<unsigned char> p = level_plane(spec, b, f);
            level.insert(level.end(), p.begin(), p.end());
        }
        images.push_back({(spec.cols - 1) / f + 1, (spec.rows - 1) / f + 1, spec.bands, bytes, spec.type == GDT_Float32,
                          level.data()});
    }
    TiffMetadata meta;
    meta.rgb = spec.rgb;
    meta.gt = spec.gt;
    meta.wkt = spec.gt ? spec.wkt : std::string();
    if (spec.height_mapping) {
        meta.has_mapping = true;
        meta.scale = spec.height_mapping->v_scale;
        meta.offset = spec.height_mapping->y_offset;
    }
    try {
        return encode_tiff(images, meta);
    } catch (const std::exception& e) {
        throw Error(path, std::string("cannot encode: ") + e.what());
    }
}

bool band_matches(GDALRasterBandH band, const RasterSpec& spec, int b) {
    if (spec.height_mapping) {
        int has_scale = 0, has_offset = 0;
        if (GDALGetRasterScale(band, &has_scale) != double(spec.height_mapping->v_scale) ||
            GDALGetRasterOffset(band, &has_offset) != double(spec.height_mapping->y_offset))
            return false;
    }
    for (int m = 0; m <= spec.levels; ++m) {
        const int f = 1 << m, cols = (spec.cols - 1) / f + 1, rows = (spec.rows - 1) / f + 1;
        GDALRasterBandH level = m == 0 ? band : level_band(band, cols, rows);
        if (!level) return false;
        const std::vector<unsigned char> want = level_plane(spec, b, f);
        std::vector<unsigned char> got(want.size());
        if (GDALRasterIO(level, GF_Read, 0, 0, cols, rows, got.data(), cols, rows, spec.type, 0, 0) != CE_None ||
            got != want)
            return false;
    }
    return true;
}

} // namespace

void write_geotiff(const std::string& path, const RasterSpec& spec, FileSync sync) {
    gdal::ensure_initialised();
    const std::vector<std::uint8_t> bytes = encode_geotiff(path, spec);
    write_file_atomically(path, bytes.data(), bytes.size(), sync);
}

bool geotiff_matches(const std::string& path, const RasterSpec& spec) {
    gdal::ensure_initialised();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return false;
    gdal::Dataset ds(GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr));
    if (!ds || GDALGetRasterXSize(ds.get()) != spec.cols || GDALGetRasterYSize(ds.get()) != spec.rows ||
        GDALGetRasterCount(ds.get()) != spec.bands || GDALGetRasterDataType(GDALGetRasterBand(ds.get(), 1)) != spec.type)
        return false;
    if (spec.gt) {
        double g[6];
        if (GDALGetGeoTransform(ds.get(), g) != CE_None || !std::equal(g, g + 6, spec.gt->begin())) return false;
    }
    for (int b = 0; b < spec.bands; ++b)
        if (!band_matches(GDALGetRasterBand(ds.get(), b + 1), spec, b)) return false;
    return true;
}

gdal::Dataset open_checked(const std::string& path, int cols, int rows, int bands, GDALDataType type) {
    gdal::Dataset ds = gdal::open_raster(path);
    const int c = GDALGetRasterXSize(ds.get()), r = GDALGetRasterYSize(ds.get()), n = GDALGetRasterCount(ds.get());
    const GDALDataType t = GDALGetRasterDataType(GDALGetRasterBand(ds.get(), 1));
    if (c != cols || r != rows || n != bands || t != type)
        throw Error(path, "holds " + std::to_string(n) + " band(s) of " + std::to_string(c) + "x" + std::to_string(r) + " " +
                              type_name(t) + " samples, the tile index expects " + std::to_string(bands) + " of " +
                              std::to_string(cols) + "x" + std::to_string(rows) + " " + type_name(type));
    return ds;
}

void read_bands(GDALDatasetH ds, const std::string& path, int cols, int rows, int bands, GDALDataType type, void* out,
                int reduce) {
    const std::size_t plane = std::size_t(cols) * std::size_t(rows) * std::size_t(GDALGetDataTypeSizeBytes(type));
    for (int b = 0; b < bands; ++b) {
        GDALRasterBandH band = GDALGetRasterBand(ds, b + 1);
        if (reduce > 1) {
            band = level_band(band, cols, rows);
            if (!band)
                throw Error(path, "has no level of every " + std::to_string(reduce) + "th sample; run `overflight tile` again");
        }
        CPLErrorReset();
        if (GDALRasterIO(band, GF_Read, 0, 0, cols, rows, static_cast<unsigned char*>(out) + std::size_t(b) * plane, cols,
                         rows, type, 0, 0) != CE_None)
            throw Error(path, "cannot read: " + gdal::last_error("I/O error"));
    }
}

} // namespace overflight
