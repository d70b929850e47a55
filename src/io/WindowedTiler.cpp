// Based on: Zamri, "Data tiling"; DESIGN sec. 4 (the loader's steps, done
// per window: io/GdalRaster.cpp); GDAL's windowed raster I/O, warped VRTs
// and GDALFillNodata.
#include "io/WindowedTiler.h"

#include "core/Error.h"
#include "core/Shading.h"
#include "io/Files.h"
#include "io/Gdal.h"
#include "io/GdalSource.h"
#include "io/HeightMapping.h"
#include "io/ImageryRaster.h"
#include "io/MetricWarp.h"
#include "core/ImageryFallback.h"
#include "io/TileFiles.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal_alg.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <list>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <unistd.h>

namespace fs = std::filesystem;

namespace overflight {

namespace {


std::string number(double v, int digits) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    return buf;
}

// Band 1 of the source in metres: its scale, offset, unit and no-data value.
struct BandToMetres {
    bool has_nodata = false;
    double nodata = 0, scale = 1, offset = 0, unit = 1;

    // The loader's conversion (io/GdalRaster.cpp heights_to_metres): kNoData
    // for a missing value.
    float metres(float v) const {
        if (!std::isfinite(v) || (has_nodata && (double(v) == nodata || float(nodata) == v)) || v == kNoData)
            return kNoData;
        return float((double(v) * scale + offset) * unit);
    }
};

// Everything a tile needs to know about the source before it is cut.
struct Plan {
    std::string path;
    std::vector<std::string> warp; // gdalwarp options of the grid; empty: the source's own grid
    MetricGridSpec grid;           // the warped grid (io/MetricWarp.h), when `warp` is not empty
    int rows = 0, cols = 0;        // the terrain grid (after any warp)
    BandToMetres band;
    bool georeferenced = false;
    std::array<double, 6> gt{0, 1, 0, 0, 0, 1};
    std::string wkt;
    float h_scale = 1;
    double h_scale_exact = 1; // before rounding to float, as load_gdal_raster gives the imagery
    float lo = 0, hi = 0; // valid elevations, metres
    bool integral = true; // whole metres, kept exact (filled voids rounded)
    HeightMapping mapping;
    float world_lo = 0, world_hi = 0; // Terrain::min_height / max_height of the whole
    std::string checksum;
    // Imagery tiled beside the heights (empty color_path: none).
    std::string color_path;
    ImageryGrid imagery;
    ImageryTileLayout layout;
};

// A thread's view of the source: the raster, its band 1 in metres and the
// warp of that onto the grid (PROJ's transformations are not shared between
// threads); the color raster and its chosen bands.
struct Reader {
    gdal::Dataset source;
    GDALRasterBandH band = nullptr;
    gdal::Dataset metres;
    std::unique_ptr<MetricWarp> warp;
    gdal::Dataset color, picked;
};

// GDAL pixel function "overflight_metres": BandToMetres::metres of each
// Float32 source value, its arguments the conversion's fields.
CPLErr metres_pixels(void** sources, int count, void* out, int cols, int rows, GDALDataType source_type,
                     GDALDataType out_type, int pixel_space, int line_space, CSLConstList args) {
    if (count != 1 || source_type != GDT_Float32) return CE_Failure;
    BandToMetres band;
    band.has_nodata = CPLTestBool(CSLFetchNameValueDef(args, "has_nodata", "NO"));
    band.nodata = CPLAtof(CSLFetchNameValueDef(args, "nodata", "0"));
    band.scale = CPLAtof(CSLFetchNameValueDef(args, "scale", "1"));
    band.offset = CPLAtof(CSLFetchNameValueDef(args, "offset", "0"));
    band.unit = CPLAtof(CSLFetchNameValueDef(args, "unit", "1"));
    const auto* in = static_cast<const float*>(sources[0]);
    std::vector<float> row(static_cast<std::size_t>(cols));
    for (int i = 0; i < rows; ++i) {
        for (int j = 0; j < cols; ++j) row[std::size_t(j)] = band.metres(in[std::size_t(i) * std::size_t(cols) + std::size_t(j)]);
        GDALCopyWords(row.data(), GDT_Float32, sizeof(float), static_cast<GByte*>(out) + std::size_t(line_space) * std::size_t(i),
                      out_type, pixel_space, cols);
    }
    return CE_None;
}

// Band 1 of the source in metres (kNoData where missing, its no-data
// value), for the warp: the loader warps the whole raster converted to
// metres (io/GdalRaster.cpp), not the source's values converted after the
// warp, which differ by rounding under a scale, offset or unit and would
// take a resampled value equal to the source's no-data value for a void. A
// virtual raster with the source's size, georeferencing and CRS (as WKT, as
// the loader's copy in memory has it), so that the warp sees the same grid;
// it reads the source only where the warp reads it.
gdal::Dataset metres_of(const Plan& plan, GDALDatasetH src) {
    static std::once_flag registered;
    std::call_once(registered, [] { GDALAddDerivedBandPixelFuncWithArgs("overflight_metres", metres_pixels, nullptr); });
    const auto escaped = [](const std::string& text) {
        char* e = CPLEscapeString(text.c_str(), -1, CPLES_XML);
        std::string out = e;
        CPLFree(e);
        return out;
    };
    double g[6];
    GDALGetGeoTransform(src, g);
    std::string gt;
    for (int k = 0; k < 6; ++k) gt += (k ? "," : "") + number(g[k], 17);
    const char* wkt = GDALGetProjectionRef(src);
    const BandToMetres& b = plan.band;
    const std::string xml =
        "<VRTDataset rasterXSize=\"" + std::to_string(GDALGetRasterXSize(src)) + "\" rasterYSize=\"" +
        std::to_string(GDALGetRasterYSize(src)) + "\"><SRS>" + escaped(wkt ? wkt : "") + "</SRS><GeoTransform>" + gt +
        "</GeoTransform><VRTRasterBand dataType=\"Float32\" band=\"1\" subClass=\"VRTDerivedRasterBand\">"
        "<NoDataValue>" + number(double(kNoData), 17) + "</NoDataValue>"
        "<PixelFunctionType>overflight_metres</PixelFunctionType><PixelFunctionArguments has_nodata=\"" +
        (b.has_nodata ? "YES" : "NO") + "\" nodata=\"" + number(b.nodata, 17) + "\" scale=\"" + number(b.scale, 17) +
        "\" offset=\"" + number(b.offset, 17) + "\" unit=\"" + number(b.unit, 17) +
        "\"/><SourceTransferType>Float32</SourceTransferType><SimpleSource><SourceFilename relativeToVRT=\"0\" "
        "shared=\"0\">" + escaped(plan.path) + "</SourceFilename><SourceBand>1</SourceBand></SimpleSource>"
        "</VRTRasterBand></VRTDataset>";
    CPLErrorReset();
    gdal::Dataset ds(GDALOpenEx(xml.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr));
    if (!ds) throw Error(plan.path, "cannot read in metres: " + gdal::last_error("GDAL refused the virtual raster"));
    return ds;
}

void open_reader(Reader& r, const Plan& plan, bool warped) {
    if (r.band) return;
    r.source = gdal::open_raster(plan.path);
    if (warped && !plan.warp.empty()) {
        r.metres = metres_of(plan, r.source.get());
        r.warp = std::make_unique<MetricWarp>(r.metres.get(), plan.grid, plan.path);
    }
    r.band = GDALGetRasterBand(r.source.get(), 1);
}

// Rows [row0, row0 + rows) x columns [col0, col0 + cols) of the grid into
// `z`, `stride` floats a row: the source's values as read, or warped from
// its metres (kNoData where missing or outside the source).
void read_window(const Reader& r, const Plan& plan, int row0, int col0, int rows, int cols, float* z, int stride) {
    if (rows <= 0 || cols <= 0) return;
    if (r.warp) {
        if (stride == cols) return r.warp->read(row0, col0, rows, cols, z);
        std::vector<float> part(std::size_t(rows) * std::size_t(cols));
        r.warp->read(row0, col0, rows, cols, part.data());
        for (int i = 0; i < rows; ++i)
            std::copy_n(part.data() + std::size_t(i) * cols, cols, z + std::size_t(i) * stride);
        return;
    }
    CPLErrorReset();
    if (GDALRasterIO(r.band, GF_Read, col0, row0, cols, rows, z, cols, rows, GDT_Float32, 0,
                     GSpacing(stride) * GSpacing(sizeof(float))) != CE_None)
        throw Error(plan.path, "unreadable raster: " + gdal::last_error("read failed"));
}

// As read_window, in metres (kNoData where missing).
void read_metres(const Reader& r, const Plan& plan, int row0, int col0, int rows, int cols, float* z, int stride) {
    read_window(r, plan, row0, col0, rows, cols, z, stride);
    if (r.warp) return; // warped from metres (metres_of)
    for (int i = 0; i < rows; ++i)
        for (float *v = z + std::size_t(i) * stride, *end = v + cols; v != end; ++v) *v = plan.band.metres(*v);
}
void read_metres(const Reader& r, const Plan& plan, int row0, int col0, int rows, int cols, std::vector<float>& z) {
    z.resize(std::size_t(rows) * std::size_t(cols));
    read_metres(r, plan, row0, col0, rows, cols, z.data(), cols);
}

// The one value, in metres, that every sample of the window reads when the
// source reports holding no data there (GDALGetDataCoverageStatus: a VRT's
// area without sources, a sparse GeoTIFF's unwritten blocks), so that the
// window need not be read: GDAL fills such an area with one value
// throughout (the band's no-data value, or 0), which its first sample
// reads. Nothing when the source holds data there, cannot tell, or is
// warped onto the grid.
std::optional<float> uniform_void(const Reader& r, const Plan& plan, int row0, int col0, int rows, int cols) {
    if (r.warp || rows <= 0 || cols <= 0 ||
        GDALGetDataCoverageStatus(r.band, col0, row0, cols, rows, 0, nullptr) != GDAL_DATA_COVERAGE_STATUS_EMPTY)
        return std::nullopt;
    float v = 0;
    read_metres(r, plan, row0, col0, 1, 1, &v, 1);
    return v;
}

// As read_metres, not reading the parts of the window the source reports
// holding no data (uniform_void), in column chunks where it holds some.
void read_metres_sparse(const Reader& r, const Plan& plan, int row0, int col0, int rows, int cols, float* z, int stride) {
    if (rows <= 0 || cols <= 0) return;
    const int status = r.warp ? 0 : GDALGetDataCoverageStatus(r.band, col0, row0, cols, rows, 0, nullptr);
    if (!(status & GDAL_DATA_COVERAGE_STATUS_EMPTY)) return read_metres(r, plan, row0, col0, rows, cols, z, stride);
    constexpr int kChunk = 4096;
    for (int j = col0; j < col0 + cols; j += kChunk) {
        const int w = std::min(kChunk, col0 + cols - j);
        float* at = z + (j - col0);
        if (const std::optional<float> v = uniform_void(r, plan, row0, j, rows, w))
            for (int i = 0; i < rows; ++i) std::fill_n(at + std::size_t(i) * stride, w, *v);
        else
            read_metres(r, plan, row0, j, rows, w, at, stride);
    }
}

// FNV-1a 64 over 32-bit words in four interleaved lanes (one dependency chain
// per lane), then over the lanes.
constexpr std::uint64_t kFnvBasis = 1469598103934665603ull, kFnvPrime = 1099511628211ull;
std::uint64_t fnv(std::uint64_t h, const void* p, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * kFnvPrime;
    return h;
}
std::uint64_t row_hash(const float* z, int n) {
    std::uint64_t lane[4] = {kFnvBasis, kFnvBasis + 1, kFnvBasis + 2, kFnvBasis + 3};
    for (int j = 0; j < n; ++j) {
        std::uint32_t w;
        std::memcpy(&w, z + j, 4);
        lane[j & 3] = (lane[j & 3] ^ w) * kFnvPrime;
    }
    return fnv(kFnvBasis, lane, sizeof lane);
}

// The terrain grid: the source's, or the loader's warp of it to square
// metric cells (io/GdalRaster.cpp to_square_metric_cells).
void plan_grid(Plan& plan, GDALDatasetH src) {
    double g[6];
    const bool has_gt = GDALGetGeoTransform(src, g) == CE_None;
    const bool real_gt = has_gt && !(g[0] == 0 && g[1] == 1 && g[2] == 0 && g[3] == 0 && g[4] == 0 && g[5] == 1);
    OGRSpatialReferenceH srs = real_gt ? GDALGetSpatialRef(src) : nullptr;
    plan.rows = GDALGetRasterYSize(src);
    plan.cols = GDALGetRasterXSize(src);
    plan.georeferenced = real_gt;
    if (real_gt) std::copy(g, g + 6, plan.gt.begin());
    const char* wkt = GDALGetProjectionRef(src);
    plan.wkt = wkt ? wkt : "";
    double hs = 1.0;
    if (srs && OSRIsGeographic(srs)) {
        const double lon = g[0] + g[1] * plan.cols * 0.5 + g[2] * plan.rows * 0.5;
        const double lat = g[3] + g[4] * plan.cols * 0.5 + g[5] * plan.rows * 0.5;
        plan.warp = {"-t_srs", to_wkt(utm_for(srs, lon, lat).get())};
    } else if (real_gt) {
        const double px = std::hypot(g[1], g[4]), py = std::hypot(g[2], g[5]);
        if (g[2] != 0 || g[4] != 0 || std::abs(px - py) > 1e-6 * std::max(px, py)) {
            const double res = std::min(px, py);
            plan.warp = {"-tr", number(res, 17), number(res, 17)};
        }
        hs = px;
    }
    if (!plan.warp.empty()) {
        const std::vector<std::string> common = metric_warp_options();
        plan.warp.insert(plan.warp.end(), {"-of", "VRT"});
        plan.warp.insert(plan.warp.end(), common.begin(), common.end());
        // The grid gdalwarp makes (a virtual dataset: no sample is warped here).
        std::vector<char*> argv;
        for (const std::string& a : plan.warp) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        GDALWarpAppOptions* o = GDALWarpAppOptionsNew(argv.data(), nullptr);
        if (!o) throw Error(plan.path, "cannot set up the reprojection: " + gdal::last_error("bad warp options"));
        int usage = 0;
        CPLErrorReset();
        gdal::Dataset w(GDALWarp("", nullptr, 1, &src, o, &usage));
        GDALWarpAppOptionsFree(o);
        if (!w) throw Error(plan.path, "cannot reproject: " + gdal::last_error("GDALWarp failed"));
        plan.rows = GDALGetRasterYSize(w.get());
        plan.cols = GDALGetRasterXSize(w.get());
        GDALGetGeoTransform(w.get(), plan.gt.data());
        const char* ww = GDALGetProjectionRef(w.get());
        plan.wkt = warped_crs_wkt(ww ? ww : "");
        plan.georeferenced = true;
        plan.grid.gt = plan.gt;
        plan.grid.cols = plan.cols;
        plan.grid.rows = plan.rows;
        if (srs && OSRIsGeographic(srs)) plan.grid.wkt = plan.warp[1]; // -t_srs WKT
        hs = std::abs(plan.gt[1]);
    }
    if (srs) {
        Srs target(OSRNewSpatialReference(plan.wkt.c_str()));
        if (target && OSRIsProjected(target.get())) hs *= OSRGetLinearUnits(target.get(), nullptr);
    }
    if (const std::string problem = horizontal_scale_problem(plan.rows, plan.cols, hs); !problem.empty())
        throw Error(plan.path, "pixel size: " + problem);
    plan.h_scale = float(hs);
    plan.h_scale_exact = hs;
}

// Pass 1: elevation range, no-data count, wholeness and checksum, over the
// source in strips of rows read in parallel (each thread its own handle).
void survey(Plan& plan, GDALDatasetH src, std::int64_t budget, const std::function<void(double)>& progress) {
    const int rows = GDALGetRasterYSize(src), cols = GDALGetRasterXSize(src);
    const int threads = tbb::this_task_arena::max_concurrency();
    const std::int64_t strip_bytes = std::max<std::int64_t>(budget / 8 / threads, std::int64_t(cols) * 4);
    const int strip = int(std::clamp<std::int64_t>(strip_bytes / (std::int64_t(cols) * 4), 1, 256));
    const int strips = (rows + strip - 1) / strip;
    std::vector<std::uint64_t> hashes(std::size_t(rows), 0);
    struct Partial {
        float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
        bool integral = true;
        long long voids = 0;
    };
    tbb::enumerable_thread_specific<Reader> readers;
    tbb::enumerable_thread_specific<Partial> partials;
    std::atomic<int> done{0};
    std::mutex progress_mutex;
    tbb::parallel_for(0, strips, [&](int s) {
        Reader& r = readers.local();
        open_reader(r, plan, false);
        Partial& p = partials.local();
        const int row0 = s * strip, n = std::min(strip, rows - row0);
        if (const std::optional<float> uniform = uniform_void(r, plan, row0, 0, n, cols); uniform && *uniform == kNoData) {
            // A strip without data (most of a sparse mosaic): voids only.
            p.voids += std::int64_t(n) * cols;
            const std::vector<float> row(std::size_t(cols), kNoData);
            std::fill_n(hashes.begin() + row0, n, row_hash(row.data(), cols));
        } else {
            std::vector<float> z(std::size_t(n) * std::size_t(cols));
            read_metres_sparse(r, plan, row0, 0, n, cols, z.data(), cols);
            for (int i = 0; i < n; ++i) {
                const float* row = z.data() + std::size_t(i) * std::size_t(cols);
                for (int j = 0; j < cols; ++j) {
                    const float v = row[j];
                    if (v == kNoData) {
                        ++p.voids;
                        continue;
                    }
                    if (!(std::abs(v) <= float(kWorldLimit)))
                        throw Error(plan.path, "row " + std::to_string(row0 + i) + ", column " + std::to_string(j) +
                                                   ": " + elevation_problem(double(v)) +
                                                   " (not a terrain height; is the no-data value set?)");
                    p.lo = std::min(p.lo, v);
                    p.hi = std::max(p.hi, v);
                    // Within kWorldLimit, so the conversion is exact and defined.
                    p.integral = p.integral && v == float(std::int32_t(v));
                }
                hashes[std::size_t(row0 + i)] = row_hash(row, cols);
            }
        }
        const int d = ++done;
        std::lock_guard<std::mutex> lock(progress_mutex);
        progress(double(d) / strips);
    });
    Partial all;
    for (const Partial& p : partials) {
        all.lo = std::min(all.lo, p.lo);
        all.hi = std::max(all.hi, p.hi);
        all.integral = all.integral && p.integral;
        all.voids += p.voids;
    }
    if (all.voids == std::int64_t(rows) * cols) throw Error(plan.path, "raster is entirely no-data");
    plan.lo = all.lo;
    plan.hi = all.hi;
    plan.integral = all.integral && plan.warp.empty();
    plan.mapping = choose_height_mapping(plan.lo, plan.hi, plan.integral);
    std::tie(plan.world_lo, plan.world_hi) = mapped_range(plan.mapping, plan.lo, plan.hi);
    std::uint64_t h = kFnvBasis;
    const double header[] = {double(plan.rows), double(plan.cols), plan.h_scale, plan.mapping.v_scale,
                             plan.mapping.y_offset, plan.gt[0], plan.gt[1], plan.gt[2], plan.gt[3], plan.gt[4], plan.gt[5]};
    h = fnv(h, header, sizeof header);
    h = fnv(h, hashes.data(), hashes.size() * sizeof(std::uint64_t));
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    plan.checksum = buf;
}

// The terrain grid in metres (kNoData where missing), as read_metres gives
// it, kept in blocks aligned to the tile grid that the tiles in flight share.
// Each window of a tile overlaps its neighbours' (the apron and the hill
// shading's margin), and a window holding no-data is widened by the fill's
// search distance, as far as the tiles around it: read per window, a sample
// near a void or the wedges of a reprojected source was warped up to nine
// times. Here each block is read once while it stays in the cache, whichever
// thread needs it first, and a window is copied from its blocks: a sample's
// value does not depend on the window that reads it (io/MetricWarp.h), so
// the tiles are the same. The least recently used blocks go first beyond
// the bound; the tile rows are cut in order, so a bound holding five block
// rows (a tile row, its neighbours and the fill's reach beyond them) reads
// each block once. A source on the grid itself is read directly: GDAL's
// block cache already holds its decoded blocks, and a read is a copy.
class BlockCache {
public:
    BlockCache(const Plan& plan, int side, std::int64_t bytes)
        : plan_(plan), side_(side), block_cols_((plan.cols + side - 1) / side),
          capacity_(std::size_t(std::max<std::int64_t>(1, bytes / (std::int64_t(side) * side * 4)))) {}

