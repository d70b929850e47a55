// Based on: Zamri, seed 001, "Data tiling" and "Run-Time Processing"
// (viewer's tile + neighbours, frustum culling of bounding spheres, Röttger
// quadtree per tile); LRU caching so a terrain larger than memory renders.
#include "lod/TileSet.h"

#include "core/Error.h"
#include "lod/Frustum.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace overflight {

namespace {
using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}
} // namespace

void TileGrid::validate(const std::string& subject) const {
    if (!is_pow2_plus1(tile_size) || tile_size < 3)
        throw Error(subject, "tile size " + std::to_string(tile_size) + " is not 2^k+1 with k >= 1");
    if (tile_rows < 1 || tile_cols < 1 || tile_rows > 65536 || tile_cols > 65536)
        throw Error(subject, "tile grid " + std::to_string(tile_rows) + "x" + std::to_string(tile_cols) + " is empty or too large");
    if (source_rows < 2 || source_cols < 2 || source_rows > padded_rows() || source_cols > padded_cols())
        throw Error(subject, "source of " + std::to_string(source_rows) + "x" + std::to_string(source_cols) +
                                 " samples does not fit the tile grid");
    const std::size_t n = std::size_t(tile_rows) * std::size_t(tile_cols);
    if (exists.size() != n || min_height.size() != n || max_height.size() != n)
        throw Error(subject, "tile grid needs one existence flag and one height range per tile");
    if (!(h_scale > 0) || !std::isfinite(h_scale) || !std::isfinite(v_scale) || !std::isfinite(y_offset))
        throw Error(subject, "tile grid scales must be finite, the horizontal one positive");
}

TileGrid terrain_tile_grid(const Terrain& terrain, int tile_size) {
    if (!is_pow2_plus1(tile_size) || tile_size < 3)
        throw Error("--tile-size", std::to_string(tile_size) + " is not 2^k+1 (3, 5, 9, ..., 257, 513, ...)");
    const int padded = next_pow2_plus1(std::max(terrain.rows(), terrain.cols()));
    TileGrid g;
    g.tile_size = std::min(tile_size, padded);
    g.tile_rows = g.tile_cols = (padded - 1) / g.stride();
    g.source_rows = terrain.rows();
    g.source_cols = terrain.cols();
    g.h_scale = terrain.h_scale();
    g.v_scale = terrain.v_scale();
    g.y_offset = terrain.y_offset();
    const std::size_t n = std::size_t(g.tile_rows) * std::size_t(g.tile_cols);
    g.exists.assign(n, 0);
    g.min_height.assign(n, 0.0f);
    g.max_height.assign(n, 0.0f);
    const int s = g.stride();
    for (int r = 0; r < g.tile_rows; ++r)
        for (int c = 0; c < g.tile_cols; ++c) {
            // Zamri: a tile exists when it holds source data; the padding
            // alone is not worth storing or drawing.
            const int r0 = r * s, c0 = c * s;
            if (r0 >= terrain.rows() || c0 >= terrain.cols()) continue;
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
            g.min_height[g.index(r, c)] = g.v_scale * float(lo) + g.y_offset;
            g.max_height[g.index(r, c)] = g.v_scale * float(hi) + g.y_offset;
        }
    return g;
}

