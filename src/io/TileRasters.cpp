#include "io/TileRasters.h"

#include "core/Error.h"
#include "io/Files.h"

#include <cpl_conv.h>
#include <cpl_string.h>
#include <cpl_vsi.h>

#include <algorithm>
#include <atomic>
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

// Writes every 2^m-th sample of each band into the overviews of `ds`
// (m = 1 .. levels). GDAL's own resampling is not used: even NEAREST picks
// samples by its own rounding of the size ratio, and a tile's reduced levels
// must keep exactly the samples at multiples of 2^m, so that the edge
// samples neighbouring tiles share stay identical (averaging would open
// cracks). "NONE" only allocates the overviews.
void write_levels(GDALDatasetH ds, const std::string& path, const RasterSpec& spec) {
    std::vector<int> factors;
    for (int m = 1; m <= spec.levels; ++m) factors.push_back(1 << m);
    if (GDALBuildOverviews(ds, "NONE", int(factors.size()), factors.data(), 0, nullptr, nullptr, nullptr) != CE_None)
        throw Error(path, "cannot create the reduced levels: " + gdal::last_error("overviews"));
    for (int b = 0; b < spec.bands; ++b)
        for (const int f : factors) {
            const int cols = (spec.cols - 1) / f + 1, rows = (spec.rows - 1) / f + 1;
            GDALRasterBandH ov = level_band(GDALGetRasterBand(ds, b + 1), cols, rows);
            if (!ov) throw Error(path, "GDAL did not create a " + std::to_string(cols) + "x" + std::to_string(rows) + " level");
            std::vector<unsigned char> dec = level_plane(spec, b, f);
            if (GDALRasterIO(ov, GF_Write, 0, 0, cols, rows, dec.data(), cols, rows, spec.type, 0, 0) != CE_None)
                throw Error(path, "cannot write a reduced level: " + gdal::last_error("I/O error"));
        }
}

void fill_dataset(GDALDatasetH ds, const std::string& path, const RasterSpec& spec) {
    if (spec.gt) {
        double g[6];
        std::copy(spec.gt->begin(), spec.gt->end(), g);
        GDALSetGeoTransform(ds, g);
        if (!spec.wkt.empty()) GDALSetProjection(ds, spec.wkt.c_str());
    }
    for (int b = 0; b < spec.bands; ++b) {
        GDALRasterBandH h = GDALGetRasterBand(ds, b + 1);
        if (spec.rgb)
            GDALSetRasterColorInterpretation(h, b == 0 ? GCI_RedBand : b == 1 ? GCI_GreenBand : b == 2 ? GCI_BlueBand : GCI_AlphaBand);
        if (spec.height_mapping) {
            GDALSetRasterScale(h, spec.height_mapping->v_scale);
            GDALSetRasterOffset(h, spec.height_mapping->y_offset);
            GDALSetRasterUnitType(h, "metre");
        }
        auto* p = const_cast<unsigned char*>(static_cast<const unsigned char*>(spec.data)) + std::size_t(b) * plane_bytes(spec);
        if (GDALRasterIO(h, GF_Write, 0, 0, spec.cols, spec.rows, p, spec.cols, spec.rows, spec.type, 0, 0) != CE_None)
            throw Error(path, "cannot encode: " + gdal::last_error("I/O error"));
    }
    if (spec.levels > 0) write_levels(ds, path, spec);
}

// The GeoTIFF bytes of `spec`, made in GDAL's in-memory file system.
std::vector<std::uint8_t> encode_geotiff(const std::string& path, const RasterSpec& spec) {
    static std::atomic<unsigned> counter{0};
    const std::string mem = "/vsimem/overflight-tile-" + std::to_string(counter++) + ".tif";
    struct MemFile {
        std::string name;
        ~MemFile() { VSIUnlink(name.c_str()); }
    } owner{mem};
    char** co = CSLSetNameValue(nullptr, "COMPRESS", "DEFLATE");
    // Encoding is most of a tiling run. Measured on 600 tiles of a 20000^2
    // DEM (heights, colors, d2): horizontal differencing (predictor 2)
    // halves the heights and shrinks the colors, while the floating-point
    // predictor (3) makes the d2 matrices 80 % larger than none and costs
    // time; level 1 (libdeflate's fastest; GDAL's default is 6) encodes
    // with about 40 % less CPU than level 2 for 5 % larger files (the whole
    // run: 20 % fewer instructions). Any DEFLATE reader
    // reads every level and predictor, so folders written otherwise stay
    // readable and resumable (a re-run compares samples, not bytes).
    if (spec.type != GDT_Float32) co = CSLSetNameValue(co, "PREDICTOR", "2");
    co = CSLSetNameValue(co, "ZLEVEL", "1");
    gdal::Dataset ds(GDALCreate(GDALGetDriverByName("GTiff"), mem.c_str(), spec.cols, spec.rows, spec.bands, spec.type, co));
    CSLDestroy(co);
    if (!ds) throw Error(path, "cannot encode: " + gdal::last_error("GTiff"));
    fill_dataset(ds.get(), path, spec);
    CPLErrorReset();
    GDALClose(ds.release());
    if (CPLGetLastErrorType() == CE_Failure || CPLGetLastErrorType() == CE_Fatal)
        throw Error(path, "cannot encode: " + gdal::last_error("close failed"));
    vsi_l_offset size = 0;
    const GByte* bytes = VSIGetMemFileBuffer(mem.c_str(), &size, FALSE);
    if (!bytes) throw Error(path, "cannot encode: GDAL wrote nothing");
    return std::vector<std::uint8_t>(bytes, bytes + size);
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
