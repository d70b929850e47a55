#pragma once
// The tiling model of a terrain: the grid of overlapping (2^k+1)^2 tiles, the
// cut of one tile (padded samples, every 2^m-th sample for level m), the
// apron of samples just outside a tile and the normals it allows at the
// tile's edges. What a tile directory's index.json describes (io) and what
// the run-time tile selection consumes (lod); no GL, no file I/O.
//
// Based on: Zamri, "Data tiling": the terrain is padded to a (2^n+1)^2
// square, cut into tiles of 2^k+1 samples per side that share their edge
// samples, and tiles without source data are flagged 0 and not stored.
//
// Limits (checked by validate() and terrain_tile_grid(), in 64-bit
// arithmetic so that no declared size overflows an int):
//   - a tile has at most kMaxTileSize = 2^15+1 samples per side, the largest
//     2^k+1 whose sample count (2^30 + 2^16 + 1) still fits a signed 32-bit
//     int, as GDAL's raster I/O and the loaders' per-tile buffers count it;
//   - the padded square has at most kMaxTiledSide = 2^20+1 samples per side.
//     Only its metadata (the tile grid, index.json, the overview) is ever
//     held whole; a tiler reads the source in windows and a renderer loads
//     tiles, so the limit of what is loaded at once (kMaxPaddedSide = 65537,
//     the largest Terrain, core/Terrain.h) does not bound it. 2^20+1 keeps
//     every global sample index and the padded extent in an int and the
//     index of 257-sample tiles (4096^2 of them) within a few hundred MB.
#include "core/Terrain.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace overflight {

inline constexpr int kMaxTileSize = 32769;
inline constexpr int kMaxPaddedSide = 65537;
inline constexpr int kMaxTiledSide = 1048577;

// The tiling of a terrain (what a tile directory's index.json describes).
// Tile (r, c) covers global samples rows r*(s-1) .. r*(s-1)+s-1 and columns
// c*(s-1) .. c*(s-1)+s-1, s = tile_size: neighbours share their edge samples.
struct TileGrid {
    int tile_size = 257;            // samples per side, 2^k+1
    int tile_rows = 0, tile_cols = 0;
    int source_rows = 0, source_cols = 0; // the terrain before padding
    float h_scale = 1.0f, v_scale = 1.0f, y_offset = 0.0f;
    std::vector<std::uint8_t> exists; // Zamri's flags, row-major tile_rows x tile_cols
    std::vector<float> min_height;    // world Y range per tile, for the bounding
    std::vector<float> max_height;    // spheres of tiles not loaded yet
    // Levels the loader can deliver (0: full resolution only), and per tile
    // Röttger's roughness of its full samples per node size (empty when
    // levels are unknown; lod/RottgerQuadtree.h rottger_roughness).
    int max_level = 0;
    std::vector<std::vector<float>> roughness;
    // Röttger's C for which the loader gives reduced tiles the full tile's
    // d2 (TileSamples::d2); 0: it does not, a bound from the roughness is used.
    double d2_min_resolution = 0.0;

    int stride() const { return tile_size - 1; }
    std::size_t index(int r, int c) const { return std::size_t(r) * std::size_t(tile_cols) + std::size_t(c); }
    bool present(int r, int c) const {
        return r >= 0 && c >= 0 && r < tile_rows && c < tile_cols && exists[index(r, c)] != 0;
    }
    double tile_world_size() const { return double(h_scale) * stride(); }
    std::int64_t padded_rows() const { return std::int64_t(tile_rows) * stride() + 1; }
    std::int64_t padded_cols() const { return std::int64_t(tile_cols) * stride() + 1; }
    // Samples per side of a tile at `level` (every 2^level-th sample).
    int level_size(int level) const { return (stride() >> level) + 1; }
    // The coarsest level a tile can drop to (a 3x3 patch); -1 for a tile
    // size below 3.
    int coarsest_level() const;
    // Whether tile (r, c) holds source samples (Zamri's existence rule).
    bool holds_source(int r, int c) const {
        return std::int64_t(r) * stride() < source_rows && std::int64_t(c) * stride() < source_cols;
    }
    // Throws Error(subject, ...) when a size is outside the limits above, or
    // sizes, flags, height ranges or roughness are inconsistent with each
    // other (a grid terrain_tile_grid() would not produce).
    void validate(const std::string& subject) const;
};

// World Y of a raw sample under the grid's height mapping, computed as
// Terrain::sample_height does (min_height / max_height hold such values).
inline float tile_world_height(const TileGrid& grid, std::uint16_t raw) {
    return grid.v_scale * float(raw) + grid.y_offset;
}

