// Based on: Zamri, seed 001, "Data tiling" (2^n+1 padding, overlapping
// 2^k+1 tiles, existence flags, one file per tile). GDAL writes the GeoTIFFs.
#include "io/TileDirectory.h"

#include "core/Error.h"
#include "io/Files.h"
#include "io/Gdal.h"

#include <cpl_conv.h>
#include <cpl_string.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace overflight {

namespace {

enum class TileFile { Heights, Colors, Apron, D2 };

std::string tile_name(int r, int c, TileFile f) {
    static const char* suffix[] = {".tif", "_rgb.tif", "_apron.tif", "_d2.tif"};
    return "r" + std::to_string(r) + "_c" + std::to_string(c) + suffix[int(f)];
}

std::string tile_path(const std::string& dir, int r, int c, TileFile f) {
    return (fs::path(dir) / tile_name(r, c, f)).string();
}

const char* const kOverviewHeights = "overview.tif";
const char* const kOverviewColors = "overview_rgb.tif";
// Röttger's C the stored d2 is computed for: TileSet's default.
const double kD2MinResolution = 4.0;

std::array<double, 6> tile_geotransform(const TileIndex& ix, int r, int c) {
    std::array<double, 6> gt = ix.geotransform;
    const double col0 = double(c) * ix.grid.stride(), row0 = double(r) * ix.grid.stride();
    gt[0] = ix.geotransform[0] + col0 * ix.geotransform[1] + row0 * ix.geotransform[2];
    gt[3] = ix.geotransform[3] + col0 * ix.geotransform[4] + row0 * ix.geotransform[5];
    return gt;
}

json index_to_json(const TileIndex& ix) {
    const TileGrid& g = ix.grid;
    json exists = json::array(), lo = json::array(), hi = json::array();
    json roughness = g.roughness.empty() ? json(nullptr) : json::array();
    for (int r = 0; r < g.tile_rows; ++r) {
        if (!g.roughness.empty()) {
            json rr = json::array();
            for (int c = 0; c < g.tile_cols; ++c) rr.push_back(g.roughness[g.index(r, c)]);
            roughness.push_back(rr);
        }
        json er = json::array(), lr = json::array(), hr = json::array();
        for (int c = 0; c < g.tile_cols; ++c) {
            er.push_back(int(g.exists[g.index(r, c)]));
            lr.push_back(g.min_height[g.index(r, c)]);
            hr.push_back(g.max_height[g.index(r, c)]);
        }
        exists.push_back(er);
        lo.push_back(lr);
        hi.push_back(hr);
    }
    return json{{"format", "overflight-tiles"},
                {"version", 1},
                {"complete", ix.complete},
                {"source", ix.source},
                {"checksum", ix.checksum},
                {"tile_size", g.tile_size},
                {"tile_rows", g.tile_rows},
                {"tile_cols", g.tile_cols},
                {"exists", exists},
                {"min_height", lo},
                {"max_height", hi},
                {"source_rows", g.source_rows},
                {"source_cols", g.source_cols},
                {"padded_size", ix.padded_size},
                {"h_scale", g.h_scale},
                {"height_mapping", {{"v_scale", g.v_scale}, {"y_offset", g.y_offset}, {"units", "metre"}}},
                {"georeferenced", ix.georeferenced},
                {"geotransform", ix.geotransform},
                {"crs", ix.crs_wkt},
                {"apron", ix.apron},
                {"levels", ix.levels},
                {"roughness", roughness},
                {"d2_min_resolution", g.d2_min_resolution},
                {"overview", ix.overview_stride > 1 ? json{{"stride", ix.overview_stride},
                                                            {"rows", ix.overview_rows},
                                                            {"cols", ix.overview_cols},
                                                            {"heights", kOverviewHeights},
                                                            {"colors", kOverviewColors}}
                                                      : json(nullptr)}};
}

void write_index(const std::string& dir, const TileIndex& ix) {
    const std::string path = (fs::path(dir) / "index.json").string();
    write_atomically(path, [&](const std::string& tmp) {
        std::ofstream f(tmp);
        f << index_to_json(ix).dump(1) << "\n";
        if (!f) throw Error(path, "cannot write");
    });
}

// One GeoTIFF written atomically: `bands` planes of cols x rows samples of
// `type` (band b at data + b * plane bytes), with a geotransform and CRS when
// `gt` is given, and for heights the index's metre mapping as band
// scale/offset so that GIS tools read metres.
struct RasterSpec {
    int cols = 0, rows = 0, bands = 1;
    GDALDataType type = GDT_UInt16;
    const void* data = nullptr;
    const std::array<double, 6>* gt = nullptr;
    std::string wkt;
    const TileGrid* height_mapping = nullptr;
    bool rgb = false;
    int levels = 0; // GeoTIFF overviews holding every 2^m-th sample, m = 1 .. levels
};

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
    const int bytes = GDALGetDataTypeSizeBytes(spec.type);
    const std::size_t plane = std::size_t(spec.cols) * std::size_t(spec.rows) * std::size_t(bytes);
    for (int b = 0; b < spec.bands; ++b) {
        GDALRasterBandH band = GDALGetRasterBand(ds, b + 1);
        const auto* src = static_cast<const unsigned char*>(spec.data) + std::size_t(b) * plane;
        for (const int f : factors) {
            const int cols = (spec.cols - 1) / f + 1, rows = (spec.rows - 1) / f + 1;
            GDALRasterBandH ov = nullptr;
            for (int o = 0; o < GDALGetOverviewCount(band) && !ov; ++o) {
                GDALRasterBandH cand = GDALGetOverview(band, o);
                if (GDALGetRasterBandXSize(cand) == cols && GDALGetRasterBandYSize(cand) == rows) ov = cand;
            }
            if (!ov) throw Error(path, "GDAL did not create a " + std::to_string(cols) + "x" + std::to_string(rows) + " level");
            std::vector<unsigned char> dec(std::size_t(cols) * std::size_t(rows) * std::size_t(bytes));
            for (int i = 0; i < rows; ++i)
                for (int j = 0; j < cols; ++j)
                    std::copy_n(src + (std::size_t(i) * f * std::size_t(spec.cols) + std::size_t(j) * f) * bytes, bytes,
                                dec.data() + (std::size_t(i) * std::size_t(cols) + std::size_t(j)) * bytes);
            if (GDALRasterIO(ov, GF_Write, 0, 0, cols, rows, dec.data(), cols, rows, spec.type, 0, 0) != CE_None)
                throw Error(path, "cannot write a reduced level: " + gdal::last_error("I/O error"));
        }
    }
}

