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
#include <numeric>
#include <string>
#include <tuple>

namespace overflight {

namespace {

// Bucket scale: the float bit pattern >> 16 keeps the exponent and the top 7
// mantissa bits, a piecewise-linear log2 with 128 steps per octave; no log()
// per triangle.
constexpr float kLeastError = 1.0f / 1024.0f;
const std::uint32_t kLeastKey = bit_cast<std::uint32_t>(kLeastError) >> 16;

// roam_bucket, inlined where every split calls it.
[[gnu::always_inline]] inline int bucket_index(float error_px) {
    if (!(error_px > kLeastError)) return 1;
    const std::uint32_t key = bit_cast<std::uint32_t>(error_px) >> 16;
    return int(std::min<std::uint32_t>(key - kLeastKey + 1, kRoamBuckets - 2));
}

// A hint that a line will be read soon, so that misses overlap.
inline void prefetch(const void* p) { __builtin_prefetch(p); }

// The next frame's order-free threshold lies this many buckets (1/64 octave)
// above this frame's last bucket, so that a camera that moved a little still
// finds its order-free count within the budget (BM_RoamFlight: no frame of a
// 240-frame flight refined again; 1-4 % of the splits made in order).
constexpr int kThresholdMargin = 2;

// Leaves this many buckets (1/4 octave) or more below the threshold are not
// queued while the worklists run: the ordered loop ends a few buckets below
// the threshold, and should it go further it gathers them then.
constexpr int kWindow = 32;

// Pool chunks (see "Both cores" in RoamMesh.h). A node chunk is a whole
// number of split_bits_ words, so regions never write the same word.
constexpr std::size_t kNodeChunk = 1024;
constexpr unsigned kVertexChunkShift = 9;
constexpr std::size_t kVertexChunk = std::size_t(1) << kVertexChunkShift;

// The regions refined at once are the 128 bintree triangles of level 6, on
// grids with at least this many levels (smaller ones are refined on one
// thread). At level 4 the region around the camera held 57 % of a 262k
// frame's splits; levels 5 and 8 were slower than 6.
constexpr int kRegionLevel = 6;
constexpr int kParallelFinest = 10;

} // namespace

int roam_bucket(float error_px) { return bucket_index(error_px); }

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
    region_level_ = (finest_ >= kParallelFinest) ? std::min(kRegionLevel, variance_.stored_depth()) : 0;
    if (region_level_ < 2) region_level_ = 0;
    // The edges of the level-L triangles lie on the grid lines row or column
    // = 0 mod n / 2^floor(L/2) and the diagonals row -+ column = 0 mod
    // n / 2^floor((L-1)/2) (L = 2: both diagonals and both midlines).
    const int cells = size_ - 1;
    axis_mask_ = (cells >> (region_level_ / 2)) - 1;
    diagonal_mask_ = (cells >> ((region_level_ - 1) / 2)) - 1;
    workers_ = std::vector<Worker>(region_level_ ? (std::size_t(2) << region_level_) + 1 : 1);
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
    // and at least two nodes. Each worker may leave the end of a chunk unused.
    const std::size_t need = 2 * std::size_t(budget) + std::size_t(budget) / 2 + 64 * std::size_t(finest_ + 2);
    if (need <= node_budget_) return;
    node_budget_ = need;
    // A worker gives up a chunk with less than a forced chain's room left
    // (4 nodes per level): a quarter more covers that and the open chunks of
    // the regions in use. Should the regions run out, the frame is refined
    // again on one thread, which wastes less.
    const std::size_t chunks = (need + need / 4) / kNodeChunk + workers_.size() + 8;
    nodes_ = decltype(nodes_)(chunks * kNodeChunk);
    split_bits_.assign(nodes_.size() / 64, 0);
    node_claims_.assign(nodes_.size() / kNodeChunk, ChunkClaim{});
    chunk_leaves_.assign(nodes_.size() / kNodeChunk, LeafCount{0});
    const std::size_t vertex_chunks = (need / 2 + need / 8) / kVertexChunk + workers_.size() + 8;
    vertices_.assign(vertex_chunks * kVertexChunk, Vertex{});
    vertex_used_.assign(vertex_chunks, 0);
    vertex_claims_.assign(vertex_chunks, ChunkClaim{});
    vertex_base_.assign(vertex_chunks, 0);
}