    // As read_metres, through the blocks; `rd` reads the blocks not cached.
    void read(const Reader& rd, int row0, int col0, int rows, int cols, float* z, int stride) {
        if (rows <= 0 || cols <= 0) return;
        if (plan_.warp.empty()) return read_metres(rd, plan_, row0, col0, rows, cols, z, stride);
        for (int br = row0 / side_; br <= (row0 + rows - 1) / side_; ++br)
            for (int bc = col0 / side_; bc <= (col0 + cols - 1) / side_; ++bc) {
                const std::shared_ptr<const Block> b = block(rd, br, bc);
                const int i0 = std::max(row0, br * side_), i1 = std::min(row0 + rows, br * side_ + b->rows);
                const int j0 = std::max(col0, bc * side_), j1 = std::min(col0 + cols, bc * side_ + b->cols);
                for (int i = i0; i < i1; ++i)
                    std::copy_n(b->z.data() + std::size_t(i - br * side_) * b->cols + std::size_t(j0 - bc * side_), j1 - j0,
                                z + std::size_t(i - row0) * stride + std::size_t(j0 - col0));
            }
    }

private:
    struct Block {
        std::once_flag once;
        int rows = 0, cols = 0;
        std::vector<float> z;
    };
    using Key = std::int64_t;

    std::shared_ptr<const Block> block(const Reader& rd, int br, int bc) {
        const Key key = Key(br) * block_cols_ + bc;
        std::shared_ptr<Block> b;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            if (const auto it = blocks_.find(key); it != blocks_.end()) {
                recent_.splice(recent_.begin(), recent_, it->second.second);
                b = it->second.first;
            } else {
                b = std::make_shared<Block>();
                recent_.push_front(key);
                blocks_.emplace(key, std::make_pair(b, recent_.begin()));
                while (blocks_.size() > capacity_) {
                    blocks_.erase(recent_.back());
                    recent_.pop_back();
                }
            }
        }
        // Outside the lock: other threads read other blocks meanwhile; one
        // asking for this block waits for it (a read that throws leaves it
        // to the next).
        std::call_once(b->once, [&] {
            b->rows = std::min(side_, plan_.rows - br * side_);
            b->cols = std::min(side_, plan_.cols - bc * side_);
            read_metres(rd, plan_, br * side_, bc * side_, b->rows, b->cols, b->z);
        });
        return b;
    }

