// Based on: CMSC 23700 project 2a sec. 5 and 5.1 (split-only ROAM, forced splits of Fig. 5,
// priority buckets, view wedge, vehicle focus); Duchaineau et al. 1997 sec. 4,
// 6 and 7.
#include "lod/RoamMesh.h"

#include "core/BitCast.h"
#include "core/Error.h"
#include "core/Parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace overflight {

namespace {

// Bucket scale: the float bit pattern >> 16 keeps the exponent and the top 7
// mantissa bits, a piecewise-linear log2 with 128 steps per octave; no log()
// per triangle.
constexpr float kLeastError = 1.0f / 1024.0f;
const std::uint32_t kLeastKey = bit_cast<std::uint32_t>(kLeastError) >> 16;

// A hint that a line will be read soon. The rebuild waits mostly on loads of
// nodes, heights and variance bounds at random places; issuing them together
// before they are needed lets the misses overlap.
inline void prefetch(const void* p) { __builtin_prefetch(p); }

// Software pipeline over the top bucket (RoamMesh::prefetch_ahead): the
// stack depths below the top at which a queued node, then what its split
// reads of its own, then its base neighbour's share are requested. Each stage
// reads only lines the previous stage asked for a few splits earlier.
constexpr std::size_t kNodeAhead = 10, kOwnAhead = 6, kMidAhead = 3;

} // namespace

int roam_bucket(float error_px) {
    if (!(error_px > kLeastError)) return 1;
    const std::uint32_t key = bit_cast<std::uint32_t>(error_px) >> 16;
    return int(std::min<std::uint32_t>(key - kLeastKey + 1, kRoamBuckets - 2));
}

int roam_scale_budget(int budget, int steps) {
    const double b = std::max(budget, 1);
    const long k = std::clamp(std::lround(2.0 * std::log2(b)) + steps, 12L, 44L);
    return int(std::lround(std::exp2(double(k) / 2.0)));
}

RoamMesh::RoamMesh(const Terrain& terrain, const RoamOptions& options) : terrain_(&terrain) {
    if (options.variance_depth < 0 || options.variance_depth > RoamOptions::kMaxVarianceDepth)
        throw Error("roam", "variance depth " + std::to_string(options.variance_depth) + " is outside 0.." +
                                std::to_string(RoamOptions::kMaxVarianceDepth));
    if (terrain.rows() != terrain.cols() || !is_pow2_plus1(terrain.rows())) {
        padded_ = true;
        padded_copy_ = pad_to_pow2_plus1(terrain);
    }
    if (grid().rows() < 3) throw Error("roam", "terrain needs at least 3x3 samples");
    // Vertices keep row and column in 16 bits.
    if (grid().rows() > 32769)
        throw Error("roam", "grid of " + std::to_string(grid().rows()) + "^2 samples is above 32769^2");
    variance_ = RoamVarianceTree(grid(), options.variance_depth);
    size_ = grid().rows();
    finest_ = variance_.finest_level();
    domain_rows_ = terrain.rows();
    domain_cols_ = terrain.cols();
    min_y_ = grid().min_height();
    max_y_ = grid().max_height();
    // A level-L triangle's hypotenuse is (size-1) * sqrt(2) / sqrt(2)^L cells;
    // every point of the triangle lies within half of it from its midpoint.
    radius_.resize(std::size_t(finest_) + 1);
    for (int level = 0; level <= finest_; ++level)
        radius_[std::size_t(level)] =
            float(0.5 * grid().h_scale() * double(size_ - 1) * std::sqrt(2.0) / std::pow(std::sqrt(2.0), level));
    buckets_.resize(kRoamBuckets);
    // Inside the terrain its own normals and colors; padding samples (reached
    // only by border-straddling triangles) take the padded copy's.
    attributes_.resize(std::size_t(size_) * std::size_t(size_));
    parallel::for_each_index(0, size_, [&](int row) {
        for (int col = 0; col < size_; ++col) {
            const Terrain& src = (row < domain_rows_ && col < domain_cols_) ? terrain : grid();
            const glm::vec3 n = src.sample_normal(row, col);
            attributes_[std::size_t(row) * std::size_t(size_) + std::size_t(col)] = {
                src.color(row, col), 0, std::int16_t(std::lround(n.x * 32767.0f)),
                std::int16_t(std::lround(n.z * 32767.0f))};
        }
    });
}

