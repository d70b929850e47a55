// Based on: Zamri, "Data tiling" (2^n+1 padding, overlapping 2^k+1 tiles,
// existence flags, one file per tile). GDAL writes the GeoTIFFs
// (io/TileRasters.h); the tiling model is core/TileGrid.h.
#include "io/TileDirectory.h"

#include "core/Error.h"
#include "io/Files.h"
#include "io/Gdal.h"
#include "io/TileFiles.h"
#include "io/TileRasters.h"

#include <gdal.h>
#include <ogr_srs_api.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <optional>
#include <tuple>
#include <unistd.h>

namespace fs = std::filesystem;

namespace overflight {

namespace {

void read_colors(GDALDatasetH ds, const std::string& path, Terrain& t, int reduce = 1) {
    const std::size_t n = t.colors().size();
    std::vector<std::uint8_t> planes(3 * n);
    read_bands(ds, path, t.cols(), t.rows(), 3, GDT_Byte, planes.data(), reduce);
    for (std::size_t i = 0; i < n; ++i) t.colors()[i] = Rgb8{planes[i], planes[n + i], planes[2 * n + i]};
}

std::string metres(float v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", double(v));
    return buf;
}

// Culling trusts the index's height range before a tile is loaded, so a tile
// must not leave it; at full resolution it spans it exactly (terrain_tile_grid
// takes it over the tile's own samples).
void check_heights(const std::string& path, const TileGrid& g, int r, int c, const Terrain& samples, bool full) {
    const auto [lo_raw, hi_raw] = std::minmax_element(samples.heights().begin(), samples.heights().end());
    const float a = tile_world_height(g, *lo_raw), b = tile_world_height(g, *hi_raw);
    const float lo = std::min(a, b), hi = std::max(a, b);
    const float want_lo = g.min_height[g.index(r, c)], want_hi = g.max_height[g.index(r, c)];
    if (full ? (lo != want_lo || hi != want_hi) : (lo < want_lo || hi > want_hi))
        throw Error(path, "heights " + metres(lo) + " .. " + metres(hi) + (full ? " differ from" : " leave") +
                              " the range " + metres(want_lo) + " .. " + metres(want_hi) + " index.json gives the tile");
}

// Samples of a full tile beyond the source are its padding: the clamped
// edge sample with a darkened color (cut_tile). Anything else means the
// index's source size is not the one the tiles were cut from.
void check_padding(const std::string& path, const TileGrid& g, int r, int c, const Terrain& samples) {
    const int r0 = r * g.stride(), c0 = c * g.stride();
    for (int i = 0; i < samples.rows(); ++i)
        for (int j = 0; j < samples.cols(); ++j) {
            const int si = std::min(r0 + i, g.source_rows - 1) - r0, sj = std::min(c0 + j, g.source_cols - 1) - c0;
            if (si == i && sj == j) continue;
            const Rgb8 edge = samples.color(si, sj), pad = samples.color(i, j);
            if (samples.raw(i, j) != samples.raw(si, sj) || pad.r != edge.r / 2 || pad.g != edge.g / 2 || pad.b != edge.b / 2)
                throw Error(path, "samples beyond the " + std::to_string(g.source_rows) + "x" + std::to_string(g.source_cols) +
                                      " source index.json gives are not its padding");
        }
}

void read_d2(GDALDatasetH ds, const std::string& path, int n, int reduce, std::vector<float>& d2) {
    d2.resize(std::size_t(n) * std::size_t(n));
    read_bands(ds, path, n, n, 1, GDT_Float32, d2.data(), reduce);
    for (const float v : d2)
        if (!(v >= 0) || !std::isfinite(v)) throw Error(path, "holds a d2 value that is not a finite number >= 0");
}

TileApron read_apron(GDALDatasetH ds, const std::string& path, int n) {
    std::vector<std::uint16_t> sides(4 * std::size_t(n));
    read_bands(ds, path, n, 4, 1, GDT_UInt16, sides.data());
    const auto side = [&](int k) {
        return std::vector<std::uint16_t>(sides.begin() + std::ptrdiff_t(k) * n, sides.begin() + std::ptrdiff_t(k + 1) * n);
    };
    return TileApron{side(0), side(1), side(2), side(3)};
}

// The index of a run over `data`: the grid, georeferencing, levels and overview.
TileIndex plan_index(const DataSet& data, const TileWriteOptions& options) {
    const Terrain& t = data.terrain;
    TileIndex ix;
    ix.grid = terrain_tile_grid(t, options.tile_size);
    ix.padded_size = int(ix.grid.padded_rows());
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
    ix.levels = options.measures.available() ? ix.grid.coarsest_level() : 0;
    ix.grid.d2_min_resolution = ix.levels > 0 ? options.measures.min_resolution : 0.0;
    const int f = overview_stride(t.rows(), t.cols(), options.overview_max_side);
    if (f > 1) {
        ix.overview_stride = f;
        ix.overview_rows = (t.rows() - 2) / f + 2;
        ix.overview_cols = (t.cols() - 2) / f + 2;
    }
    if (const ImageryPyramid* p = t.imagery()) {
        try {
            ix.imagery = plan_imagery_tiles(ix.grid, p->x0(), p->z0(), p->extent_x(), p->extent_z(), p->level(0).width,
                                            p->level(0).height);
        } catch (const std::invalid_argument& e) {
            throw Error("tile size", std::string("imagery: ") + e.what() + "; use a smaller --tile-size");
        }
    }
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
    ix = plan_index(data, options);
    prepare_folder(dir);
    FolderSync tiles_on_device(dir);
    const bool resume = resumable(dir, ix);
    ix.complete = false;
    write_index(dir, ix);

    std::error_code ec;
    if (ix.overview_stride == 0) {
        fs::remove(fs::path(dir) / kOverviewHeights, ec); // left over from a larger source
        fs::remove(fs::path(dir) / kOverviewColors, ec);
    } else {
        write_overview(dir, ix, decimate(t, ix.overview_stride, ix.overview_rows, ix.overview_cols), resume);
    }

    const TileGrid& g = ix.grid;
    std::vector<std::vector<float>> roughness(ix.levels > 0 ? g.exists.size() : 0);
    const int total = g.tile_rows * g.tile_cols;
    const bool progress = options.terminal_progress && ::isatty(2);
    // Tiles are cut and encoded on all cores (encoding is most of the run);
    // each tile's files and slot of `roughness` are its own, so the folder
    // is the same whatever the order.
    std::atomic<int> written{0}, skipped{0}, empty{0};
    std::atomic<bool> stop{false};
    std::mutex progress_mutex;
    int done = 0;
    tbb::parallel_for(0, total, [&](int k) {
        if (stop) return;
        const int r = k / g.tile_cols, c = k % g.tile_cols;
        std::error_code err;
        if (!g.present(r, c)) {
            ++empty;
            for (const TileFile f : {TileFile::Heights, TileFile::Colors, TileFile::Apron, TileFile::D2, TileFile::Imagery})
                fs::remove(tile_path(dir, r, c, f), err); // left over from an earlier tiling of another source
        } else {
            const TileSamples tile = cut_tile(t, g, r, c, false);
            if (ix.levels > 0) roughness[g.index(r, c)] = options.measures.roughness(tile.samples);
            if (ix.levels == 0) fs::remove(tile_path(dir, r, c, TileFile::D2), err);
            std::optional<TileImagery> imagery;
            if (ix.imagery.present())
                imagery = cut_tile_imagery(*t.imagery(), ix.imagery, g, r, c);
            else
                fs::remove(tile_path(dir, r, c, TileFile::Imagery), err);
            const TileContent content(dir, ix, r, c, tile, cut_apron(t, g, r, c), options.measures,
                                      imagery ? &*imagery : nullptr);
            if (resume && content.on_disk()) {
                ++skipped;
            } else {
                content.write();
                ++written;
            }
        }
        std::lock_guard<std::mutex> lock(progress_mutex);
        ++done;
        if (progress) GDALTermProgress(double(done) / total, nullptr, nullptr);
        if (options.on_tile && !options.on_tile(done, total)) stop = true;
    });
    if (stop) throw Error(dir, "interrupted");
    report.written = written;
    report.skipped = skipped;
    report.empty = empty;
    ix.grid.roughness = std::move(roughness);
    ix.grid.max_level = ix.levels;
    ix.complete = true;
    tiles_on_device.sync();
    write_index(dir, ix);
    return report;
}

bool is_tile_directory(const std::string& path) {
    std::error_code ec;
    return fs::is_directory(path, ec) && fs::is_regular_file(fs::path(path) / "index.json", ec);
}

TileIndex read_tile_index(const std::string& dir) {
    const std::string path = index_path(dir);
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) throw Error(path, "missing (not a tile directory)");
    const std::vector<std::uint8_t> bytes = read_file_bytes(path);
    TileIndex ix = parse_tile_index(std::string(bytes.begin(), bytes.end()), path);
    if (!ix.complete)
        throw Error(path, "tiling did not finish (interrupted?); run `overflight tile` again to complete it");
    return ix;
}

TileSamples read_tile(const std::string& dir, const TileIndex& ix, int r, int c, bool with_normals, int level) {
    const TileGrid& g = ix.grid;
    const std::string h_path = tile_path(dir, r, c, TileFile::Heights), c_path = tile_path(dir, r, c, TileFile::Colors),
                      d_path = tile_path(dir, r, c, TileFile::D2), a_path = tile_path(dir, r, c, TileFile::Apron);
    if (level < 0 || level > ix.levels)
        throw Error(h_path, "level " + std::to_string(level) + " not stored (" + std::to_string(ix.levels) + " levels)");
    if (!g.present(r, c)) throw Error(h_path, "tile is flagged 0 (no data) in index.json");
    const int full = g.tile_size, n = g.level_size(level), step = 1 << level;
    const bool with_d2 = level > 0 && g.d2_min_resolution > 0, with_apron = with_normals && ix.apron && level == 0;
    // Every file is checked against the index before a buffer is sized from it.
    const gdal::Dataset heights = open_checked(h_path, full, full, 1, GDT_UInt16);
    const gdal::Dataset colors = open_checked(c_path, full, full, 3, GDT_Byte);
    const int half = (full - 1) / 2 + 1;
    const gdal::Dataset d2 = with_d2 ? open_checked(d_path, half, half, 1, GDT_Float32) : gdal::Dataset();
    const gdal::Dataset apron = with_apron ? open_checked(a_path, full, 4, 1, GDT_UInt16) : gdal::Dataset();
    TileSamples t{Terrain(n, n, g.h_scale * float(step), g.v_scale, g.y_offset), {}, {}};
    read_bands(heights.get(), h_path, n, n, 1, GDT_UInt16, t.samples.heights().data(), step);
    check_heights(h_path, g, r, c, t.samples, level == 0);
    read_colors(colors.get(), c_path, t.samples, step);
    if (level == 0) check_padding(h_path, g, r, c, t.samples);
    if (with_d2) read_d2(d2.get(), d_path, n, step / 2, t.d2);
    if (with_apron) t.normals = tile_normals(t.samples, read_apron(apron.get(), a_path, full), g, r, c);
    return t;
}

TileImagery read_tile_imagery(const std::string& dir, const TileIndex& ix, int r, int c) {
    const std::string path = tile_path(dir, r, c, TileFile::Imagery);
    if (!ix.imagery.present()) throw Error(path, "the tile directory has no imagery tiles");
    if (!ix.grid.present(r, c)) throw Error(path, "tile is flagged 0 (no data) in index.json");
    const ImageryTileLayout& l = ix.imagery;
    const gdal::Dataset ds = open_checked(path, l.cols, l.rows, 4, GDT_Byte);
    TileImagery t;
    t.r = r;
    t.c = c;
    std::tie(t.u0, t.v0) = imagery_tile_origin(l, ix.grid, r, c);
    std::vector<std::uint8_t> planes;
    for (int m = 0; m <= l.levels; ++m) {
        const int w = l.cols >> m, h = l.rows >> m;
        const std::size_t n = std::size_t(w) * std::size_t(h);
        planes.resize(4 * n);
        read_bands(ds.get(), path, w, h, 4, GDT_Byte, planes.data(), 1 << m);
        Image2D<Rgba8> img(w, h);
        for (std::size_t i = 0; i < n; ++i)
            img.pixels[i] = Rgba8{planes[i], planes[n + i], planes[2 * n + i], planes[3 * n + i]};
        t.levels.push_back(std::move(img));
    }
    return t;
}

TileImageryLoader tile_directory_imagery_loader(const std::string& dir, const TileIndex& index) {
    if (!index.imagery.present()) return {};
    return [dir, index](int r, int c) { return read_tile_imagery(dir, index, r, c); };
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
    if (ix.imagery.present()) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "%dx%d texels of %.3g m, %dx%d per tile with %d levels (tile _img.tif files)",
                      ix.imagery.width, ix.imagery.height, std::max(ix.imagery.texel_x(), ix.imagery.texel_z()),
                      ix.imagery.cols, ix.imagery.rows, ix.imagery.levels);
        info.metadata.emplace_back("imagery_tiles", buf);
    }
}

} // namespace