TileSamples cut_tile(const Terrain& terrain, const TileGrid& grid, int tile_row, int tile_col, bool with_normals) {
    const int n = grid.tile_size, s = grid.stride();
    TileSamples t{Terrain(n, n, grid.h_scale, grid.v_scale, grid.y_offset), {}};
    if (with_normals) t.normals.resize(std::size_t(n) * std::size_t(n));
    for (int i = 0; i < n; ++i) {
        const int gi = tile_row * s + i, si = std::min(gi, terrain.rows() - 1);
        for (int j = 0; j < n; ++j) {
            const int gj = tile_col * s + j, sj = std::min(gj, terrain.cols() - 1);
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
    const int n = grid.tile_size, S = grid.stride();
    const int r0 = tile_row * S, c0 = tile_col * S;
    auto raw = [&](int gi, int gj) {
        return terrain.raw(std::clamp(gi, 0, terrain.rows() - 1), std::clamp(gj, 0, terrain.cols() - 1));
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

TileLoader terrain_tile_loader(const Terrain& terrain, const TileGrid& grid) {
    return [&terrain, grid_copy = grid](int r, int c) { return cut_tile(terrain, grid_copy, r, c, true); };
}

struct TileSet::Tile {
    int row = 0, col = 0;
    TileSamples data;
    std::unique_ptr<RottgerQuadtree> quadtree;
    std::list<std::uint64_t>::iterator lru;
    std::uint64_t used_frame = 0;
    std::size_t bytes = 0;
};

TileSet::TileSet(TileGrid grid, TileLoader loader, std::size_t memory_bound, double min_resolution)
    : grid_(std::move(grid)), loader_(std::move(loader)), bound_(memory_bound), C_(min_resolution) {
    grid_.validate("tiles");
    if (!loader_) throw Error("tiles", "no tile loader");
}

TileSet::~TileSet() = default;

TileSet::Tile& TileSet::acquire(int r, int c, TileFrameStats& stats) {
    const std::uint64_t k = key(r, c);
    auto it = cache_.find(k);
    if (it != cache_.end()) {
        Tile& t = *it->second;
        lru_.splice(lru_.begin(), lru_, t.lru);
        t.used_frame = frame_;
        return t;
    }
    auto tile = std::make_unique<Tile>();
    tile->row = r;
    tile->col = c;
    tile->data = loader_(r, c);
    const Terrain& s = tile->data.samples;
    if (s.rows() != grid_.tile_size || s.cols() != grid_.tile_size)
        throw Error("tile " + std::to_string(r) + "," + std::to_string(c),
                    "loader returned " + std::to_string(s.rows()) + "x" + std::to_string(s.cols()) + " samples, expected " +
                        std::to_string(grid_.tile_size));
    if (tile->data.normals.empty()) {
        tile->data.normals.resize(s.heights().size());
        for (int i = 0; i < s.rows(); ++i)
            for (int j = 0; j < s.cols(); ++j) tile->data.normals[s.index(i, j)] = s.sample_normal(i, j);
    }
    tile->quadtree = std::make_unique<RottgerQuadtree>(tile->data.samples, tile->data.normals, r * grid_.stride(),
                                                       c * grid_.stride(), C_);
    tile->bytes = sizeof(Tile) + s.heights().size() * (sizeof(std::uint16_t) + sizeof(Rgb8) + sizeof(glm::vec3)) +
                  tile->quadtree->memory_bytes();
    tile->used_frame = frame_;
    lru_.push_front(k);
    tile->lru = lru_.begin();
    bytes_ += tile->bytes;
    ++stats.loaded;
    Tile& ref = *tile;
    cache_.emplace(k, std::move(tile));
    return ref;
}

void TileSet::evict(TileFrameStats& stats) {
    // Least recently used first; tiles of the current frame stay.
    while (bytes_ > bound_ && !lru_.empty()) {
        const std::uint64_t k = lru_.back();
        auto it = cache_.find(k);
        if (it->second->used_frame == frame_) break; // everything older is gone
        bytes_ -= it->second->bytes;
        lru_.pop_back();
        cache_.erase(it);
        ++stats.evicted;
    }
}

TileFrameStats TileSet::build_mesh(const Camera& camera, double error_px, MeshArrays& out) {
    camera.validate();
    out.clear();
    ++frame_;
    TileFrameStats stats;
    auto t0 = Clock::now();

    // The viewer's tile, then rings until `far` is covered: a tile in ring r
    // is at least (r - 1) tile widths away horizontally, so rings beyond
    // far / width + 1 cannot hold anything in front of the far plane.
    const double tw = grid_.tile_world_size();
    const int tr0 = int(std::floor(camera.eye.z / tw)), tc0 = int(std::floor(camera.eye.x / tw));
    const int max_ring = std::max(grid_.tile_rows, grid_.tile_cols) + std::max(std::abs(tr0), std::abs(tc0));
    const int R = std::clamp(int(std::ceil(camera.far / tw)) + 1, 1, max_ring);
    stats.rings = R;
    const int W = 2 * R + 1;
    window_.assign(std::size_t(W) * std::size_t(W), nullptr);
    const Frustum frustum = Frustum::from_camera(camera);
    visible_keys_.clear();
    inside_.clear();
    for (int r = std::max(tr0 - R, 0); r <= std::min(tr0 + R, grid_.tile_rows - 1); ++r)
        for (int c = std::max(tc0 - R, 0); c <= std::min(tc0 + R, grid_.tile_cols - 1); ++c) {
            if (!grid_.present(r, c)) continue;
            ++stats.candidates;
            // Bounding sphere of the tile's box (X, Z extent; Y range from the index).
            const std::size_t gi = grid_.index(r, c);
            const double y0 = grid_.min_height[gi], y1 = grid_.max_height[gi];
            const glm::dvec3 centre((c + 0.5) * tw, 0.5 * (y0 + y1), (r + 0.5) * tw);
            const double radius = std::sqrt(0.5 * tw * tw + 0.25 * (y1 - y0) * (y1 - y0));
            const Containment k = frustum.classify(centre, radius);
            if (k == Containment::AllOutside) {
                ++stats.culled;
                continue;
            }
            visible_keys_.emplace_back(r, c);
            inside_.push_back(k == Containment::AllInside);
        }
    stats.visible = int(visible_keys_.size());
    stats.ms_select = ms_since(t0);

    t0 = Clock::now();
    visible_.clear();
    for (const auto& [r, c] : visible_keys_) {
        Tile& t = acquire(r, c, stats);
        visible_.push_back(&t);
        window_[std::size_t(r - (tr0 - R)) * std::size_t(W) + std::size_t(c - (tc0 - R))] = &t;
    }
    evict(stats);
    stats.ms_load = ms_since(t0);

    // Seams: each quadtree asks its drawn edge neighbours (RottgerQuadtree).
    auto at = [&](int r, int c) -> const RottgerQuadtree* {
        const int wr = r - (tr0 - R), wc = c - (tc0 - R);
        if (wr < 0 || wc < 0 || wr >= W || wc >= W) return nullptr;
        const Tile* t = window_[std::size_t(wr) * std::size_t(W) + std::size_t(wc)];
        return t ? t->quadtree.get() : nullptr;
    };
    t0 = Clock::now();
    const double c = rottger_c(error_px, camera.focal_px(), C_);
    for (std::size_t k = 0; k < visible_.size(); ++k) {
        Tile* t = visible_[k];
        t->quadtree->set_neighbour(RottgerQuadtree::North, at(t->row - 1, t->col));
        t->quadtree->set_neighbour(RottgerQuadtree::South, at(t->row + 1, t->col));
        t->quadtree->set_neighbour(RottgerQuadtree::West, at(t->row, t->col - 1));
        t->quadtree->set_neighbour(RottgerQuadtree::East, at(t->row, t->col + 1));
        // A tile wholly inside needs no per-node frustum tests.
        t->quadtree->refine(camera.eye, c, inside_[k] ? nullptr : &frustum);
    }
    stats.ms_refine = ms_since(t0);

    t0 = Clock::now();
    for (Tile* t : visible_) stats.triangles += t->quadtree->append_fans(out);
    stats.ms_fans = ms_since(t0);

    stats.cached = int(cache_.size());
    stats.cache_bytes = bytes_;
    return stats;
}

} // namespace overflight
