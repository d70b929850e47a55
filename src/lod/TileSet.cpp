// Based on: Zamri, "Data tiling" and "Run-Time Processing"
// (viewer's tile + neighbours, frustum culling of bounding spheres, Röttger
// quadtree per tile); LRU caching so a terrain larger than memory renders.
#include "lod/TileSet.h"

#include "core/Error.h"
#include "lod/Frustum.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace overflight {

namespace {
using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}
} // namespace

TileLoader terrain_tile_loader(const Terrain& terrain, const TileGrid& grid) {
    return [&terrain, grid_copy = grid](int r, int c, int level) {
        return cut_tile(terrain, grid_copy, r, c, true, level);
    };
}

void add_tile_levels(const Terrain& terrain, TileGrid& grid) {
    grid.roughness.assign(grid.exists.size(), {});
    for (int r = 0; r < grid.tile_rows; ++r)
        for (int c = 0; c < grid.tile_cols; ++c)
            if (grid.present(r, c))
                grid.roughness[grid.index(r, c)] = rottger_roughness(cut_tile(terrain, grid, r, c, false).samples);
    grid.max_level = grid.coarsest_level();
}

TileMeasures rottger_tile_measures(double min_resolution) {
    TileMeasures m;
    m.roughness = [](const Terrain& tile) { return rottger_roughness(tile); };
    m.d2 = [min_resolution](const Terrain& tile) { return rottger_d2(tile, min_resolution); };
    m.min_resolution = min_resolution;
    return m;
}