    const Plan& plan_;
    const int side_, block_cols_;
    const std::size_t capacity_;
    std::mutex mutex_;
    std::list<Key> recent_; // most recently used first
    std::unordered_map<Key, std::pair<std::shared_ptr<Block>, std::list<Key>::iterator>> blocks_;
};

// The samples of tile (r, c) and its apron, plus one sample around them, as a
// window of the terrain (heights and colors) with no-data filled.
struct CutWindow {
    Terrain samples;
    int row0, col0;
};

// Rows r0 .. r1 and columns c0 .. c1 of the terrain.
CutWindow cut_window(const Reader& rd, BlockCache& cache, const Plan& plan, int r0, int r1, int c0, int c1) {
    const int h = r1 - r0 + 1, w = c1 - c0 + 1;
    std::vector<float> z(std::size_t(h) * std::size_t(w));
    // The fill of a sample reads only the samples within the search
    // distance, so a window widened by it fills the core as the whole raster
    // would.
    const int d = std::min(kFillSearchDistance, std::max(plan.rows, plan.cols));
    const int br0 = std::max(0, r0 - d), br1 = std::min(plan.rows - 1, r1 + d);
    const int bc0 = std::max(0, c0 - d), bc1 = std::min(plan.cols - 1, c1 + d);
    const int bh = br1 - br0 + 1, bw = bc1 - bc0 + 1;
    const std::optional<float> around = uniform_void(rd, plan, br0, bc0, bh, bw);
    const bool void_around = around && *around == kNoData;
    if (void_around) {
        // No data within the fill's reach (most of a sparse mosaic): the fill
        // has nothing to spread and leaves the window void, which becomes
        // the lowest elevation below, so neither is done.
        std::fill(z.begin(), z.end(), plan.integral ? std::round(plan.lo) : plan.lo);
    } else {
        cache.read(rd, r0, c0, h, w, z.data(), w);
    }
    if (!void_around && std::find(z.begin(), z.end(), kNoData) != z.end()) {
        std::vector<float> big(std::size_t(bh) * std::size_t(bw));
        cache.read(rd, br0, bc0, bh, bw, big.data(), bw);
        gdal::Dataset mem = gdal::create_mem(plan.path, bw, bh, 1, GDT_Float32);
        GDALRasterBandH band = GDALGetRasterBand(mem.get(), 1);
        GDALSetRasterNoDataValue(band, kNoData);
        CPLErrorReset();
        if (GDALRasterIO(band, GF_Write, 0, 0, bw, bh, big.data(), bw, bh, GDT_Float32, 0, 0) != CE_None)
            throw Error(plan.path, "cannot fill no-data: " + gdal::last_error("I/O error"));
        gdal::fill_nodata(band, d, plan.path);
        if (GDALRasterIO(band, GF_Read, c0 - bc0, r0 - br0, w, h, z.data(), w, h, GDT_Float32, 0, 0) != CE_None)
            throw Error(plan.path, "cannot fill no-data: " + gdal::last_error("I/O error"));
        for (float& v : z) {
            // Beyond the search distance: the lowest elevation, never a spike
            // (the loader's too for a void reaching the raster's border; it
            // searches the whole raster for an enclosed one).
            if (v == kNoData) v = plan.lo;
            if (plan.integral) v = std::round(v);
        }
    }
    CutWindow cw{Terrain(h, w, plan.h_scale, plan.mapping.v_scale, plan.mapping.y_offset), r0, c0};
    quantise_heights(z, plan.mapping, cw.samples.heights());
    for (int i = 0; i < h; ++i) shade_row(cw.samples, i, plan.world_lo, plan.world_hi, 0.0f);
    return cw;
}

