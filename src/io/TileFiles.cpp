// The files of a tile directory (io/TileDirectory.h) as both tilers write
// them: names, per-tile contents, the overview, the index, resuming.
#include "io/TileFiles.h"

#include "core/Error.h"
#include "io/Files.h"

#include <algorithm>
#include <filesystem>

namespace fs = std::filesystem;

namespace overflight {

std::string tile_path(const std::string& dir, int r, int c, TileFile f) {
    static const char* suffix[] = {".tif", "_rgb.tif", "_apron.tif", "_d2.tif", "_img.tif"};
    return (fs::path(dir) / ("r" + std::to_string(r) + "_c" + std::to_string(c) + suffix[int(f)])).string();
}

std::string index_path(const std::string& dir) { return (fs::path(dir) / "index.json").string(); }

std::array<double, 6> tile_geotransform(const TileIndex& ix, int r, int c) {
    std::array<double, 6> gt = ix.geotransform;
    const double col0 = double(c) * ix.grid.stride(), row0 = double(r) * ix.grid.stride();
    gt[0] = ix.geotransform[0] + col0 * ix.geotransform[1] + row0 * ix.geotransform[2];
    gt[3] = ix.geotransform[3] + col0 * ix.geotransform[4] + row0 * ix.geotransform[5];
    return gt;
}

void write_index(const std::string& dir, const TileIndex& ix) {
    const std::string path = index_path(dir);
    validate_tile_index(ix, path);
    const std::string text = tile_index_text(ix);
    write_file_atomically(path, text.data(), text.size());
}

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

std::vector<std::uint8_t> rgba_planes(const Image2D<Rgba8>& img) {
    const std::size_t n = img.pixels.size();
    std::vector<std::uint8_t> planes(4 * n);
    for (std::size_t i = 0; i < n; ++i) {
        planes[i] = img.pixels[i].r;
        planes[n + i] = img.pixels[i].g;
        planes[2 * n + i] = img.pixels[i].b;
        planes[3 * n + i] = img.pixels[i].a;
    }
    return planes;
}

std::array<double, 6> imagery_tile_geotransform(const TileIndex& ix, int u0, int v0) {
    const ImageryTileLayout& l = ix.imagery;
    const std::array<double, 6>& g = ix.geotransform;
    const double hs = ix.grid.h_scale;
    // World x maps to the map's X as the samples do: sample j's centre (x =
    // hs j) is g[0] + (j + 1/2) g[1] (north-up grids: g[2] = g[4] = 0).
    const double x = l.x_of(u0), z = l.z_of(v0);
    return {g[0] + (x / hs + 0.5) * g[1], g[1] * l.texel_x() / hs, 0.0, g[3] + (z / hs + 0.5) * g[5], 0.0,
            g[5] * l.texel_z() / hs};
}

TileContent::TileContent(const std::string& dir, const TileIndex& ix, int r, int c, const TileSamples& t,
                         const TileApron& apron, const TileMeasures& measures, const TileImagery* imagery)
    : gt_(tile_geotransform(ix, r, c)), rgb_(color_planes(t.samples)) {
    const int n = ix.grid.tile_size;
    if (imagery && ix.imagery.present()) {
        imagery_gt_ = imagery_tile_geotransform(ix, imagery->u0, imagery->v0);
        for (const Image2D<Rgba8>& level : imagery->levels) imagery_planes_.push_back(rgba_planes(level));
        for (std::size_t m = 1; m < imagery_planes_.size(); ++m) imagery_levels_.push_back(imagery_planes_[m].data());
        files_.emplace_back(tile_path(dir, r, c, TileFile::Imagery),
                            RasterSpec{ix.imagery.cols, ix.imagery.rows, 4, GDT_Byte, imagery_planes_[0].data(),
                                       ix.georeferenced ? &imagery_gt_ : nullptr, ix.crs_wkt, nullptr, true,
                                       ix.imagery.levels, &imagery_levels_});
    }
    for (const auto* side : {&apron.north, &apron.south, &apron.west, &apron.east})
        sides_.insert(sides_.end(), side->begin(), side->end());
    files_.emplace_back(tile_path(dir, r, c, TileFile::Colors),
                        RasterSpec{n, n, 3, GDT_Byte, rgb_.data(), &gt_, ix.crs_wkt, nullptr, true, ix.levels});
    files_.emplace_back(tile_path(dir, r, c, TileFile::Apron),
                        RasterSpec{n, 4, 1, GDT_UInt16, sides_.data(), nullptr, "", nullptr, false, 0});
    if (ix.levels > 0) {
        // The full tile's d2 at its even samples (the centres of all nodes a
        // level >= 1 keeps), with levels of every 2^m-th of them: level m of
        // the tile reads level m - 1 of this file.
        const std::vector<float> d2 = measures.d2(t.samples);
        const int h = (n - 1) / 2 + 1;
        even_d2_.resize(std::size_t(h) * std::size_t(h));
        for (int i = 0; i < h; ++i)
            for (int j = 0; j < h; ++j)
                even_d2_[std::size_t(i) * std::size_t(h) + std::size_t(j)] = d2[t.samples.index(2 * i, 2 * j)];
        files_.emplace_back(tile_path(dir, r, c, TileFile::D2),
                            RasterSpec{h, h, 1, GDT_Float32, even_d2_.data(), nullptr, "", nullptr, false, ix.levels - 1});
    }
    files_.emplace_back(tile_path(dir, r, c, TileFile::Heights),
                        RasterSpec{n, n, 1, GDT_UInt16, t.samples.heights().data(), &gt_, ix.crs_wkt, &ix.grid, false,
                                   ix.levels});
}

void TileContent::write() const {
    for (const auto& [path, spec] : files_) write_geotiff(path, spec, FileSync::Later);
}
bool TileContent::on_disk() const {
    return std::all_of(files_.begin(), files_.end(), [](const auto& f) { return geotiff_matches(f.first, f.second); });
}

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

void write_overview(const std::string& dir, const TileIndex& ix, const Terrain& o, bool resume) {
    const int f = ix.overview_stride;
    const std::array<double, 6>& g = ix.geotransform;
    const std::array<double, 6> gt{g[0], g[1] * f, g[2] * f, g[3], g[4] * f, g[5] * f};
    const std::vector<std::uint8_t> rgb = color_planes(o);
    const std::pair<std::string, RasterSpec> files[] = {
        {(fs::path(dir) / kOverviewColors).string(),
         RasterSpec{o.cols(), o.rows(), 3, GDT_Byte, rgb.data(), &gt, ix.crs_wkt, nullptr, true, 0}},
        {(fs::path(dir) / kOverviewHeights).string(),
         RasterSpec{o.cols(), o.rows(), 1, GDT_UInt16, o.heights().data(), &gt, ix.crs_wkt, &ix.grid, false, 0}}};
    for (const auto& [path, spec] : files)
        if (!(resume && geotiff_matches(path, spec))) write_geotiff(path, spec);
}

void prepare_folder(const std::string& dir, const std::function<bool(const std::string&)>& mine) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (!fs::is_directory(dir)) throw Error(dir, "cannot create the output folder");
    for (const auto& e : fs::directory_iterator(dir, ec)) {
        const std::string name = e.path().filename().string();
        if (name.size() > 1 && name[0] == '.' && name.find(".tmp") != std::string::npos &&
            (name.rfind(".r", 0) == 0 || name.rfind(".index.json", 0) == 0 || name.rfind(".overview", 0) == 0 ||
             name.rfind("." + std::string(kPartPrefix), 1) == 1) &&
            (!mine || mine(name)))
            fs::remove(e.path(), ec);
    }
}

bool resumable(const std::string& dir, const TileIndex& ix) {
    std::error_code ec;
    if (!fs::exists(index_path(dir), ec)) return false;
    try {
        const std::vector<std::uint8_t> bytes = read_file_bytes(index_path(dir));
        const TileIndex old = parse_tile_index(std::string(bytes.begin(), bytes.end()), index_path(dir));
        return old.checksum == ix.checksum && old.grid.tile_size == ix.grid.tile_size &&
               old.geotransform == ix.geotransform && old.crs_wkt == ix.crs_wkt && old.apron &&
               old.overview_stride == ix.overview_stride && old.levels == ix.levels &&
               old.imagery.present() == ix.imagery.present() && old.imagery.x0 == ix.imagery.x0 &&
               old.imagery.z0 == ix.imagery.z0 && old.imagery.extent_x == ix.imagery.extent_x &&
               old.imagery.extent_z == ix.imagery.extent_z && old.imagery.width == ix.imagery.width &&
               old.imagery.height == ix.imagery.height &&
               old.grid.d2_min_resolution == ix.grid.d2_min_resolution;
    } catch (const Error&) {
        return false;
    }
}

} // namespace overflight
