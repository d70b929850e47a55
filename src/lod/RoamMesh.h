#pragma once
// Split-only ROAM: every frame the mesh is rebuilt from the two root triangles
// of the binary triangle tree by splitting the triangle of highest priority
// until the triangle budget is reached. Splitting a triangle also splits its
// base neighbour, after first splitting that neighbour when it is coarser
// (forced splits, recursively), so the mesh is always conforming.
//
// Based on: CMSC 23700 project 2a sec. 5 and 5.1, after
// Duchaineau et al., "ROAMing terrain: real-time optimally adapting meshes",
// IEEE Visualization 1997, sec. 4 (forced splits, Fig. 5), sec. 6 (nested
// error bounds) and sec. 7 (priority queue of buckets). The bintree layout is
// described in RoamVarianceTree.h.
//
// Priority = projected screen-space error: the variance-tree bound divided by
// the distance from the eye to the nearest point of the triangle's bounding
// circle, times the focal length in pixels (DESIGN sec. 2). It is clamped to
// the parent's value so that priorities are nested (Duchaineau sec. 6): then
// the largest error of the mesh never rises as the budget grows. Triangles
// outside the view wedge (RoamViewWedge) get error 0 and are never split
// unless forced; the triangles containing the focus point (the vehicle) get
// the maximum priority and reach the finest level first. The queue is a set
// of buckets on a logarithmic scale (the paper's "think radix sort"): O(1)
// insert and remove; a bucket spans a factor 1 + 1/128.
//
// Order. A priority depends only on the triangle and its ancestors, so once
// every bucket above some bucket B is drained the mesh is the smallest
// conforming refinement without a leaf above B, whatever order the splits
// came in. Only the last buckets, where the budget runs out, need the order.
// So a frame first splits everything above the previous frame's last bucket
// (plus a margin) from depth-first worklists, with no queue, and only then
// pops the buckets in order; within a bucket the order is the exact error,
// ties broken by the triangle's position, so that the mesh depends neither on
// the threshold nor on earlier frames (only the order of the output arrays
// does). The worklists give the ordered loop's mesh as long as their count stays
// within the budget less the longest forced chain (2 triangles per level):
// counts only grow, so the ordered loop would not have set a split aside on
// the way. A frame that passes that line is refined again wholly in order.
//
// Terrains that are not (2^N+1)^2 are padded (pad_to_pow2_plus1). Triangles
// lying wholly in the padding are neither counted nor output; visible
// triangles that straddle the border are split first, so the output ends at
// the terrain's edge as soon as the bintree can represent it.
//
// Both cores. The order-free part is refined in parallel over regions: the
// 128 bintree triangles of level 6. A region's worker owns the nodes below
// its triangle and splits them from its own worklist; a split whose forced
// chain would write or relink a node across a region edge (one lying on the
// grid lines those triangles' edges follow) is deferred to the sequential
// part, which also refines the levels above the regions. Rounds of the two
// alternate until no worklist is left. Both threads take regions one at a
// time, the previous frame's busiest first. Node and vertex pools are handed
// out in chunks (1024 nodes, 512 vertices), so that workers never write the
// same line of a pool or of the split bits; the unused end of a chunk is
// marked, and output vertex ids skip it. The leaves of each node chunk are
// counted as splits come and go, so that the output pass writes the chunks'
// triangles at once, each at its own offset. The output follows the chunks
// by worker, then by claim, so that the arrays are the same on one thread or
// two, however the threads ran.
//
// No allocation per split: the pools are reserved for the budget once and
// reused across frames (they grow only when the budget grows).
//
// The output arrays are part of the per-frame cost: the triangle indices are
// gathered in the pass that sums the statistics, and each sample's normal and
// color are packed at construction into one 8-byte record, so writing a
// vertex touches one cache line instead of the four rows and the color plane.
//
// Speed (the target: >= 15 M triangles/s at 262144 triangles). The rebuild
// is bound by cache misses on the nodes it touches at random (the split
// triangle, its base neighbour and the outer neighbours it relinks), so a
// node is 32 bytes, the two children of a split share one 64-byte line and a
// split node keeps its children's index where its error was (no other line
// written per split); the queue keeps no links in the nodes (a bucket is a
// stack, a node split by force is dropped when popped); the view wedge is
// tested once per vertex (outcodes) instead of once per triangle; the cost of
// a forced-split chain is only worked out within reach of the budget; leaves
// far below the threshold are never queued unless the ordered loop gets there.
#include "core/Camera.h"
#include "core/MeshArrays.h"
#include "core/Parallel.h"
#include "core/Terrain.h"
#include "lod/RoamVarianceTree.h"
#include "lod/RoamViewWedge.h"

#include <glm/vec2.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace overflight {