void write_raster(const std::string& path, const RasterSpec& spec) {
    GDALDriverH gtiff = GDALGetDriverByName("GTiff");
    char** co = nullptr;
    co = CSLSetNameValue(co, "COMPRESS", "DEFLATE");
    co = CSLSetNameValue(co, "PREDICTOR", spec.type == GDT_Float32 ? "3" : "2");
    struct OptionsFree {
        char** p;
        ~OptionsFree() { CSLDestroy(p); }
    } co_free{co};
    write_atomically(path, [&](const std::string& tmp) {
        gdal::Dataset ds(GDALCreate(gtiff, tmp.c_str(), spec.cols, spec.rows, spec.bands, spec.type, co));
        if (!ds) throw Error(path, "cannot create: " + gdal::last_error("GTiff"));
        if (spec.gt) {
            double g[6];
            std::copy(spec.gt->begin(), spec.gt->end(), g);
            GDALSetGeoTransform(ds.get(), g);
            if (!spec.wkt.empty()) GDALSetProjection(ds.get(), spec.wkt.c_str());
        }
        const std::size_t plane =
            std::size_t(spec.cols) * std::size_t(spec.rows) * std::size_t(GDALGetDataTypeSizeBytes(spec.type));
        for (int b = 0; b < spec.bands; ++b) {
            GDALRasterBandH h = GDALGetRasterBand(ds.get(), b + 1);
            if (spec.rgb)
                GDALSetRasterColorInterpretation(h, b == 0 ? GCI_RedBand : b == 1 ? GCI_GreenBand : GCI_BlueBand);
            if (spec.height_mapping) {
                GDALSetRasterScale(h, spec.height_mapping->v_scale);
                GDALSetRasterOffset(h, spec.height_mapping->y_offset);
                GDALSetRasterUnitType(h, "metre");
            }
            auto* p = const_cast<unsigned char*>(static_cast<const unsigned char*>(spec.data)) + std::size_t(b) * plane;
            if (GDALRasterIO(h, GF_Write, 0, 0, spec.cols, spec.rows, p, spec.cols, spec.rows, spec.type, 0, 0) !=
                CE_None)
                throw Error(path, "cannot write: " + gdal::last_error("I/O error"));
        }
        if (spec.levels > 0) write_levels(ds.get(), path, spec);
        // Closing flushes the file: a failure there (disk full) must not pass.
        CPLErrorReset();
        GDALClose(ds.release());
        if (CPLGetLastErrorType() == CE_Failure || CPLGetLastErrorType() == CE_Fatal)
            throw Error(path, "cannot write: " + gdal::last_error("close failed"));
    });
}

