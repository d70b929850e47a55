// Based on: Zamri, sec. 3 (USGS DEM ingestion); DESIGN sec. 4
// (rasters through GDAL: metric reprojection at native resolution, no-data
// filling, float/negative elevations mapped to 16 bits, color rasters warped
// onto the DEM grid, elevation ramp with hill shading otherwise).
#include "io/GdalRaster.h"

#include "core/Error.h"
#include "core/Shading.h"
#include "core/Terrain.h"
#include "io/Gdal.h"
#include "io/HeightMapping.h"
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

// Marks no-data inside our float buffers: far below any elevation on Earth,
// exactly representable, and distinct from every source's own no-data value.
constexpr float kNoData = -1.0e30f;

struct SrsCloser {
    void operator()(OGRSpatialReferenceH s) const { if (s) OSRDestroySpatialReference(s); }
};
using Srs = std::unique_ptr<void, SrsCloser>;

std::string fmt(double v, int precision = 6) {
    std::ostringstream o;
    o.precision(precision);
    o << v;
    return o.str();
}

std::string lower(std::string s) {
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

// Metres per vertical unit from GDAL's band unit type (free text in practice).
double metres_per_unit(const std::string& unit, std::string& name) {
    const std::string u = lower(unit);
    if (u.empty() || u == "m" || u == "metre" || u == "meter" || u == "metres" || u == "meters") {
        name = "metre";
        return 1.0;
    }
    if (u == "us-ft" || u == "ftus" || u == "us survey foot" || u == "us_survey_foot" || u == "foot_us" ||
        u == "us foot" || u == "survey foot") {
        name = "US survey foot";
        return 1200.0 / 3937.0;
    }
    if (u == "ft" || u == "foot" || u == "feet" || u == "international foot" || u == "intl foot") {
        name = "foot";
        return 0.3048;
    }
    if (u == "cm" || u == "centimetre" || u == "centimeter") {
        name = "centimetre";
        return 0.01;
    }
    name = unit + " (unknown, taken as metres)";
    return 1.0;
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

std::string to_wkt(OGRSpatialReferenceH srs) {
    char* wkt = nullptr;
    OSRExportToWkt(srs, &wkt);
    std::string s = wkt ? wkt : "";
    CPLFree(wkt);
    return s;
}

// The UTM zone of (lon, lat) on the datum of the geographic `src`: EPSG codes
// for WGS 84, otherwise the datum is kept so no datum shift is introduced.
Srs utm_for(OGRSpatialReferenceH src, double lon, double lat) {
    const int zone = std::clamp(int(std::floor((lon + 180.0) / 6.0)) + 1, 1, 60);
    const bool north = lat >= 0;
    Srs utm(OSRNewSpatialReference(nullptr));
    const char* code = OSRGetAuthorityCode(src, nullptr);
    const char* auth = OSRGetAuthorityName(src, nullptr);
    if (auth && code && std::string(auth) == "EPSG" && std::string(code) == "4326") {
        OSRImportFromEPSG(utm.get(), (north ? 32600 : 32700) + zone);
    } else {
        OSRCopyGeogCSFrom(utm.get(), src);
        OSRSetUTM(utm.get(), zone, north);
        const char* geog = OSRGetAttrValue(src, "GEOGCS", 0);
        const std::string name = std::string(geog ? geog : "unknown") + " / UTM zone " + std::to_string(zone) +
                                 (north ? "N" : "S");
        OSRSetProjCS(utm.get(), name.c_str());
    }
    OSRSetAxisMappingStrategy(utm.get(), OAMS_TRADITIONAL_GIS_ORDER);
    return utm;
}

// Largest side of a Terrain (2^16 + 1 samples, core/Terrain.h).
constexpr int kMaxSide = 65537;
// Peak bytes per sample while loading: float elevations, a float copy for
// no-data filling or warping, 16-bit heights, RGB colors, with slack for
// GDAL's own buffers.
constexpr double kLoadBytesPerSample = 16;

// Record A of a USGS DEM is its first 1024-byte record (Zamri, sec. 3).
std::string usgs_record_a_text(const std::string& path) {
    std::string head(1024, ' ');
    if (FILE* f = std::fopen(path.c_str(), "rb")) {
        head.resize(std::fread(head.data(), 1, head.size(), f));
        std::fclose(f);
    }
    return head;
}

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

// Fills kNoData samples by inverse-distance interpolation from valid
// neighbours (GDALFillNodata, the algorithm of gdal_fillnodata), searching as
// far as needed: voids of any size are filled, never left as spikes.
void fill_nodata(Grid& g, const std::string& subject) {
    // Its cost grows with the search distance, so first a short search (enough
    // for SRTM voids and the wedges a UTM reprojection leaves at the corners of
    // a 1-degree tile), and a search over the whole grid only if that left any.
    const int whole = std::max(g.rows, g.cols);
    for (const int distance : {std::min(256, whole), whole}) {
        gdal::Dataset ds = grid_dataset(g, subject);
        GDALRasterBandH band = GDALGetRasterBand(ds.get(), 1);
        CPLErrorReset();
        if (GDALFillNodata(band, nullptr, double(distance), 0, 0, nullptr, nullptr, nullptr) != CE_None)
            throw Error(subject, "cannot fill no-data: " + gdal::last_error("GDALFillNodata failed"));
        read_band(band, g.cols, g.rows, g.z, subject);
        if (std::find(g.z.begin(), g.z.end(), kNoData) == g.z.end() || distance == whole) break;
    }
}

struct ColorResult {
    ColorImage image;
    std::string description;
};

// Resamples the color raster onto the DEM grid (DESIGN sec. 4: `--color FILE`).
ColorResult color_on_grid(const std::string& color_path, const Grid& dem) {
    gdal::Dataset src = gdal::open_raster(color_path);
    const int bands = GDALGetRasterCount(src.get());
    std::vector<int> pick;
    int r = 0, g = 0, b = 0;
    for (int k = 1; k <= bands; ++k) {
        const GDALColorInterp ci = GDALGetRasterColorInterpretation(GDALGetRasterBand(src.get(), k));
        if (ci == GCI_RedBand && !r) r = k;
        if (ci == GCI_GreenBand && !g) g = k;
        if (ci == GCI_BlueBand && !b) b = k;
    }
    std::string bands_used;
    std::vector<std::string> opts;
    GDALRasterBandH first = GDALGetRasterBand(src.get(), 1);
    const bool palette = bands == 1 && GDALGetRasterColorTable(first) != nullptr;
    if (r && g && b) {
        pick = {r, g, b};
        bands_used = "RGB bands";
    } else if (bands >= 6) {
        pick = {3, 2, 1}; // Landsat TM/ETM+: bands 3, 2, 1 are red, green, blue
        bands_used = "bands 3,2,1";
    } else if (bands >= 3) {
        pick = {1, 2, 3};
        bands_used = "bands 1,2,3";
    } else if (palette) {
        pick = {1};
        opts = {"-expand", "rgb"};
        bands_used = "palette";
    } else {
        pick = {1};
        bands_used = "band 1 as grey";
    }
    for (int k : pick) {
        opts.push_back("-b");
        opts.push_back(std::to_string(k));
    }
    bool rescaled = false;
    if (GDALGetRasterDataType(GDALGetRasterBand(src.get(), pick[0])) != GDT_Byte) {
        // Each band stretched from its own min..max: a 16-bit orthophoto or a
        // reflectance raster would otherwise be black or clipped.
        opts.insert(opts.end(), {"-ot", "Byte", "-scale"});
        rescaled = true;
    }
    double cgt[6];
    const bool color_geo = GDALGetGeoTransform(src.get(), cgt) == CE_None && GDALGetSpatialRef(src.get()) != nullptr;
    const bool warp = color_geo && dem.georeferenced && !dem.wkt.empty();
    if (!warp) {
        opts.insert(opts.end(), {"-outsize", std::to_string(dem.cols), std::to_string(dem.rows), "-r", "bilinear"});
    }
    gdal::Dataset picked = gdal::translate(src.get(), opts, color_path);
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
                             "-r", method},
                            color_path);
        how = std::string("warped onto the DEM grid (") + method + ")";
    }
    const int out_bands = GDALGetRasterCount(picked.get());
    std::vector<std::uint8_t> channel(std::size_t(dem.rows) * std::size_t(dem.cols));
    ColorResult result;
    result.image.resize(dem.cols, dem.rows);
    bool any = false;
    for (int c = 0; c < 3; ++c) {
        GDALRasterBandH band = GDALGetRasterBand(picked.get(), std::min(c + 1, out_bands));
        CPLErrorReset();
        if (GDALRasterIO(band, GF_Read, 0, 0, dem.cols, dem.rows, channel.data(), dem.cols, dem.rows, GDT_Byte, 0, 0) !=
            CE_None)
            throw Error(color_path, "unreadable raster: " + gdal::last_error("read failed"));
        for (std::size_t i = 0; i < channel.size(); ++i) {
            (&result.image.pixels[i].r)[c] = channel[i];
            any = any || channel[i] != 0;
        }
    }
    if (!any) throw Error(color_path, "color raster is entirely black on the terrain (does it overlap the DEM?)");
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

