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

std::string tile_name(int r, int c, bool rgb) {
    return "r" + std::to_string(r) + "_c" + std::to_string(c) + (rgb ? "_rgb.tif" : ".tif");
}

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
    for (int r = 0; r < g.tile_rows; ++r) {
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
                {"source_rows", ix.source_rows},
                {"source_cols", ix.source_cols},
                {"padded_size", ix.padded_size},
                {"h_scale", g.h_scale},
                {"height_mapping", {{"v_scale", g.v_scale}, {"y_offset", g.y_offset}, {"units", "metre"}}},
                {"georeferenced", ix.georeferenced},
                {"geotransform", ix.geotransform},
                {"crs", ix.crs_wkt}};
}

void write_index(const std::string& dir, const TileIndex& ix) {
    const std::string path = (fs::path(dir) / "index.json").string();
    write_atomically(path, [&](const std::string& tmp) {
        std::ofstream f(tmp);
        f << index_to_json(ix).dump(1) << "\n";
        if (!f) throw Error(path, "cannot write");
    });
}

void set_georeferencing(GDALDatasetH ds, const std::array<double, 6>& gt, const std::string& wkt) {
    double g[6];
    std::copy(gt.begin(), gt.end(), g);
    GDALSetGeoTransform(ds, g);
    if (!wkt.empty()) GDALSetProjection(ds, wkt.c_str());
}

void write_tile_files(const std::string& dir, const TileIndex& ix, int r, int c, const TileSamples& t) {
    GDALDriverH gtiff = GDALGetDriverByName("GTiff");
    const int n = ix.grid.tile_size;
    const auto gt = tile_geotransform(ix, r, c);
    char** co = nullptr;
    co = CSLSetNameValue(co, "COMPRESS", "DEFLATE");
    co = CSLSetNameValue(co, "PREDICTOR", "2");
    struct OptionsFree {
        char** p;
        ~OptionsFree() { CSLDestroy(p); }
    } co_free{co};
    const std::string rgb_path = (fs::path(dir) / tile_name(r, c, true)).string();
    write_atomically(rgb_path, [&](const std::string& tmp) {
        gdal::Dataset ds(GDALCreate(gtiff, tmp.c_str(), n, n, 3, GDT_Byte, co));
        if (!ds) throw Error(rgb_path, "cannot create: " + gdal::last_error("GTiff"));
        set_georeferencing(ds.get(), gt, ix.crs_wkt);
        std::vector<std::uint8_t> band(std::size_t(n) * std::size_t(n));
        for (int b = 0; b < 3; ++b) {
            for (std::size_t i = 0; i < band.size(); ++i) {
                const Rgb8 px = t.samples.colors()[i];
                band[i] = b == 0 ? px.r : b == 1 ? px.g : px.b;
            }
            GDALRasterBandH h = GDALGetRasterBand(ds.get(), b + 1);
            GDALSetRasterColorInterpretation(h, b == 0 ? GCI_RedBand : b == 1 ? GCI_GreenBand : GCI_BlueBand);
            if (GDALRasterIO(h, GF_Write, 0, 0, n, n, band.data(), n, n, GDT_Byte, 0, 0) != CE_None)
                throw Error(rgb_path, "cannot write: " + gdal::last_error("I/O error"));
        }
        // Closing flushes the file: a failure there (disk full) must not pass.
        CPLErrorReset();
        GDALClose(ds.release());
        if (CPLGetLastErrorType() == CE_Failure || CPLGetLastErrorType() == CE_Fatal)
            throw Error(rgb_path, "cannot write: " + gdal::last_error("close failed"));
    });
    const std::string h_path = (fs::path(dir) / tile_name(r, c, false)).string();
    write_atomically(h_path, [&](const std::string& tmp) {
        gdal::Dataset ds(GDALCreate(gtiff, tmp.c_str(), n, n, 1, GDT_UInt16, co));
        if (!ds) throw Error(h_path, "cannot create: " + gdal::last_error("GTiff"));
        set_georeferencing(ds.get(), gt, ix.crs_wkt);
        GDALRasterBandH h = GDALGetRasterBand(ds.get(), 1);
        GDALSetRasterScale(h, ix.grid.v_scale);
        GDALSetRasterOffset(h, ix.grid.y_offset);
        GDALSetRasterUnitType(h, "metre");
        std::vector<std::uint16_t> v(t.samples.heights());
        if (GDALRasterIO(h, GF_Write, 0, 0, n, n, v.data(), n, n, GDT_UInt16, 0, 0) != CE_None)
            throw Error(h_path, "cannot write: " + gdal::last_error("I/O error"));
        // Closing flushes the file: a failure there (disk full) must not pass.
        CPLErrorReset();
        GDALClose(ds.release());
        if (CPLGetLastErrorType() == CE_Failure || CPLGetLastErrorType() == CE_Fatal)
            throw Error(h_path, "cannot write: " + gdal::last_error("close failed"));
    });
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
        ix.source_rows = j.at("source_rows").get<int>();
        ix.source_cols = j.at("source_cols").get<int>();
        ix.padded_size = j.at("padded_size").get<int>();
        ix.georeferenced = j.at("georeferenced").get<bool>();
        ix.geotransform = j.at("geotransform").get<std::array<double, 6>>();
        ix.crs_wkt = j.at("crs").get<std::string>();
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
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(path, std::string("malformed index: ") + e.what());
    }
    ix.grid.validate(path);
    if (ix.padded_size != ix.grid.tile_rows * ix.grid.stride() + 1 || ix.source_rows < 2 || ix.source_cols < 2 ||
        ix.source_rows > ix.padded_size || ix.source_cols > ix.padded_size)
        throw Error(path, "source and padded sizes do not match the tile grid");
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