// Colors as three planes (red, green, blue), the layout write_raster takes.
std::vector<std::uint8_t> color_planes(const Terrain& t) {
    const std::size_t n = t.colors().size();
    std::vector<std::uint8_t> planes(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
        planes[i] = t.colors()[i].r;
        planes[n + i] = t.colors()[i].g;
        planes[2 * n + i] = t.colors()[i].b;
    }
    return planes;
}

// Writes the colors, then the apron, then the heights: the heights file
// appearing under its final name marks a finished tile.
void write_tile_files(const std::string& dir, const TileIndex& ix, int r, int c, const TileSamples& t,
                      const TileApron& apron) {
    const int n = ix.grid.tile_size;
    const auto gt = tile_geotransform(ix, r, c);
    const std::vector<std::uint8_t> rgb = color_planes(t.samples);
    write_raster(tile_path(dir, r, c, TileFile::Colors),
                 {n, n, 3, GDT_Byte, rgb.data(), &gt, ix.crs_wkt, nullptr, true, ix.levels});
    std::vector<std::uint16_t> sides;
    for (const auto* side : {&apron.north, &apron.south, &apron.west, &apron.east})
        sides.insert(sides.end(), side->begin(), side->end());
    write_raster(tile_path(dir, r, c, TileFile::Apron), {n, 4, 1, GDT_UInt16, sides.data(), nullptr, "", nullptr, false});
    if (ix.levels > 0) {
        // The full tile's d2 at its even samples (the centres of all nodes a
        // level >= 1 keeps), with levels of every 2^m-th of them: level m of
        // the tile reads level m - 1 of this file.
        const std::vector<float> d2 = rottger_d2(t.samples, ix.grid.d2_min_resolution);
        const int h = (n - 1) / 2 + 1;
        std::vector<float> even(std::size_t(h) * std::size_t(h));
        for (int i = 0; i < h; ++i)
            for (int j = 0; j < h; ++j) even[std::size_t(i) * std::size_t(h) + std::size_t(j)] = d2[t.samples.index(2 * i, 2 * j)];
        write_raster(tile_path(dir, r, c, TileFile::D2),
                     {h, h, 1, GDT_Float32, even.data(), nullptr, "", nullptr, false, ix.levels - 1});
    }
    write_raster(tile_path(dir, r, c, TileFile::Heights),
                 {n, n, 1, GDT_UInt16, t.samples.heights().data(), &gt, ix.crs_wkt, &ix.grid, false, ix.levels});
}

// Every f-th sample of `t` (clamped to its last row and column, with the
// padding's darkened colors there, as cut_tile does).
Terrain decimate(const Terrain& t, int f, int rows, int cols) {
    Terrain o(rows, cols, t.h_scale() * float(f), t.v_scale(), t.y_offset());
    for (int i = 0; i < rows; ++i) {
        const int gi = i * f, si = std::min(gi, t.rows() - 1);
        for (int j = 0; j < cols; ++j) {
            const int gj = j * f, sj = std::min(gj, t.cols() - 1);
            o.raw(i, j) = t.raw(si, sj);
            Rgb8 col = t.color(si, sj);
            if (si != gi || sj != gj) col = Rgb8{std::uint8_t(col.r / 2), std::uint8_t(col.g / 2), std::uint8_t(col.b / 2)};
            o.color(i, j) = col;
        }
    }
    return o;
}

std::array<double, 6> scaled_geotransform(const std::array<double, 6>& gt, int f) {
    return {gt[0], gt[1] * f, gt[2] * f, gt[3], gt[4] * f, gt[5] * f};
}

void write_overview(const std::string& dir, const TileIndex& ix, const Terrain& t) {
    const Terrain o = decimate(t, ix.overview_stride, ix.overview_rows, ix.overview_cols);
    const auto gt = scaled_geotransform(ix.geotransform, ix.overview_stride);
    const std::vector<std::uint8_t> rgb = color_planes(o);
    write_raster((fs::path(dir) / kOverviewColors).string(),
                 {o.cols(), o.rows(), 3, GDT_Byte, rgb.data(), &gt, ix.crs_wkt, nullptr, true});
    write_raster((fs::path(dir) / kOverviewHeights).string(),
                 {o.cols(), o.rows(), 1, GDT_UInt16, o.heights().data(), &gt, ix.crs_wkt, &ix.grid, false});
}