void RoamMesh::reserve_for(int budget) {
    // Without padding the leaves are the output triangles (<= budget) and a
    // binary forest of L leaves has 2L - 2 nodes; the slack covers leaves in
    // the padding and the deepest forced-split chain. A split adds one vertex
    // and at least two nodes.
    const std::size_t cap = 2 * std::size_t(budget) + std::size_t(budget) / 2 + 64 * std::size_t(finest_ + 2);
    if (cap > nodes_.size()) {
        nodes_ = decltype(nodes_)(cap);
        split_bits_.assign((cap + 63) / 64, 0);
        vertices_.assign(cap / 2 + 4, Vertex{});
    }
}

std::uint32_t RoamMesh::add_vertex(std::int32_t row, std::int32_t col) {
    const double hs = grid().h_scale();
    Vertex& v = vertices_[vertex_count_];
    v.row = std::uint16_t(row);
    v.col = std::uint16_t(col);
    v.raw = heights_[std::size_t(row) * std::size_t(size_) + std::size_t(col)];
    v.outcode = wedge_.outcode({hs * col, hs * row});
    return std::uint32_t(vertex_count_++);
}

bool RoamMesh::outside_domain(Rc a, Rc b, Rc c) const {
    // The padding is col > cols-1 or row > rows-1. Conservative: a triangle in
    // neither strip alone counts as inside (it is output, never lost).
    return std::min({a.col, b.col, c.col}) >= domain_cols_ - 1 || std::min({a.row, b.row, c.row}) >= domain_rows_ - 1;
}

bool RoamMesh::straddles_domain(Rc a, Rc b, Rc c) const {
    return std::max({a.col, b.col, c.col}) > domain_cols_ - 1 || std::max({a.row, b.row, c.row}) > domain_rows_ - 1;
}

int RoamMesh::split_delta(Rc a, Rc v0, Rc v1, bool outside) const {
    if (outside) return 0;
    if (!padded_) return 1;
    const Rc m{(v0.row + v1.row) / 2, (v0.col + v1.col) / 2};
    return int(!outside_domain(m, a, v0)) + int(!outside_domain(m, v1, a)) - 1;
}

int RoamMesh::chain_cost(std::int32_t t) const {
    const Node& T = nodes_[std::size_t(t)];
    int cost = split_delta(rc(T.v[0]), rc(T.v[1]), rc(T.v[2]), T.flags() & kOutside);
    const std::int32_t b = T.nb[1];
    if (b < 0) return cost;
    const Node& B = nodes_[std::size_t(b)];
    if (B.nb[1] == t) return cost + split_delta(rc(B.v[0]), rc(B.v[1]), rc(B.v[2]), B.flags() & kOutside);
    // B is one level coarser (Fig. 5): it splits first, then its child that
    // faces T splits together with T.
    const Rc a = rc(B.v[0]), v0 = rc(B.v[1]), v1 = rc(B.v[2]);
    const Rc m{(v0.row + v1.row) / 2, (v0.col + v1.col) / 2};
    const bool facing0 = B.nb[0] == t;
    const Rc c0 = m, c1 = facing0 ? a : v1, c2 = facing0 ? v0 : a;
    const bool child_outside = (B.flags() & kOutside) || (padded_ && outside_domain(c0, c1, c2));
    return cost + chain_cost(b) + split_delta(c0, c1, c2, child_outside);
}