// The sizes a raster declares, checked before anything is allocated from them:
// a few bytes of header can claim billions of samples (a sparse GeoTIFF, a
// USGS Record A with a false profile count).
void check_declared_size(GDALDatasetH ds, const std::string& path, const std::string& driver) {
    if (driver == "USGSDEM") {
        // GDAL sizes the grid by Record A's profile count; each profile needs a
        // Record B in the file (USGS DEM Standards Part 2).
        const long profiles = usgs_profile_count(usgs_record_a_text(path));
        std::error_code ec;
        const auto bytes = std::filesystem::file_size(path, ec);
        if (profiles > kMaxSide)
            throw Error(path, "Record A declares " + std::to_string(profiles) + " profiles, more than " +
                                  std::to_string(kMaxSide));
        if (!ec && profiles > 0 && (long long)bytes < usgs_minimum_file_size(profiles))
            throw Error(path, "Record A declares " + std::to_string(profiles) + " profiles but the file holds only " +
                                  std::to_string(bytes) + " bytes (at least " +
                                  std::to_string(kUsgsRecordBHeaderBytes) + " per profile)");
    }
    const int cols = GDALGetRasterXSize(ds), rows = GDALGetRasterYSize(ds);
    if (rows < 2 || cols < 2)
        throw Error(path, "raster is " + std::to_string(cols) + "x" + std::to_string(rows) +
                              ", a terrain needs at least 2x2 samples");
    if (rows > kMaxSide || cols > kMaxSide)
        throw Error(path, "raster is " + std::to_string(cols) + "x" + std::to_string(rows) + ", more than " +
                              std::to_string(kMaxSide) + " samples per side");
    // Loading holds the elevations as floats, a float copy for GDAL's no-data
    // filling or warping, and the terrain's 16-bit heights and RGB colors.
    const double needed = double(rows) * double(cols) * kLoadBytesPerSample;
    const double memory = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
    if (memory > 0 && needed > memory)
        throw Error(path, "raster is " + std::to_string(cols) + "x" + std::to_string(rows) + ", loading it needs about " +
                              fmt(needed / 1073741824.0, 3) + " GiB, more than this machine's " +
                              fmt(memory / 1073741824.0, 3) + " GiB of memory");
}