// The samples tile (r, c) reads: its own, the apron and one sample around
// them (the hill shading's 3x3); with imagery, those under its texels (the
// fallback colors, bilinear) and one around them.
std::array<int, 4> window_of(const Plan& plan, const TileGrid& g, int r, int c) {
    const int S = g.stride();
    int r0 = r * S - 1, r1 = r * S + S + 1, c0 = c * S - 1, c1 = c * S + S + 1;
    if (plan.layout.present()) {
        const ImageryTileLayout& l = plan.layout;
        const auto [u0, v0] = imagery_tile_origin(l, g, r, c);
        const double hs = plan.h_scale;
        c0 = std::min(c0, int(std::floor(l.x_of(u0) / hs)) - 1);
        c1 = std::max(c1, int(std::ceil(l.x_of(u0 + l.cols) / hs)) + 1);
        r0 = std::min(r0, int(std::floor(l.z_of(v0) / hs)) - 1);
        r1 = std::max(r1, int(std::ceil(l.z_of(v0 + l.rows) / hs)) + 1);
    }
    return {std::max(0, r0), std::min(plan.rows - 1, r1), std::max(0, c0), std::min(plan.cols - 1, c1)};
}

// Peak bytes of one tile in flight: the widened float window, GDAL's copy of
// it for the fill and the fill's work planes (a UInt16 index, float values, a
// byte mask), the tile's samples, colors, d2, encoded files; with
// imagery its warped window, blend, levels and encoded planes.
std::int64_t bytes_per_tile(const Plan& plan, int tile_size) {
    std::int64_t side = tile_size + 2;
    if (plan.layout.present())
        side = std::max<std::int64_t>(side, std::int64_t(std::ceil(std::max(plan.layout.cols * plan.layout.texel_x(),
                                                                             plan.layout.rows * plan.layout.texel_z()) /
                                                                    plan.h_scale)) + 4);
    side = std::min<std::int64_t>(side + 2 * kFillSearchDistance, std::max(plan.rows, plan.cols));
    std::int64_t bytes = 16 * side * side + 48 * std::int64_t(tile_size) * tile_size + (16 << 20);
    if (plan.layout.present())
        bytes += 40 * std::int64_t(plan.layout.cols + 6) * (plan.layout.rows + 6);
    return bytes;
}