void RoamMesh::init_node(Node& n, int level, std::uint32_t var_node, unsigned inherited, float parent_error) const {
    // Fields are computed first and written once each, whole (see split_pair).
    unsigned flags = 0;
    float error = 0;
    const Vertex& a = vertices_[n.v[0]];
    const Vertex& b = vertices_[n.v[1]];
    const Vertex& c = vertices_[n.v[2]];
    if (inherited & kOutside) {
        flags = kOutside;
    } else {
        if ((inherited & kStraddle) && padded_) {
            const Rc ra{a.row, a.col}, rb{b.row, b.col}, rcc{c.row, c.col};
            if (outside_domain(ra, rb, rcc))
                flags = kOutside;
            else if (straddles_domain(ra, rb, rcc))
                flags = kStraddle;
        }
        if (!(flags & kOutside)) error = priority(a, b, c, level, var_node, inherited, parent_error, flags);
    }
    n.error = error;
    n.bits = Node::pack(var_node, level, flags);
}

float RoamMesh::priority(const Vertex& a, const Vertex& b, const Vertex& c, int level, std::uint32_t var_node,
                         unsigned inherited, float parent_error, unsigned& flags) const {
    if ((inherited & kFocus) && focus_) {
        // Inclusive point-in-triangle in grid units, either winding.
        const double hs = grid().h_scale();
        const double px = focus_->x / hs, pz = focus_->y / hs;
        auto edge = [&](const Vertex& p, const Vertex& q) {
            return (double(q.col) - p.col) * (pz - p.row) - (double(q.row) - p.row) * (px - p.col);
        };
        const double e0 = edge(a, b), e1 = edge(b, c), e2 = edge(c, a);
        if ((e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0)) flags |= kFocus;
    }
    if ((inherited & kInvisible) || RoamViewWedge::outside(a.outcode, b.outcode, c.outcode)) {
        flags |= kInvisible;
        return 0; // nothing of it reaches the screen
    }
    if (level >= finest_) return 0; // half cells are exact
    // The hypotenuse midpoint, from the eye.
    const float mx = half_hs_ * float(b.col + c.col) - eye_x_;
    const float mz = half_hs_ * float(b.row + c.row) - eye_z_;
    const float my = half_vs_ * float(b.raw + c.raw) + y_offset_ - eye_y_;
    return roam_projected_error(variance_.world(var_node), mx, my, mz, radius_[std::size_t(level)], near_, focal_px_,
                                parent_error);
}

void RoamMesh::enqueue(std::int32_t t, const Node& n) {
    if (int(n.level()) >= finest_ || (n.flags() & kOutside)) return;
    int b;
    if (n.flags() & kFocus)
        b = kRoamBuckets - 1;
    else if (n.flags() & kInvisible)
        return; // minimum priority: split only when forced
    else if (n.flags() & kStraddle)
        b = kRoamBuckets - 1;
    else
        b = roam_bucket(n.error);
    // A node queued at the top is popped next (LIFO): its split is prepared
    // now, while its base neighbour, just relinked, is still in cache.
    if (b >= max_bucket_) prefetch_split(t, n);
    buckets_[std::size_t(b)].push_back(t);
    max_bucket_ = std::max(max_bucket_, b);
}

void RoamMesh::prefetch_split(std::int32_t t, const Node& n) const {
    // What splitting t reads: its neighbours (base and relinked outer ones),
    // the height at its hypotenuse midpoint (the new vertex) and its
    // children's bounds; and, t's base neighbour being in cache, what
    // splitting that one along with t reads.
    for (const std::int32_t x : n.nb)
        if (x >= 0) prefetch(&nodes_[std::size_t(x)]);
    const Vertex& v0 = vertices_[n.v[1]];
    const Vertex& v1 = vertices_[n.v[2]];
    prefetch(&heights_[midpoint_sample(v0, v1)]);
    const bool stored = int(n.level()) < variance_.stored_depth();
    if (stored) prefetch(variance_.data() + 2 * n.var_node());
    if (n.nb[1] < 0) return;
    const Node& b = nodes_[std::size_t(n.nb[1])];
    if (b.nb[1] != t) return;
    if (b.nb[0] >= 0) prefetch(&nodes_[std::size_t(b.nb[0])]);
    if (b.nb[2] >= 0) prefetch(&nodes_[std::size_t(b.nb[2])]);
    if (stored) prefetch(variance_.data() + 2 * b.var_node());
}