// What a user should know about the bands: only band 1 is read as heights.
void warn_about_bands(GDALDatasetH ds, TerrainInfo& info) {
    const int bands = GDALGetRasterCount(ds);
    GDALRasterBandH first = GDALGetRasterBand(ds, 1);
    const GDALColorInterp ci = GDALGetRasterColorInterpretation(first);
    if (GDALGetRasterColorTable(first) != nullptr)
        info.warnings.push_back("band 1 is a palette image: its color indices are taken as heights");
    else if (bands > 1)
        info.warnings.push_back(
            "has " + std::to_string(bands) + " bands; band 1 (" + lower(GDALGetColorInterpretationName(ci)) +
            ") is taken as heights" +
            (ci == GCI_RedBand ? " (an RGB image? give heights as TERRAIN and the image as --color)" : ""));
}

// Converts band 1's values in `grid` to metres (band scale/offset, then the
// unit type) and marks no-data as kNoData. Returns the number of no-data
// samples; `integral` tells whether every valid value is whole metres.
long long heights_to_metres(Grid& grid, GDALDatasetH src_ds, const std::string& path, TerrainInfo& info,
                            bool& integral) {
    GDALRasterBandH band = GDALGetRasterBand(src_ds, 1);
    int has_nodata = 0;
    const double nodata = GDALGetRasterNoDataValue(band, &has_nodata);
    int has_scale = 0, has_offset = 0;
    double scale = GDALGetRasterScale(band, &has_scale), offset = GDALGetRasterOffset(band, &has_offset);
    if (!has_scale || scale == 0) scale = 1;
    if (!has_offset) offset = 0;
    const char* unit = GDALGetRasterUnitType(band);
    info.unit_to_metre = metres_per_unit(unit ? unit : "", info.vertical_units);
    long long voids = 0;
    integral = true; // whole metres in the source: kept exact (v_scale = 1) when not resampled
    for (std::size_t i = 0; i < grid.z.size(); ++i) {
        float& v = grid.z[i];
        const bool missing = !std::isfinite(v) || (has_nodata && (double(v) == nodata || float(nodata) == v));
        if (missing) {
            v = kNoData;
            ++voids;
            continue;
        }
        // Rejected here, naming the file: such a value would otherwise become
        // an infinite elevation range that later steps blame on something else.
        const double metres = (double(v) * scale + offset) * info.unit_to_metre;
        if (const std::string problem = elevation_problem(metres); !problem.empty())
            throw Error(path, "row " + std::to_string(i / std::size_t(grid.cols)) + ", column " +
                                  std::to_string(i % std::size_t(grid.cols)) + ": " + problem +
                                  " (not a terrain height; is the no-data value set?)");
        v = float(metres);
        integral = integral && v == std::round(v);
    }
    return voids;
}