// Reads `bands` planes of cols x rows samples of `type` from `path` into
// `out`; with reduce > 1, from the overview of the full raster written by
// write_levels() that holds every reduce-th sample (cols x rows is its size).
void read_raster(const std::string& path, int cols, int rows, int bands, GDALDataType type, void* out, int reduce = 1) {
    gdal::Dataset ds = gdal::open_raster(path);
    const int full_cols = (cols - 1) * reduce + 1, full_rows = (rows - 1) * reduce + 1;
    if (GDALGetRasterXSize(ds.get()) != full_cols || GDALGetRasterYSize(ds.get()) != full_rows ||
        GDALGetRasterCount(ds.get()) != bands)
        throw Error(path, "expected " + std::to_string(bands) + " band(s) of " + std::to_string(full_cols) + "x" +
                              std::to_string(full_rows) + " samples");
    const std::size_t plane = std::size_t(cols) * std::size_t(rows) * std::size_t(GDALGetDataTypeSizeBytes(type));
    for (int b = 0; b < bands; ++b) {
        GDALRasterBandH band = GDALGetRasterBand(ds.get(), b + 1);
        if (reduce > 1) {
            GDALRasterBandH level = nullptr;
            for (int o = 0; o < GDALGetOverviewCount(band) && !level; ++o) {
                GDALRasterBandH cand = GDALGetOverview(band, o);
                if (GDALGetRasterBandXSize(cand) == cols && GDALGetRasterBandYSize(cand) == rows) level = cand;
            }
            if (!level) throw Error(path, "has no level of every " + std::to_string(reduce) + "th sample; run `overflight tile` again");
            band = level;
        }
        if (GDALRasterIO(band, GF_Read, 0, 0, cols, rows, static_cast<unsigned char*>(out) + std::size_t(b) * plane, cols,
                         rows, type, 0, 0) != CE_None)
            throw Error(path, "cannot read: " + gdal::last_error("I/O error"));
    }
}

void read_colors(const std::string& path, Terrain& t, int reduce = 1) {
    const std::size_t n = t.colors().size();
    std::vector<std::uint8_t> planes(3 * n);
    read_raster(path, t.cols(), t.rows(), 3, GDT_Byte, planes.data(), reduce);
    for (std::size_t i = 0; i < n; ++i) t.colors()[i] = Rgb8{planes[i], planes[n + i], planes[2 * n + i]};
}

