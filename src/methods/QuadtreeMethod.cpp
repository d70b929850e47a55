// `quadtree`: Röttger's quadtree refined per tile over overlapping 2^n+1 tiles
// around the viewer, culled against the view frustum and kept in an LRU cache
// within a memory bound; the tiles come from a tile directory read lazily or
// are cut from the terrain in memory. The level-of-detail knob divides the
// screen-space error.
//
// Based on: Röttger, Heidrich, Slusallek, Seidel, "Real-Time Generation of
// Continuous Levels of Detail for Height Fields" (WSCG 1998); Zamri,
// "Real-time terrain rendering and visualization based on hierarchical method"
// (tiles, frustum culling, run-time processing).
#include "methods/MethodTable.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

namespace overflight {

namespace {

std::unique_ptr<TileSet> tiles_of(const MethodContext& c) {
    if (c.tiles) return c.tiles();
    TileGrid grid = terrain_tile_grid(c.terrain, c.settings.tile_size);
    TileLoader loader = terrain_tile_loader(c.terrain, grid);
    return std::make_unique<TileSet>(std::move(grid), std::move(loader), c.settings.cache_bytes);
}

class QuadtreeMethod final : public TerrainMethod {
public:
    explicit QuadtreeMethod(const MethodContext& c) : tiles_(tiles_of(c)), error_px_(c.settings.error_px) {}
    MethodOutputKind output_kind() const override { return MethodOutputKind::Mesh; }
    MethodOutput produce(const MethodView& view, MethodStats& stats) override {
        stats.clear();
        const auto t0 = std::chrono::steady_clock::now();
        stats.tiles = tiles_->build_mesh(view.camera, error_px_, mesh_);
        stats.add_step_since("quadtree", t0); // select, load, refine and fans together
        stats.triangles = (long long)mesh_.triangle_count();
        MethodOutput out = MethodOutput::of_mesh(mesh_);
        if (tiles_->imagery_frame().layout.present()) out.tile_imagery = &tiles_->imagery_frame();
        return out;
    }
    void scale_detail(double factor) override {
        error_px_ = std::clamp(error_px_ / factor, MethodSettings::kMinErrorPx, MethodSettings::kMaxErrorPx);
    }
    std::string detail() const override {
        char buf[32];
        std::snprintf(buf, sizeof buf, "error %.2f px", error_px_);
        return buf;
    }

private:
    std::unique_ptr<TileSet> tiles_;
    double error_px_;
    MeshArrays mesh_;
};

} // namespace

std::unique_ptr<TerrainMethod> make_quadtree_method(const MethodContext& c) {
    return std::make_unique<QuadtreeMethod>(c);
}

} // namespace overflight