struct RoamOptions {
    // Deepest bintree level with its own variance bound (memory 2^(depth+2) x 2
    // bytes); 0 .. kMaxVarianceDepth.
    static constexpr int kMaxVarianceDepth = 20;
    int variance_depth = RoamVarianceTree::kDefaultMaxDepth;
};

struct RoamStats {
    std::size_t triangles = 0;     // output triangles
    std::size_t vertices = 0;      // output vertices
    std::size_t splits = 0;        // bintree triangles split, forced ones included
    std::size_t forced_splits = 0; // of which forced by a neighbour (Fig. 5)
    int max_level = 0;             // deepest leaf
    // Projected error in pixels of the visible output triangles (the priority
    // metric before the wedge and focus adjustments): largest and mean.
    double max_error_px = 0;
    double mean_error_px = 0;
    std::size_t visible_triangles = 0;
    // Splits made in priority order (the rest needed none: RoamMesh's
    // "Order"), and 2 when the previous frame's order-free threshold did not
    // hold and the frame was refined again wholly in order, else 1.
    std::size_t ordered_splits = 0;
    int passes = 1;
};

// The bucket of a projected error in pixels: 1 for errors <= 2^-10 px, then
// 128 buckets per octave up to 2^20 px; kRoamBuckets - 1 is reserved for the
// maximum priority (focus, border). Monotone in `error_px`.
constexpr int kRoamBuckets = 4096;
int roam_bucket(float error_px);

// A triangle's priority (Duchaineau sec. 6): its variance bound `bound` (world
// units) projected at the nearest point of its bounding circle of `radius`
// around the hypotenuse midpoint, which lies (dx, dy, dz) from the eye, no
// nearer than `near`; times the focal length in pixels; clamped to the
// parent's value so that priorities are nested.
inline float roam_projected_error(float bound, float dx, float dy, float dz, float radius, float near, float focal_px,
                                  float parent_error) {
    const float d = std::max(std::sqrt(dx * dx + dy * dy + dz * dz) - radius, near);
    return std::min(bound * focal_px / d, parent_error);
}

// Level-of-detail control (the flight's + and _ keys): the budget times
// sqrt(2)^steps, snapped to the ladder round(2^(k/2)) so that +1 then -1
// returns the original budget; kept within 64 .. 2^22.
int roam_scale_budget(int budget, int steps);

class RoamMesh {
public:
    // Builds the variance tree of `terrain` (padded to (2^N+1)^2 when needed).
    // `terrain` must outlive the RoamMesh (vertex colors and normals are read
    // from it). Throws Error("roam", ...) for a bad variance depth or a grid
    // larger than 32769^2.
    explicit RoamMesh(const Terrain& terrain, const RoamOptions& options = {});

    // One frame: rebuilds the mesh for `camera` with at most `budget` output
    // triangles (>= 2). The result has between budget - 1 and budget triangles
    // unless every visible triangle reached the finest level first. `focus`
    // is the world (x, z) of the vehicle. Throws Error("camera", ...) for an
    // invalid camera and Error("triangle budget", ...) for a budget < 2.
    RoamStats tessellate(const Camera& camera, int budget, std::optional<glm::dvec2> focus = std::nullopt);

    // The current mesh as plain arrays (positions in world coordinates,
    // normals Terrain::sample_normal to 16 bits per component, colors Terrain::colors, counter-clockwise
    // seen from above). Reuses the capacity of `out`.
    void write_mesh(MeshArrays& out) const;

    // The (2^N+1)^2 grid the bintree covers (the terrain itself or its padded copy).
    const Terrain& grid() const { return padded_ ? padded_copy_ : *terrain_; }
    const RoamVarianceTree& variance() const { return variance_; }