TileIndex parse_index(const std::string& path, bool require_complete) {
    std::ifstream f(path);
    if (!f) throw Error(path, "missing (not a tile directory)");
    json j;
    try {
        j = json::parse(f);
    } catch (const std::exception& e) {
        throw Error(path, std::string("malformed JSON: ") + e.what());
    }
    TileIndex ix;
    try {
        if (j.at("format").get<std::string>() != "overflight-tiles") throw Error(path, "not an overflight tile index");
        if (j.at("version").get<int>() != 1) throw Error(path, "unsupported version");
        ix.complete = j.at("complete").get<bool>();
        ix.source = j.value("source", "");
        ix.checksum = j.at("checksum").get<std::string>();
        TileGrid& g = ix.grid;
        g.tile_size = j.at("tile_size").get<int>();
        g.tile_rows = j.at("tile_rows").get<int>();
        g.tile_cols = j.at("tile_cols").get<int>();
        g.h_scale = j.at("h_scale").get<float>();
        g.v_scale = j.at("height_mapping").at("v_scale").get<float>();
        g.y_offset = j.at("height_mapping").at("y_offset").get<float>();
        g.source_rows = j.at("source_rows").get<int>();
        g.source_cols = j.at("source_cols").get<int>();
        ix.padded_size = j.at("padded_size").get<int>();
        ix.georeferenced = j.at("georeferenced").get<bool>();
        ix.geotransform = j.at("geotransform").get<std::array<double, 6>>();
        ix.crs_wkt = j.at("crs").get<std::string>();
        // Written by later versions of the tiler; absent means none.
        ix.apron = j.value("apron", false);
        ix.levels = j.value("levels", 0);
        g.d2_min_resolution = j.value("d2_min_resolution", 0.0);
        if (j.contains("overview") && !j.at("overview").is_null()) {
            const auto& o = j.at("overview");
            ix.overview_stride = o.at("stride").get<int>();
            ix.overview_rows = o.at("rows").get<int>();
            ix.overview_cols = o.at("cols").get<int>();
        }
        const auto& ex = j.at("exists");
        const auto& lo = j.at("min_height");
        const auto& hi = j.at("max_height");
        if (g.tile_rows < 1 || g.tile_cols < 1 || g.tile_rows > 65536 || g.tile_cols > 65536 || int(ex.size()) != g.tile_rows ||
            int(lo.size()) != g.tile_rows || int(hi.size()) != g.tile_rows)
            throw Error(path, "tile grid does not match tile_rows x tile_cols");
        for (int r = 0; r < g.tile_rows; ++r) {
            if (int(ex[std::size_t(r)].size()) != g.tile_cols || int(lo[std::size_t(r)].size()) != g.tile_cols ||
                int(hi[std::size_t(r)].size()) != g.tile_cols)
                throw Error(path, "tile grid does not match tile_rows x tile_cols");
            for (int c = 0; c < g.tile_cols; ++c) {
                g.exists.push_back(std::uint8_t(ex[std::size_t(r)][std::size_t(c)].get<int>() != 0));
                g.min_height.push_back(lo[std::size_t(r)][std::size_t(c)].get<float>());
                g.max_height.push_back(hi[std::size_t(r)][std::size_t(c)].get<float>());
            }
        }
        // Roughness is written with the finished index; without it (older
        // directories, an unfinished run) tiles load at full resolution.
        if (ix.levels > 0 && j.contains("roughness") && !j.at("roughness").is_null()) {
            const auto& ro = j.at("roughness");
            if (int(ro.size()) != g.tile_rows) throw Error(path, "roughness does not match tile_rows x tile_cols");
            for (int r = 0; r < g.tile_rows; ++r) {
                if (int(ro[std::size_t(r)].size()) != g.tile_cols)
                    throw Error(path, "roughness does not match tile_rows x tile_cols");
                for (int c = 0; c < g.tile_cols; ++c)
                    g.roughness.push_back(ro[std::size_t(r)][std::size_t(c)].get<std::vector<float>>());
            }
            g.max_level = ix.levels;
        }
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(path, std::string("malformed index: ") + e.what());
    }
    if (ix.levels < 0 || ix.levels > 30) throw Error(path, "levels out of range");
    if (ix.grid.d2_min_resolution != 0 && !(ix.grid.d2_min_resolution > 1))
        throw Error(path, "d2_min_resolution must be 0 or greater than 1");
    ix.grid.validate(path);
    if (ix.padded_size != ix.grid.padded_rows() || ix.padded_size != ix.grid.padded_cols())
        throw Error(path, "source and padded sizes do not match the tile grid");
    if (ix.overview_stride != 0) {
        const int k = ix.overview_stride;
        if (k < 2 || k > 65536 || (k & (k - 1)) != 0 ||
            ix.overview_rows != (ix.grid.source_rows - 2) / k + 2 || ix.overview_cols != (ix.grid.source_cols - 2) / k + 2)
            throw Error(path, "overview stride and size do not match the source");
    }
    if (require_complete && !ix.complete)
        throw Error(path, "tiling did not finish (interrupted?); run `overflight tile` again to complete it");
    return ix;
}

} // namespace

std::string terrain_checksum(const Terrain& t) {
    std::uint64_t h = 1469598103934665603ull;
    auto mix = [&](const void* p, std::size_t n) {
        const auto* b = static_cast<const unsigned char*>(p);
        for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
    };
    const int rows = t.rows(), cols = t.cols();
    const float s[3] = {t.h_scale(), t.v_scale(), t.y_offset()};
    mix(&rows, sizeof rows);
    mix(&cols, sizeof cols);
    mix(s, sizeof s);
    mix(t.heights().data(), t.heights().size() * sizeof(std::uint16_t));
    mix(t.colors().data(), t.colors().size() * sizeof(Rgb8));
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
}

int overview_stride(int rows, int cols, int max_side) {
    if (max_side < 2) throw Error("overview", "at least 2 samples per side are needed");
    const int n = std::max(rows, cols);
    int f = 1;
    while ((n - 2) / f + 2 > max_side) f *= 2;
    return f;
}

