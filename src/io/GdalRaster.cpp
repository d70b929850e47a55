// Based on: Zamri, sec. 3 (USGS DEM ingestion); DESIGN sec. 4
// (rasters through GDAL: metric reprojection at native resolution, no-data
// filling, float/negative elevations mapped to 16 bits, color rasters warped
// onto the DEM grid, elevation ramp with hill shading otherwise).
#include "io/GdalRaster.h"

#include "core/Error.h"
#include "core/ImageryFallback.h"
#include "core/Shading.h"
#include "core/Terrain.h"
#include "io/Gdal.h"
#include "io/GdalReducedReads.h"
#include "io/GdalSource.h"
#include "io/HeightMapping.h"
#include "io/ImageryRaster.h"
#include "io/MetricWarp.h"
#include "io/UsgsDemHeader.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal_alg.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <new>
#include <sstream>
#include <unistd.h>

namespace overflight {

namespace {


std::string fmt(double v, int precision = 6) {
    std::ostringstream o;
    o.precision(precision);
    o << v;
    return o.str();
}

std::string srs_name(OGRSpatialReferenceH srs) {
    if (!srs) return {};
    const char* name = OSRGetName(srs);
    std::string s = name ? name : "unnamed";
    if (s == "unnamed" || s.empty()) {
        // USGS DEMs and VTP .bt files carry an unnamed CRS: name it by its parts.
        const char* geog = OSRGetAttrValue(srs, "GEOGCS", 0);
        int north = 0;
        const int zone = OSRGetUTMZone(srs, &north);
        const char* projection = OSRGetAttrValue(srs, "PROJECTION", 0);
        s = geog ? geog : "unknown datum";
        if (zone > 0)
            s += " / UTM zone " + std::to_string(zone) + (north ? "N" : "S");
        else if (projection)
            s += std::string(" / ") + projection;
    }
    const char* auth = OSRGetAuthorityName(srs, nullptr);
    const char* code = OSRGetAuthorityCode(srs, nullptr);
    if (auth && code) s += " (" + std::string(auth) + ":" + code + ")";
    return s;
}

// Largest side of a Terrain (2^16 + 1 samples, core/Terrain.h).
constexpr int kMaxSide = 65537;
// Peak bytes per sample while loading: float elevations, a float copy for
// no-data filling or warping, 16-bit heights, RGB colors, with slack for
// GDAL's own buffers.
constexpr double kLoadBytesPerSample = 16;
// Samples a survey reads for the elevation range and no-data share: 64 blocks
// of a tiled GeoTIFF, a few hundred rows of a striped one.
constexpr long long kSurveySamples = 1LL << 22;

struct Grid {
    int rows = 0, cols = 0;
    std::vector<float> z;     // elevations in metres, kNoData where missing
    double gt[6] = {0, 1, 0, 0, 0, 1};
    bool georeferenced = false; // gt is a real geotransform
    std::string wkt;            // CRS, empty if none
};

void read_band(GDALRasterBandH band, int cols, int rows, std::vector<float>& out, const std::string& subject) {
    try {
        out.resize(std::size_t(rows) * std::size_t(cols));
    } catch (const std::bad_alloc&) {
        throw Error(subject, "not enough memory for a " + std::to_string(cols) + "x" + std::to_string(rows) + " raster");
    }
    CPLErrorReset();
    if (GDALRasterIO(band, GF_Read, 0, 0, cols, rows, out.data(), cols, rows, GDT_Float32, 0, 0) != CE_None)
        throw Error(subject, "unreadable raster: " + gdal::last_error("read failed"));
}

gdal::Dataset grid_dataset(const Grid& g, const std::string& subject) {
    gdal::Dataset ds =
        gdal::create_mem(subject, g.cols, g.rows, 1, GDT_Float32, g.georeferenced ? g.gt : nullptr, g.wkt);
    GDALRasterBandH band = GDALGetRasterBand(ds.get(), 1);
    GDALSetRasterNoDataValue(band, kNoData);
    if (GDALRasterIO(band, GF_Write, 0, 0, g.cols, g.rows, const_cast<float*>(g.z.data()), g.cols, g.rows, GDT_Float32,
                     0, 0) != CE_None)
        throw Error(subject, "cannot write a temporary raster: " + gdal::last_error("write failed"));
    return ds;
}

Grid grid_of(GDALDatasetH ds, const std::string& subject) {
    Grid g;
    g.cols = GDALGetRasterXSize(ds);
    g.rows = GDALGetRasterYSize(ds);
    g.georeferenced = GDALGetGeoTransform(ds, g.gt) == CE_None;
    const char* wkt = GDALGetProjectionRef(ds);
    g.wkt = wkt ? wkt : "";
    read_band(GDALGetRasterBand(ds, 1), g.cols, g.rows, g.z, subject);
    return g;
}

// Band 1 decimated by `factor`: each sample the mean of a factor x factor
// block of source samples (the last cols % factor columns and rows % factor
// rows are left out), the geotransform's pixel size multiplied by `factor`,
// so each sample keeps the footprint of its block.
Grid decimated_grid_of(GDALDatasetH ds, const std::string& path, int factor) {
    Grid g;
    g.cols = GDALGetRasterXSize(ds) / factor;
    g.rows = GDALGetRasterYSize(ds) / factor;
    g.georeferenced = GDALGetGeoTransform(ds, g.gt) == CE_None;
    for (const int k : {1, 2, 4, 5}) g.gt[k] *= factor;
    const char* wkt = GDALGetProjectionRef(ds);
    g.wkt = wkt ? wkt : "";
    gdal::read_block_averages(path, factor, g.cols, g.rows, g.z, path);
    return g;
}

// One GDALFillNodata pass over `g` searching up to `distance` samples.
void fill_within(Grid& g, int distance, const std::string& subject) {
    gdal::Dataset ds = grid_dataset(g, subject);
    GDALRasterBandH band = GDALGetRasterBand(ds.get(), 1);
    gdal::fill_nodata(band, distance, subject);
    read_band(band, g.cols, g.rows, g.z, subject);
}

// Sets the kNoData samples 4-connected to the grid's border to `value`;
// returns whether any kNoData sample is left (a void enclosed by data).
bool set_border_voids(Grid& g, float value) {
    std::vector<std::size_t> stack;
    const auto push = [&](int i, int j) {
        const std::size_t k = std::size_t(i) * std::size_t(g.cols) + std::size_t(j);
        if (g.z[k] != kNoData) return;
        g.z[k] = value;
        stack.push_back(k);
    };
    for (int i = 0; i < g.rows; ++i) push(i, 0), push(i, g.cols - 1);
    for (int j = 0; j < g.cols; ++j) push(0, j), push(g.rows - 1, j);
    while (!stack.empty()) {
        const std::size_t k = stack.back();
        stack.pop_back();
        const int i = int(k / std::size_t(g.cols)), j = int(k % std::size_t(g.cols));
        if (i > 0) push(i - 1, j);
        if (i + 1 < g.rows) push(i + 1, j);
        if (j > 0) push(i, j - 1);
        if (j + 1 < g.cols) push(i, j + 1);
    }
    return std::find(g.z.begin(), g.z.end(), kNoData) != g.z.end();
}

// Fills kNoData samples by inverse-distance interpolation from valid
// neighbours (GDALFillNodata, the algorithm of gdal_fillnodata) within
// kFillSearchDistance; what that leaves gets `lowest` (never a spike) where
// it reaches the grid's border: the wedges a reprojection leaves outside the
// source, whose search over the whole grid took most of a large geographic
// load, as the windowed tiler's windows do. A void enclosed by data is
// searched for as far as needed. The cost of a pass grows with its search
// distance times the samples left to fill.
void fill_nodata(Grid& g, float lowest, const std::string& subject) {
    const int whole = std::max(g.rows, g.cols);
    fill_within(g, std::min(kFillSearchDistance, whole), subject);
    if (!set_border_voids(g, lowest)) return;
    fill_within(g, whole, subject);
    for (float& v : g.z)
        if (v == kNoData) v = lowest;
}

struct ColorResult {
    ColorImage image;
    std::string description;
};

// Resamples the color raster onto the DEM grid (DESIGN sec. 4: `--color FILE`);
// where it does not cover the grid (ImageryFallback.h) the terrain keeps the
// colors it holds, blended by the warp's coverage alpha.
ColorResult color_on_grid(const std::string& color_path, const Grid& dem, const std::vector<Rgb8>& fallback) {
    gdal::Dataset src = gdal::open_raster(color_path);
    std::string bands_used;
    bool rescaled = false;
    std::vector<std::string> opts = color_band_options(src.get(), bands_used, rescaled);
    double cgt[6];
    const bool color_geo = GDALGetGeoTransform(src.get(), cgt) == CE_None && GDALGetSpatialRef(src.get()) != nullptr;
    const bool warp = color_geo && dem.georeferenced && !dem.wkt.empty();
    if (!warp) {
        opts.insert(opts.end(), {"-outsize", std::to_string(dem.cols), std::to_string(dem.rows), "-r", "bilinear"});
    }
    // Picked lazily: only the warp or the read onto the DEM grid below reads
    // the color raster, block by block, so one larger than memory fits.
    gdal::Dataset picked = gdal::translate_lazily(src.get(), opts, color_path);
    std::string how = "stretched to the DEM grid (bilinear; no common georeferencing)";
    if (warp) {
        // The DEM's samples are its pixel centres, so the color grid is the DEM's pixel grid.
        const double xmin = dem.gt[0], xmax = dem.gt[0] + dem.gt[1] * dem.cols;
        const double ymax = dem.gt[3], ymin = dem.gt[3] + dem.gt[5] * dem.rows;
        const double color_px = std::abs(cgt[1]);
        const bool finer = color_px < std::abs(dem.gt[1]);
        // Averaging when the color raster is finer avoids aliasing (a 28.5 m
        // Landsat pixel onto a 90 m DEM cell); bilinear when it is coarser.
        const char* method = finer ? "average" : "bilinear";
        picked = gdal::warp(picked.get(),
                            {"-t_srs", dem.wkt, "-te", fmt(xmin, 17), fmt(std::min(ymin, ymax), 17), fmt(xmax, 17),
                             fmt(std::max(ymin, ymax), 17), "-ts", std::to_string(dem.cols), std::to_string(dem.rows),
                             "-r", method, "-ovr", "NONE", "-dstalpha"},
                            color_path);
        how = std::string("warped onto the DEM grid (") + method + ")";
    }
    const int out_bands = GDALGetRasterCount(picked.get());
    const int colour_bands = warp ? out_bands - 1 : out_bands;
    std::vector<std::uint8_t> channel(std::size_t(dem.rows) * std::size_t(dem.cols));
    std::vector<std::uint8_t> alpha(channel.size(), 255);
    ColorResult result;
    result.image.resize(dem.cols, dem.rows);
    auto read = [&](int band_index, std::vector<std::uint8_t>& into) {
        CPLErrorReset();
        if (GDALRasterIO(GDALGetRasterBand(picked.get(), band_index), GF_Read, 0, 0, dem.cols, dem.rows, into.data(),
                         dem.cols, dem.rows, GDT_Byte, 0, 0) != CE_None)
            throw Error(color_path, "unreadable raster: " + gdal::last_error("read failed"));
    };
    if (warp) read(out_bands, alpha);
    bool any = false;
    for (int c = 0; c < 3; ++c) {
        read(std::min(c + 1, colour_bands), channel);
        for (std::size_t i = 0; i < channel.size(); ++i) {
            (&result.image.pixels[i].r)[c] = channel[i];
            any = any || (channel[i] != 0 && alpha[i] != 0);
        }
    }
    if (!any) throw Error(color_path, "color raster is entirely black on the terrain (does it overlap the DEM?)");
    for (std::size_t i = 0; i < alpha.size(); ++i) {
        if (alpha[i] == 255) continue;
        const float w = float(alpha[i]) / 255.0f;
        Rgb8& p = result.image.pixels[i];
        const Rgb8 f = fallback[i];
        for (int c = 0; c < 3; ++c)
            (&p.r)[c] = std::uint8_t(std::lround(float((&p.r)[c]) * w + float((&f.r)[c]) * (1.0f - w)));
    }
    result.description = color_path + " (" + bands_used + (rescaled ? ", rescaled to 8 bits" : "") + ", " + how + ")";
    return result;
}

std::vector<std::pair<std::string, std::string>> metadata_of(GDALDatasetH ds, const std::string& path,
                                                             const std::string& driver) {
    std::vector<std::pair<std::string, std::string>> out;
    auto add_list = [&](char** list, const std::string& prefix) {
        for (char** p = list; p && *p; ++p) {
            char* key = nullptr;
            const char* value = CPLParseNameValue(*p, &key);
            if (key) out.emplace_back(prefix + key, value ? value : "");
            CPLFree(key);
        }
    };
    add_list(GDALGetMetadata(ds, nullptr), "");
    add_list(GDALGetMetadata(GDALGetRasterBand(ds, 1), nullptr), "BAND1_");
    if (driver == "USGSDEM")
        for (auto& kv : usgs_record_a(usgs_record_a_text(path))) out.push_back(std::move(kv));
    return out;
}

// Loading holds the elevations as floats, a float copy for GDAL's no-data
// filling or warping, and the terrain's 16-bit heights and RGB colors: a
// cols x rows read is refused before allocating when that exceeds the
// machine's memory.
void check_memory(const std::string& path, int cols, int rows) {
    const double needed = double(rows) * double(cols) * kLoadBytesPerSample;
    const double memory = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
    if (memory > 0 && needed > memory)
        throw Error(path, "raster is " + std::to_string(cols) + "x" + std::to_string(rows) + ", loading it needs about " +
                              fmt(needed / 1073741824.0, 3) + " GiB, more than this machine's " +
                              fmt(memory / 1073741824.0, 3) + " GiB of memory");
}

// Band 1's values as metres: its no-data value (and NaN) mark voids, then its
// scale/offset and unit type apply. Records the unit in `info`.
struct HeightConversion {
    int has_nodata = 0;
    double nodata = 0, scale = 1, offset = 0, unit_to_metre = 1;

