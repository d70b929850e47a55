#pragma once
// Run-time tile selection for overlapping (2^k+1)^2 tiles: which tiles around
// the viewer are needed, which survive frustum culling, a memory-bounded LRU
// cache of loaded tiles, and one Röttger quadtree per visible tile whose fans
// are stitched across the seams.
//
// Based on: Zamri, seed 001, "Data tiling" (overlapping 2^n+1 tiles sharing
// their edge samples, existence flags, one file per tile) and "Run-Time
// Processing" (the viewer's tile and its 8 neighbours, view-frustum culling
// of their bounding spheres, Röttger et al. 1998 per tile). Zamri keeps a
// fixed 3x3 window; we extend it by rings of tiles until the far plane is
// covered, because with tiles smaller than `far` the 3x3 window would cut
// the view short.
//
// lod does no I/O: tiles come from an injected TileLoader (a tile directory
// through io, or a Terrain already in memory through terrain_tile_loader()).
//
// Levels: a far tile needs only coarse data. Röttger's f = l / (d C max(c
// d2, 1)) stops subdividing large nodes far away, so when no node of
// half-size 2^m of a tile can be subdivided at the tile's distance (checked
// before loading, with the tile's per-level roughness from the index), the
// tile is loaded at level m: every 2^m-th sample, 4^m times less memory.
// The cache is keyed by (tile, level); a reduced quadtree gets the full
// tile's d2 from the loader (or a conservative bound without it), so it
// refines as the full tile would, and stitches to neighbours of other levels
// (lod/RottgerQuadtree.h).
// If even the visible tiles at their levels exceed the memory bound, the
// frame is built row by row of tiles and drawn tiles are evicted once their
// neighbours' fans are done (streamed within the frame).
#include "core/Camera.h"
#include "core/MeshArrays.h"
#include "core/Terrain.h"
#include "lod/RottgerQuadtree.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>
#include <list>
#include <memory>
#include <unordered_map>
#include <vector>

namespace overflight {

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
    // rottger_roughness() of its full samples (empty when levels are unknown).
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
    int padded_rows() const { return tile_rows * stride() + 1; }
    int padded_cols() const { return tile_cols * stride() + 1; }
    // Samples per side of a tile at `level` (every 2^level-th sample).
    int level_size(int level) const { return (stride() >> level) + 1; }
    // The coarsest level a tile can drop to (a 3x3 patch).
    int coarsest_level() const;
    // Throws Error(subject, ...) when sizes or vectors are inconsistent.
    void validate(const std::string& subject) const;
};

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
// (virtually) padded to a (2^n+1)^2 square, n from its larger side, and cut
// into tiles of tile_size (clamped to that square); tiles wholly outside the
// source are flagged 0. Padding repeats the edge samples with darkened colors
// (as pad_to_pow2_plus1 does) without copying the terrain. Throws
// Error("tile size", ...) when tile_size is not 2^k+1 >= 3.
TileGrid terrain_tile_grid(const Terrain& terrain, int tile_size);
// Loader that cuts tiles out of `terrain` (which must outlive it); normals
// come from Terrain::sample_normal of the whole terrain, so they agree at seams.
TileLoader terrain_tile_loader(const Terrain& terrain, const TileGrid& grid);
// The padded samples of one tile at `level` (what the loader above returns),
// exposed for the tiler.
TileSamples cut_tile(const Terrain& terrain, const TileGrid& grid, int tile_row, int tile_col, bool with_normals,
                     int level = 0);
// Fills grid.roughness from the tiles of `terrain` and sets max_level, so
// that a TileSet over terrain_tile_loader() loads far tiles reduced.
void add_tile_levels(const Terrain& terrain, TileGrid& grid);

struct TileFrameStats {
    int candidates = 0;   // present tiles in the rings around the viewer
    int visible = 0;      // ALL-INSIDE or INTERSECT
    int culled = 0;       // ALL-OUTSIDE: neither loaded nor drawn
    int loaded = 0;       // loaded this frame (cache misses)
    int cached = 0;       // tiles in the cache after the frame
    int evicted = 0;      // dropped this frame to respect the memory bound
    int streamed = 0;     // drawn this frame, then dropped before its end (bound < visible set)
    std::vector<int> per_level; // visible tiles drawn at level 0, 1, ...
    int rings = 0;        // rings around the viewer's tile (1 = Zamri's 3x3)
    std::size_t cache_bytes = 0;
    std::size_t triangles = 0;
    double ms_select = 0, ms_load = 0, ms_refine = 0, ms_fans = 0;
};

class TileSet {
public:
    // memory_bound: bytes of loaded tiles (samples, normals, quadtree) the
    // cache may hold; it is exceeded only when three rows of visible tiles
    // at their levels do not fit. min_resolution is Röttger's C.
    TileSet(TileGrid grid, TileLoader loader, std::size_t memory_bound, double min_resolution = 4.0);
    ~TileSet();
    TileSet(const TileSet&) = delete;
    TileSet& operator=(const TileSet&) = delete;

    const TileGrid& grid() const { return grid_; }
    std::size_t memory_bound() const { return bound_; }

    // One frame: select the tiles around the camera, cull them against its
    // frustum, load the missing ones, refine each visible tile's quadtree
    // for a screen-space error of error_px pixels (nodes outside the frustum
    // stay coarse) and append the stitched fans to `out` (cleared first).
    // Throws what the loader throws.
    TileFrameStats build_mesh(const Camera& camera, double error_px, MeshArrays& out);

    // The visible tiles of the last frame, as (row, col).
    const std::vector<std::pair<int, int>>& visible_tiles() const { return visible_keys_; }
    // Whether tile (r, c) is cached at any level.
    bool is_cached(int r, int c) const;

    // The coarsest level at which tile (r, c) yields the quadtree the full
    // tile would for an eye at `eye` and Röttger's c (0 without roughness).
    int needed_level(int r, int c, const glm::dvec3& eye, double c_rottger) const;

private:
    struct Tile;
    struct Pick {
        int row, col, level;
        bool inside; // ALL-INSIDE the frustum
    };
    std::uint64_t key(int r, int c, int level) const { return std::uint64_t(grid_.index(r, c)) * 32u + std::uint64_t(level); }
    std::size_t estimated_bytes(int level) const;
    Tile& acquire(const Pick& p, int done_row, TileFrameStats& stats);
    void make_room(std::size_t bytes, int done_row, TileFrameStats& stats);
    void evict(TileFrameStats& stats);

    TileGrid grid_;
    TileLoader loader_;
    std::size_t bound_;
    double C_;
    std::size_t bytes_ = 0;
    std::uint64_t frame_ = 0;
    std::list<std::uint64_t> lru_; // front = most recently used
    std::unordered_map<std::uint64_t, std::unique_ptr<Tile>> cache_;
    // Per-frame scratch, reused.
    std::vector<std::pair<int, int>> visible_keys_;
    std::vector<Pick> picks_;   // visible tiles, row-major, with their levels
    std::vector<Tile*> window_; // (2R+1)^2 window around the viewer's tile (loaded this frame)
    std::vector<int> window_level_; // level of each visible tile in the window, -1 elsewhere
    int win_r0_ = 0, win_c0_ = 0, win_w_ = 0; // the window's first tile row, column and width
};

} // namespace overflight