void RoamMesh::prefetch_ahead(const std::vector<std::int32_t>& bucket) const {
    // Entries split by force since they were queued (most entries at large
    // budgets) are dropped when popped and need nothing.
    const std::size_t n = bucket.size();
    if (n > kNodeAhead && !is_split(bucket[n - 1 - kNodeAhead]))
        prefetch(&nodes_[std::size_t(bucket[n - 1 - kNodeAhead])]);
    if (n > kOwnAhead && !is_split(bucket[n - 1 - kOwnAhead])) {
        const std::int32_t t = bucket[n - 1 - kOwnAhead];
        const Node& N = nodes_[std::size_t(t)];
        for (const std::int32_t x : N.nb)
            if (x >= 0) prefetch(&nodes_[std::size_t(x)]);
        for (const std::uint32_t v : N.v) prefetch(&vertices_[v]);
        if (int(N.level()) < variance_.stored_depth()) prefetch(variance_.data() + 2 * N.var_node());
    }
    if (n > kMidAhead && !is_split(bucket[n - 1 - kMidAhead])) {
        const std::int32_t t = bucket[n - 1 - kMidAhead];
        const Node& N = nodes_[std::size_t(t)];
        const Vertex& v0 = vertices_[N.v[1]];
        const Vertex& v1 = vertices_[N.v[2]];
        prefetch(&heights_[midpoint_sample(v0, v1)]);
        if (N.nb[1] >= 0) {
            const Node& B = nodes_[std::size_t(N.nb[1])];
            if (B.nb[1] == t) {
                if (B.nb[0] >= 0) prefetch(&nodes_[std::size_t(B.nb[0])]);
                if (B.nb[2] >= 0) prefetch(&nodes_[std::size_t(B.nb[2])]);
                prefetch(&vertices_[B.v[0]]);
                if (int(B.level()) < variance_.stored_depth()) prefetch(variance_.data() + 2 * B.var_node());
            }
        }
    }
    if (n > 0 && !is_split(bucket.back())) prefetch(&nodes_[std::size_t(bucket.back())]);
}

void RoamMesh::make_children(std::int32_t t, std::int32_t c, std::uint32_t m, std::int32_t across) {
    // Fields of T are read one by one and new nodes written field by field,
    // never copied whole: a load of a word after narrower stores into it
    // would wait for every older store, the relinks' cache misses included,
    // to reach the cache.
    Node& T = nodes_[std::size_t(t)];
    const std::uint32_t apex = T.v[0], v0 = T.v[1], v1 = T.v[2];
    const std::int32_t n0 = T.nb[0], n2 = T.nb[2];
    const std::uint32_t bits = T.bits;
    const float error = T.error;
    // Child 0 = (m, apex, v0), child 1 = (m, v1, apex). Across the halves of
    // the hypotenuse, child 0 meets the partner's child 1 and child 1 meets
    // the partner's child 0 (`across`).
    Node& c0 = nodes_[std::size_t(c)];
    Node& c1 = nodes_[std::size_t(c) + 1];
    c0.v = {m, apex, v0};
    c0.nb = {c + 1, n0, across >= 0 ? across + 1 : -1};
    c1.v = {m, v1, apex};
    c1.nb = {across, n2, c};
    // The outer neighbours now border a child instead of T.
    auto relink = [&](std::int32_t n, std::int32_t to) {
        if (n < 0) return;
        for (auto& x : nodes_[std::size_t(n)].nb)
            if (x == t) {
                x = to;
                return;
            }
    };
    relink(n0, c);
    relink(n2, c + 1);
    T.bits = bits | std::uint32_t(kSplit) << 27;
    split_bits_[std::size_t(t) >> 6] |= std::uint64_t(1) << (t & 63);
    T.first_child = c;
    const Node parent{{}, {}, error, bits};
    const int level = parent.level() + 1;
    const unsigned flags = parent.flags();
    const bool deeper = parent.level() < variance_.stored_depth();
    const std::uint32_t var = parent.var_node();
    init_node(c0, level, deeper ? 2 * var : var, flags, error);
    init_node(c1, level, deeper ? 2 * var + 1 : var, flags, error);
    count_ += int(!(c0.flags() & kOutside)) + int(!(c1.flags() & kOutside)) - int(!(flags & kOutside));
    ++splits_;
}