// What a loader returns for one tile at a level: level_size(level)^2 samples
// (every 2^level-th sample of the tile: heights, colors, the grid's vertical
// scales, h_scale times 2^level) and optionally one normal per sample
// (empty: computed from the tile's own samples, one-sided on its border,
// which shows a lighting seam where tiles meet), and for a reduced level
// optionally the full tile's rottger_d2() at each sample (empty: bounded).
struct TileSamples {
    Terrain samples;
    std::vector<glm::vec3> normals;
    std::vector<float> d2;
};
using TileLoader = std::function<TileSamples(int tile_row, int tile_col, int level)>;

// The per-tile measures a tiler stores so that far tiles can be loaded
// reduced: Röttger's roughness per node size and the full tile's propagated
// d2 for Röttger's C = min_resolution. They belong to the level-of-detail
// code (lod/RottgerQuadtree.h); the caller of a tiler hands them over
// (lod/TileSet.h rottger_tile_measures()). Empty: no reduced levels.
struct TileMeasures {
    std::function<std::vector<float>(const Terrain& tile)> roughness;
    std::function<std::vector<float>(const Terrain& tile)> d2;
    double min_resolution = 0.0;
    bool available() const { return roughness && d2 && min_resolution > 1.0; }
};

// The raw samples just outside tile (r, c), s = tile_size, S = s - 1:
// `north` is global row r*S - 1 and `south` row r*S + s, both over the
// tile's columns c*S .. c*S + S; `west` and `east` are columns c*S - 1 and
// c*S + s over the tile's rows. A central difference at a tile edge needs
// them because overlapping tiles share their edge samples, so the sample
// beyond an edge lives only in the neighbour. Positions outside the source
// hold the clamped source sample (they are never used for normals).
struct TileApron {
    std::vector<std::uint16_t> north, south, west, east; // tile_size values each
};
TileApron cut_apron(const Terrain& terrain, const TileGrid& grid, int tile_row, int tile_col);

// One unit normal per sample of tile (r, c), equal to Terrain::sample_normal
// of the whole source terrain at that sample (at the clamped source sample in
// the padding): central differences, one-sided only at the source's own
// border, using `apron` across the tile's edges, so both tiles of a seam
// compute identical normals there. Throws Error("tile", ...) when the tile or
// apron sizes do not match the grid.
std::vector<glm::vec3> tile_normals(const Terrain& tile, const TileApron& apron, const TileGrid& grid, int tile_row,
                                    int tile_col);

// Tiling of a terrain held in memory, following Zamri's rule: the terrain is
// (virtually) padded to a (2^n+1)^2 square, n from its larger side (at least
// 3x3, so that a 2x2 terrain still makes one 3x3 tile), and cut into tiles of
// tile_size (clamped to that square); tiles wholly outside the source are
// flagged 0. Padding repeats the edge samples with darkened colors (as
// pad_to_pow2_plus1 does) without copying the terrain. Throws
// Error("tile size", ...) when tile_size is not 2^k+1 >= 3 or the clamped
// size exceeds kMaxTileSize.
TileGrid terrain_tile_grid(const Terrain& terrain, int tile_size);
// The same grid for a source of rows x cols samples that is not held in
// memory: sizes, scales and existence flags; min_height/max_height hold the
// height mapping's whole range until the tiles are cut. Throws as
// terrain_tile_grid, and Error("source", ...) when the padded square would
// exceed kMaxTiledSide.
TileGrid sized_tile_grid(int rows, int cols, int tile_size, float h_scale, float v_scale, float y_offset);
// The padded samples of one tile at `level` (every 2^level-th sample), with
// Terrain::sample_normal of the whole terrain when with_normals.
TileSamples cut_tile(const Terrain& terrain, const TileGrid& grid, int tile_row, int tile_col, bool with_normals,
                     int level = 0);

// A window of a source too large to hold whole: `samples` are the source's
// rows row0 .. row0 + samples.rows() - 1 and columns col0 .. col0 +
// samples.cols() - 1 (grid.source_rows x source_cols is the whole source).
struct TerrainWindow {
    const Terrain& samples;
    int row0 = 0, col0 = 0;
};
// cut_tile (level 0, without normals) and cut_apron of the whole source, from
// a window holding every source sample they read: the tile's samples and the
// apron around them, clamped to the source. The result equals the cut of
// the whole terrain.
TileSamples cut_tile(const TerrainWindow& window, const TileGrid& grid, int tile_row, int tile_col);
TileApron cut_apron(const TerrainWindow& window, const TileGrid& grid, int tile_row, int tile_col);

} // namespace overflight
