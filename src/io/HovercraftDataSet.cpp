// Based on: CMSC 23700 project 2a, sec. 6 (data set directory,
// 16-bit PGM height field, PPM with one color per grid square).
#include "io/HovercraftDataSet.h"

#include "core/Error.h"
#include "core/ImageryFallback.h"
#include "core/Shading.h"
#include "io/Files.h"
#include "io/ImageryRaster.h"
#include "io/MapFile.h"
#include "io/Pnm.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <utility>

namespace overflight {

namespace fs = std::filesystem;

ColorImage cell_colors_to_samples(const ColorImage& cells) {
    const int rows = cells.height + 1, cols = cells.width + 1;
    ColorImage out(cols, rows);
    for (int i = 0; i < rows; ++i) {
        for (int j = 0; j < cols; ++j) {
            // A sample is the shared corner of up to four cells: the mean of
            // them keeps the cell colors' look without shifting them by half a cell.
            unsigned r = 0, g = 0, b = 0, n = 0;
            for (int ci = i - 1; ci <= i; ++ci) {
                for (int cj = j - 1; cj <= j; ++cj) {
                    if (ci < 0 || cj < 0 || ci >= cells.height || cj >= cells.width) continue;
                    const Rgb8 c = cells.at(cj, ci);
                    r += c.r;
                    g += c.g;
                    b += c.b;
                    ++n;
                }
            }
            out.at(j, i) = Rgb8{std::uint8_t((r + n / 2) / n), std::uint8_t((g + n / 2) / n), std::uint8_t((b + n / 2) / n)};
        }
    }
    return out;
}

ColorImage sample_colors_to_cells(const Terrain& t) {
    ColorImage out(t.cols() - 1, t.rows() - 1);
    for (int i = 0; i + 1 < t.rows(); ++i) {
        for (int j = 0; j + 1 < t.cols(); ++j) {
            const Rgb8 a = t.color(i, j), b = t.color(i, j + 1), c = t.color(i + 1, j), d = t.color(i + 1, j + 1);
            out.at(j, i) = Rgb8{std::uint8_t((a.r + b.r + c.r + d.r + 2) / 4), std::uint8_t((a.g + b.g + c.g + d.g + 2) / 4),
                                std::uint8_t((a.b + b.b + c.b + d.b + 2) / 4)};
        }
    }
    return out;
}

namespace {

std::string number(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

// The map's scales are doubles but the terrain holds floats: they must give a
// terrain whose extent and elevations float world coordinates can hold, and
// the error must name the map, not the terrain built from it.
void check_scales(const MapFile& map, const Image2D<std::uint16_t>& hf, const std::string& map_path) {
    if (const std::string problem = horizontal_scale_problem(hf.height, hf.width, map.h_scale); !problem.empty())
        throw Error(map_path, "h_scale = " + number(map.h_scale) + " for a " + std::to_string(hf.width) + "x" +
                                  std::to_string(hf.height) + " hf.pgm: " + problem);
    for (const auto& [key, value] : {std::pair{"h_scale", map.h_scale}, std::pair{"v_scale", map.v_scale}})
        if (!(float(value) > 0) || !std::isfinite(float(value)))
            throw Error(map_path, std::string(key) + " = " + number(value) + " is beyond float range");
    const auto [lowest, highest] = std::minmax_element(hf.pixels.begin(), hf.pixels.end());
    for (const std::uint16_t sample : {*lowest, *highest}) {
        const double elevation = map.v_scale * double(sample) + map.y_offset;
        if (const std::string problem = elevation_problem(elevation); !problem.empty())
            throw Error(map_path, "v_scale = " + number(map.v_scale) + ", y_offset = " + number(map.y_offset) +
                                      ": for sample " + std::to_string(sample) + " of hf.pgm, " + problem);
    }
}

} // namespace

DataSet load_hovercraft(const std::string& dir) {
    const fs::path root(dir);
    const std::string map_path = (root / "map").string();
    std::error_code ec;
    if (!fs::is_regular_file(map_path, ec))
        throw Error(dir, "directory without a `map` file (not a hovercraft data set)");
    MapFile map = load_map(map_path);
    const std::string hf_path = (root / "hf.pgm").string();
    if (!fs::exists(hf_path, ec)) throw Error(hf_path, "no such file (a data set needs hf.pgm)");
    GrayImage16 hf = read_pgm(hf_path);
    if (hf.image.width < 2 || hf.image.height < 2)
        throw Error(hf_path, "height field must be at least 2x2 samples");

    check_scales(map, hf.image, map_path);

    DataSet data;
    data.terrain = Terrain(hf.image.height, hf.image.width, float(map.h_scale), float(map.v_scale), float(map.y_offset));
    data.terrain.heights().assign(hf.image.pixels.begin(), hf.image.pixels.end());
    const Terrain& t = data.terrain;
    if (map.start.given && !t.contains(float(map.start.x), float(map.start.z)))
        throw Error(map_path, "[vehicle] start x = " + number(map.start.x) + ", z = " + number(map.start.z) +
                                  " is outside the terrain (x 0.." + number(t.width()) + ", z 0.." +
                                  number(t.depth()) + ")");
    data.environment = map.environment;
    data.start = map.start;
    data.scene = std::move(map.scene);
    TerrainInfo& info = data.info;
    info.source = dir;
    info.kind = "hovercraft";
    info.driver = "PGM";
    info.source_rows = data.terrain.rows();
    info.source_cols = data.terrain.cols();
    info.metadata.emplace_back("PGM_MAXVAL", std::to_string(hf.maxval));

    const std::string color_path = (root / "color.ppm").string();
    if (fs::exists(color_path, ec)) {
        ColorImage color = read_ppm(color_path);
        const int rows = data.terrain.rows(), cols = data.terrain.cols();
        if (color.width == cols - 1 && color.height == rows - 1) {
            const ColorImage samples = cell_colors_to_samples(color);
            data.terrain.colors().assign(samples.pixels.begin(), samples.pixels.end());
            info.color_source = color_path + " (one pixel per grid cell, averaged to samples)";
        } else if (color.width == cols && color.height == rows) {
            data.terrain.colors().assign(color.pixels.begin(), color.pixels.end());
            info.color_source = color_path + " (one pixel per sample)";
        } else if (color.width >= cols && color.height >= rows) {
            // Finer than the grid: imagery at its own resolution over the grid squares.
            auto imagery = imagery_over_cells(color, t.width(), t.depth());
            colors_from_imagery(*imagery, data.terrain);
            data.terrain.set_imagery(std::move(imagery));
            info.color_source = color_path + " (imagery at its own " + std::to_string(color.width) + "x" +
                                std::to_string(color.height) + " over the grid cells)";
        } else {
            throw Error(color_path, "size " + std::to_string(color.width) + "x" + std::to_string(color.height) +
                                        " matches neither the grid cells (" + std::to_string(cols - 1) + "x" +
                                        std::to_string(rows - 1) + ") nor the samples (" + std::to_string(cols) + "x" +
                                        std::to_string(rows) + ") of hf.pgm, nor is it larger than both");
        }
    } else {
        shade_by_elevation(data.terrain, data.terrain.min_height());
        info.color_source = "elevation ramp + hillshade (no color.ppm)";
    }
    return data;
}

void save_hovercraft(const std::string& dir, const DataSet& data) {
    const Terrain& t = data.terrain;
    if (t.rows() < 2 || t.cols() < 2) throw Error(dir, "cannot save an empty terrain");
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw Error(dir, "cannot create directory: " + ec.message());
    const fs::path root(dir);
    Image2D<std::uint16_t> hf;
    hf.width = t.cols();
    hf.height = t.rows();
    hf.pixels.assign(t.heights().begin(), t.heights().end());
    write_pgm((root / "hf.pgm").string(), hf, 65535);
    write_ppm((root / "color.ppm").string(), sample_colors_to_cells(t));
    MapFile map;
    map.h_scale = t.h_scale();
    map.v_scale = t.v_scale();
    map.y_offset = t.y_offset();
    map.environment = data.environment;
    map.start = data.start;
    map.scene = data.scene;
    const std::string text = format_map(map);
    const std::string map_path = (root / "map").string();
    // The map last: a directory only becomes a data set once its heights and colors are complete.
    write_atomically(map_path, [&](const std::string& temp) {
        FILE* f = std::fopen(temp.c_str(), "wb");
        if (!f) throw Error(map_path, "cannot create file");
        const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
        if ((std::fclose(f) != 0) || !ok) throw Error(map_path, "write failed (disk full?)");
    });
}

} // namespace overflight
