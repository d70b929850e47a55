// `quadtree` flight method: Röttger's quadtree over overlapping tiles (257^2
// cut from the terrain in memory, or a tile directory's read lazily), tiles
// around the viewer selected and frustum-culled every frame, drawn lit and
// fogged like the full mesh.
// + / _ divide / multiply the screen-space error by sqrt 2.
//
// Based on: Zamri, seed 001 (tiles, frustum culling, Röttger et al. 1998) and
// seed 003 sec. 3.1 (+ / _ level of detail by sqrt 2).
#include "gl/FlightMethods.h"
#include "gl/StreamedFlightMethod.h"
#include "lod/TileSet.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>

namespace overflight::gl {

namespace {

// Tiles are cut from the terrain in memory when first needed; the cache keeps
// at most 1 GiB of them with their quadtrees (as `render --method quadtree`).
std::unique_ptr<TileSet> make_tiles(const Terrain& terrain) {
    TileGrid grid = terrain_tile_grid(terrain, 257);
    TileLoader loader = terrain_tile_loader(terrain, grid);
    return std::make_unique<TileSet>(std::move(grid), std::move(loader), std::size_t(1) << 30);
}

class QuadtreeFlightMethod final : public StreamedFlightMethod {
public:
    static constexpr double kDefaultErrorPx = 1.0; // as `render --method quadtree`
    static constexpr double kMinErrorPx = 0.01, kMaxErrorPx = 1000.0;

    explicit QuadtreeFlightMethod(std::unique_ptr<TileSet> tiles) : tiles_(std::move(tiles)) {}
    const char* name() const override { return "quadtree"; }

    const char* build_step() const override { return "refine"; }
    void build(const FlightView& view, MeshArrays& mesh) override { tiles_->build_mesh(view.camera, error_px_, mesh); }

    void scale_detail(double factor) override {
        error_px_ = std::clamp(error_px_ / factor, kMinErrorPx, kMaxErrorPx);
    }
    std::string detail() const override {
        char buf[32];
        std::snprintf(buf, sizeof buf, "error %.2f px", error_px_);
        return buf;
    }

private:
    std::unique_ptr<TileSet> tiles_;
    double error_px_ = kDefaultErrorPx;
};

} // namespace

std::unique_ptr<FlightMethod> make_quadtree_flight_method(const DataSet& data) {
    return std::make_unique<QuadtreeFlightMethod>(make_tiles(data.terrain));
}

std::unique_ptr<FlightMethod> make_quadtree_flight_method(std::unique_ptr<TileSet> tiles) {
    return std::make_unique<QuadtreeFlightMethod>(std::move(tiles));
}

} // namespace overflight::gl