    // Read access to the bintree of the last frame, for tests and tools.
    enum NodeFlags : std::uint8_t {
        kFocus = 1,     // contains the focus point
        kOutside = 2,   // wholly in the padding
        kStraddle = 4,  // partly in the padding
        kInvisible = 8, // outside the view wedge
        kSplit = 16,    // has children (child(i))
    };
    struct alignas(32) Node {
        std::array<std::int32_t, 3> nb;  // neighbours across (apex,v0), (v0,v1) = base, (v1,apex); -1 = border
        std::array<std::uint32_t, 3> v;  // vertex ids: apex, v0, v1 (hypotenuse v0-v1)
        // A leaf's projected error in pixels, nested; once split (kSplit), the
        // index of its first child, so that the split writes no other line.
        union {
            float error;
            std::int32_t first_child;
        };
        // var_node | level << 22 | flags << 27, one word so that it is always
        // written and read whole.
        std::uint32_t bits;
        // Stored variance-tree node (itself or its deepest stored ancestor).
        std::uint32_t var_node() const { return bits & ((1u << 22) - 1); }
        int level() const { return int(bits >> 22 & 31u); }
        // A pool slot no split used this frame (the pools are handed out in
        // chunks; see "Both cores"); its flags say kSplit | kOutside.
        bool unused() const { return level() == kUnusedLevel; }
        static constexpr int kUnusedLevel = 31;
        unsigned flags() const { return bits >> 27; } // NodeFlags
        static std::uint32_t pack(std::uint32_t var_node, int level, unsigned flags) {
            return var_node | std::uint32_t(level) << 22 | flags << 27;
        }
    };
    static_assert(sizeof(Node) == 32);
    struct Vertex {
        std::uint16_t row, col;
        std::uint16_t raw;    // height sample of grid()
        std::uint8_t outcode; // RoamViewWedge::outcode of the vertex
    };
    std::span<const Node> nodes() const { return {nodes_.data(), node_top_}; }
    std::span<const Vertex> vertices() const { return {vertices_.data(), vertex_top_}; }
    // First child of a split node i (the second is child(i) + 1).
    std::int32_t child(std::size_t i) const { return nodes_[i].first_child; }

private:
    struct Rc {
        std::int32_t row, col;
    };
    // What one thread refining one region (or the sequential part) owns: its
    // current chunks of the node and vertex pools, its counts and its lists.
    struct alignas(64) Worker {
        std::size_t node_next = 0, node_end = 0;
        std::size_t vertex_next = 0, vertex_end = 0;
        long long count = 0; // output triangles added
        std::size_t splits = 0, forced = 0, nodes = 0;
        std::size_t recent = 0; // splits in the last frame refined from the worklists
        std::uint32_t claims = 0; // chunks claimed this frame
        std::vector<std::int32_t> worklist; // leaves above the threshold
        std::vector<std::int32_t> window;   // leaves just below it, queued once the order matters
        std::vector<std::int32_t> deferred; // splits that would reach another region
    };
    Worker& sequential() { return workers_.back(); }
    void reserve_for(int budget);
    bool room(Worker& w);
    // Gives up the worker's current node chunk (marking its rest unused) or vertex chunk.
    void close_chunks(Worker& w, bool vertices);
    std::uint32_t add_vertex(Worker& w, std::int32_t row, std::int32_t col);
    void init_node(Node& n, int level, std::uint32_t var_node, unsigned inherited_flags, float parent_error) const;
    float priority(const Vertex& a, const Vertex& b, const Vertex& c, int level, std::uint32_t var_node,
                   unsigned inherited_flags, float parent_error, unsigned& flags) const;
    bool outside_domain(Rc a, Rc b, Rc c) const;
    bool straddles_domain(Rc a, Rc b, Rc c) const;
    int split_delta(Rc a, Rc v0, Rc v1, bool outside) const;
    int chain_cost(std::int32_t t) const;
    void split(Worker& w, std::int32_t t, bool forced);
    void split_pair(Worker& w, std::int32_t t, std::int32_t b);
    void make_children(Worker& w, std::int32_t t, std::int32_t c, std::uint32_t m, std::int32_t across);
    // The bucket a leaf is queued in, or -1 when it is split only by force.
    int bucket_of(const Node& n) const;
    void enqueue(Worker& w, std::int32_t t, const Node& n);
    // The region (bintree triangle at region_level_) holding a node at or
    // below that level, and whether a neighbour of n lies in another region
    // (an edge with a neighbour on a region boundary).
    int region_of(const Node& n) const;
    bool crosses(const Node& n) const;
    // Whether splitting t, forced chain included, stays within t's region.
    bool chain_inside(std::int32_t t) const;
    // The roots, queued; the per-frame counts reset.
    void seed();
    // Refines from seed(): every leaf above bucket `threshold` from the
    // worklists, then in priority order until `budget`. Returns false, with
    // the mesh half made, when the worklists' count passes `limit`. `found`:
    // the lowest bucket whose refinement from the worklists would have held.
    // A `probe` takes each bucket LIFO and stops (false) once the count
    // passes `limit`; true when it refined everything before that.
    bool refine(int budget, long long limit, int threshold, int& found, bool probe = false);
    bool refine_order_free(long long limit);
    // The buckets in priority order, from what refine_order_free left.
    bool refine_in_order(int budget, long long limit, int& found, bool probe);
    void drain(Worker& w, long long limit, long long& added, bool& over);
    void queue_below_floor();
    // A queued leaf in the exact order used within a bucket: error, then the
    // grid indices of its hypotenuse midpoint and apex (a key independent of
    // the order the splits came in).
    struct Queued {
        float error;
        std::int32_t node;
        std::uint64_t key;
        bool operator<(const Queued& o) const { return error < o.error || (error == o.error && key < o.key); }
    };
    Queued queued(std::int32_t t) const;
    Rc rc(std::uint32_t vid) const { return {vertices_[vid].row, vertices_[vid].col}; }
    // Row-major index in grid() of the sample halfway between two vertices.
    std::size_t midpoint_sample(const Vertex& a, const Vertex& b) const {
        return std::size_t((a.row + b.row) / 2) * std::size_t(size_) + std::size_t((a.col + b.col) / 2);
    }
    // The output index of a vertex: pool ids skip the unused ends of chunks.
    std::uint32_t dense(std::uint32_t vid) const;
    // Terrain::sample_normal (x, z in 1/32767) and color of one grid sample.
    struct SampleAttributes {
        Rgb8 color;
        std::uint8_t unused;
        std::int16_t nx, nz; // ny = sqrt(1 - nx^2 - nz^2) > 0 on a height field
    };
    static_assert(sizeof(SampleAttributes) == 8);