bool RoamMesh::room(Worker& w) {
    // A forced chain adds at most 4 nodes and 1 vertex per level; chunks are
    // claimed before it starts so that it never runs out half way. Pool
    // sizes are whole chunks, so a claim fits or starts past the end.
    const std::size_t chain_nodes = 4 * std::size_t(finest_ + 2), chain_vertices = std::size_t(finest_ + 2);
    if (w.node_end - w.node_next < chain_nodes) {
        close_chunks(w, false);
        const std::size_t start = parallel::fetch_add(node_top_, kNodeChunk);
        if (start >= nodes_.size()) return false;
        node_claims_[start / kNodeChunk] = {std::uint32_t(&w - workers_.data()), w.claims++};
        chunk_leaves_[start / kNodeChunk].leaves = 0;
        w.node_next = start;
        w.node_end = start + kNodeChunk;
    }
    if (w.vertex_end - w.vertex_next < chain_vertices) {
        close_chunks(w, true);
        const std::size_t start = parallel::fetch_add(vertex_top_, kVertexChunk);
        if (start >= vertices_.size()) return false;
        vertex_claims_[start >> kVertexChunkShift] = {std::uint32_t(&w - workers_.data()), w.claims++};
        w.vertex_next = start;
        w.vertex_end = start + kVertexChunk;
    }
    return true;
}

void RoamMesh::close_chunks(Worker& w, bool vertices) {
    if (vertices) {
        if (w.vertex_end > 0) {
            const std::size_t chunk = (w.vertex_end - 1) >> kVertexChunkShift;
            vertex_used_[chunk] = std::uint32_t(w.vertex_next - (chunk << kVertexChunkShift));
        }
        w.vertex_next = w.vertex_end = 0;
        return;
    }
    for (std::size_t i = w.node_next; i < w.node_end; ++i)
        nodes_[i].bits = Node::pack(0, Node::kUnusedLevel, kSplit | kOutside);
    w.node_next = w.node_end = 0;
}

[[gnu::always_inline]] inline std::uint32_t RoamMesh::dense(std::uint32_t vid) const {
    return vertex_base_[vid >> kVertexChunkShift] + (vid & std::uint32_t(kVertexChunk - 1));
}