void open_imagery(Reader& r, const Plan& plan) {
    if (r.picked) return;
    r.color = gdal::open_raster(plan.color_path);
    r.picked = gdal::translate_lazily(r.color.get(), plan.imagery.band_options, plan.color_path);
}

// Tile (r, c)'s imagery from its window of the color raster, blended over
// the window's elevation colors as load_terrain blends the whole.
TileImagery cut_imagery(Reader& rd, const Plan& plan, const TileGrid& g, const CutWindow& cw, int r, int c) {
    open_imagery(rd, plan);
    const ImageryTileLayout& l = plan.layout;
    TileImagery t;
    t.r = r;
    t.c = c;
    std::tie(t.u0, t.v0) = imagery_tile_origin(l, g, r, c);
    const int f = kImageryFeatherTexels;
    const Image2D<Rgba8> window = warp_imagery_window(rd.picked.get(), plan.imagery, plan.wkt, t.u0 - f, t.v0 - f,
                                                      l.cols + 2 * f, l.rows + 2 * f, plan.color_path);
    const FallbackWindow fallback{&cw.samples, cw.row0, cw.col0, plan.rows, plan.cols};
    t.levels = imagery_tile_levels(blend_imagery_window(window, l, t.u0, t.v0, f, fallback), l.levels);
    return t;
}