void RoamMesh::split_pair(std::int32_t t, std::int32_t b) {
    const Vertex& v0 = vertices_[nodes_[std::size_t(t)].v[1]];
    const Vertex& v1 = vertices_[nodes_[std::size_t(t)].v[2]];
    const std::uint32_t m = add_vertex((v0.row + v1.row) / 2, (v0.col + v1.col) / 2);
    const std::int32_t c = std::int32_t(node_count_), d = c + 2;
    node_count_ += b >= 0 ? 4 : 2; // within the reserved pool: no allocation
    make_children(t, c, m, b >= 0 ? d : -1);
    if (b >= 0) {
        make_children(b, d, m, c);
        enqueue(d, nodes_[std::size_t(d)]);
        enqueue(d + 1, nodes_[std::size_t(d) + 1]);
        ++forced_;
    }
    enqueue(c, nodes_[std::size_t(c)]);
    enqueue(c + 1, nodes_[std::size_t(c) + 1]);
}

void RoamMesh::split(std::int32_t t, bool forced) {
    std::int32_t b = nodes_[std::size_t(t)].nb[1];
    if (b >= 0 && nodes_[std::size_t(b)].nb[1] != t) {
        // Fig. 5: the base neighbour is coarser; splitting it makes one of its
        // children T's base neighbour at T's own level.
        split(b, true);
        b = nodes_[std::size_t(t)].nb[1];
    }
    if (forced) ++forced_;
    split_pair(t, b);
}