std::uint32_t RoamMesh::add_vertex(Worker& w, std::int32_t row, std::int32_t col) {
    const double hs = grid().h_scale();
    Vertex& v = vertices_[w.vertex_next];
    v.row = std::uint16_t(row);
    v.col = std::uint16_t(col);
    v.raw = heights_[std::size_t(row) * std::size_t(size_) + std::size_t(col)];
    v.outcode = wedge_.outcode({hs * col, hs * row});
    return std::uint32_t(w.vertex_next++);
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

[[gnu::always_inline]] inline int RoamMesh::bucket_of(const Node& n) const {
    if (n.level() >= finest_ || (n.flags() & kOutside)) return -1;
    if (n.flags() & kFocus) return kRoamBuckets - 1;
    if (n.flags() & kInvisible) return -1; // minimum priority: split only when forced
    if (n.flags() & kStraddle) return kRoamBuckets - 1;
    return bucket_index(n.error);
}

void RoamMesh::enqueue(Worker& w, std::int32_t t, const Node& n) {
    const int b = bucket_of(n);
    if (b < 0) return;
    if (b > order_free_above_) {
        // The sequential part hands what it reaches below the region level
        // to the region's worker, unless splitting it reaches another region.
        if (region_level_ && &w == &workers_.back() && n.level() >= region_level_ && !crosses(n))
            workers_[std::size_t(region_of(n))].worklist.push_back(t);
        else
            w.worklist.push_back(t);
        return;
    }
    if (b <= queue_floor_) return;
    if (order_free_above_ < kRoamBuckets) {
        w.window.push_back(t);
        return;
    }
    max_bucket_ = std::max(max_bucket_, b);
    if (b == heap_bucket_) {
        heap_.push_back(queued(t));
        std::push_heap(heap_.begin(), heap_.end());
        return;
    }
    buckets_[std::size_t(b)].push_back(t);
}

RoamMesh::Queued RoamMesh::queued(std::int32_t t) const {
    const Node& n = nodes_[std::size_t(t)];
    const Vertex& a = vertices_[n.v[0]];
    const std::uint64_t apex = std::uint64_t(a.row) * std::uint64_t(size_) + a.col;
    return {n.error, t, std::uint64_t(midpoint_sample(vertices_[n.v[1]], vertices_[n.v[2]])) << 32 | apex};
}

int RoamMesh::region_of(const Node& n) const {
    const int shift = std::min(n.level(), variance_.stored_depth()) - region_level_;
    return int(n.var_node() >> shift) - (2 << region_level_);
}

bool RoamMesh::crosses(const Node& n) const {
    // Region edges are the edges of the level-L triangles; an edge of a finer
    // triangle lies on one of their lines only if it lies on a region edge.
    for (int e = 0; e < 3; ++e) {
        if (n.nb[std::size_t(e)] < 0) continue;
        const Vertex& p = vertices_[n.v[std::size_t(e)]];
        const Vertex& q = vertices_[n.v[std::size_t((e + 1) % 3)]];
        const int pr = p.row, pc = p.col, qr = q.row, qc = q.col;
        bool on_line;
        if (pr == qr)
            on_line = (pr & axis_mask_) == 0;
        else if (pc == qc)
            on_line = (pc & axis_mask_) == 0;
        else if (pr - pc == qr - qc)
            on_line = ((pr - pc) & diagonal_mask_) == 0;
        else
            on_line = ((pr + pc) & diagonal_mask_) == 0;
        if (on_line) return true;
    }
    return false;
}

bool RoamMesh::chain_inside(std::int32_t t) const {
    // split() splits t's coarser base neighbours first (Fig. 5), then t with
    // its partner; every node it writes or relinks borders one of these.
    for (std::int32_t x = t;;) {
        const Node& X = nodes_[std::size_t(x)];
        if (crosses(X)) return false;
        const std::int32_t b = X.nb[1];
        if (b < 0) return true;
        const Node& B = nodes_[std::size_t(b)];
        if (B.nb[1] == x) return !crosses(B);
        x = b;
    }
}

void RoamMesh::make_children(Worker& w, std::int32_t t, std::int32_t c, std::uint32_t m, std::int32_t across) {
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
    // The sequential worker's chunks hold nodes of every region, and so
    // their words of split_bits_ are shared while the regions run.
    std::uint64_t& word = split_bits_[std::size_t(t) >> 6];
    const std::uint64_t bit = std::uint64_t(1) << (t & 63);
    const std::size_t chunk = std::size_t(t) / kNodeChunk;
    const int was_leaf = !(bits >> 27 & kOutside);
    if (node_claims_[chunk].worker == std::uint32_t(&w - workers_.data())) {
        word |= bit;
        chunk_leaves_[chunk].leaves -= was_leaf;
    } else {
        parallel::fetch_or(word, bit);
        parallel::fetch_add(chunk_leaves_[chunk].leaves, -was_leaf);
    }
    T.first_child = c;
    const Node parent{{}, {}, error, bits};
    const int level = parent.level() + 1;
    const unsigned flags = parent.flags();
    const bool deeper = parent.level() < variance_.stored_depth();
    const std::uint32_t var = parent.var_node();
    init_node(c0, level, deeper ? 2 * var : var, flags, error);
    init_node(c1, level, deeper ? 2 * var + 1 : var, flags, error);
    const int leaves = int(!(c0.flags() & kOutside)) + int(!(c1.flags() & kOutside));
    chunk_leaves_[std::size_t(c) / kNodeChunk].leaves += leaves; // the worker's own chunk
    w.count += leaves - was_leaf;
    ++w.splits;
}

void RoamMesh::split_pair(Worker& w, std::int32_t t, std::int32_t b) {
    const Vertex& v0 = vertices_[nodes_[std::size_t(t)].v[1]];
    const Vertex& v1 = vertices_[nodes_[std::size_t(t)].v[2]];
    const std::uint32_t m = add_vertex(w, (v0.row + v1.row) / 2, (v0.col + v1.col) / 2);
    const std::int32_t c = std::int32_t(w.node_next), d = c + 2;
    const std::size_t added = b >= 0 ? 4 : 2; // within the worker's chunk: room() came first
    w.node_next += added;
    w.nodes += added;
    make_children(w, t, c, m, b >= 0 ? d : -1);
    if (b >= 0) {
        make_children(w, b, d, m, c);
        enqueue(w, d, nodes_[std::size_t(d)]);
        enqueue(w, d + 1, nodes_[std::size_t(d) + 1]);
        ++w.forced;
    }
    enqueue(w, c, nodes_[std::size_t(c)]);
    enqueue(w, c + 1, nodes_[std::size_t(c) + 1]);
}

void RoamMesh::split(Worker& w, std::int32_t t, bool forced) {
    std::int32_t b = nodes_[std::size_t(t)].nb[1];
    if (b >= 0 && nodes_[std::size_t(b)].nb[1] != t) {
        // Fig. 5: the base neighbour is coarser; splitting it makes one of its
        // children T's base neighbour at T's own level.
        split(w, b, true);
        b = nodes_[std::size_t(t)].nb[1];
    }
    if (forced) ++w.forced;
    split_pair(w, t, b);
}

void RoamMesh::seed() {
    node_top_ = std::min(node_top_, nodes_.size());
    std::fill(split_bits_.begin(), split_bits_.begin() + std::ptrdiff_t((node_top_ + 63) / 64), 0);
    node_top_ = vertex_top_ = 0;
    for (Worker& w : workers_) {
        w.node_next = w.node_end = w.vertex_next = w.vertex_end = 0;
        w.count = 0;
        w.splits = w.forced = w.nodes = 0;
        w.claims = 0;
        w.worklist.clear();
        w.window.clear();
        w.deferred.clear();
    }
    for (auto& bucket : buckets_) bucket.clear();
    max_bucket_ = 0;
    heap_.clear();
    heap_bucket_ = -1;
    Worker& w = sequential();
    room(w); // the first chunks: the roots are nodes 0 and 1
    const std::int32_t n = size_ - 1;
    const std::uint32_t nw = add_vertex(w, 0, 0), ne = add_vertex(w, 0, n), sw = add_vertex(w, n, 0),
                        se = add_vertex(w, n, n);
    w.node_next = 2;
    w.nodes = 2;
    nodes_[0].v = {ne, nw, se};
    nodes_[0].nb = {-1, 1, -1};
    nodes_[1].v = {sw, se, nw};
    nodes_[1].nb = {-1, 0, -1};
    const unsigned test = kFocus | kStraddle;
    const float unbounded = std::numeric_limits<float>::max();
    for (int r = 0; r < 2; ++r) {
        init_node(nodes_[std::size_t(r)], 0, std::uint32_t(2 + r), test, unbounded);
        const int leaf = !(nodes_[std::size_t(r)].flags() & kOutside);
        w.count += leaf;
        chunk_leaves_[0].leaves += leaf;
        enqueue(w, r, nodes_[std::size_t(r)]);
    }
}

void RoamMesh::drain(Worker& w, long long limit, long long& added, bool& over) {
    // A region's worklist on one thread. The count is shared every 256
    // splits, only to stop early a frame that will be refined again anyway.
    long long shared = 0;
    std::size_t since = 0;
    while (!w.worklist.empty()) {
        const std::int32_t t = w.worklist.back();
        w.worklist.pop_back();
        if (is_split(t)) continue;
        if (!chain_inside(t)) {
            w.deferred.push_back(t);
            continue;
        }
        if (!room(w)) {
            parallel::store(over, true);
            return;
        }
        split(w, t, false);
        if (++since < 256) continue;
        since = 0;
        const long long total = parallel::fetch_add(added, w.count - shared) + (w.count - shared);
        shared = w.count;
        if (total > limit || parallel::load(over)) {
            parallel::store(over, true);
            return;
        }
    }
}

bool RoamMesh::refine_order_free(long long limit) {
    region_order_.resize(workers_.size() - 1);
    std::iota(region_order_.begin(), region_order_.end(), std::size_t(0));
    std::stable_sort(region_order_.begin(), region_order_.end(),
                     [&](std::size_t a, std::size_t b) { return workers_[a].recent > workers_[b].recent; });
    Worker& seq = sequential();
    const std::size_t chain_nodes = 4 * std::size_t(finest_ + 2);
    const std::size_t regions = workers_.size() - 1;
    for (Worker& w : workers_) w.recent = 0;
    for (;;) {
        // The top levels and the strips along region edges, on this thread.
        while (!seq.worklist.empty()) {
            const std::int32_t t = seq.worklist.back();
            seq.worklist.pop_back();
            if (is_split(t)) continue;
            if (seq.count > limit || seq.nodes + chain_nodes > node_budget_ || !room(seq)) return false;
            split(seq, t, false);
        }
        bool any = false;
        for (std::size_t r = 0; r < regions; ++r) any |= !workers_[r].worklist.empty();
        if (!any) return true;
        // The regions at once: two threads take them one at a time, the
        // previous frame's busiest first, so that neither is left alone with
        // a large one at the end (the region around the camera holds a fifth
        // of the splits at 262144 triangles). What they add is summed into
        // the sequential worker; what would reach another region comes back
        // to it.
        long long added = seq.count;
        bool over = false;
        std::size_t next = 0;
        auto take = [&] {
            for (;;) {
                const std::size_t i = parallel::fetch_add(next, std::size_t(1));
                if (i >= regions) return;
                drain(workers_[region_order_[i]], limit, added, over);
            }
        };
        parallel::invoke(take, take);
        for (std::size_t r = 0; r < regions; ++r) {
            Worker& w = workers_[r];
            w.recent += w.splits;
            seq.count += w.count;
            seq.splits += w.splits;
            seq.forced += w.forced;
            seq.nodes += w.nodes;
            w.count = 0;
            w.splits = w.forced = w.nodes = 0;
            seq.worklist.insert(seq.worklist.end(), w.deferred.begin(), w.deferred.end());
            w.deferred.clear();
        }
        if (over) return false;
    }
}

void RoamMesh::queue_below_floor() {
    // The ordered loop went further below the threshold than the window: the
    // leaves not queued so far are gathered from the pool.
    const int floor = queue_floor_;
    queue_floor_ = 0;
    for (Worker& w : workers_) close_chunks(w, false); // the rest of an open chunk holds no node of this frame
    for (std::size_t i = 0; i < node_top_; ++i) {
        const Node& n = nodes_[i];
        if (n.flags() & kSplit) continue;
        const int b = bucket_of(n);
        if (b <= 0 || b > floor) continue;
        buckets_[std::size_t(b)].push_back(std::int32_t(i));
        max_bucket_ = std::max(max_bucket_, b);
    }
}

bool RoamMesh::refine(int budget, long long limit, int threshold, int& found, bool probe) {
    order_free_above_ = threshold;
    queue_floor_ = threshold >= kRoamBuckets - 1 ? 0 : std::max(0, threshold - kWindow);
    seed();
    Worker& seq = sequential();
    const std::size_t chain_nodes = 4 * std::size_t(finest_ + 2);
    if (!refine_order_free(limit)) return false;

    if (seq.splits > 0 && (seq.count > limit || seq.nodes + chain_nodes > node_budget_)) return false;
    order_free_above_ = kRoamBuckets;
    for (Worker& w : workers_) {
        for (const std::int32_t t : w.window) {
            if (is_split(t)) continue;
            const int b = bucket_of(nodes_[std::size_t(t)]);
            buckets_[std::size_t(b)].push_back(t);
            max_bucket_ = std::max(max_bucket_, b);
        }
        w.window.clear();
    }
    found = threshold;
    const std::size_t order_free = seq.splits;
    const bool finished = refine_in_order(budget, limit, found, probe);
    ordered_ = seq.splits - order_free;
    return finished;
}

bool RoamMesh::refine_in_order(int budget, long long limit, int& found, bool probe) {
    Worker& seq = sequential();
    const std::size_t chain_nodes = 4 * std::size_t(finest_ + 2);
    // Seed 003 sec. 5: "while (size of mesh < limit) split highest priority
    // triangle". A split whose forced chain would overshoot the budget is set
    // aside (the triangle stays a leaf for this frame) and the next one is
    // tried, so the mesh ends within one triangle of the budget. A chain adds
    // at most two triangles per level, so its cost is only worked out when
    // that many could overshoot.
    const long long chain_bound = 2 * (finest_ + 1);
    int entered = kRoamBuckets;
    while (seq.count + 2 <= budget && seq.nodes + chain_nodes <= node_budget_) {
        while (max_bucket_ > 0 && buckets_[std::size_t(max_bucket_)].empty() &&
               (max_bucket_ != heap_bucket_ || heap_.empty()))
            --max_bucket_;
        if (max_bucket_ == 0 && queue_floor_ > 0) {
            queue_below_floor();
            continue;
        }
        if (max_bucket_ == 0) break;
        if (max_bucket_ < entered) { // a bucket entered for the first time
            entered = max_bucket_;
            if (seq.count <= limit) found = entered;
        }
        if (probe) {
            // Each bucket LIFO: only the bucket the budget ends in needs the
            // exact order, and the probe stops before it gets there.
            auto& bucket = buckets_[std::size_t(max_bucket_)];
            const std::int32_t t = bucket.back();
            bucket.pop_back();
            if (is_split(t)) continue;
            if (seq.count > limit || !room(seq)) return false;
            split(seq, t, false);
            continue;
        }
        if (max_bucket_ != heap_bucket_) {
            // A bucket is drained in exact order: its live entries become a
            // heap (a higher bucket refilled by a forced chain interrupts it,
            // and its heap goes back to being a plain stack).
            if (heap_bucket_ >= 0)
                for (const Queued& q : heap_) buckets_[std::size_t(heap_bucket_)].push_back(q.node);
            heap_.clear();
            heap_bucket_ = max_bucket_;
            auto& bucket = buckets_[std::size_t(max_bucket_)];
            for (const std::int32_t t : bucket)
                if (!is_split(t)) heap_.push_back(queued(t));
            bucket.clear();
            std::make_heap(heap_.begin(), heap_.end());
            continue;
        }
        std::pop_heap(heap_.begin(), heap_.end());
        const std::int32_t t = heap_.back().node;
        heap_.pop_back();
        if (is_split(t)) continue; // split by force since it was queued
        if (seq.count + chain_bound > budget && seq.count + chain_cost(t) > budget) continue; // set aside
        if (!room(seq)) break;
        split(seq, t, false);
    }
    return !probe || max_bucket_ == 0;
}

RoamStats RoamMesh::tessellate(const Camera& camera, int budget, std::optional<glm::dvec2> focus) {
    camera.validate();
    if (budget < 2) throw Error("triangle budget", std::to_string(budget) + " is below 2");
    reserve_for(budget);
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

    // The previous frame's threshold, unless the worklists' count would pass
    // the line below which no split of the ordered loop is ever set aside.
    const long long limit = budget - 2LL * (finest_ + 1);
    int found = kRoamBuckets - 1;
    int passes = 1;
    if (threshold_ == kRoamBuckets - 1 || !refine(budget, limit, threshold_, found)) {
        // No threshold yet, or it did not hold: the buckets in order, each
        // LIFO, until the count reaches the line; the frame is then refined
        // again from the worklists up to the last bucket entered below it.
        passes = 2;
        if (!refine(budget, limit, kRoamBuckets - 1, found, true) && !refine(budget, limit, found, found))
            refine(budget, limit, kRoamBuckets - 1, found); // the regions' chunks ran out: wholly in order
    }
    threshold_ = std::min(found + kThresholdMargin, kRoamBuckets - 1);
    for (Worker& w : workers_) {
        close_chunks(w, false);
        close_chunks(w, true);
    }
    node_top_ = std::min(node_top_, nodes_.size());
    vertex_top_ = std::min(vertex_top_, vertices_.size());
    // The output follows the chunks in the order of their workers and, for
    // each worker, of its claims: each region's work is the same whatever
    // the threads do, the order the chunks were claimed in is not.
    auto by_worker = [](const std::vector<ChunkClaim>& claims, std::vector<std::uint32_t>& order, std::size_t n) {
        order.resize(n);
        std::iota(order.begin(), order.end(), 0u);
        std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
            return std::tie(claims[a].worker, claims[a].seq) < std::tie(claims[b].worker, claims[b].seq);
        });
    };
    by_worker(vertex_claims_, chunk_order_, (vertex_top_ + kVertexChunk - 1) >> kVertexChunkShift);
    std::uint32_t vertices = 0;
    for (const std::uint32_t k : chunk_order_) {
        vertex_base_[k] = vertices;
        vertices += vertex_used_[k];
    }
    output_vertices_ = vertices;

    const Worker& seq = sequential();
    RoamStats s;
    s.splits = seq.splits;
    s.forced_splits = seq.forced;
    s.ordered_splits = ordered_;
    s.passes = passes;
    s.vertices = vertices;
    // The leaves of each chunk were counted as they came and went, so that
    // the chunks write their triangles at once, each at its own offset.
    const std::size_t chunks = node_top_ / kNodeChunk;
    by_worker(node_claims_, chunk_order_, chunks);
    chunk_first_.resize(chunks);
    std::size_t triangles = 0;
    for (const std::uint32_t k : chunk_order_) {
        chunk_first_[k] = triangles;
        triangles += std::size_t(chunk_leaves_[k].leaves);
    }
    indices_.resize(3 * triangles);
    chunk_stats_.resize(chunks);
    parallel::for_each_range(std::size_t(0), chunks, std::size_t(16), [&](std::size_t first, std::size_t last) {
        for (std::size_t k = first; k < last; ++k) {
            ChunkStats& cs = chunk_stats_[k];
            cs = {};
            std::uint32_t* idx = indices_.data() + 3 * chunk_first_[k];
            for (std::size_t i = k * kNodeChunk; i < (k + 1) * kNodeChunk; ++i) {
                const Node& nd = nodes_[i];
                if (nd.flags() & (kSplit | kOutside)) continue;
                idx[0] = dense(nd.v[0]);
                idx[1] = dense(nd.v[1]);
                idx[2] = dense(nd.v[2]);
                idx += 3;
                cs.max_level = std::max(cs.max_level, nd.level());
                if (nd.flags() & kInvisible) continue;
                ++cs.visible;
                cs.error_sum += nd.error;
                cs.max_error = std::max(cs.max_error, nd.error);
            }
        }
    });
    double sum = 0;
    s.triangles = triangles;
    for (const ChunkStats& cs : chunk_stats_) {
        s.max_level = std::max(s.max_level, cs.max_level);
        s.visible_triangles += cs.visible;
        sum += cs.error_sum;
        s.max_error_px = std::max(s.max_error_px, double(cs.max_error));
    }
    s.mean_error_px = s.visible_triangles ? sum / double(s.visible_triangles) : 0.0;
    return s;
}

void RoamMesh::write_mesh(MeshArrays& out) const {
    const std::size_t nv = output_vertices_;
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
    const std::size_t chunks = (vertex_top_ + kVertexChunk - 1) >> kVertexChunkShift;
    parallel::for_each_index(std::size_t(0), chunks, [&](std::size_t k) {
        const std::size_t first = k << kVertexChunkShift, end = first + vertex_used_[k];
        for (std::size_t i = first; i < std::min(first + ahead, end); ++i) prefetch(record(vertices_[i]));
        for (std::size_t i = first, o = dense(std::uint32_t(first)); i < end; ++i, ++o) {
            if (i + ahead < end) prefetch(record(vertices_[i + ahead]));
            const Vertex& v = vertices_[i];
            out.positions[o] = {hs * float(v.col), vs * float(v.raw) + y0, hs * float(v.row)};
            const SampleAttributes& a = *record(v);
            const float nx = unit * float(a.nx), nz = unit * float(a.nz);
            out.normals[o] = {nx, std::sqrt(std::max(1.0f - nx * nx - nz * nz, 0.0f)), nz};
            out.colors[o] = a.color;
        }
    });
    out.indices.assign(indices_.begin(), indices_.end());
}

} // namespace overflight