// Plans the imagery of `plan` over tiles of `grid` (the plan's grid known):
// Error(color path, ...) as load_imagery when it cannot be placed; nothing
// when it is not finer than the DEM.
void plan_imagery(Plan& plan, const TileGrid& grid, const std::string& color_path) {
    const ImageryTarget target{plan.rows, plan.cols, plan.h_scale_exact, plan.georeferenced, plan.gt, plan.wkt};
    plan.imagery = plan_imagery_grid(color_path, target);
    if (!plan.imagery.finer) return;
    plan.color_path = color_path;
    // The in-memory pyramid's rectangle: the DEM's pixels (ImageryRaster.cpp load_imagery).
    const double hs = plan.h_scale_exact;
    try {
        plan.layout = plan_imagery_tiles(grid, -0.5 * hs, -0.5 * hs, hs * plan.cols, hs * plan.rows, plan.imagery.width,
                                         plan.imagery.height);
    } catch (const std::invalid_argument& e) {
        throw Error(color_path, e.what());
    }
}

// The tile grid of the planned terrain; Error(path, ...) when it is too large.
TileGrid grid_of(const Plan& plan, int tile_size) {
    try {
        return sized_tile_grid(plan.rows, plan.cols, tile_size, plan.h_scale, plan.mapping.v_scale, plan.mapping.y_offset);
    } catch (const Error& e) {
        if (e.subject() != "source") throw;
        throw Error(plan.path, e.problem());
    }
}

// How many tiles may be in flight: half the bound is theirs (a quarter is
// GDAL's block cache, an eighth the survey's strips and then the cache of
// warped blocks, the rest the index).
int workers_within(const Plan& plan, int tile_size, std::int64_t budget) {
    const std::int64_t per_tile = bytes_per_tile(plan, tile_size), for_tiles = budget / 2;
    if (per_tile > for_tiles)
        throw Error("memory bound", std::to_string(budget >> 20) + " MiB cannot hold one " + std::to_string(tile_size) +
                                        "-sample tile's window (about " + std::to_string(2 * per_tile >> 20) +
                                        " MiB needed); give more or use a smaller --tile-size");
    return int(std::min<std::int64_t>(tbb::this_task_arena::max_concurrency(), for_tiles / per_tile));
}

} // namespace

bool windowed_imagery_applies(const std::string& path, const std::string& color_path) {
    gdal::ensure_initialised();
    Plan plan;
    plan.path = path;
    gdal::Dataset src = gdal::open_raster(path);
    plan_grid(plan, src.get());
    if (!plan.georeferenced || plan.wkt.empty()) return false;
    gdal::Dataset color = gdal::open_raster(color_path);
    double cgt[6];
    if (GDALGetGeoTransform(color.get(), cgt) != CE_None || GDALGetSpatialRef(color.get()) == nullptr) return false;
    const ImageryTarget target{plan.rows, plan.cols, plan.h_scale_exact, plan.georeferenced, plan.gt, plan.wkt};
    return plan_imagery_grid(color_path, target).finer;
}