TileWriteReport write_tile_directory(const DataSet& data, const std::string& dir, const TileWriteOptions& options) {
    gdal::ensure_initialised();
    const Terrain& t = data.terrain;
    TileWriteReport report;
    TileIndex& ix = report.index;
    ix.grid = terrain_tile_grid(t, options.tile_size);
    ix.padded_size = ix.grid.padded_rows();
    ix.source = data.info.source;
    ix.checksum = terrain_checksum(t);
    ix.georeferenced = data.info.georeferenced;
    ix.crs_wkt = data.info.georeferenced ? data.info.crs_wkt : std::string();
    if (data.info.georeferenced) {
        ix.geotransform = data.info.geotransform;
    } else {
        // Local frame: pixel (j, i) centre at X = hs j, Y = -hs i (north up).
        const double hs = t.h_scale();
        ix.geotransform = {-0.5 * hs, hs, 0, 0.5 * hs, 0, -hs};
    }
    ix.apron = true;
    ix.levels = ix.grid.coarsest_level();
    ix.grid.d2_min_resolution = ix.levels > 0 ? kD2MinResolution : 0.0;
    const int f = overview_stride(t.rows(), t.cols(), options.overview_max_side);
    if (f > 1) {
        ix.overview_stride = f;
        ix.overview_rows = (t.rows() - 2) / f + 2;
        ix.overview_cols = (t.cols() - 2) / f + 2;
    }

    std::error_code ec;
    fs::create_directories(dir, ec);
    if (!fs::is_directory(dir)) throw Error(dir, "cannot create the output folder");
    // Temporary files of a run that was killed cannot have cleaned up after themselves.
    for (const auto& e : fs::directory_iterator(dir, ec)) {
        const std::string name = e.path().filename().string();
        if (name.size() > 1 && name[0] == '.' && name.find(".tmp") != std::string::npos &&
            (name.rfind(".r", 0) == 0 || name.rfind(".index.json", 0) == 0 || name.rfind(".overview", 0) == 0))
            fs::remove(e.path(), ec);
    }
    // Resume only a run of the same source, tile size and layout; otherwise start over.
    bool resume = false;
    const std::string index_path = (fs::path(dir) / "index.json").string();
    if (fs::exists(index_path)) {
        try {
            const TileIndex old = parse_index(index_path, false);
            resume = old.checksum == ix.checksum && old.grid.tile_size == ix.grid.tile_size &&
                     old.geotransform == ix.geotransform && old.crs_wkt == ix.crs_wkt && old.apron &&
                     old.overview_stride == ix.overview_stride && old.levels == ix.levels &&
                     old.grid.d2_min_resolution == ix.grid.d2_min_resolution;
        } catch (const Error&) {
            resume = false;
        }
    }
    ix.complete = false;
    write_index(dir, ix);

    const fs::path ov_heights = fs::path(dir) / kOverviewHeights, ov_colors = fs::path(dir) / kOverviewColors;
    if (f == 1) {
        fs::remove(ov_heights, ec); // left over from a larger source
        fs::remove(ov_colors, ec);
    } else if (!(resume && fs::exists(ov_heights) && fs::exists(ov_colors))) {
        write_overview(dir, ix, t);
    }

    std::vector<std::vector<float>> roughness(ix.grid.exists.size());
    const int total = ix.grid.tile_rows * ix.grid.tile_cols;
    const bool progress = options.terminal_progress && ::isatty(2);
    int done = 0;
    for (int r = 0; r < ix.grid.tile_rows; ++r)
        for (int c = 0; c < ix.grid.tile_cols; ++c) {
            const std::string paths[] = {tile_path(dir, r, c, TileFile::Heights), tile_path(dir, r, c, TileFile::Colors),
                                         tile_path(dir, r, c, TileFile::Apron), tile_path(dir, r, c, TileFile::D2)};
            if (!ix.grid.present(r, c)) {
                ++report.empty;
                for (const auto& p : paths) fs::remove(p, ec); // left over from an earlier tiling of another source
            } else {
                const TileSamples tile = cut_tile(t, ix.grid, r, c, false);
                roughness[ix.grid.index(r, c)] = rottger_roughness(tile.samples);
                if (resume && std::all_of(std::begin(paths), std::end(paths), [&](const std::string& p) {
                        return fs::exists(p) || (ix.levels == 0 && p == paths[3]);
                    })) {
                    ++report.skipped;
                } else {
                    write_tile_files(dir, ix, r, c, tile, cut_apron(t, ix.grid, r, c));
                    ++report.written;
                }
            }
            ++done;
            if (progress) GDALTermProgress(double(done) / total, nullptr, nullptr);
            if (options.on_tile && !options.on_tile(done, total)) throw Error(dir, "interrupted");
        }
    ix.grid.roughness = std::move(roughness);
    ix.grid.max_level = ix.levels;
    ix.complete = true;
    write_index(dir, ix);
    return report;
}

