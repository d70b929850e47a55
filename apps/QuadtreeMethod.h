#pragma once
// The `quadtree` terrain method of `overflight render` / `bench` (issue 6):
// a data set in memory or a tile directory + the camera + a screen-space
// error in pixels -> MeshArrays (drawn by the gl layer) and the --stats JSON.
//
// Based on: Zamri, seed 001 (tiles around the viewer, frustum culling,
// Röttger's quadtree per tile); see lod/TileSet.h and lod/RottgerQuadtree.h.
// c of Röttger's criterion is fp / (error_px * C): lod/RottgerQuadtree.h.
#include "core/Camera.h"
#include "core/DataSet.h"
#include "core/MeshArrays.h"
#include "lod/TileSet.h"

#include <memory>
#include <string>

namespace overflight::app {

// --cache-mib in bytes; throws Error("--cache-mib", ...) outside 1..2^24 MiB.
std::size_t tile_cache_bytes(int cache_mib);

// The tiles of a directory written by `overflight tile`, read lazily within
// memory_bound bytes. Throws as read_tile_index.
std::unique_ptr<TileSet> tile_directory_tiles(const std::string& tile_dir, std::size_t memory_bound);

class QuadtreeMethod {
public:
    static constexpr std::size_t default_memory_bound = std::size_t(1) << 30; // 1 GiB of loaded tiles

    // Tiles cut on demand from data.terrain (which must outlive this), tile_size 2^k+1.
    explicit QuadtreeMethod(const DataSet& data, int tile_size = 257, std::size_t memory_bound = default_memory_bound);
    // Tiles read lazily from a directory written by `overflight tile`.
    explicit QuadtreeMethod(const std::string& tile_dir, std::size_t memory_bound = default_memory_bound);

    // One frame: fills `out` and returns its statistics. Throws Error for a
    // bad camera, an error_px <= 0 ("--error") or an unreadable tile.
    const TileFrameStats& build(const Camera& camera, double error_px, MeshArrays& out);

    // {"method":"quadtree","triangles":..,"tiles_visible":..,"tiles_culled":..,
    //  "tiles_loaded":..,"tiles_cached":..,"tiles_evicted":..,"tiles_streamed":..,
    //  "tiles_per_level":[visible tiles at level 0, 1, ..],"cache_mib":..,"bound_mib":..,"error_px":..,
    //  "ms":{"select":..,"load":..,"refine":..,"fans":..,"total":..}}
    std::string stats_json() const;

    const TileSet& tiles() const { return *tiles_; }

private:
    std::unique_ptr<TileSet> tiles_;
    TileFrameStats last_;
    double error_px_ = 1.0;
};

} // namespace overflight::app
