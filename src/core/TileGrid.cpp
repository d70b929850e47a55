// Based on: Zamri, "Data tiling" (2^n+1 padding, overlapping 2^k+1 tiles
// sharing their edge samples, existence flags).
#include "core/TileGrid.h"

#include "core/Error.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <limits>

namespace overflight {

namespace {

std::string tile_name(int r, int c) { return "r" + std::to_string(r) + "_c" + std::to_string(c); }

std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

// Sizes first, in 64-bit: everything else is indexed by them.
void validate_sizes(const TileGrid& g, const std::string& subject) {
    if (!is_pow2_plus1(g.tile_size) || g.tile_size < 3 || g.tile_size > kMaxTileSize)
        throw Error(subject, "tile size " + std::to_string(g.tile_size) + " is not 2^k+1 in 3 .. " +
                                 std::to_string(kMaxTileSize));
    const std::string grid_text = "tile grid " + std::to_string(g.tile_rows) + "x" + std::to_string(g.tile_cols) +
                                  " of " + std::to_string(g.tile_size) + "-sample tiles";
    if (g.tile_rows < 1 || g.tile_cols < 1 || g.padded_rows() > kMaxTiledSide || g.padded_cols() > kMaxTiledSide)
        throw Error(subject, grid_text + " is empty or larger than " + std::to_string(kMaxTiledSide) +
                                 " samples per side");
    const std::string source_text = std::to_string(g.source_rows) + "x" + std::to_string(g.source_cols) + " samples";
    if (g.source_rows < 2 || g.source_cols < 2 || g.source_rows > g.padded_rows() || g.source_cols > g.padded_cols())
        throw Error(subject, "source of " + source_text + " does not fit the " + grid_text);
    // Zamri's padding: the smallest 2^n+1 square holding the source, cut
    // into whole tiles; any other grid would describe tiles nobody wrote.
    const std::int64_t padded = std::max(3, next_pow2_plus1(std::max(g.source_rows, g.source_cols)));
    if (g.padded_rows() != padded || g.padded_cols() != padded)
        throw Error(subject, grid_text + " does not cut the " + std::to_string(padded) + "^2 square padding a source of " +
                                 source_text);
    const std::size_t n = std::size_t(g.tile_rows) * std::size_t(g.tile_cols);
    if (g.exists.size() != n || g.min_height.size() != n || g.max_height.size() != n)
        throw Error(subject, "tile grid needs one existence flag and one height range per tile");
}

void validate_scales(const TileGrid& g, const std::string& subject) {
    if (!(g.h_scale > 0) || !std::isfinite(g.h_scale) || double(g.h_scale) * double(g.padded_rows()) > FLT_MAX)
        throw Error(subject, "horizontal scale " + num(g.h_scale) + " is not a positive number with a finite extent");
    const float lo = tile_world_height(g, 0), hi = tile_world_height(g, 65535);
    if (!std::isfinite(g.v_scale) || !std::isfinite(g.y_offset) || !std::isfinite(lo) || !std::isfinite(hi))
        throw Error(subject, "height mapping " + num(g.v_scale) + " * raw + " + num(g.y_offset) + " is not finite");
    if (g.d2_min_resolution != 0 && !(g.d2_min_resolution > 1 && std::isfinite(g.d2_min_resolution)))
        throw Error(subject, "d2_min_resolution " + num(g.d2_min_resolution) + " is neither 0 nor a number above 1");
}

// Flags follow from the sizes; height ranges lie within what the height
// mapping can give (culling trusts them before a tile is loaded).
void validate_tiles(const TileGrid& g, const std::string& subject) {
    const float a = tile_world_height(g, 0), b = tile_world_height(g, 65535);
    const float lowest = std::min(a, b), highest = std::max(a, b);
    for (int r = 0; r < g.tile_rows; ++r)
        for (int c = 0; c < g.tile_cols; ++c) {
            const std::size_t i = g.index(r, c);
            const bool holds = g.holds_source(r, c);
            if (g.exists[i] != (holds ? 1 : 0))
                throw Error(subject, "tile " + tile_name(r, c) + " is flagged " + std::to_string(int(g.exists[i])) +
                                         (holds ? " but holds source samples" : " but lies wholly in the padding"));
            const float lo = g.min_height[i], hi = g.max_height[i];
            if (holds && !(lo >= lowest && lo <= hi && hi <= highest))
                throw Error(subject, "height range " + num(lo) + " .. " + num(hi) + " of tile " + tile_name(r, c) +
                                         " is not within the height mapping's " + num(lowest) + " .. " + num(highest));
        }
}

void validate_levels(const TileGrid& g, const std::string& subject) {
    const int coarsest = g.coarsest_level();
    const std::size_t n = g.exists.size();
    if (g.max_level < 0 || g.max_level > coarsest)
        throw Error(subject, "levels " + std::to_string(g.max_level) + " is outside 0 .. " + std::to_string(coarsest) +
                                 " for tiles of " + std::to_string(g.tile_size) + " samples");
    if (g.max_level > 0 && g.roughness.size() != n) throw Error(subject, "tile levels need one roughness per tile");
    for (std::size_t i = 0; i < g.roughness.size(); ++i) {
        const std::vector<float>& ro = g.roughness[i];
        if (ro.size() != (g.exists[i] ? std::size_t(coarsest + 1) : 0u))
            throw Error(subject, "tile roughness needs one value per node size (none for tiles flagged 0)");
        for (const float v : ro)
            if (!(v >= 0) || !std::isfinite(v)) throw Error(subject, "tile roughness " + num(v) + " is not a finite number >= 0");
    }
}

} // namespace

void TileGrid::validate(const std::string& subject) const {
    validate_sizes(*this, subject);
    validate_scales(*this, subject);
    validate_tiles(*this, subject);
    validate_levels(*this, subject);
}

int TileGrid::coarsest_level() const {
    // stride = 2^k: levels 0 .. k - 1 (level k - 1 leaves a 3x3 patch).
    // 64-bit, so that a stride of 2^30 or more cannot overflow the shift.
    int k = 0;
    while ((std::int64_t(2) << k) <= std::int64_t(stride())) ++k;
    return k - 1;
}

TileGrid sized_tile_grid(int rows, int cols, int tile_size, float h_scale, float v_scale, float y_offset) {
    if (!is_pow2_plus1(tile_size) || tile_size < 3)
        throw Error("tile size", std::to_string(tile_size) + " is not 2^k+1 (3, 5, 9, ..., 257, 513, ...)");
    if (std::max(rows, cols) > kMaxTiledSide - 1)
        throw Error("source", std::to_string(cols) + "x" + std::to_string(rows) + " samples pad to more than " +
                                  std::to_string(kMaxTiledSide) + " per side, the largest tile grid");
    // At least 3x3: a 2x2 terrain still makes one tile with a centre sample.
    const int padded = std::max(3, next_pow2_plus1(std::max(rows, cols)));
    TileGrid g;
    g.tile_size = std::min(tile_size, padded);
    if (g.tile_size > kMaxTileSize)
        throw Error("tile size", std::to_string(tile_size) + " makes tiles of " + std::to_string(g.tile_size) +
                                       " samples per side, more than the " + std::to_string(kMaxTileSize) + " a tile may have");
    g.tile_rows = g.tile_cols = (padded - 1) / g.stride();
    g.source_rows = rows;
    g.source_cols = cols;
    g.h_scale = h_scale;
    g.v_scale = v_scale;
    g.y_offset = y_offset;
    const std::size_t n = std::size_t(g.tile_rows) * std::size_t(g.tile_cols);
    g.exists.assign(n, 0);
    const float a = tile_world_height(g, 0), b = tile_world_height(g, 65535);
    g.min_height.assign(n, 0.0f);
    g.max_height.assign(n, 0.0f);
    for (int r = 0; r < g.tile_rows; ++r)
        for (int c = 0; c < g.tile_cols; ++c)
            if (g.holds_source(r, c)) {
                g.exists[g.index(r, c)] = 1;
                g.min_height[g.index(r, c)] = std::min(a, b);
                g.max_height[g.index(r, c)] = std::max(a, b);
            }
    return g;
}

TileGrid terrain_tile_grid(const Terrain& terrain, int tile_size) {
    TileGrid g = sized_tile_grid(terrain.rows(), terrain.cols(), tile_size, terrain.h_scale(), terrain.v_scale(),
                                 terrain.y_offset());
    const int s = g.stride();
    for (int r = 0; r < g.tile_rows; ++r)
        for (int c = 0; c < g.tile_cols; ++c) {
            // Zamri: a tile exists when it holds source data; the padding
            // alone is not worth storing or drawing.
            if (!g.holds_source(r, c)) continue;
            const int r0 = r * s, c0 = c * s;
            std::uint16_t lo = std::numeric_limits<std::uint16_t>::max(), hi = 0;
            // Padded samples repeat edge samples, so the clamped source window bounds them.
            const int r1 = std::min(r0 + s, terrain.rows() - 1), c1 = std::min(c0 + s, terrain.cols() - 1);
            for (int i = r0; i <= r1; ++i)
                for (int j = c0; j <= c1; ++j) {
                    const std::uint16_t v = terrain.raw(i, j);
                    lo = std::min(lo, v);
                    hi = std::max(hi, v);
                }
            g.exists[g.index(r, c)] = 1;
            // Ordered, should the height mapping's scale be negative.
            const float a = tile_world_height(g, lo), b = tile_world_height(g, hi);
            g.min_height[g.index(r, c)] = std::min(a, b);
            g.max_height[g.index(r, c)] = std::max(a, b);
        }
    return g;
}

TileSamples cut_tile(const TerrainWindow& window, const TileGrid& grid, int tile_row, int tile_col) {
    const int n = grid.tile_size, s = grid.stride();
    const Terrain& w = window.samples;
    TileSamples t{Terrain(n, n, grid.h_scale, grid.v_scale, grid.y_offset), {}};
    for (int i = 0; i < n; ++i) {
        const int gi = tile_row * s + i, si = std::min(gi, grid.source_rows - 1);
        for (int j = 0; j < n; ++j) {
            const int gj = tile_col * s + j, sj = std::min(gj, grid.source_cols - 1);
            t.samples.raw(i, j) = w.raw(si - window.row0, sj - window.col0);
            Rgb8 col = w.color(si - window.row0, sj - window.col0);
            if (si != gi || sj != gj) col = Rgb8{std::uint8_t(col.r / 2), std::uint8_t(col.g / 2), std::uint8_t(col.b / 2)};
            t.samples.color(i, j) = col;
        }
    }
    return t;
}

TileApron cut_apron(const TerrainWindow& window, const TileGrid& grid, int tile_row, int tile_col) {
    const int n = grid.tile_size, S = grid.stride();
    const int r0 = tile_row * S, c0 = tile_col * S;
    auto raw = [&](int gi, int gj) {
        return window.samples.raw(std::clamp(gi, 0, grid.source_rows - 1) - window.row0,
                                  std::clamp(gj, 0, grid.source_cols - 1) - window.col0);
    };
    TileApron a;
    for (int k = 0; k < n; ++k) {
        a.north.push_back(raw(r0 - 1, c0 + k));
        a.south.push_back(raw(r0 + n, c0 + k));
        a.west.push_back(raw(r0 + k, c0 - 1));
        a.east.push_back(raw(r0 + k, c0 + n));
    }
    return a;
}

TileSamples cut_tile(const Terrain& terrain, const TileGrid& grid, int tile_row, int tile_col, bool with_normals,
                     int level) {
    const int n = grid.level_size(level), s = grid.stride(), step = 1 << level;
    TileSamples t{Terrain(n, n, grid.h_scale * float(step), grid.v_scale, grid.y_offset), {}};
    if (with_normals) t.normals.resize(std::size_t(n) * std::size_t(n));
    for (int i = 0; i < n; ++i) {
        const int gi = tile_row * s + i * step, si = std::min(gi, terrain.rows() - 1);
        for (int j = 0; j < n; ++j) {
            const int gj = tile_col * s + j * step, sj = std::min(gj, terrain.cols() - 1);
            t.samples.raw(i, j) = terrain.raw(si, sj);
            Rgb8 col = terrain.color(si, sj);
            // Same darkening as pad_to_pow2_plus1: padding reads as "no data".
            if (si != gi || sj != gj) col = Rgb8{std::uint8_t(col.r / 2), std::uint8_t(col.g / 2), std::uint8_t(col.b / 2)};
            t.samples.color(i, j) = col;
            if (with_normals) t.normals[t.samples.index(i, j)] = terrain.sample_normal(si, sj);
        }
    }
    return t;
}

TileApron cut_apron(const Terrain& terrain, const TileGrid& grid, int tile_row, int tile_col) {
    return cut_apron(TerrainWindow{terrain, 0, 0}, grid, tile_row, tile_col);
}

std::vector<glm::vec3> tile_normals(const Terrain& tile, const TileApron& apron, const TileGrid& grid, int tile_row,
                                    int tile_col) {
    const int n = grid.tile_size, S = grid.stride();
    const auto un = std::size_t(n);
    if (tile.rows() != n || tile.cols() != n || apron.north.size() != un || apron.south.size() != un ||
        apron.west.size() != un || apron.east.size() != un)
        throw Error("tile", "samples or apron do not match the tile size " + std::to_string(n));
    const int r0 = tile_row * S, c0 = tile_col * S;
    // Height at local (i, j) in -1..n, at most one of them outside the tile.
    auto height = [&](int i, int j) {
        std::uint16_t raw;
        if (i < 0) raw = apron.north[std::size_t(j)];
        else if (i >= n) raw = apron.south[std::size_t(j)];
        else if (j < 0) raw = apron.west[std::size_t(i)];
        else if (j >= n) raw = apron.east[std::size_t(i)];
        else raw = tile.raw(i, j);
        return tile.v_scale() * float(raw) + tile.y_offset(); // as Terrain::sample_height
    };
    std::vector<glm::vec3> normals(un * un);
    const float hs = tile.h_scale();
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            // The same clamping and float arithmetic as Terrain::sample_normal
            // on the source, in global sample indices.
            const int row = std::min(r0 + i, grid.source_rows - 1), col = std::min(c0 + j, grid.source_cols - 1);
            const int cl = std::max(col - 1, 0), cr = std::min(col + 1, grid.source_cols - 1);
            const int rt = std::max(row - 1, 0), rb = std::min(row + 1, grid.source_rows - 1);
            const float dhdx = (height(row - r0, cr - c0) - height(row - r0, cl - c0)) / (hs * float(cr - cl));
            const float dhdz = (height(rb - r0, col - c0) - height(rt - r0, col - c0)) / (hs * float(rb - rt));
            normals[std::size_t(i) * un + std::size_t(j)] = glm::normalize(glm::vec3(-dhdx, 1.0f, -dhdz));
        }
    return normals;
}

} // namespace overflight