bool is_tile_directory(const std::string& path) {
    std::error_code ec;
    return fs::is_directory(path, ec) && fs::is_regular_file(fs::path(path) / "index.json", ec);
}

TileIndex read_tile_index(const std::string& dir) {
    return parse_index((fs::path(dir) / "index.json").string(), true);
}

TileSamples read_tile(const std::string& dir, const TileIndex& ix, int r, int c, bool with_normals, int level) {
    const std::string h_path = tile_path(dir, r, c, TileFile::Heights);
    if (level < 0 || level > ix.levels)
        throw Error(h_path, "level " + std::to_string(level) + " not stored (" + std::to_string(ix.levels) + " levels)");
    const int n = ix.grid.level_size(level), step = 1 << level;
    TileSamples t{Terrain(n, n, ix.grid.h_scale * float(step), ix.grid.v_scale, ix.grid.y_offset), {}};
    if (!ix.grid.present(r, c)) throw Error(h_path, "tile is flagged 0 (no data) in index.json");
    read_raster(h_path, n, n, 1, GDT_UInt16, t.samples.heights().data(), step);
    read_colors(tile_path(dir, r, c, TileFile::Colors), t.samples, step);
    if (level > 0 && ix.grid.d2_min_resolution > 0) {
        t.d2.resize(std::size_t(n) * std::size_t(n));
        read_raster(tile_path(dir, r, c, TileFile::D2), n, n, 1, GDT_Float32, t.d2.data(), step / 2);
    }
    if (with_normals && ix.apron && level == 0) {
        std::vector<std::uint16_t> sides(4 * std::size_t(n));
        read_raster(tile_path(dir, r, c, TileFile::Apron), n, 4, 1, GDT_UInt16, sides.data());
        TileApron a;
        const auto side = [&](int k) { return std::vector<std::uint16_t>(sides.begin() + k * n, sides.begin() + (k + 1) * n); };
        a.north = side(0);
        a.south = side(1);
        a.west = side(2);
        a.east = side(3);
        t.normals = tile_normals(t.samples, a, ix.grid, r, c);
    }
    return t;
}

TileLoader tile_directory_loader(const std::string& dir, const TileIndex& index) {
    return [dir, index](int r, int c, int level) { return read_tile(dir, index, r, c, true, level); };
}

namespace {

// info of a tile directory, for both loaders.
void fill_info(TerrainInfo& info, const std::string& dir, const TileIndex& ix) {
    info.source = dir;
    info.kind = "tiles";
    info.driver = "GTiff";
    info.color_source = "tile _rgb.tif files";
    info.source_rows = ix.grid.source_rows;
    info.source_cols = ix.grid.source_cols;
    info.georeferenced = ix.georeferenced;
    info.geotransform = ix.geotransform;
    info.crs_wkt = ix.crs_wkt;
    if (!ix.crs_wkt.empty()) {
        OGRSpatialReferenceH srs = OSRNewSpatialReference(ix.crs_wkt.c_str());
        if (srs) {
            if (const char* name = OSRGetName(srs)) info.crs = name;
            OSRDestroySpatialReference(srs);
        }
    }
    info.metadata.emplace_back("tile_size", std::to_string(ix.grid.tile_size));
    info.metadata.emplace_back("tiles", std::to_string(ix.grid.tile_rows) + "x" + std::to_string(ix.grid.tile_cols));
    info.metadata.emplace_back("checksum", ix.checksum);
    info.metadata.emplace_back("tiled_from", ix.source);
}

} // namespace

DataSet load_tile_directory(const std::string& dir) {
    const TileIndex ix = read_tile_index(dir);
    DataSet d;
    Terrain t(ix.grid.source_rows, ix.grid.source_cols, ix.grid.h_scale, ix.grid.v_scale, ix.grid.y_offset);
    const int s = ix.grid.stride();
    for (int r = 0; r < ix.grid.tile_rows; ++r)
        for (int c = 0; c < ix.grid.tile_cols; ++c) {
            if (!ix.grid.present(r, c)) continue;
            const TileSamples tile = read_tile(dir, ix, r, c, false);
            for (int i = 0; i < ix.grid.tile_size && r * s + i < t.rows(); ++i)
                for (int j = 0; j < ix.grid.tile_size && c * s + j < t.cols(); ++j) {
                    t.raw(r * s + i, c * s + j) = tile.samples.raw(i, j);
                    t.color(r * s + i, c * s + j) = tile.samples.color(i, j);
                }
        }
    d.terrain = std::move(t);
    fill_info(d.info, dir, ix);
    return d;
}

