#pragma once
// Run-time tile selection for overlapping (2^k+1)^2 tiles: which tiles around
// the viewer are needed, which survive frustum culling, a memory-bounded LRU
// cache of loaded tiles, and one Röttger quadtree per visible tile whose fans
// are stitched across the seams.
//
// Based on: Zamri, "Data tiling" (overlapping 2^n+1 tiles sharing
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
#include "core/TileGrid.h"
#include "core/TiledImagery.h"
#include "lod/Frustum.h"
#include "lod/RottgerQuadtree.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>
#include <list>
#include <memory>
#include <unordered_map>
#include <vector>

namespace overflight {

// Loader that cuts tiles out of `terrain` (which must outlive it); normals
// come from Terrain::sample_normal of the whole terrain, so they agree at seams.
TileLoader terrain_tile_loader(const Terrain& terrain, const TileGrid& grid);
// Fills grid.roughness from the tiles of `terrain` and sets max_level, so
// that a TileSet over terrain_tile_loader() loads far tiles reduced.
void add_tile_levels(const Terrain& terrain, TileGrid& grid);
// Röttger's measures of a tile (rottger_roughness, rottger_d2 for C =
// min_resolution, TileSet's default), for a tiler that stores them so that
// a TileSet over its directory loads far tiles reduced.
TileMeasures rottger_tile_measures(double min_resolution = 4.0);

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
    int imagery_tiles = 0;  // visible tiles shown with their imagery tiles
    int imagery_loaded = 0; // imagery tiles loaded this frame
    double ms_imagery = 0;
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

    // Streams imagery tiles (core/TiledImagery.h) with the heights: after
    // each frame's mesh, every visible tile near enough that its imagery
    // is finer on screen than its samples' colors (the nearest point of
    // its box closer than focal_px x the texel of the level after the
    // tile's coarsest) is loaded, most recently used kept within
    // `memory_bound` bytes (beyond it the farthest visible tiles go without
    // and show their samples' colors). An empty loader turns it off.
    void set_imagery(const ImageryTileLayout& layout, TileImageryLoader loader, std::size_t memory_bound);
    // The imagery tiles of the last frame (tiles empty without imagery).
    const TileImageryFrame& imagery_frame() const { return imagery_frame_; }

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
    // Index of tile (r, c) in the window around the viewer, -1 outside it.
    std::ptrdiff_t cell(int r, int c) const;
    // The visible tiles around the camera with their levels (picks_, window_level_).
    void select(const Camera& camera, double c_rottger, const Frustum& frustum, TileFrameStats& stats);
    // Loads, refines and appends the fans of the picked tiles row by row.
    void draw(const Camera& camera, double c_rottger, const Frustum& frustum, TileFrameStats& stats, MeshArrays& out);
    // Loads the imagery of the visible tiles near the camera (set_imagery).
    void stream_imagery(const Camera& camera, TileFrameStats& stats);

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
    // Imagery tiles: LRU by tile index, front = most recently used.
    TileImageryLoader imagery_loader_;
    std::size_t imagery_bound_ = 0, imagery_bytes_ = 0;
    std::list<std::pair<std::size_t, std::shared_ptr<const TileImagery>>> imagery_lru_;
    std::unordered_map<std::size_t, decltype(imagery_lru_)::iterator> imagery_cache_;
    TileImageryFrame imagery_frame_;
};

} // namespace overflight
