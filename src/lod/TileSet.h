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

    int stride() const { return tile_size - 1; }
    std::size_t index(int r, int c) const { return std::size_t(r) * std::size_t(tile_cols) + std::size_t(c); }
    bool present(int r, int c) const {
        return r >= 0 && c >= 0 && r < tile_rows && c < tile_cols && exists[index(r, c)] != 0;
    }
    double tile_world_size() const { return double(h_scale) * stride(); }
    int padded_rows() const { return tile_rows * stride() + 1; }
    int padded_cols() const { return tile_cols * stride() + 1; }
    // Throws Error(subject, ...) when sizes or vectors are inconsistent.
    void validate(const std::string& subject) const;
};

// What a loader returns for one tile: tile_size^2 samples (heights, colors,
// the grid's scales) and optionally one normal per sample (empty: computed
// from the tile's own samples, one-sided on its border, which shows a
// lighting seam where tiles meet).
struct TileSamples {
    Terrain samples;
    std::vector<glm::vec3> normals;
};
using TileLoader = std::function<TileSamples(int tile_row, int tile_col)>;

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
// Error("--tile-size", ...) when tile_size is not 2^k+1 >= 3.
TileGrid terrain_tile_grid(const Terrain& terrain, int tile_size);
// Loader that cuts tiles out of `terrain` (which must outlive it); normals
// come from Terrain::sample_normal of the whole terrain, so they agree at seams.
TileLoader terrain_tile_loader(const Terrain& terrain, const TileGrid& grid);
// The padded samples of one tile (what the loader above returns), exposed for the tiler.
TileSamples cut_tile(const Terrain& terrain, const TileGrid& grid, int tile_row, int tile_col, bool with_normals);

struct TileFrameStats {
    int candidates = 0;   // present tiles in the rings around the viewer
    int visible = 0;      // ALL-INSIDE or INTERSECT
    int culled = 0;       // ALL-OUTSIDE: neither loaded nor drawn
    int loaded = 0;       // loaded this frame (cache misses)
    int cached = 0;       // tiles in the cache after the frame
    int evicted = 0;      // dropped this frame to respect the memory bound
    int rings = 0;        // rings around the viewer's tile (1 = Zamri's 3x3)
    std::size_t cache_bytes = 0;
    std::size_t triangles = 0;
    double ms_select = 0, ms_load = 0, ms_refine = 0, ms_fans = 0;
};

class TileSet {
public:
    // memory_bound: bytes of loaded tiles (samples, normals, quadtree) the
    // cache may hold; tiles visible in the current frame are never evicted,
    // so one frame may exceed it. min_resolution is Röttger's C.
    TileSet(TileGrid grid, TileLoader loader, std::size_t memory_bound, double min_resolution = 4.0);
    ~TileSet();
    TileSet(const TileSet&) = delete;
    TileSet& operator=(const TileSet&) = delete;

    const TileGrid& grid() const { return grid_; }

    // One frame: select the tiles around the camera, cull them against its
    // frustum, load the missing ones, refine each visible tile's quadtree
    // for a screen-space error of error_px pixels (nodes outside the frustum
    // stay coarse) and append the stitched fans to `out` (cleared first).
    // Throws what the loader throws.
    TileFrameStats build_mesh(const Camera& camera, double error_px, MeshArrays& out);

    // The visible tiles of the last frame, as (row, col).
    const std::vector<std::pair<int, int>>& visible_tiles() const { return visible_keys_; }
    bool is_cached(int r, int c) const { return cache_.count(key(r, c)) != 0; }

private:
    struct Tile;
    std::uint64_t key(int r, int c) const { return std::uint64_t(grid_.index(r, c)); }
    Tile& acquire(int r, int c, TileFrameStats& stats);
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
    std::vector<bool> inside_; // per visible tile: ALL-INSIDE the frustum
    std::vector<Tile*> visible_;
    std::vector<Tile*> window_; // (2R+1)^2 window around the viewer's tile
};

} // namespace overflight