// Warps `grid` to square metric cells when its CRS is geographic or its cells
// are rotated or not square (DESIGN sec. 4); returns the cell size in metres.
double to_square_metric_cells(Grid& grid, GDALDatasetH src_ds, const std::string& path, TerrainInfo& info) {
    const bool real_gt = grid.georeferenced &&
                         !(grid.gt[0] == 0 && grid.gt[1] == 1 && grid.gt[2] == 0 && grid.gt[3] == 0 &&
                           grid.gt[4] == 0 && grid.gt[5] == 1);
    grid.georeferenced = real_gt;
    OGRSpatialReferenceH srs = GDALGetSpatialRef(src_ds);
    if (!real_gt) srs = nullptr; // a CRS without a geotransform places nothing
    info.source_crs = srs_name(srs);
    info.crs = info.source_crs;
    double hs = 1.0;
    std::vector<std::string> warp_opts;
    if (srs && OSRIsGeographic(srs)) {
        const double lon = grid.gt[0] + grid.gt[1] * grid.cols * 0.5 + grid.gt[2] * grid.rows * 0.5;
        const double lat = grid.gt[3] + grid.gt[4] * grid.cols * 0.5 + grid.gt[5] * grid.rows * 0.5;
        Srs utm = utm_for(srs, lon, lat);
        // No -tr: gdalwarp's suggested output keeps the source's sample count
        // along the diagonal with square cells, i.e. its native resolution.
        warp_opts = {"-t_srs", to_wkt(utm.get())};
        info.crs = srs_name(utm.get());
    } else if (real_gt) {
        const double px = std::hypot(grid.gt[1], grid.gt[4]), py = std::hypot(grid.gt[2], grid.gt[5]);
        const bool rotated = grid.gt[2] != 0 || grid.gt[4] != 0;
        if (rotated || std::abs(px - py) > 1e-6 * std::max(px, py)) {
            const double res = std::min(px, py); // the finer spacing: no detail is lost
            warp_opts = {"-tr", fmt(res, 17), fmt(res, 17)};
        }
        hs = px;
    }
    if (!warp_opts.empty()) {
        warp_opts.insert(warp_opts.end(), {"-r", "bilinear", "-srcnodata", fmt(kNoData, 9), "-dstnodata",
                                           fmt(kNoData, 9), "-ot", "Float32", "-wo", "INIT_DEST=NO_DATA"});
        gdal::Dataset source = grid_dataset(grid, path);
        gdal::Dataset warped = gdal::warp(source.get(), warp_opts, path);
        grid = grid_of(warped.get(), path);
        grid.georeferenced = true;
        hs = std::abs(grid.gt[1]);
        info.reprojected = true;
        info.reprojection = (info.source_crs.empty() ? std::string("no CRS") : info.source_crs) + " -> " + info.crs +
                            ", bilinear, square cells of " + fmt(hs, 6) + " (was " + std::to_string(info.source_cols) +
                            "x" + std::to_string(info.source_rows) + " cells)";
    }
    if (srs) {
        // Projected CRSs in feet: world units are metres (DESIGN sec. 4).
        OGRSpatialReferenceH target = srs;
        Srs parsed;
        if (info.reprojected) {
            parsed.reset(OSRNewSpatialReference(grid.wkt.c_str()));
            target = parsed.get();
        }
        if (target && OSRIsProjected(target)) hs *= OSRGetLinearUnits(target, nullptr);
    }
    return hs;
}