TileWriteReport tile_raster_in_windows(const std::string& path, const std::string& dir,
                                       const WindowedTileOptions& options) {
    gdal::ensure_initialised();
    const TileWriteOptions& o = options.tile;
    const std::int64_t budget = options.memory_bytes;
    // GDAL's block cache holds the strips of the source rows the tiles in
    // flight read, so that each is decompressed about once.
    GDALSetCacheMax64(budget / 4);
    const bool progress_bar = o.terminal_progress && ::isatty(2);
    std::mutex progress_mutex;
    const auto progress = [&](double f) {
        if (progress_bar) GDALTermProgress(f, nullptr, nullptr);
    };

    Plan plan;
    plan.path = path;
    {
        gdal::Dataset src = gdal::open_raster(path);
        // The loader's checks and warnings; no side limit but the tile grid's (grid_of).
        check_declared_size(src.get(), path, 0);
        std::vector<std::string> warnings;
        append_band_warnings(src.get(), warnings);
        if (options.warn)
            for (const std::string& w : warnings) options.warn(w);
        GDALRasterBandH band = GDALGetRasterBand(src.get(), 1);
        int has = 0;
        plan.band.nodata = GDALGetRasterNoDataValue(band, &has);
        plan.band.has_nodata = has != 0;
        double v = GDALGetRasterScale(band, &has);
        plan.band.scale = has && v != 0 ? v : 1.0;
        v = GDALGetRasterOffset(band, &has);
        plan.band.offset = has ? v : 0.0;
        const char* unit = GDALGetRasterUnitType(band);
        std::string unit_name;
        plan.band.unit = metres_per_unit(unit ? unit : "", unit_name);
        plan_grid(plan, src.get());
        // Sizes and memory are checked before the source is read.
        const TileGrid sized = grid_of(plan, o.tile_size);
        if (!options.color_path.empty()) plan_imagery(plan, sized, options.color_path);
        workers_within(plan, sized.tile_size, budget);
        const int tiles = sized.tile_rows * sized.tile_cols;
        survey(plan, src.get(), budget, [&](double f) {
            progress(0.1 * f);
            // A stop asked for while the source is surveyed (it may take minutes).
            if (o.on_tile && !o.on_tile(0, tiles)) throw Error(dir, "interrupted");
        });
    }

    TileWriteReport report;
    TileIndex& ix = report.index;
    ix.grid = grid_of(plan, o.tile_size);
    const TileGrid& g = ix.grid;
    ix.padded_size = int(g.padded_rows());
    ix.source = path;
    ix.checksum = plan.checksum;
    ix.georeferenced = plan.georeferenced;
    ix.crs_wkt = plan.georeferenced ? plan.wkt : std::string();
    if (plan.georeferenced)
        ix.geotransform = plan.gt;
    else
        ix.geotransform = {-0.5 * g.h_scale, g.h_scale, 0, 0.5 * g.h_scale, 0, -g.h_scale}; // as plan_index
    ix.apron = true;
    ix.imagery = plan.layout;
    if (plan.layout.present()) {
        // Parts tiling other imagery (or none) must not merge with these.
        const double l[] = {plan.layout.x0, plan.layout.z0, plan.layout.extent_x, plan.layout.extent_z,
                            double(plan.layout.width), double(plan.layout.height)};
        std::uint64_t h = fnv(kFnvBasis, ix.checksum.data(), ix.checksum.size());
        h = fnv(h, l, sizeof l);
        h = fnv(h, plan.color_path.data(), plan.color_path.size());
        char buf[17];
        std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
        ix.checksum = plan.checksum = buf;
    }
    ix.levels = o.measures.available() ? g.coarsest_level() : 0;
    ix.grid.d2_min_resolution = ix.levels > 0 ? o.measures.min_resolution : 0.0;
    const int f = overview_stride(plan.rows, plan.cols, o.overview_max_side);
    if (f > 1) {
        ix.overview_stride = f;
        ix.overview_rows = (plan.rows - 2) / f + 2;
        ix.overview_cols = (plan.cols - 2) / f + 2;
    }

    const int workers = workers_within(plan, g.tile_size, budget);

    const TilePart part = options.part;
    // Named variables, not a structured binding: lambdas below capture them,
    // which clang before 16 refuses for bindings (the fuzz build uses clang).
    const std::pair<int, int> part_rows = part_tile_rows(g.tile_rows, part);
    const int first_row = part_rows.first, end_row = part_rows.second;
    const std::string own_prefix =
        "." + std::string(kPartPrefix) + std::to_string(part.index) + "-of-" + std::to_string(part.count);
    prepare_folder(dir, [&](const std::string& name) {
        if (part.count == 1) return true;
        int r = -1;
        if (name.rfind("." + own_prefix, 0) == 0) return true; // a temporary of its record
        return std::sscanf(name.c_str(), ".r%d_c", &r) == 1 && r >= first_row && r < end_row;
    });
    FolderSync tiles_on_device(dir);
    const bool resume = resumable(dir, ix);
    ix.complete = false;
    write_index(dir, ix);

    PartRecord rec;
    rec.part = part;
    rec.checksum = ix.checksum;
    rec.tile_size = g.tile_size;
    rec.first_row = first_row;
    rec.end_row = end_row;
    const std::size_t n = std::size_t(end_row - first_row) * std::size_t(g.tile_cols);
    rec.min_height.assign(n, 0.0f);
    rec.max_height.assign(n, 0.0f);
    rec.roughness.assign(ix.levels > 0 ? n : 0, {});
    if (f > 1) {
        std::tie(rec.overview_first, rec.overview_end) = part_overview_rows(ix, first_row, end_row);
        const std::size_t m = std::size_t(rec.overview_end - rec.overview_first) * std::size_t(ix.overview_cols);
        rec.overview_heights.assign(m, 0);
        rec.overview_rgb.assign(3 * m, 0);
    }

    // The files in the folder before this run, listed once: a tile without
    // data removes what an earlier run may have left only where there is
    // something (a 131073^2 grid has 262144 tiles, most of them empty).
    std::unordered_set<std::string> before;
    for (const fs::directory_entry& e : fs::directory_iterator(dir)) before.insert(e.path().filename().string());
    tbb::enumerable_thread_specific<Reader> readers;
    std::atomic<int> written{0}, skipped{0}, empty{0};
    std::atomic<bool> stop{false};
    int done = 0;
    const int total = int(n);
    const int S = g.stride();
    BlockCache cache(plan, S, budget / 8);
    const auto cut = [&](int r, int c) {
        std::error_code ec;
        if (!g.present(r, c)) {
            ++empty;
            for (const TileFile file :
                 {TileFile::Heights, TileFile::Colors, TileFile::Apron, TileFile::D2, TileFile::Imagery}) {
                const fs::path stale = tile_path(dir, r, c, file);
                if (before.count(stale.filename().string())) fs::remove(stale, ec);
            }
            return;
        }
        Reader& rd = readers.local();
        open_reader(rd, plan, true);
        const std::array<int, 4> bounds = window_of(plan, g, r, c);
        CutWindow cw = cut_window(rd, cache, plan, bounds[0], bounds[1], bounds[2], bounds[3]);
        std::optional<TileImagery> imagery;
        if (plan.layout.present()) {
            imagery = cut_imagery(rd, plan, g, cw, r, c);
            // The samples' colors are the imagery's (colors_from_imagery).
            const int level = tile_sample_color_level(plan.layout, plan.h_scale);
            const double hs = plan.h_scale;
            for (int i = std::max(r * S, cw.row0); i <= std::min(r * S + S, cw.row0 + cw.samples.rows() - 1); ++i)
                for (int j = std::max(c * S, cw.col0); j <= std::min(c * S + S, cw.col0 + cw.samples.cols() - 1); ++j) {
                    const Rgba8 t = tile_imagery_bilinear(*imagery, plan.layout, hs * j, hs * i, level);
                    cw.samples.color(i - cw.row0, j - cw.col0) = Rgb8{t.r, t.g, t.b};
                }
        } else {
            fs::remove(tile_path(dir, r, c, TileFile::Imagery), ec);
        }
        const TerrainWindow window{cw.samples, cw.row0, cw.col0};
        const TileSamples tile = cut_tile(window, g, r, c);
        const std::size_t k = std::size_t(r - first_row) * std::size_t(g.tile_cols) + std::size_t(c);
        if (ix.levels > 0) rec.roughness[k] = o.measures.roughness(tile.samples);
        if (ix.levels == 0) fs::remove(tile_path(dir, r, c, TileFile::D2), ec);
        const TileContent content(dir, ix, r, c, tile, cut_apron(window, g, r, c), o.measures,
                                  imagery ? &*imagery : nullptr);
        if (resume && content.on_disk()) {
            ++skipped;
        } else {
            content.write();
            ++written;
        }
        const auto [lo_raw, hi_raw] = std::minmax_element(tile.samples.heights().begin(), tile.samples.heights().end());
        const float a = tile_world_height(g, *lo_raw), b = tile_world_height(g, *hi_raw);
        rec.min_height[k] = std::min(a, b);
        rec.max_height[k] = std::max(a, b);
        if (f > 1) {
            // The overview samples whose source sample this tile owns (the
            // tile row and column holding it; the last holds the grid's last).
            const int ov_cols = ix.overview_cols;
            const std::size_t m = rec.overview_heights.size();
            for (int i = std::max(rec.overview_first, r * S / f - 1); i < rec.overview_end && i <= (r + 1) * S / f + 1; ++i) {
                const int si = std::min(i * f, g.source_rows - 1);
                if (std::min(si / S, g.tile_rows - 1) != r) continue;
                for (int j = std::max(0, c * S / f - 1); j < ov_cols && j <= (c + 1) * S / f + 1; ++j) {
                    const int sj = std::min(j * f, g.source_cols - 1);
                    if (std::min(sj / S, g.tile_cols - 1) != c) continue;
                    const std::size_t at = std::size_t(i - rec.overview_first) * std::size_t(ov_cols) + std::size_t(j);
                    rec.overview_heights[at] = tile.samples.raw(si - r * S, sj - c * S);
                    Rgb8 col = tile.samples.color(si - r * S, sj - c * S);
                    if (si != i * f || sj != j * f)
                        col = Rgb8{std::uint8_t(col.r / 2), std::uint8_t(col.g / 2), std::uint8_t(col.b / 2)};
                    rec.overview_rgb[at] = col.r;
                    rec.overview_rgb[m + at] = col.g;
                    rec.overview_rgb[2 * m + at] = col.b;
                }
            }
        }
    };
    tbb::task_arena arena(std::max(1, workers));
    for (int r = first_row; r < end_row && !stop; ++r)
        arena.execute([&] {
            tbb::parallel_for(0, g.tile_cols, [&](int c) {
                if (stop) return;
                cut(r, c);
                std::lock_guard<std::mutex> lock(progress_mutex);
                ++done;
                progress(0.1 + 0.9 * double(done) / total);
                if (o.on_tile && !o.on_tile(done, total)) stop = true;
            });
        });
    if (stop) throw Error(dir, "interrupted");
    report.written = written;
    report.skipped = skipped;
    report.empty = empty;

    tiles_on_device.sync();
    write_part_record(dir, rec);
    auto [merged, complete] = merge_tile_parts(dir, part.count, false);
    if (complete) {
        ix = std::move(merged);
        if (part.count == 1) {
            std::error_code ec;
            fs::remove(fs::path(dir) / (own_prefix + ".json"), ec);
            fs::remove(fs::path(dir) / (own_prefix + ".overview"), ec);
        }
    }
    return report;
}

} // namespace overflight