TileWriteReport write_tile_directory(const DataSet& data, const std::string& dir, const TileWriteOptions& options) {
    gdal::ensure_initialised();
    const Terrain& t = data.terrain;
    TileWriteReport report;
    TileIndex& ix = report.index;
    ix.grid = terrain_tile_grid(t, options.tile_size);
    ix.source_rows = t.rows();
    ix.source_cols = t.cols();
    ix.padded_size = ix.grid.tile_rows * ix.grid.stride() + 1;
    ix.source = data.info.source;
    ix.checksum = terrain_checksum(t);
    ix.georeferenced = options.georeferenced;
    ix.crs_wkt = options.crs_wkt;
    if (options.georeferenced) {
        ix.geotransform = options.geotransform;
    } else {
        // Local frame: pixel (j, i) centre at X = hs j, Y = -hs i (north up).
        const double hs = t.h_scale();
        ix.geotransform = {-0.5 * hs, hs, 0, 0.5 * hs, 0, -hs};
    }

    std::error_code ec;
    fs::create_directories(dir, ec);
    if (!fs::is_directory(dir)) throw Error(dir, "cannot create the output folder");
    // Temporary files of a run that was killed cannot have cleaned up after themselves.
    for (const auto& e : fs::directory_iterator(dir, ec)) {
        const std::string name = e.path().filename().string();
        if (name.size() > 1 && name[0] == '.' && name.find(".tmp") != std::string::npos &&
            (name.rfind(".r", 0) == 0 || name.rfind(".index.json", 0) == 0))
            fs::remove(e.path(), ec);
    }
    // Resume only a run of the same source and tile size; otherwise start over.
    bool resume = false;
    const std::string index_path = (fs::path(dir) / "index.json").string();
    if (fs::exists(index_path)) {
        try {
            const TileIndex old = parse_index(index_path, false);
            resume = old.checksum == ix.checksum && old.grid.tile_size == ix.grid.tile_size &&
                     old.geotransform == ix.geotransform && old.crs_wkt == ix.crs_wkt;
        } catch (const Error&) {
            resume = false;
        }
    }
    ix.complete = false;
    write_index(dir, ix);

    const int total = ix.grid.tile_rows * ix.grid.tile_cols;
    const bool progress = options.terminal_progress && ::isatty(2);
    int done = 0;
    for (int r = 0; r < ix.grid.tile_rows; ++r)
        for (int c = 0; c < ix.grid.tile_cols; ++c) {
            const std::string h_path = (fs::path(dir) / tile_name(r, c, false)).string();
            const std::string rgb_path = (fs::path(dir) / tile_name(r, c, true)).string();
            if (!ix.grid.present(r, c)) {
                ++report.empty;
                fs::remove(h_path, ec); // left over from an earlier tiling of another source
                fs::remove(rgb_path, ec);
            } else if (resume && fs::exists(h_path) && fs::exists(rgb_path)) {
                ++report.skipped;
            } else {
                write_tile_files(dir, ix, r, c, cut_tile(t, ix.grid, r, c, false));
                ++report.written;
            }
            ++done;
            if (progress) GDALTermProgress(double(done) / total, nullptr, nullptr);
            if (options.on_tile && !options.on_tile(done, total)) throw Error(dir, "interrupted");
        }
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

TileSamples read_tile(const std::string& dir, const TileIndex& ix, int r, int c) {
    const int n = ix.grid.tile_size;
    TileSamples t{Terrain(n, n, ix.grid.h_scale, ix.grid.v_scale, ix.grid.y_offset), {}};
    const std::string h_path = (fs::path(dir) / tile_name(r, c, false)).string();
    const std::string rgb_path = (fs::path(dir) / tile_name(r, c, true)).string();
    if (!ix.grid.present(r, c)) throw Error(h_path, "tile is flagged 0 (no data) in index.json");
    {
        gdal::Dataset ds = gdal::open_raster(h_path);
        if (GDALGetRasterXSize(ds.get()) != n || GDALGetRasterYSize(ds.get()) != n || GDALGetRasterCount(ds.get()) < 1)
            throw Error(h_path, "expected " + std::to_string(n) + "x" + std::to_string(n) + " samples");
        if (GDALRasterIO(GDALGetRasterBand(ds.get(), 1), GF_Read, 0, 0, n, n, t.samples.heights().data(), n, n,
                         GDT_UInt16, 0, 0) != CE_None)
            throw Error(h_path, "cannot read: " + gdal::last_error("I/O error"));
    }
    {
        gdal::Dataset ds = gdal::open_raster(rgb_path);
        if (GDALGetRasterXSize(ds.get()) != n || GDALGetRasterYSize(ds.get()) != n || GDALGetRasterCount(ds.get()) != 3)
            throw Error(rgb_path, "expected 3 bands of " + std::to_string(n) + "x" + std::to_string(n));
        std::vector<std::uint8_t> band(std::size_t(n) * std::size_t(n));
        for (int b = 0; b < 3; ++b) {
            if (GDALRasterIO(GDALGetRasterBand(ds.get(), b + 1), GF_Read, 0, 0, n, n, band.data(), n, n, GDT_Byte, 0,
                             0) != CE_None)
                throw Error(rgb_path, "cannot read: " + gdal::last_error("I/O error"));
            for (std::size_t i = 0; i < band.size(); ++i) {
                Rgb8& px = t.samples.colors()[i];
                (b == 0 ? px.r : b == 1 ? px.g : px.b) = band[i];
            }
        }
    }
    return t;
}

TileLoader tile_directory_loader(const std::string& dir, const TileIndex& index) {
    return [dir, index](int r, int c) { return read_tile(dir, index, r, c); };
}

DataSet load_tile_directory(const std::string& dir) {
    const TileIndex ix = read_tile_index(dir);
    DataSet d;
    Terrain t(ix.source_rows, ix.source_cols, ix.grid.h_scale, ix.grid.v_scale, ix.grid.y_offset);
    const int s = ix.grid.stride();
    for (int r = 0; r < ix.grid.tile_rows; ++r)
        for (int c = 0; c < ix.grid.tile_cols; ++c) {
            if (!ix.grid.present(r, c)) continue;
            const TileSamples tile = read_tile(dir, ix, r, c);
            for (int i = 0; i < ix.grid.tile_size && r * s + i < t.rows(); ++i)
                for (int j = 0; j < ix.grid.tile_size && c * s + j < t.cols(); ++j) {
                    t.raw(r * s + i, c * s + j) = tile.samples.raw(i, j);
                    t.color(r * s + i, c * s + j) = tile.samples.color(i, j);
                }
        }
    d.terrain = std::move(t);
    d.info.source = dir;
    d.info.kind = "tiles";
    d.info.driver = "GTiff";
    d.info.color_source = "tile _rgb.tif files";
    d.info.source_rows = ix.source_rows;
    d.info.source_cols = ix.source_cols;
    if (!ix.crs_wkt.empty()) {
        OGRSpatialReferenceH srs = OSRNewSpatialReference(ix.crs_wkt.c_str());
        if (srs) {
            if (const char* name = OSRGetName(srs)) d.info.crs = name;
            OSRDestroySpatialReference(srs);
        }
    }
    d.info.metadata.emplace_back("tile_size", std::to_string(ix.grid.tile_size));
    d.info.metadata.emplace_back("tiles", std::to_string(ix.grid.tile_rows) + "x" + std::to_string(ix.grid.tile_cols));
    d.info.metadata.emplace_back("checksum", ix.checksum);
    d.info.metadata.emplace_back("tiled_from", ix.source);
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

} // namespace overflight
