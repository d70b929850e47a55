// Based on: seed 003 sec. 5 and 5.1 (split-only ROAM, forced splits of Fig. 5,
// priority buckets, view wedge, vehicle focus); Duchaineau et al. 1997 sec. 4,
// 6 and 7.
#include "lod/RoamMesh.h"

#include "core/Error.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <string>

namespace overflight {

namespace {

// Bucket scale: the float bit pattern >> 16 keeps the exponent and the top 7
// mantissa bits, a piecewise-linear log2 with 128 steps per octave; no log()
// per triangle.
constexpr float kLeastError = 1.0f / 1024.0f;
const std::uint32_t kLeastKey = std::bit_cast<std::uint32_t>(kLeastError) >> 16;

inline double sq(double v) { return v * v; }

} // namespace

int roam_bucket(float error_px) {
    if (!(error_px > kLeastError)) return 1;
    const std::uint32_t key = std::bit_cast<std::uint32_t>(error_px) >> 16;
    return int(std::min<std::uint32_t>(key - kLeastKey + 1, kRoamBuckets - 2));
}

int roam_scale_budget(int budget, int steps) {
    const double b = std::max(budget, 1);
    const long k = std::clamp(std::lround(2.0 * std::log2(b)) + steps, 12L, 44L);
    return int(std::lround(std::exp2(double(k) / 2.0)));
}

RoamMesh::RoamMesh(const Terrain& terrain, const RoamOptions& options) : terrain_(&terrain) {
    if (terrain.rows() != terrain.cols() || !is_pow2_plus1(terrain.rows())) {
        padded_ = true;
        padded_copy_ = pad_to_pow2_plus1(terrain);
    }
    if (grid().rows() < 3) throw Error("roam", "terrain needs at least 3x3 samples");
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
    heads_.assign(kRoamBuckets, -1);
}

void RoamMesh::reserve_for(int budget) {
    // Without padding the leaves are the output triangles (<= budget) and a
    // binary forest of L leaves has 2L - 2 nodes; the slack covers leaves in
    // the padding and the deepest forced-split chain.
    const std::size_t cap = 2 * std::size_t(budget) + std::size_t(budget) / 2 + 64 * std::size_t(finest_ + 2);
    if (cap > capacity_) {
        nodes_.reserve(cap);
        vertices_.reserve(cap);
        capacity_ = cap;
    }
}

std::uint32_t RoamMesh::add_vertex(std::int32_t row, std::int32_t col) {
    vertices_.push_back({row, col, grid().sample_height(row, col)});
    return std::uint32_t(vertices_.size() - 1);
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
    int cost = split_delta(rc(T.v[0]), rc(T.v[1]), rc(T.v[2]), T.flags & kOutside);
    const std::int32_t b = T.nb[1];
    if (b < 0) return cost;
    const Node& B = nodes_[std::size_t(b)];
    if (B.nb[1] == t) return cost + split_delta(rc(B.v[0]), rc(B.v[1]), rc(B.v[2]), B.flags & kOutside);
    // B is one level coarser (Fig. 5): it splits first, then its child that
    // faces T splits together with T.
    const Rc a = rc(B.v[0]), v0 = rc(B.v[1]), v1 = rc(B.v[2]);
    const Rc m{(v0.row + v1.row) / 2, (v0.col + v1.col) / 2};
    const bool facing0 = B.nb[0] == t;
    const Rc c0 = m, c1 = facing0 ? a : v1, c2 = facing0 ? v0 : a;
    const bool child_outside = (B.flags & kOutside) || (padded_ && outside_domain(c0, c1, c2));
    return cost + chain_cost(b) + split_delta(c0, c1, c2, child_outside);
}

void RoamMesh::init_node(Node& n, int level, std::uint32_t var_node, std::uint8_t inherited, float parent_error) {
    n.child = -1;
    n.var_node = var_node;
    n.prev = n.next = -1;
    n.bucket = 0;
    n.level = std::uint8_t(level);
    n.flags = 0;
    n.error = 0;
    const Vertex& a = vertices_[n.v[0]];
    const Vertex& b = vertices_[n.v[1]];
    const Vertex& c = vertices_[n.v[2]];
    if (inherited & kOutside) {
        n.flags = kOutside;
        return;
    }
    if ((inherited & kStraddle) && padded_) {
        const Rc ra{a.row, a.col}, rb{b.row, b.col}, rcc{c.row, c.col};
        if (outside_domain(ra, rb, rcc)) {
            n.flags = kOutside;
            return;
        }
        if (straddles_domain(ra, rb, rcc)) n.flags |= kStraddle;
    }
    const double hs = grid().h_scale();
    if ((inherited & kFocus) && focus_) {
        // Inclusive point-in-triangle in grid units, either winding.
        const double px = focus_->x / hs, pz = focus_->y / hs;
        auto edge = [&](const Vertex& p, const Vertex& q) {
            return (double(q.col) - p.col) * (pz - p.row) - (double(q.row) - p.row) * (px - p.col);
        };
        const double e0 = edge(a, b), e1 = edge(b, c), e2 = edge(c, a);
        if ((e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0)) n.flags |= kFocus;
    }
    if ((inherited & kInvisible) ||
        wedge_.outside({hs * a.col, hs * a.row}, {hs * b.col, hs * b.row}, {hs * c.col, hs * c.row})) {
        n.flags |= kInvisible;
        return; // error 0: nothing of it reaches the screen
    }
    if (level >= finest_) return; // half cells are exact
    // Projected error of the variance bound at the nearest point of the
    // triangle's bounding circle around its hypotenuse midpoint.
    const double mx = hs * 0.5 * (b.col + c.col), mz = hs * 0.5 * (b.row + c.row), my = 0.5 * (double(b.y) + c.y);
    const double dist = std::sqrt(sq(mx - camera_.eye.x) + sq(my - camera_.eye.y) + sq(mz - camera_.eye.z));
    const double d = std::max(dist - double(radius_[std::size_t(level)]), camera_.near);
    const double e = double(variance_.world(var_node)) * focal_px_ / d;
    n.error = std::min(float(e), parent_error);
}

void RoamMesh::enqueue(std::int32_t t) {
    Node& n = nodes_[std::size_t(t)];
    if (n.level >= finest_ || (n.flags & kOutside)) return;
    int b;
    if (n.flags & kFocus)
        b = kRoamBuckets - 1;
    else if (n.flags & kInvisible)
        return; // minimum priority: split only when forced
    else if (n.flags & kStraddle)
        b = kRoamBuckets - 1;
    else
        b = roam_bucket(n.error);
    n.bucket = std::uint16_t(b);
    n.prev = -1;
    n.next = heads_[std::size_t(b)];
    if (n.next >= 0) nodes_[std::size_t(n.next)].prev = t;
    heads_[std::size_t(b)] = t;
    max_bucket_ = std::max(max_bucket_, b);
}

void RoamMesh::dequeue(std::int32_t t) {
    Node& n = nodes_[std::size_t(t)];
    if (n.bucket == 0) return;
    if (n.prev >= 0)
        nodes_[std::size_t(n.prev)].next = n.next;
    else
        heads_[n.bucket] = n.next;
    if (n.next >= 0) nodes_[std::size_t(n.next)].prev = n.prev;
    n.bucket = 0;
    n.prev = n.next = -1;
}

std::int32_t RoamMesh::top() {
    while (max_bucket_ > 0 && heads_[std::size_t(max_bucket_)] < 0) --max_bucket_;
    return max_bucket_ > 0 ? heads_[std::size_t(max_bucket_)] : -1;
}

void RoamMesh::make_children(std::int32_t t, std::uint32_t m) {
    const std::int32_t c = std::int32_t(nodes_.size());
    nodes_.resize(nodes_.size() + 2); // within the reserved capacity: no reallocation
    Node& T = nodes_[std::size_t(t)];
    Node& c0 = nodes_[std::size_t(c)];
    Node& c1 = nodes_[std::size_t(c) + 1];
    c0.v = {m, T.v[0], T.v[1]};
    c1.v = {m, T.v[2], T.v[0]};
    c0.nb = {c + 1, T.nb[0], -1};
    c1.nb = {-1, T.nb[2], c};
    // The outer neighbours now border a child instead of T.
    auto relink = [&](std::int32_t n, std::int32_t to) {
        if (n < 0) return;
        for (auto& x : nodes_[std::size_t(n)].nb)
            if (x == t) {
                x = to;
                return;
            }
    };
    relink(T.nb[0], c);
    relink(T.nb[2], c + 1);
    T.child = c;
    dequeue(t);
    const int level = T.level + 1;
    const std::uint32_t var0 = T.level < variance_.stored_depth() ? 2 * T.var_node : T.var_node;
    const std::uint32_t var1 = T.level < variance_.stored_depth() ? 2 * T.var_node + 1 : T.var_node;
    if (!(T.flags & kOutside)) count_ -= 1;
    init_node(c0, level, var0, T.flags, T.error);
    init_node(c1, level, var1, T.flags, T.error);
    count_ += int(!(c0.flags & kOutside)) + int(!(c1.flags & kOutside));
    ++splits_;
}

void RoamMesh::split_pair(std::int32_t t, std::int32_t b) {
    const Node& T = nodes_[std::size_t(t)];
    const Vertex& v0 = vertices_[T.v[1]];
    const Vertex& v1 = vertices_[T.v[2]];
    const std::uint32_t m = add_vertex((v0.row + v1.row) / 2, (v0.col + v1.col) / 2);
    make_children(t, m);
    const std::int32_t c = nodes_[std::size_t(t)].child;
    if (b >= 0) {
        make_children(b, m);
        const std::int32_t d = nodes_[std::size_t(b)].child;
        // The halves of the common hypotenuse: T's child 0 meets B's child 1
        // and T's child 1 meets B's child 0.
        nodes_[std::size_t(c)].nb[2] = d + 1;
        nodes_[std::size_t(c) + 1].nb[0] = d;
        nodes_[std::size_t(d)].nb[2] = c + 1;
        nodes_[std::size_t(d) + 1].nb[0] = c;
        enqueue(d);
        enqueue(d + 1);
        ++forced_;
    }
    enqueue(c);
    enqueue(c + 1);
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
    if (budget < 2) throw Error("--triangles", "budget " + std::to_string(budget) + " is below 2 triangles");
    reserve_for(budget);
    nodes_.clear();
    vertices_.clear();
    std::fill(heads_.begin(), heads_.end(), -1);
    max_bucket_ = 0;
    count_ = 0;
    splits_ = forced_ = 0;
    camera_ = camera;
    focal_px_ = camera.focal_px();
    wedge_ = RoamViewWedge::from_camera(camera, min_y_, max_y_);
    focus_ = focus;

    const std::int32_t n = size_ - 1;
    const std::uint32_t nw = add_vertex(0, 0), ne = add_vertex(0, n), sw = add_vertex(n, 0), se = add_vertex(n, n);
    nodes_.resize(2);
    nodes_[0].v = {ne, nw, se};
    nodes_[0].nb = {-1, 1, -1};
    nodes_[1].v = {sw, se, nw};
    nodes_[1].nb = {-1, 0, -1};
    const std::uint8_t test = kFocus | kStraddle;
    const float unbounded = std::numeric_limits<float>::max();
    for (int r = 0; r < 2; ++r) {
        init_node(nodes_[std::size_t(r)], 0, std::uint32_t(2 + r), test, unbounded);
        count_ += !(nodes_[std::size_t(r)].flags & kOutside);
        enqueue(r);
    }

    // Seed 003 sec. 5: "while (size of mesh < limit) split highest priority
    // triangle". A split whose forced chain would overshoot the budget is set
    // aside (the triangle stays a leaf for this frame) and the next one is
    // tried, so the mesh ends within one triangle of the budget.
    const std::size_t chain_nodes = 4 * std::size_t(finest_ + 2);
    while (count_ + 2 <= budget && nodes_.size() + chain_nodes <= capacity_) {
        const std::int32_t t = top();
        if (t < 0) break;
        if (count_ + chain_cost(t) > budget) {
            dequeue(t);
            continue;
        }
        split(t, false);
    }

    RoamStats s;
    s.splits = splits_;
    s.forced_splits = forced_;
    s.vertices = vertices_.size();
    double sum = 0;
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
        if (!is_output(i)) continue;
        const Node& nd = nodes_[i];
        ++s.triangles;
        s.max_level = std::max(s.max_level, int(nd.level));
        if (nd.flags & kInvisible) continue;
        ++s.visible_triangles;
        sum += nd.error;
        s.max_error_px = std::max(s.max_error_px, double(nd.error));
    }
    s.mean_error_px = s.visible_triangles ? sum / double(s.visible_triangles) : 0.0;
    return s;
}

void RoamMesh::write_mesh(MeshArrays& out) const {
    const std::size_t nv = vertices_.size();
    out.positions.resize(nv);
    out.normals.resize(nv);
    out.colors.resize(nv);
    const float hs = grid().h_scale();
    for (std::size_t i = 0; i < nv; ++i) {
        const Vertex& v = vertices_[i];
        out.positions[i] = {hs * float(v.col), v.y, hs * float(v.row)};
        // Inside the terrain its own normals and colors; padding vertices
        // (only on border-straddling triangles) take the padded copy's.
        const Terrain& src = (v.row < domain_rows_ && v.col < domain_cols_) ? *terrain_ : padded_copy_;
        out.normals[i] = src.sample_normal(v.row, v.col);
        out.colors[i] = src.color(v.row, v.col);
    }
    out.indices.clear();
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
        if (!is_output(i)) continue;
        const Node& nd = nodes_[i];
        out.indices.insert(out.indices.end(), {nd.v[0], nd.v[1], nd.v[2]});
    }
}

} // namespace overflight