    const Terrain* terrain_;
    bool padded_ = false;
    Terrain padded_copy_;
    RoamVarianceTree variance_;
    int size_ = 0;           // 2^N + 1
    int finest_ = 0;         // 2N
    int domain_rows_ = 0, domain_cols_ = 0;
    double min_y_ = 0, max_y_ = 0; // world height range of the grid
    std::vector<float> radius_; // half hypotenuse in world units per level
    std::vector<SampleAttributes> attributes_; // per grid() sample, row-major
    // Regions refined at once: the bintree triangles of this level (0: none),
    // and the grid lines their edges lie on (see crosses()).
    int region_level_ = 0;
    int axis_mask_ = 0, diagonal_mask_ = 0;

    // Per-frame state.
    Camera camera_;
    RoamViewWedge wedge_;
    float eye_x_ = 0, eye_y_ = 0, eye_z_ = 0, focal_px_ = 1, near_ = 1;
    float half_hs_ = 0.5f, half_vs_ = 0.5f, y_offset_ = 0; // of grid()
    const std::uint16_t* heights_ = nullptr; // grid() samples, row-major
    std::optional<glm::dvec2> focus_;
    // Pools sized once for the budget and handed out in chunks; node_top_
    // and vertex_top_ are the ends of the chunks handed out this frame.
    std::vector<Node, parallel::CacheAlignedAllocator<Node>> nodes_;
    // One bit per node, set when it is split (its kSplit flag): 64 nodes per
    // word, so that the queue's stale entries (nodes split by force since
    // they were queued: most of the pops at large budgets) are recognised
    // without loading their nodes.
    std::vector<std::uint64_t> split_bits_;
    bool is_split(std::int32_t t) const { return parallel::load(split_bits_[std::size_t(t) >> 6]) >> (t & 63) & 1u; }
    // Per node chunk: its output triangles, one line each (the two threads
    // update the counts of neighbouring chunks at every split).
    struct alignas(64) LeafCount {
        std::int32_t leaves;
    };
    std::vector<LeafCount> chunk_leaves_;
    std::vector<std::size_t> chunk_first_;   // per node chunk: its first output triangle
    struct ChunkClaim {
        std::uint32_t worker = 0, seq = 0; // who claimed a chunk, and its how-manieth claim
    };
    std::vector<ChunkClaim> node_claims_, vertex_claims_;
    std::vector<std::uint32_t> chunk_order_; // chunks by worker, then claim
    struct ChunkStats {
        int max_level = 0;
        std::size_t visible = 0;
        double error_sum = 0;
        float max_error = 0;
    };
    std::vector<ChunkStats> chunk_stats_;
    std::vector<Vertex> vertices_;
    std::size_t node_budget_ = 0; // nodes the ordered loop may use (the rest covers unused chunk ends)
    std::size_t node_top_ = 0, vertex_top_ = 0, output_vertices_ = 0;
    std::vector<std::uint32_t> vertex_used_, vertex_base_; // per vertex chunk: vertices used, first output index
    std::vector<Worker> workers_; // one per region, then the sequential one
    std::vector<std::size_t> region_order_; // busiest first
    std::vector<std::uint32_t> indices_; // of the output triangles, 3 each
    std::vector<std::vector<std::int32_t>> buckets_; // stacks of queued nodes
    int max_bucket_ = 0;
    // Leaves above this bucket go to the worklists instead of the buckets;
    // leaves at or below queue_floor_ are queued only if the loop gets there.
    int order_free_above_ = kRoamBuckets;
    int queue_floor_ = 0;
    // The bucket being drained in exact order, as a binary heap (-1: none).
    std::vector<Queued> heap_;
    int heap_bucket_ = -1;
    // The threshold for the next frame (kRoamBuckets - 1: none yet).
    int threshold_ = kRoamBuckets - 1;
    std::size_t ordered_ = 0;
};

} // namespace overflight