DataSet load_tile_directory_overview(const std::string& dir, int max_side) {
    const TileIndex ix = read_tile_index(dir);
    const TileGrid& g = ix.grid;
    const int f = overview_stride(g.source_rows, g.source_cols, max_side);
    if (f == 1) return load_tile_directory(dir);
    const int rows = (g.source_rows - 2) / f + 2, cols = (g.source_cols - 2) / f + 2;
    DataSet d;
    if (ix.overview_stride > 1 && f % ix.overview_stride == 0) {
        // The stored overview, decimated further when a smaller one is asked for.
        Terrain stored(ix.overview_rows, ix.overview_cols, g.h_scale * float(ix.overview_stride), g.v_scale, g.y_offset);
        read_raster((fs::path(dir) / kOverviewHeights).string(), stored.cols(), stored.rows(), 1, GDT_UInt16,
                    stored.heights().data());
        read_colors((fs::path(dir) / kOverviewColors).string(), stored);
        const int k = f / ix.overview_stride;
        if (k == 1) {
            d.terrain = std::move(stored);
        } else {
            // Stored sample (i k) is source sample min(i f, rows - 1), as decimate() picks it.
            d.terrain = Terrain(rows, cols, g.h_scale * float(f), g.v_scale, g.y_offset);
            for (int i = 0; i < rows; ++i)
                for (int j = 0; j < cols; ++j) {
                    const int si = std::min(i * k, stored.rows() - 1), sj = std::min(j * k, stored.cols() - 1);
                    d.terrain.raw(i, j) = stored.raw(si, sj);
                    d.terrain.color(i, j) = stored.color(si, sj);
                }
        }
    } else {
        // From the tiles, one at a time: memory stays at one tile plus the overview.
        d.terrain = Terrain(rows, cols, g.h_scale * float(f), g.v_scale, g.y_offset);
        const int s = g.stride();
        for (int r = 0; r < g.tile_rows; ++r)
            for (int c = 0; c < g.tile_cols; ++c) {
                if (!g.present(r, c)) continue;
                const TileSamples tile = read_tile(dir, ix, r, c, false);
                // Overview samples whose (clamped) source sample lies in this tile.
                for (int i = 0; i < rows; ++i) {
                    const int gi = std::min(i * f, g.source_rows - 1) - r * s;
                    if (gi < 0 || gi >= g.tile_size) continue;
                    for (int j = 0; j < cols; ++j) {
                        const int gj = std::min(j * f, g.source_cols - 1) - c * s;
                        if (gj < 0 || gj >= g.tile_size) continue;
                        d.terrain.raw(i, j) = tile.samples.raw(gi, gj);
                        Rgb8 col = tile.samples.color(gi, gj);
                        if (std::min(i * f, g.source_rows - 1) != i * f || std::min(j * f, g.source_cols - 1) != j * f)
                            col = Rgb8{std::uint8_t(col.r / 2), std::uint8_t(col.g / 2), std::uint8_t(col.b / 2)};
                        d.terrain.color(i, j) = col;
                    }
                }
            }
    }
    fill_info(d.info, dir, ix);
    d.info.metadata.emplace_back("overview_stride", std::to_string(f));
    return d;
}

bool read_georeferencing(const std::string& path, std::array<double, 6>& gt, std::string& wkt, int& rows, int& cols) {
    gdal::ensure_initialised();
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return false;
    GDALDatasetH ds = GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr);
    if (!ds) return false;
    gdal::Dataset owner(ds);
    double g[6];
    if (GDALGetGeoTransform(ds, g) != CE_None) return false;
    std::copy(g, g + 6, gt.begin());
    const char* p = GDALGetProjectionRef(ds);
    wkt = p ? p : "";
    rows = GDALGetRasterYSize(ds);
    cols = GDALGetRasterXSize(ds);
    return true;
}

BandMapping read_band_mapping(const std::string& path) {
    gdal::Dataset ds = gdal::open_raster(path);
    GDALRasterBandH band = GDALGetRasterBand(ds.get(), 1);
    BandMapping m;
    int has = 0;
    const double scale = GDALGetRasterScale(band, &has);
    if (has) m.scale = scale;
    const double offset = GDALGetRasterOffset(band, &has);
    if (has) m.offset = offset;
    const char* unit = GDALGetRasterUnitType(band);
    m.unit = unit ? unit : "";
    return m;
}

} // namespace overflight