    HeightConversion(GDALDatasetH src_ds, TerrainInfo& info) {
        GDALRasterBandH band = GDALGetRasterBand(src_ds, 1);
        nodata = GDALGetRasterNoDataValue(band, &has_nodata);
        int has_scale = 0, has_offset = 0;
        scale = GDALGetRasterScale(band, &has_scale);
        offset = GDALGetRasterOffset(band, &has_offset);
        if (!has_scale || scale == 0) scale = 1;
        if (!has_offset) offset = 0;
        const char* unit = GDALGetRasterUnitType(band);
        info.unit_to_metre = unit_to_metre = metres_per_unit(unit ? unit : "", info.vertical_units);
    }
    bool missing(float v) const {
        return !std::isfinite(v) || (has_nodata && (double(v) == nodata || float(nodata) == v));
    }
    // Rejects, naming the file and the sample, a value that would otherwise
    // become an infinite elevation range that later steps blame on something else.
    double metres(float v, long long row, long long col, const std::string& path) const {
        const double m = (double(v) * scale + offset) * unit_to_metre;
        if (const std::string problem = elevation_problem(m); !problem.empty())
            throw Error(path, "row " + std::to_string(row) + ", column " + std::to_string(col) + ": " + problem +
                                  " (not a terrain height; is the no-data value set?)");
        return m;
    }
};

// Converts band 1's values in `grid` to metres and marks no-data as kNoData.
// Returns the number of no-data samples; `integral` tells whether every valid
// value is whole metres.
long long heights_to_metres(Grid& grid, GDALDatasetH src_ds, const std::string& path, TerrainInfo& info,
                            bool& integral) {
    const HeightConversion conversion(src_ds, info);
    long long voids = 0;
    integral = true; // whole metres in the source: kept exact (v_scale = 1) when not resampled
    for (std::size_t i = 0; i < grid.z.size(); ++i) {
        float& v = grid.z[i];
        if (conversion.missing(v)) {
            v = kNoData;
            ++voids;
            continue;
        }
        v = float(conversion.metres(v, i / std::size_t(grid.cols), i % std::size_t(grid.cols), path));
        integral = integral && v == std::round(v);
    }
    return voids;
}

// The square metric grid a raster is loaded onto (DESIGN sec. 4), worked out
// from its georeferencing alone, before any sample is read: its own grid, or
// the grid gdalwarp suggests (GDALSuggestedWarpOutput2) in the UTM zone of its
// centre for a geographic CRS, or in its own CRS at its finer pixel size for
// rotated or non-square cells.
struct MetricGrid {
    bool georeferenced = false;        // a real geotransform, not GDAL's default
    std::string source_crs, crs;       // srs_name of the source's CRS and of the grid's
    bool warped = false;               // the grid is not the raster's own
    std::vector<std::string> target;   // gdalwarp's "-t_srs WKT" to a UTM zone, or nothing
    bool finer_cells = false;          // warped within its CRS to square cells of `res`
    int cols = 0, rows = 0;            // of the grid at full resolution
    double gt[6] = {0, 1, 0, 0, 0, 1}; // of the grid at full resolution
    double res = 1.0;                  // its cell size in CRS units
    double metres_per_unit = 1.0;      // linear unit of its CRS (a projected CRS in feet)
    std::string wkt;                   // its CRS, empty if none
    double inside_share = 1.0;         // share of the grid's cells whose centre falls on the source
};

// The share of `m`'s cells whose centre `transformer` (source pixels to the
// grid's CRS) maps back inside the source raster, from a 64x64 lattice: the
// rest is filled as no-data after a reprojection.
double share_inside_source(void* transformer, const MetricGrid& m, int src_cols, int src_rows) {
    constexpr int kLattice = 64;
    std::vector<double> x, y, z(kLattice * kLattice, 0.0);
    for (int i = 0; i < kLattice; ++i)
        for (int j = 0; j < kLattice; ++j) {
            const double col = (j + 0.5) * m.cols / kLattice, row = (i + 0.5) * m.rows / kLattice;
            x.push_back(m.gt[0] + col * m.gt[1] + row * m.gt[2]);
            y.push_back(m.gt[3] + col * m.gt[4] + row * m.gt[5]);
        }
    std::vector<int> ok(x.size(), 0);
    GDALGenImgProjTransform(transformer, TRUE, int(x.size()), x.data(), y.data(), z.data(), ok.data());
    long long inside = 0;
    for (std::size_t k = 0; k < x.size(); ++k)
        inside += ok[k] && x[k] >= 0 && y[k] >= 0 && x[k] < src_cols && y[k] < src_rows;
    return double(inside) / double(x.size());
}

MetricGrid metric_grid_of(GDALDatasetH ds, const std::string& path) {
    MetricGrid m;
    m.cols = GDALGetRasterXSize(ds);
    m.rows = GDALGetRasterYSize(ds);
    const bool has_gt = GDALGetGeoTransform(ds, m.gt) == CE_None;
    m.georeferenced = has_gt && !(m.gt[0] == 0 && m.gt[1] == 1 && m.gt[2] == 0 && m.gt[3] == 0 && m.gt[4] == 0 &&
                                  m.gt[5] == 1);
    OGRSpatialReferenceH srs = m.georeferenced ? GDALGetSpatialRef(ds) : nullptr; // a CRS without a geotransform places nothing
    m.source_crs = srs_name(srs);
    m.crs = m.source_crs;
    m.wkt = srs ? to_wkt(srs) : "";
    const double px = std::hypot(m.gt[1], m.gt[4]), py = std::hypot(m.gt[2], m.gt[5]);
    m.res = m.georeferenced ? px : 1.0;
    Srs utm;
    if (srs && OSRIsGeographic(srs)) {
        const double lon = m.gt[0] + m.gt[1] * m.cols * 0.5 + m.gt[2] * m.rows * 0.5;
        const double lat = m.gt[3] + m.gt[4] * m.cols * 0.5 + m.gt[5] * m.rows * 0.5;
        utm = utm_for(srs, lon, lat);
        m.wkt = to_wkt(utm.get());
        m.crs = srs_name(utm.get());
        // No -tr: gdalwarp's suggested output keeps the source's sample count
        // along the diagonal with square cells, i.e. its native resolution.
        m.target = {"-t_srs", m.wkt};
        m.warped = true;
    } else if (m.georeferenced) {
        const bool rotated = m.gt[2] != 0 || m.gt[4] != 0;
        if (rotated || std::abs(px - py) > 1e-6 * std::max(px, py)) {
            m.res = std::min(px, py); // the finer spacing: no detail is lost
            m.finer_cells = m.warped = true;
        }
    }
    if (m.warped) {
        // The output grid gdalwarp would make, from the transformer alone.
        const gdal::SuggestedWarpOutput out(ds, m.target.empty() ? "" : m.wkt, path, "cannot reproject raster");
        const double* gt = out.geotransform;
        const int nx = out.cols, ny = out.rows;
        std::copy(gt, gt + 6, m.gt);
        m.cols = nx;
        m.rows = ny;
        if (m.finer_cells) {
            // gdalwarp -tr: the suggested extent in whole cells of `res`.
            m.cols = int((nx * gt[1] + m.res / 2) / m.res);
            m.rows = int((std::abs(ny * gt[5]) + m.res / 2) / m.res);
            const double grid[6] = {gt[0], m.res, 0, gt[3], 0, -m.res};
            std::copy(grid, grid + 6, m.gt);
        } else {
            m.res = std::abs(gt[1]);
        }
        m.inside_share = share_inside_source(out.transformer(), m, GDALGetRasterXSize(ds), GDALGetRasterYSize(ds));
    }
    if (!m.wkt.empty()) {
        Srs parsed(OSRNewSpatialReference(m.wkt.c_str()));
        if (parsed && OSRIsProjected(parsed.get())) m.metres_per_unit = OSRGetLinearUnits(parsed.get(), nullptr);
    }
    return m;
}

// The whole factor by which a raster is decimated so that its metric grid
// has at most `max_side` samples on a side (1: read at full resolution).
int decimation_factor(const MetricGrid& m, int max_side) {
    const int side = std::max(m.cols, m.rows);
    if (max_side <= 0 || side <= max_side) return 1;
    return (side + max_side - 1) / max_side;
}

// Warps `grid` (band 1 read decimated by `factor`) to the square metric cells
// of `m` when they are not the raster's own (DESIGN sec. 4); returns the cell
// size in metres. Decimated, the cells are `factor` times coarser over the
// full-resolution grid's extent.
double to_square_metric_cells(Grid& grid, const MetricGrid& m, int factor, const std::string& path,
                              TerrainInfo& info) {
    grid.georeferenced = m.georeferenced;
    info.source_crs = m.source_crs;
    info.crs = m.crs;
    double hs = m.georeferenced ? std::hypot(grid.gt[1], grid.gt[4]) : 1.0;
    if (m.warped) {
        gdal::Dataset source = grid_dataset(grid, path);
        if (factor > 1) {
            // A decimated read is rendered, never tiled: gdalwarp with its
            // approximate transformer onto the coarser cells.
            std::vector<std::string> warp_opts = m.target;
            const double res = m.res * factor;
            const double xmax = m.gt[0] + m.gt[1] * m.cols, ymin = m.gt[3] + m.gt[5] * m.rows;
            warp_opts.insert(warp_opts.end(), {"-tr", fmt(res, 17), fmt(res, 17), "-te", fmt(m.gt[0], 17),
                                               fmt(ymin, 17), fmt(xmax, 17), fmt(m.gt[3], 17)});
            const std::vector<std::string> common = metric_warp_options();
            warp_opts.insert(warp_opts.end(), common.begin(), common.end());
            warp_opts.insert(warp_opts.end(), {"-srcnodata", fmt(kNoData, 9), "-et", "0.125"});
            gdal::Dataset warped = gdal::warp(source.get(), warp_opts, path);
            grid = grid_of(warped.get(), path);
        } else {
            // Full resolution: the warp the windowed tiler makes per window
            // (io/MetricWarp.h), so that tiles cut from either agree.
            MetricGridSpec spec;
            std::copy(m.gt, m.gt + 6, spec.gt.begin());
            spec.cols = m.cols;
            spec.rows = m.rows;
            if (!m.target.empty()) spec.wkt = m.wkt;
            const MetricWarp warp(source.get(), spec, path);
            Grid out;
            out.cols = m.cols;
            out.rows = m.rows;
            std::copy(m.gt, m.gt + 6, out.gt);
            out.wkt = warped_crs_wkt(m.wkt);
            try {
                out.z.resize(std::size_t(out.rows) * std::size_t(out.cols));
            } catch (const std::bad_alloc&) {
                throw Error(path, "not enough memory for a " + std::to_string(out.cols) + "x" +
                                      std::to_string(out.rows) + " raster");
            }
            warp.read(0, 0, out.rows, out.cols, out.z.data());
            source.reset();
            grid = std::move(out);
        }
        grid.georeferenced = true;
        hs = std::abs(grid.gt[1]);
        info.reprojected = true;
        info.reprojection = (info.source_crs.empty() ? std::string("no CRS") : info.source_crs) + " -> " + info.crs +
                            ", bilinear, square cells of " + fmt(hs, 6) + " (was " + std::to_string(info.source_cols) +
                            "x" + std::to_string(info.source_rows) + " cells" +
                            (factor > 1 ? ", averaged " + std::to_string(factor) + "x" + std::to_string(factor) +
                                              " first"
                                        : "") +
                            ")";
    }
    return hs * m.metres_per_unit;
}

// Fills the no-data samples from their valid neighbours (the rest: `lowest`,
// the lowest valid elevation of the source, never a spike), recording what
// was done in `info`.
void fill_voids(Grid& grid, const std::string& path, TerrainInfo& info, long long source_voids, float lowest,
                bool& integral) {
    long long missing = 0;
    for (float v : grid.z) missing += v == kNoData;
    if (missing == (long long)grid.z.size()) throw Error(path, "raster is entirely no-data");
    if (missing > 0) {
        fill_nodata(grid, lowest, path);
    }
    // Interpolated voids of an integer DEM are rounded to whole metres, so the
    // DEM keeps its exact 1 m mapping; resampled grids are no longer integral.
    integral = integral && !info.reprojected;
    if (integral && missing > 0)
        for (float& v : grid.z) v = std::round(v);
    info.nodata_filled = missing;
    if (missing > 0) {
        info.nodata_method = "inverse-distance interpolation from valid neighbours (GDALFillNodata); " +
                             std::to_string(source_voids) + " no-data samples in the source";
        if (info.reprojected) info.nodata_method += ", the rest outside the source after reprojection";
    }
}

DataSet load_checked(GDALDatasetH src_ds, const std::string& path, const std::string& driver_name,
                     const std::string& color_path, int max_direct_size, std::size_t imagery_bytes) {
    DataSet data;
    TerrainInfo& info = data.info;
    info.source = path;
    info.kind = "gdal";
    info.driver = driver_name;
    append_band_warnings(src_ds, info.warnings);
    info.source_rows = GDALGetRasterYSize(src_ds);
    info.source_cols = GDALGetRasterXSize(src_ds);
    const MetricGrid metric = metric_grid_of(src_ds, path);
    const int factor = decimation_factor(metric, max_direct_size);
    check_memory(path, info.source_cols / factor, info.source_rows / factor);
    Grid grid = factor == 1 ? grid_of(src_ds, path) : decimated_grid_of(src_ds, path, factor);

    bool integral = true;
    const long long voids = heights_to_metres(grid, src_ds, path, info, integral);
    if (voids == (long long)grid.z.size()) throw Error(path, "raster is entirely no-data");
    info.metadata = metadata_of(src_ds, path, info.driver);
    // The height mapping and the colour ramp span the source's elevations:
    // reprojected and filled values are weighted means of them, so they lie
    // within, and the windowed tiler (io/WindowedTiler.h), which cannot see
    // the whole reprojected grid, knows the same range from its first pass.
    float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
    for (float v : grid.z)
        if (v != kNoData) {
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }

    const double hs = to_square_metric_cells(grid, metric, factor, path, info);
    if (const std::string problem = horizontal_scale_problem(grid.rows, grid.cols, hs); !problem.empty())
        throw Error(path, "pixel size: " + problem);
    if (factor > 1) {
        info.decimation = factor;
        info.warnings.push_back(std::to_string(metric.cols) + "x" + std::to_string(metric.rows) +
                                " samples is more than --max-direct-size " + std::to_string(max_direct_size) +
                                "; rendering it decimated by " + std::to_string(factor) + " to " +
                                std::to_string(grid.cols) + "x" + std::to_string(grid.rows) +
                                " (overflight tile keeps the full resolution)");
    }

    fill_voids(grid, path, info, voids, lo, integral);

    const HeightMapping mapping = choose_height_mapping(lo, hi, integral);
    data.terrain = Terrain(grid.rows, grid.cols, float(hs), mapping.v_scale, mapping.y_offset);
    info.georeferenced = grid.georeferenced;
    if (grid.georeferenced) {
        std::copy(grid.gt, grid.gt + 6, info.geotransform.begin());
        info.crs_wkt = grid.wkt;
    }
    quantise_heights(grid.z, mapping, data.terrain.heights());

    if (!color_path.empty()) {
        // The elevation ramp first: the fallback wherever the imagery does not cover the terrain.
        shade_by_elevation(data.terrain, 0.0f);
        ImageryTarget target{grid.rows, grid.cols, hs, grid.georeferenced, {}, grid.wkt};
        std::copy(grid.gt, grid.gt + 6, target.gt.begin());
        ImageryLoad imagery = load_imagery(color_path, target, imagery_bytes);
        if (imagery.pyramid) {
            blend_over_terrain_colors(*imagery.pyramid, data.terrain);
            colors_from_imagery(*imagery.pyramid, data.terrain);
            data.terrain.set_imagery(std::move(imagery.pyramid));
            info.color_source = imagery.description;
            if (!imagery.warning.empty()) info.warnings.push_back(imagery.warning);
        } else {
            ColorResult color = color_on_grid(color_path, grid, data.terrain.colors());
            data.terrain.colors().assign(color.image.pixels.begin(), color.image.pixels.end());
            info.color_source = color.description;
        }
    } else {
        const auto [world_lo, world_hi] = mapped_range(mapping, lo, hi);
        shade_by_elevation(data.terrain, 0.0f, world_lo, world_hi);
        info.color_source = "elevation ramp + hillshade";
    }
    return data;
}

} // namespace

DataSet load_gdal_raster(const std::string& path, const std::string& color_path, int max_direct_size,
                         std::size_t imagery_bytes) {
    gdal::Dataset src = gdal::open_raster(path);
    GDALDriverH driver = GDALGetDatasetDriver(src.get());
    const std::string driver_name = driver ? GDALGetDriverShortName(driver) : "?";
    check_declared_size(src.get(), path, kMaxSide);
    try {
        return load_checked(src.get(), path, driver_name, color_path, max_direct_size, imagery_bytes);
    } catch (const std::bad_alloc&) {
        // Sizes were checked against the machine's memory, not against a
        // process limit (ulimit -v) or what other programs hold.
        throw Error(path, "not enough memory to load a " + std::to_string(GDALGetRasterXSize(src.get())) + "x" +
                              std::to_string(GDALGetRasterYSize(src.get())) + " raster");
    }
}

TerrainDescription survey_gdal_raster(const std::string& path, const std::string& color_path) {
    gdal::Dataset src = gdal::open_raster(path);
    GDALDriverH driver = GDALGetDatasetDriver(src.get());
    TerrainDescription d;
    TerrainInfo& info = d.info;
    info.source = path;
    info.kind = "gdal";
    info.driver = driver ? GDALGetDriverShortName(driver) : "?";
    check_declared_size(src.get(), path, kMaxSide);
    append_band_warnings(src.get(), info.warnings);
    info.source_rows = GDALGetRasterYSize(src.get());
    info.source_cols = GDALGetRasterXSize(src.get());
    const MetricGrid m = metric_grid_of(src.get(), path);
    const double hs = m.res * m.metres_per_unit;
    if (const std::string problem = horizontal_scale_problem(m.rows, m.cols, hs); !problem.empty())
        throw Error(path, "pixel size: " + problem);

    // Elevation range and no-data share from a sample spread over the raster
    // (as GDAL's approximate statistics), in metres as the loader converts them.
    const HeightConversion conversion(src.get(), info);
    long long sampled = 0, voids = 0;
    double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
    bool integral = true;
    const std::string how = gdal::sample_band(
        GDALGetRasterBand(src.get(), 1), kSurveySamples,
        [&](int col, int row, float v) {
            ++sampled;
            if (conversion.missing(v)) {
                ++voids;
                return;
            }
            const double metres = conversion.metres(v, row, col, path);
            lo = std::min(lo, metres);
            hi = std::max(hi, metres);
            integral = integral && metres == std::round(metres);
        },
        path);
    const bool whole = how == "every sample";
    if (voids == sampled && whole) throw Error(path, "raster is entirely no-data");
    info.metadata = metadata_of(src.get(), path, info.driver);

    info.source_crs = m.source_crs;
    info.crs = m.crs;
    info.reprojected = m.warped;
    if (m.warped)
        info.reprojection = (info.source_crs.empty() ? std::string("no CRS") : info.source_crs) + " -> " + info.crs +
                            ", bilinear, square cells of " + fmt(hs, 6) + " (was " + std::to_string(info.source_cols) +
                            "x" + std::to_string(info.source_rows) + " cells)";
    info.georeferenced = m.georeferenced;
    if (m.georeferenced) {
        std::copy(m.gt, m.gt + 6, info.geotransform.begin());
        info.crs_wkt = m.wkt;
    }
    d.rows = m.rows;
    d.cols = m.cols;
    d.h_scale = float(hs);
    d.extent_x = d.h_scale * float(m.cols - 1); // as Terrain::width and depth compute them
    d.extent_z = d.h_scale * float(m.rows - 1);
    const double source_share = sampled > 0 ? double(voids) / double(sampled) : 0.0;
    d.nodata_share = 1.0 - m.inside_share * (1.0 - source_share);
    info.nodata_filled = std::llround(d.nodata_share * double(m.rows) * double(m.cols));
    if (info.nodata_filled > 0) {
        info.nodata_method = "inverse-distance interpolation from valid neighbours (GDALFillNodata) when loaded; " +
                             fmt(100.0 * source_share, 3) + "% of the source sample is no-data";
        if (m.warped)
            info.nodata_method +=
                ", " + fmt(100.0 * (1.0 - m.inside_share), 3) + "% of the grid is outside the source after reprojection";
    }
    d.elevation_known = voids < sampled;
    if (d.elevation_known) {
        const HeightMapping mapping = choose_height_mapping(lo, hi, integral && !m.warped);
        d.v_scale = mapping.v_scale;
        d.y_offset = mapping.y_offset;
        d.elevation_min = float(lo);
        d.elevation_max = float(hi);
    } else {
        info.warnings.push_back("no valid elevation among the " + std::to_string(sampled) + " samples read");
    }
    if (!color_path.empty()) {
        gdal::open_raster(color_path); // a missing or unreadable color raster is reported now, not at render
        info.color_source = color_path + " (resampled onto the DEM grid when loaded; not read by info)";
    } else {
        info.color_source = "elevation ramp + hillshade";
    }
    const std::string figures = "elevation range, height mapping and no-data share from ";
    if (whole)
        d.approximation = figures + "all " + std::to_string(sampled) +
                          " source samples, before the no-data filling and reprojection of a load";
    else
        d.approximation = figures + std::to_string(sampled) + " of " +
                          std::to_string((long long)info.source_cols * info.source_rows) + " source samples (" + how +
                          "); the raster is not read whole";
    return d;
}

} // namespace overflight