struct TileSet::Tile {
    int row = 0, col = 0, level = 0;
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

void TileSet::set_imagery(const ImageryTileLayout& layout, TileImageryLoader loader, std::size_t memory_bound) {
    imagery_loader_ = std::move(loader);
    imagery_bound_ = memory_bound;
    imagery_lru_.clear();
    imagery_cache_.clear();
    imagery_bytes_ = 0;
    imagery_frame_ = TileImageryFrame{};
    imagery_frame_.layout = layout;
    imagery_frame_.tile_rows = grid_.tile_rows;
    imagery_frame_.tile_cols = grid_.tile_cols;
    imagery_frame_.tile_world_size = grid_.tile_world_size();
}

void TileSet::stream_imagery(const Camera& camera, TileFrameStats& stats) {
    const auto t0 = Clock::now();
    const ImageryTileLayout& l = imagery_frame_.layout;
    // Beyond this distance a pixel spans more than the texels of the level
    // after the tile's coarsest, where the shader shows the samples' colors.
    const double reach = camera.focal_px() * std::max(l.texel_x(), l.texel_z()) * double(2 << l.levels);
    const double size = grid_.tile_world_size();
    const glm::dvec3 eye = camera.eye;
    std::vector<std::pair<double, std::size_t>> wanted;
    for (const auto& [r, c] : visible_keys_) {
        const std::size_t i = grid_.index(r, c);
        const double x0 = c * size, z0 = r * size;
        const double dx = std::max({x0 - eye.x, 0.0, eye.x - (x0 + size)});
        const double dz = std::max({z0 - eye.z, 0.0, eye.z - (z0 + size)});
        const double dy = std::max({double(grid_.min_height[i]) - eye.y, 0.0, eye.y - double(grid_.max_height[i])});
        const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
        if (d < reach) wanted.emplace_back(d, i);
    }
    std::sort(wanted.begin(), wanted.end());
    imagery_frame_.tiles.clear();
    const std::size_t per_tile = l.tile_bytes();
    for (const auto& [d, i] : wanted) {
        // The nearest first, as many as the bound holds.
        if (imagery_frame_.tiles.size() * per_tile + per_tile > std::max(imagery_bound_, per_tile)) break;
        auto it = imagery_cache_.find(i);
        if (it != imagery_cache_.end()) {
            imagery_lru_.splice(imagery_lru_.begin(), imagery_lru_, it->second);
        } else {
            const int r = int(i / std::size_t(grid_.tile_cols)), c = int(i % std::size_t(grid_.tile_cols));
            auto tile = std::make_shared<const TileImagery>(imagery_loader_(r, c));
            imagery_bytes_ += tile->bytes();
            imagery_lru_.emplace_front(i, std::move(tile));
            imagery_cache_[i] = imagery_lru_.begin();
            ++stats.imagery_loaded;
        }
        imagery_frame_.tiles.push_back(imagery_lru_.front().second);
    }
    // Drop the least recently used beyond the bound (never this frame's).
    while (imagery_bytes_ > imagery_bound_ && imagery_lru_.size() > imagery_frame_.tiles.size()) {
        imagery_bytes_ -= imagery_lru_.back().second->bytes();
        imagery_cache_.erase(imagery_lru_.back().first);
        imagery_lru_.pop_back();
    }
    stats.imagery_tiles = int(imagery_frame_.tiles.size());
    stats.ms_imagery = ms_since(t0);
}

bool TileSet::is_cached(int r, int c) const {
    for (int l = 0; l <= grid_.coarsest_level(); ++l)
        if (cache_.count(key(r, c, l))) return true;
    return false;
}

int TileSet::needed_level(int r, int c, const glm::dvec3& eye, double c_rottger) const {
    const std::size_t gi = grid_.index(r, c);
    if (grid_.max_level == 0 || grid_.roughness[gi].empty()) return 0;
    // l >= distance from the eye to the tile's box for every node centre in it.
    const double tw = grid_.tile_world_size();
    const glm::dvec3 lo(c * tw, grid_.min_height[gi], r * tw), hi((c + 1) * tw, grid_.max_height[gi], (r + 1) * tw);
    const double l = glm::length(glm::max(glm::max(lo - eye, eye - hi), glm::dvec3(0.0)));
    for (int m = grid_.max_level; m >= 1; --m) {
        // Nodes of half-size 2^m are never subdivided: f >= 1 for all of them
        // (d = their edge, d2 bounded by the roughness), so samples 2^m apart suffice.
        const double d = double(2 << m) * grid_.h_scale;
        if (l >= d * C_ * std::max(c_rottger * propagated_d2_bound(grid_.roughness[gi], m, C_), 1.0)) return m;
    }
    return 0;
}

std::size_t TileSet::estimated_bytes(int level) const {
    const int n = grid_.level_size(level);
    return sizeof(Tile) + std::size_t(n) * std::size_t(n) * (sizeof(std::uint16_t) + sizeof(Rgb8) + sizeof(glm::vec3)) +
           RottgerQuadtree::matrix_bytes(n);
}

TileSet::Tile& TileSet::acquire(const Pick& p, int done_row, TileFrameStats& stats) {
    const std::uint64_t k = key(p.row, p.col, p.level);
    auto it = cache_.find(k);
    if (it != cache_.end()) {
        Tile& t = *it->second;
        lru_.splice(lru_.begin(), lru_, t.lru);
        t.used_frame = frame_;
        return t;
    }
    make_room(estimated_bytes(p.level), done_row, stats);
    auto tile = std::make_unique<Tile>();
    tile->row = p.row;
    tile->col = p.col;
    tile->level = p.level;
    tile->data = loader_(p.row, p.col, p.level);
    const Terrain& s = tile->data.samples;
    const int n = grid_.level_size(p.level);
    if (s.rows() != n || s.cols() != n)
        throw Error("tile " + std::to_string(p.row) + "," + std::to_string(p.col),
                    "loader returned " + std::to_string(s.rows()) + "x" + std::to_string(s.cols()) + " samples, expected " +
                        std::to_string(n) + " at level " + std::to_string(p.level));
    if (tile->data.normals.empty()) {
        tile->data.normals.resize(s.heights().size());
        for (int i = 0; i < s.rows(); ++i)
            for (int j = 0; j < s.cols(); ++j) tile->data.normals[s.index(i, j)] = s.sample_normal(i, j);
    }
    // A reduced tile takes the full tile's d2 when the loader has it for our
    // C, else the bound from the roughness (lod/RottgerQuadtree.h).
    const bool exact = p.level > 0 && grid_.d2_min_resolution == C_ && tile->data.d2.size() == s.heights().size();
    const double finer_d2 =
        p.level > 0 && !exact ? propagated_d2_bound(grid_.roughness[grid_.index(p.row, p.col)], p.level - 1, C_) : 0.0;
    tile->quadtree = std::make_unique<RottgerQuadtree>(tile->data.samples, tile->data.normals, p.row * grid_.stride(),
                                                       p.col * grid_.stride(), C_, 1 << p.level, finer_d2,
                                                       exact ? &tile->data.d2 : nullptr);
    tile->data.d2 = {}; // only needed to build the matrix
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

void TileSet::make_room(std::size_t bytes, int done_row, TileFrameStats& stats) {
    // Least recently used first: tiles of earlier frames, then this frame's
    // tiles in the (row-major) order they were drawn, as long as their rows
    // are done (no fan of a later row asks them about the seam any more).
    while (bytes_ + bytes > bound_ && !lru_.empty()) {
        const std::uint64_t k = lru_.back();
        auto it = cache_.find(k);
        Tile& t = *it->second;
        if (t.used_frame == frame_) {
            if (t.row > done_row) break;
            window_[std::size_t(t.row - win_r0_) * std::size_t(win_w_) + std::size_t(t.col - win_c0_)] = nullptr;
            ++stats.streamed;
        } else {
            ++stats.evicted;
        }
        bytes_ -= t.bytes;
        lru_.pop_back();
        cache_.erase(it);
    }
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

std::ptrdiff_t TileSet::cell(int r, int c) const {
    const int wr = r - win_r0_, wc = c - win_c0_;
    if (wr < 0 || wc < 0 || wr >= win_w_ || wc >= win_w_) return -1;
    return std::ptrdiff_t(wr) * win_w_ + wc;
}

void TileSet::select(const Camera& camera, double c_rottger, const Frustum& frustum, TileFrameStats& stats) {
    // The viewer's tile, then rings until `far` is covered: a tile in ring r
    // is at least (r - 1) tile widths away horizontally, so rings beyond
    // far / width + 1 cannot hold anything in front of the far plane.
    const double tw = grid_.tile_world_size();
    const int tr0 = int(std::floor(camera.eye.z / tw)), tc0 = int(std::floor(camera.eye.x / tw));
    const int max_ring = std::max(grid_.tile_rows, grid_.tile_cols) + std::max(std::abs(tr0), std::abs(tc0));
    const int R = std::clamp(int(std::ceil(camera.far / tw)) + 1, 1, max_ring);
    stats.rings = R;
    win_r0_ = tr0 - R;
    win_c0_ = tc0 - R;
    win_w_ = 2 * R + 1;
    const std::size_t cells = std::size_t(win_w_) * std::size_t(win_w_);
    window_.assign(cells, nullptr);
    window_level_.assign(cells, -1);
    visible_keys_.clear();
    picks_.clear();
    for (int r = std::max(tr0 - R, 0); r <= std::min(tr0 + R, grid_.tile_rows - 1); ++r)
        for (int c2 = std::max(tc0 - R, 0); c2 <= std::min(tc0 + R, grid_.tile_cols - 1); ++c2) {
            if (!grid_.present(r, c2)) continue;
            ++stats.candidates;
            // Bounding sphere of the tile's box (X, Z extent; Y range from the index).
            const std::size_t gi = grid_.index(r, c2);
            const double y0 = grid_.min_height[gi], y1 = grid_.max_height[gi];
            const glm::dvec3 centre((c2 + 0.5) * tw, 0.5 * (y0 + y1), (r + 0.5) * tw);
            const double radius = std::sqrt(0.5 * tw * tw + 0.25 * (y1 - y0) * (y1 - y0));
            const Containment k = frustum.classify(centre, radius);
            if (k == Containment::AllOutside) {
                ++stats.culled;
                continue;
            }
            const int level = needed_level(r, c2, camera.eye, c_rottger);
            visible_keys_.emplace_back(r, c2);
            picks_.push_back({r, c2, level, k == Containment::AllInside});
            window_level_[std::size_t(cell(r, c2))] = level;
        }
    // Neighbours differ by at most one level, as nodes do inside a tile with
    // Röttger's d2 propagation: a finer tile's seam follows its coarser
    // neighbour's vertices (lod/RottgerQuadtree.h), so a larger difference
    // would coarsen the finer tile along the whole seam.
    for (bool changed = true; changed;) {
        changed = false;
        for (Pick& p : picks_) {
            int& level = window_level_[std::size_t(cell(p.row, p.col))];
            for (const auto& [dr, dc] : {std::pair{-1, 0}, std::pair{1, 0}, std::pair{0, -1}, std::pair{0, 1}}) {
                const std::ptrdiff_t i = cell(p.row + dr, p.col + dc);
                const int nl = i < 0 ? -1 : window_level_[std::size_t(i)];
                if (nl >= 0 && level > nl + 1) {
                    level = nl + 1;
                    changed = true;
                }
            }
            p.level = level;
        }
    }
    for (Pick& p : picks_) {
        // A finer level already in the cache serves as well, without I/O.
        for (int l = p.level; l >= 0; --l)
            if (cache_.count(key(p.row, p.col, l))) {
                p.level = l;
                break;
            }
        window_level_[std::size_t(cell(p.row, p.col))] = p.level;
        ++stats.per_level[std::size_t(p.level)];
    }
}

void TileSet::draw(const Camera& camera, double c_rottger, const Frustum& frustum, TileFrameStats& stats,
                   MeshArrays& out) {
    // Row by row: a row's fans ask its neighbours about the seams, so the
    // rows above and below must be loaded and refined; once a row is drawn,
    // the row above it is done and may be evicted if the bound requires it.
    auto at = [&](int r, int c2) -> const RottgerQuadtree* {
        const std::ptrdiff_t i = cell(r, c2);
        const Tile* t = i < 0 ? nullptr : window_[std::size_t(i)];
        return t ? t->quadtree.get() : nullptr;
    };
    auto seam_ratio = [&](int level, int r, int c2) {
        const std::ptrdiff_t i = cell(r, c2);
        const int nl = i < 0 ? -1 : window_level_[std::size_t(i)];
        return nl > level ? 1 << (nl - level) : 1;
    };
    std::size_t next = 0;
    auto load_through = [&](int row, int done_row) {
        for (; next < picks_.size() && picks_[next].row <= row; ++next) {
            const Pick& p = picks_[next];
            auto t1 = Clock::now();
            Tile& t = acquire(p, done_row, stats);
            window_[std::size_t(cell(p.row, p.col))] = &t;
            stats.ms_load += ms_since(t1);
            t1 = Clock::now();
            RottgerQuadtree& q = *t.quadtree;
            q.set_seam_ratio(RottgerQuadtree::North, seam_ratio(p.level, p.row - 1, p.col));
            q.set_seam_ratio(RottgerQuadtree::South, seam_ratio(p.level, p.row + 1, p.col));
            q.set_seam_ratio(RottgerQuadtree::West, seam_ratio(p.level, p.row, p.col - 1));
            q.set_seam_ratio(RottgerQuadtree::East, seam_ratio(p.level, p.row, p.col + 1));
            // A tile wholly inside needs no per-node frustum tests.
            q.refine(camera.eye, c_rottger, p.inside ? nullptr : &frustum);
            stats.ms_refine += ms_since(t1);
        }
    };
    for (std::size_t k = 0; k < picks_.size();) {
        const int row = picks_[k].row;
        load_through(row + 1, row - 2);
        const auto t1 = Clock::now();
        for (; k < picks_.size() && picks_[k].row == row; ++k) {
            const Pick& p = picks_[k];
            RottgerQuadtree& q = *window_[std::size_t(cell(p.row, p.col))]->quadtree;
            q.set_neighbour(RottgerQuadtree::North, at(p.row - 1, p.col));
            q.set_neighbour(RottgerQuadtree::South, at(p.row + 1, p.col));
            q.set_neighbour(RottgerQuadtree::West, at(p.row, p.col - 1));
            q.set_neighbour(RottgerQuadtree::East, at(p.row, p.col + 1));
            stats.triangles += q.append_fans(out);
            // With imagery tiles, each vertex names its tile (MeshArrays::tiles).
            if (imagery_loader_)
                out.tiles.resize(out.positions.size(), (std::uint32_t(p.row) << 16) | std::uint32_t(p.col));
        }
        stats.ms_fans += ms_since(t1);
    }
}

TileFrameStats TileSet::build_mesh(const Camera& camera, double error_px, MeshArrays& out) {
    camera.validate();
    out.clear();
    ++frame_;
    TileFrameStats stats;
    stats.per_level.assign(std::size_t(grid_.coarsest_level() + 1), 0);
    const double c_rottger = rottger_c(error_px, camera.focal_px(), C_);
    const Frustum frustum = Frustum::from_camera(camera);
    const auto t0 = Clock::now();
    select(camera, c_rottger, frustum, stats);
    stats.visible = int(picks_.size());
    stats.ms_select = ms_since(t0);
    draw(camera, c_rottger, frustum, stats, out);
    evict(stats);
    if (imagery_loader_) stream_imagery(camera, stats);

    stats.cached = int(cache_.size());
    stats.cache_bytes = bytes_;
    return stats;
}

} // namespace overflight
