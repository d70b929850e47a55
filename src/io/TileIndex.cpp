#include "io/TileIndex.h"

#include "core/Error.h"

#include <nlohmann/json.hpp>

#include <cfloat>
#include <climits>
#include <cmath>
#include <cstdint>
#include <functional>
#include <algorithm>
#include <stdexcept>

namespace overflight {

using json = nlohmann::json;

namespace {

json grid_rows(const TileGrid& g, const std::function<json(std::size_t)>& value) {
    json rows = json::array();
    for (int r = 0; r < g.tile_rows; ++r) {
        json row = json::array();
        for (int c = 0; c < g.tile_cols; ++c) row.push_back(value(g.index(r, c)));
        rows.push_back(row);
    }
    return rows;
}

// Numbers are range-checked before they are converted: converting a double
// outside the range of int or float is undefined behaviour.
int int_of(const json& v, const std::string& what, const std::string& subject) {
    if (!v.is_number_integer()) throw Error(subject, what + " is not an integer");
    if (v.is_number_unsigned() ? v.get<std::uint64_t>() > std::uint64_t(INT_MAX)
                               : (v.get<std::int64_t>() < INT_MIN || v.get<std::int64_t>() > INT_MAX))
        throw Error(subject, what + " is out of range");
    return int(v.get<std::int64_t>());
}

double double_of(const json& v, const std::string& what, const std::string& subject) {
    if (!v.is_number()) throw Error(subject, what + " is not a number");
    const double d = v.get<double>();
    if (!std::isfinite(d)) throw Error(subject, what + " is not a finite number");
    return d;
}

float float_of(const json& v, const std::string& what, const std::string& subject) {
    const double d = double_of(v, what, subject);
    if (std::abs(d) > double(FLT_MAX)) throw Error(subject, what + " is beyond the range of a float");
    return float(d);
}

// An array of tile_rows arrays of tile_cols values, row-major into `out`.
template <typename T, typename Read>
void read_grid(const json& j, const char* key, const TileGrid& g, std::vector<T>& out, const std::string& subject,
               Read read) {
    const json& rows = j.at(key);
    if (!rows.is_array() || rows.size() != std::size_t(g.tile_rows))
        throw Error(subject, std::string(key) + " does not match tile_rows x tile_cols");
    out.clear();
    for (int r = 0; r < g.tile_rows; ++r) {
        const json& row = rows.at(std::size_t(r));
        if (!row.is_array() || row.size() != std::size_t(g.tile_cols))
            throw Error(subject, std::string(key) + " does not match tile_rows x tile_cols");
        for (int c = 0; c < g.tile_cols; ++c)
            out.push_back(read(row.at(std::size_t(c)), std::string(key) + " of tile r" + std::to_string(r) + "_c" +
                                                           std::to_string(c)));
    }
}

void read_header(const json& j, TileIndex& ix, const std::string& subject) {
    if (j.at("format").get<std::string>() != "overflight-tiles") throw Error(subject, "not an overflight tile index");
    if (int_of(j.at("version"), "version", subject) != 1) throw Error(subject, "unsupported version");
    ix.complete = j.at("complete").get<bool>();
    ix.source = j.contains("source") ? j.at("source").get<std::string>() : std::string();
    ix.checksum = j.at("checksum").get<std::string>();
    TileGrid& g = ix.grid;
    g.tile_size = int_of(j.at("tile_size"), "tile_size", subject);
    g.tile_rows = int_of(j.at("tile_rows"), "tile_rows", subject);
    g.tile_cols = int_of(j.at("tile_cols"), "tile_cols", subject);
    g.h_scale = float_of(j.at("h_scale"), "h_scale", subject);
    g.v_scale = float_of(j.at("height_mapping").at("v_scale"), "v_scale", subject);
    g.y_offset = float_of(j.at("height_mapping").at("y_offset"), "y_offset", subject);
    g.source_rows = int_of(j.at("source_rows"), "source_rows", subject);
    g.source_cols = int_of(j.at("source_cols"), "source_cols", subject);
    ix.padded_size = int_of(j.at("padded_size"), "padded_size", subject);
    ix.georeferenced = j.at("georeferenced").get<bool>();
    const json& gt = j.at("geotransform");
    if (!gt.is_array() || gt.size() != 6) throw Error(subject, "geotransform needs 6 numbers");
    for (std::size_t k = 0; k < 6; ++k) ix.geotransform[k] = double_of(gt.at(k), "geotransform", subject);
    ix.crs_wkt = j.at("crs").get<std::string>();
    // Written by later versions of the tiler; absent means none.
    ix.apron = j.contains("apron") && j.at("apron").get<bool>();
    ix.levels = j.contains("levels") ? int_of(j.at("levels"), "levels", subject) : 0;
    g.d2_min_resolution = j.contains("d2_min_resolution") ? double_of(j.at("d2_min_resolution"), "d2_min_resolution", subject)
                                                          : 0.0;
    if (j.contains("imagery") && !j.at("imagery").is_null()) {
        const json& m = j.at("imagery");
        ImageryTileLayout& l = ix.imagery;
        l.x0 = double_of(m.at("x0"), "imagery x0", subject);
        l.z0 = double_of(m.at("z0"), "imagery z0", subject);
        l.extent_x = double_of(m.at("extent_x"), "imagery extent_x", subject);
        l.extent_z = double_of(m.at("extent_z"), "imagery extent_z", subject);
        l.width = int_of(m.at("width"), "imagery width", subject);
        l.height = int_of(m.at("height"), "imagery height", subject);
        l.levels = int_of(m.at("levels"), "imagery levels", subject);
        l.cols = int_of(m.at("tile_cols"), "imagery tile_cols", subject);
        l.rows = int_of(m.at("tile_rows"), "imagery tile_rows", subject);
        if (l.width < 1 || l.height < 1) throw Error(subject, "imagery width and height must be at least 1");
    }
    if (j.contains("overview") && !j.at("overview").is_null()) {
        const json& o = j.at("overview");
        ix.overview_stride = int_of(o.at("stride"), "overview stride", subject);
        ix.overview_rows = int_of(o.at("rows"), "overview rows", subject);
        ix.overview_cols = int_of(o.at("cols"), "overview cols", subject);
    }
}

void read_tiles(const json& j, TileIndex& ix, const std::string& subject) {
    TileGrid& g = ix.grid;
    // Each array must hold tile_rows x tile_cols values: a claim of many
    // tiles allocates only as much as the text backs it with.
    read_grid(j, "exists", g, g.exists, subject, [&](const json& v, const std::string& what) {
        const int flag = int_of(v, what, subject);
        if (flag != 0 && flag != 1) throw Error(subject, what + " is neither 0 nor 1");
        return std::uint8_t(flag);
    });
    const auto as_float = [&](const json& v, const std::string& what) { return float_of(v, what, subject); };
    read_grid(j, "min_height", g, g.min_height, subject, as_float);
    read_grid(j, "max_height", g, g.max_height, subject, as_float);
    // Roughness is written with the finished index; without it (older
    // directories, an unfinished run) tiles load at full resolution.
    if (ix.levels > 0 && j.contains("roughness") && !j.at("roughness").is_null()) {
        read_grid(j, "roughness", g, g.roughness, subject, [&](const json& v, const std::string& what) {
            if (!v.is_array() || v.size() > 32) throw Error(subject, what + " is not a list of node sizes");
            std::vector<float> per_size;
            for (const json& x : v) per_size.push_back(float_of(x, what, subject));
            return per_size;
        });
        g.max_level = ix.levels;
    }
}

} // namespace

std::string tile_index_text(const TileIndex& ix) {
    const TileGrid& g = ix.grid;
    const json roughness =
        g.roughness.empty() ? json(nullptr) : grid_rows(g, [&](std::size_t i) { return json(g.roughness[i]); });
    const json j{{"format", "overflight-tiles"},
                 {"version", 1},
                 {"complete", ix.complete},
                 {"source", ix.source},
                 {"checksum", ix.checksum},
                 {"tile_size", g.tile_size},
                 {"tile_rows", g.tile_rows},
                 {"tile_cols", g.tile_cols},
                 {"exists", grid_rows(g, [&](std::size_t i) { return json(int(g.exists[i])); })},
                 {"min_height", grid_rows(g, [&](std::size_t i) { return json(g.min_height[i]); })},
                 {"max_height", grid_rows(g, [&](std::size_t i) { return json(g.max_height[i]); })},
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
                 {"imagery", ix.imagery.present() ? json{{"format", kImageryTileFormat},
                                                         {"files", "r{R}_c{C}_img.tif"},
                                                         {"x0", ix.imagery.x0},
                                                         {"z0", ix.imagery.z0},
                                                         {"extent_x", ix.imagery.extent_x},
                                                         {"extent_z", ix.imagery.extent_z},
                                                         {"width", ix.imagery.width},
                                                         {"height", ix.imagery.height},
                                                         {"texel_size", std::max(ix.imagery.texel_x(), ix.imagery.texel_z())},
                                                         {"levels", ix.imagery.levels},
                                                         {"tile_cols", ix.imagery.cols},
                                                         {"tile_rows", ix.imagery.rows}}
                                                   : json(nullptr)},
                 {"overview", ix.overview_stride > 1 ? json{{"stride", ix.overview_stride},
                                                             {"rows", ix.overview_rows},
                                                             {"cols", ix.overview_cols},
                                                             {"heights", kOverviewHeights},
                                                             {"colors", kOverviewColors}}
                                                       : json(nullptr)}};
    return j.dump(1) + "\n";
}

void validate_tile_index(const TileIndex& ix, const std::string& subject) {
    ix.grid.validate(subject);
    if (ix.levels < 0 || ix.levels > ix.grid.coarsest_level())
        throw Error(subject, "levels " + std::to_string(ix.levels) + " is outside 0 .. " +
                                 std::to_string(ix.grid.coarsest_level()) + " for tiles of " +
                                 std::to_string(ix.grid.tile_size) + " samples");
    if (ix.grid.max_level != 0 && ix.grid.max_level != ix.levels)
        throw Error(subject, "roughness is given for other levels than the tiles hold");
    if (ix.padded_size != ix.grid.padded_rows() || ix.padded_size != ix.grid.padded_cols())
        throw Error(subject, "padded_size does not match the tile grid");
    if (ix.imagery.present()) {
        // The tile sizes follow from the grids: recomputed, not trusted.
        ImageryTileLayout want;
        try {
            want = plan_imagery_tiles(ix.grid, ix.imagery.x0, ix.imagery.z0, ix.imagery.extent_x, ix.imagery.extent_z,
                                      ix.imagery.width, ix.imagery.height);
        } catch (const std::invalid_argument& e) {
            throw Error(subject, std::string("imagery: ") + e.what());
        }
        if (want.levels != ix.imagery.levels || want.cols != ix.imagery.cols || want.rows != ix.imagery.rows)
            throw Error(subject, "imagery levels and tile sizes do not match its grid and the tiles'");
    }
    if (ix.overview_stride != 0) {
        const int k = ix.overview_stride;
        if (k < 2 || k > 65536 || (k & (k - 1)) != 0 || ix.overview_rows != (ix.grid.source_rows - 2) / k + 2 ||
            ix.overview_cols != (ix.grid.source_cols - 2) / k + 2)
            throw Error(subject, "overview stride and size do not match the source");
    }
}

TileIndex parse_tile_index(const std::string& text, const std::string& subject) {
    json j;
    try {
        j = json::parse(text);
    } catch (const std::exception& e) {
        throw Error(subject, std::string("malformed JSON: ") + e.what());
    }
    TileIndex ix;
    try {
        read_header(j, ix, subject);
        read_tiles(j, ix, subject);
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(subject, std::string("malformed index: ") + e.what());
    }
    validate_tile_index(ix, subject);
    return ix;
}

} // namespace overflight