RoamStats RoamMesh::tessellate(const Camera& camera, int budget, std::optional<glm::dvec2> focus) {
    camera.validate();
    if (budget < 2) throw Error("triangle budget", std::to_string(budget) + " is below 2");
    reserve_for(budget);
    std::fill(split_bits_.begin(), split_bits_.begin() + std::ptrdiff_t((node_count_ + 63) / 64), 0);
    node_count_ = vertex_count_ = 0;
    for (auto& bucket : buckets_) bucket.clear();
    max_bucket_ = 0;
    count_ = 0;
    splits_ = forced_ = 0;
    camera_ = camera;
    eye_x_ = float(camera.eye.x);
    eye_y_ = float(camera.eye.y);
    eye_z_ = float(camera.eye.z);
    focal_px_ = float(camera.focal_px());
    half_hs_ = 0.5f * grid().h_scale();
    half_vs_ = 0.5f * grid().v_scale();
    y_offset_ = grid().y_offset();
    near_ = float(camera.near);
    heights_ = grid().heights().data();
    wedge_ = RoamViewWedge::from_camera(camera, min_y_, max_y_);
    focus_ = focus;

    const std::int32_t n = size_ - 1;
    const std::uint32_t nw = add_vertex(0, 0), ne = add_vertex(0, n), sw = add_vertex(n, 0), se = add_vertex(n, n);
    node_count_ = 2;
    nodes_[0].v = {ne, nw, se};
    nodes_[0].nb = {-1, 1, -1};
    nodes_[1].v = {sw, se, nw};
    nodes_[1].nb = {-1, 0, -1};
    const unsigned test = kFocus | kStraddle;
    const float unbounded = std::numeric_limits<float>::max();
    for (int r = 0; r < 2; ++r) {
        init_node(nodes_[std::size_t(r)], 0, std::uint32_t(2 + r), test, unbounded);
        count_ += !(nodes_[std::size_t(r)].flags() & kOutside);
        enqueue(r, nodes_[std::size_t(r)]);
    }

    // Seed 003 sec. 5: "while (size of mesh < limit) split highest priority
    // triangle". A split whose forced chain would overshoot the budget is set
    // aside (the triangle stays a leaf for this frame) and the next one is
    // tried, so the mesh ends within one triangle of the budget. A chain adds
    // at most two triangles per level, so its cost is only worked out when
    // that many could overshoot.
    const std::size_t chain_nodes = 4 * std::size_t(finest_ + 2);
    const long long chain_bound = 2 * (finest_ + 1);
    while (count_ + 2 <= budget && node_count_ + chain_nodes <= nodes_.size()) {
        while (max_bucket_ > 0 && buckets_[std::size_t(max_bucket_)].empty()) --max_bucket_;
        if (max_bucket_ == 0) break;
        auto& bucket = buckets_[std::size_t(max_bucket_)];
        const std::int32_t t = bucket.back();
        bucket.pop_back();
        prefetch_ahead(bucket);
        if (is_split(t)) continue; // split by force since it was queued
        if (count_ + chain_bound > budget && count_ + chain_cost(t) > budget) continue; // set aside
        split(t, false);
    }

    RoamStats s;
    s.splits = splits_;
    s.forced_splits = forced_;
    s.vertices = vertex_count_;
    double sum = 0;
    indices_.resize(3 * std::size_t(count_));
    std::uint32_t* idx = indices_.data();
    for (std::size_t i = 0; i < node_count_; ++i) {
        const Node& nd = nodes_[i];
        if (nd.flags() & (kSplit | kOutside)) continue;
        idx[0] = nd.v[0];
        idx[1] = nd.v[1];
        idx[2] = nd.v[2];
        idx += 3;
        ++s.triangles;
        s.max_level = std::max(s.max_level, int(nd.level()));
        if (nd.flags() & kInvisible) continue;
        ++s.visible_triangles;
        sum += nd.error;
        s.max_error_px = std::max(s.max_error_px, double(nd.error));
    }
    s.mean_error_px = s.visible_triangles ? sum / double(s.visible_triangles) : 0.0;
    return s;
}

void RoamMesh::write_mesh(MeshArrays& out) const {
    const std::size_t nv = vertex_count_;
    out.positions.resize(nv);
    out.normals.resize(nv);
    out.colors.resize(nv);
    const Terrain& g = grid();
    const float hs = g.h_scale(), vs = g.v_scale(), y0 = g.y_offset();
    constexpr float unit = 1.0f / 32767.0f;
    // Vertices are in split order, scattered over the grid: ask for the
    // records well ahead so that their misses overlap.
    constexpr std::size_t ahead = 16;
    auto record = [&](const Vertex& v) {
        return &attributes_[std::size_t(v.row) * std::size_t(size_) + std::size_t(v.col)];
    };
    for (std::size_t i = 0; i < std::min(ahead, nv); ++i) prefetch(record(vertices_[i]));
    for (std::size_t i = 0; i < nv; ++i) {
        if (i + ahead < nv) prefetch(record(vertices_[i + ahead]));
        const Vertex& v = vertices_[i];
        out.positions[i] = {hs * float(v.col), vs * float(v.raw) + y0, hs * float(v.row)};
        const SampleAttributes& a = *record(v);
        const float nx = unit * float(a.nx), nz = unit * float(a.nz);
        out.normals[i] = {nx, std::sqrt(std::max(1.0f - nx * nx - nz * nz, 0.0f)), nz};
        out.colors[i] = a.color;
    }
    out.indices.assign(indices_.begin(), indices_.end());
}

} // namespace overflight