DataSet load_tile_directory(const std::string& dir) {
    const TileIndex ix = read_tile_index(dir);
    // The whole terrain is allocated only once every tile the index claims is
    // there in the size it claims (headers only; read_tile checks the rest).
    for (int r = 0; r < ix.grid.tile_rows; ++r)
        for (int c = 0; c < ix.grid.tile_cols; ++c)
            if (ix.grid.present(r, c))
                open_checked(tile_path(dir, r, c, TileFile::Heights), ix.grid.tile_size, ix.grid.tile_size, 1, GDT_UInt16);
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
        const std::string h_path = (fs::path(dir) / kOverviewHeights).string(),
                          c_path = (fs::path(dir) / kOverviewColors).string();
        const gdal::Dataset heights = open_checked(h_path, ix.overview_cols, ix.overview_rows, 1, GDT_UInt16);
        const gdal::Dataset colors = open_checked(c_path, ix.overview_cols, ix.overview_rows, 3, GDT_Byte);
        Terrain stored(ix.overview_rows, ix.overview_cols, g.h_scale * float(ix.overview_stride), g.v_scale, g.y_offset);
        read_bands(heights.get(), h_path, stored.cols(), stored.rows(), 1, GDT_UInt16, stored.heights().data());
        read_colors(colors.get(), c_path, stored);
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