// Fills the no-data samples from their valid neighbours (the rest: the lowest
// valid elevation, never a spike), recording what was done in `info`.
void fill_voids(Grid& grid, const std::string& path, TerrainInfo& info, long long source_voids,
                     bool& integral) {
    long long missing = 0;
    for (float v : grid.z) missing += v == kNoData;
    if (missing == (long long)grid.z.size()) throw Error(path, "raster is entirely no-data");
    if (missing > 0) {
        fill_nodata(grid, path);
        // Whatever the search could not reach keeps the lowest valid elevation, never a spike.
        float lowest = std::numeric_limits<float>::max();
        for (float v : grid.z)
            if (v != kNoData) lowest = std::min(lowest, v);
        for (float& v : grid.z)
            if (v == kNoData) v = lowest;
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
                     const std::string& color_path) {
    DataSet data;
    TerrainInfo& info = data.info;
    info.source = path;
    info.kind = "gdal";
    info.driver = driver_name;
    warn_about_bands(src_ds, info);
    Grid grid = grid_of(src_ds, path);
    info.source_rows = grid.rows;
    info.source_cols = grid.cols;

    bool integral = true;
    const long long voids = heights_to_metres(grid, src_ds, path, info, integral);
    if (voids == (long long)grid.z.size()) throw Error(path, "raster is entirely no-data");
    info.metadata = metadata_of(src_ds, path, info.driver);

    const double hs = to_square_metric_cells(grid, src_ds, path, info);
    if (const std::string problem = horizontal_scale_problem(grid.rows, grid.cols, hs); !problem.empty())
        throw Error(path, "pixel size: " + problem);

    fill_voids(grid, path, info, voids, integral);

    float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
    for (float v : grid.z) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    const HeightMapping mapping = choose_height_mapping(lo, hi, integral);
    data.terrain = Terrain(grid.rows, grid.cols, float(hs), mapping.v_scale, mapping.y_offset);
    info.georeferenced = grid.georeferenced;
    if (grid.georeferenced) {
        std::copy(grid.gt, grid.gt + 6, info.geotransform.begin());
        info.crs_wkt = grid.wkt;
    }
    quantise_heights(grid.z, mapping, data.terrain.heights());

    if (!color_path.empty()) {
        ColorResult color = color_on_grid(color_path, grid);
        data.terrain.colors() = std::move(color.image.pixels);
        info.color_source = color.description;
    } else {
        shade_by_elevation(data.terrain, 0.0f);
        info.color_source = "elevation ramp + hillshade";
    }
    return data;
}

} // namespace

DataSet load_gdal_raster(const std::string& path, const std::string& color_path) {
    gdal::Dataset src = gdal::open_raster(path);
    GDALDriverH driver = GDALGetDatasetDriver(src.get());
    const std::string driver_name = driver ? GDALGetDriverShortName(driver) : "?";
    check_declared_size(src.get(), path, driver_name);
    try {
        return load_checked(src.get(), path, driver_name, color_path);
    } catch (const std::bad_alloc&) {
        // Sizes were checked against the machine's memory, not against a
        // process limit (ulimit -v) or what other programs hold.
        throw Error(path, "not enough memory to load a " + std::to_string(GDALGetRasterXSize(src.get())) + "x" +
                              std::to_string(GDALGetRasterYSize(src.get())) + " raster");
    }
}

} // namespace overflight
