// Based on: Zamri, seed 001 ("Run-Time Processing"); Röttger et al. 1998.
#include "QuadtreeMethod.h"

#include "core/Error.h"
#include "io/TileDirectory.h"

#include <cstdio>

namespace overflight::app {

std::size_t tile_cache_bytes(int cache_mib) {
    if (cache_mib < 1 || cache_mib > (1 << 24)) throw Error("--cache-mib", "must be in 1..16777216 MiB");
    return std::size_t(cache_mib) << 20;
}

std::unique_ptr<TileSet> tile_directory_tiles(const std::string& tile_dir, std::size_t memory_bound) {
    const TileIndex index = read_tile_index(tile_dir);
    return std::make_unique<TileSet>(index.grid, tile_directory_loader(tile_dir, index), memory_bound);
}

QuadtreeMethod::QuadtreeMethod(const DataSet& data, int tile_size, std::size_t memory_bound) {
    TileGrid grid = terrain_tile_grid(data.terrain, tile_size);
    TileLoader loader = terrain_tile_loader(data.terrain, grid);
    tiles_ = std::make_unique<TileSet>(std::move(grid), std::move(loader), memory_bound);
}

QuadtreeMethod::QuadtreeMethod(const std::string& tile_dir, std::size_t memory_bound)
    : tiles_(tile_directory_tiles(tile_dir, memory_bound)) {}

const TileFrameStats& QuadtreeMethod::build(const Camera& camera, double error_px, MeshArrays& out) {
    error_px_ = error_px;
    last_ = tiles_->build_mesh(camera, error_px, out);
    return last_;
}

std::string QuadtreeMethod::stats_json() const {
    const TileFrameStats& s = last_;
    std::string levels;
    for (std::size_t l = 0; l < s.per_level.size(); ++l) levels += (l ? "," : "") + std::to_string(s.per_level[l]);
    char buf[768];
    std::snprintf(buf, sizeof buf,
                  "{\"method\":\"quadtree\",\"triangles\":%zu,\"error_px\":%g,\"tiles_candidates\":%d,"
                  "\"tiles_visible\":%d,\"tiles_culled\":%d,\"tiles_loaded\":%d,\"tiles_cached\":%d,"
                  "\"tiles_evicted\":%d,\"tiles_streamed\":%d,\"tiles_per_level\":[%s],\"rings\":%d,"
                  "\"cache_mib\":%.1f,\"bound_mib\":%.1f,"
                  "\"ms\":{\"select\":%.3f,\"load\":%.3f,\"refine\":%.3f,\"fans\":%.3f,\"total\":%.3f}}",
                  s.triangles, error_px_, s.candidates, s.visible, s.culled, s.loaded, s.cached, s.evicted, s.streamed,
                  levels.c_str(), s.rings, double(s.cache_bytes) / (1024.0 * 1024.0),
                  double(tiles_->memory_bound()) / (1024.0 * 1024.0), s.ms_select, s.ms_load, s.ms_refine, s.ms_fans,
                  s.ms_select + s.ms_load + s.ms_refine + s.ms_fans);
    return buf;
}

} // namespace overflight::app
