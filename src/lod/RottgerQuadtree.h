#pragma once
// Röttger's continuous level of detail for one square patch of a height field.
//
// Based on: Röttger, Heidrich, Slusallek, Seidel, "Real-Time Generation of
// Continuous Levels of Detail for Height Fields" (WSCG 1998), sec. 3 (the
// quadtree matrix, the subdivision criterion f, the d2 roughness and its
// upward propagation, triangle fans), as used per tile by Zamri ("Run-Time Processing").
//
// A patch is (2^k+1)^2 samples. A node is centred on a sample (ci, cj) with
// half-size h (its corners are (ci+-h, cj+-h)); its children have half-size
// h/2. Because every sample is the centre of at most one node, one matrix
// entry per sample is enough for the per-node data (Röttger's quadtree
// matrix): the d2 value, and a frame stamp that says "subdivided this frame"
// (so nothing is cleared per frame).
//
// Subdivision criterion (Röttger eq. 3): f = l / (d * C * max(c * d2, 1)),
// subdivide when f < 1; l = Euclidean distance eye -> node centre, d = node
// edge length (world units), C = minimum global resolution, c = desired
// global resolution.
//
// Choice of c from a screen-space error tau (pixels): d2 * d is the largest
// vertical deviation the node's fan makes at its check points (d2 is
// max|dh| / d). A vertical segment of length e at distance l projects to at
// most fp * e / l pixels (fp = camera focal length in pixels; equality when it
// is perpendicular to the view ray). So the node is accurate enough when
// fp * d2 * d / l <= tau, i.e. l >= d * (fp / tau) * d2. Matching Röttger's
// f with the max(.,1) term gives C * c = fp / tau, c = fp / (tau * C): see
// rottger_c(). The max(., 1) keeps nodes within C * d of the eye subdivided
// regardless of roughness (the minimum resolution).
//
// Default C = 4 (K = 2/3): with C = 2 (K = 1) every ancestor inherits its
// descendants' d2 undiminished, i.e. its absolute error estimate doubles per
// level; C = 4 keeps the estimate close to the children's absolute error
// while subdividing everything within 4 node sizes of the eye. On the demo
// island (2049^2, 1 px) C in 3..20 changed the triangle count by < 10 %.
//
// d2 propagation (Röttger sec. 3.3): d2(node) = max(d2(node), K * d2(child))
// over the four children, K = C / (2 (C - 1)). It makes f monotone along
// every root-to-leaf path (a child never wants subdividing when its parent
// does not), so the top-down traversal that stops at the first f >= 1 is
// exact.
//
// Fans and cracks: each leaf (a reached node that is not subdivided, or a
// smallest 3x3 node) is drawn as a fan around its centre. Röttger's rule is
// to include an edge midpoint only where the neighbour of the same size is
// present in the mesh (skip it where the neighbour is coarser). We apply
// that rule recursively along the edge: where the neighbour of the same size
// is itself subdivided, the corners of its leaves on the shared edge are
// included too. With Röttger's propagation neighbours differ by at most one
// level and this is exactly his fan; if they ever differ by more (another
// tile's different roughness, a different C) the mesh still has no
// T-junction, because every vertex lying on a leaf's edge is in its fan.
// At tile seams the same query goes to the neighbouring tile's quadtree
// (set_neighbour), so tiles agree on the seam: the seam vertices are the
// finer side's, as the coarser side includes them. Tiles share their edge
// samples (overlapping 2^k+1 tiles), so both sides use identical positions.
//
// Reduced patches: a far tile may be loaded with only every `step`-th sample
// (step = 2^m; TileSet picks m where Röttger's f stops subdivision above node
// size 2^m anyway). Such a patch is a quadtree over the decimated samples
// whose finest nodes are the full tree's nodes of half-size `step`: their
// check points are samples the decimated patch keeps, so their own d2 is
// exact, but the d2 their full-resolution children would have propagated up
// is lost. The full tree's d2 at the finest nodes (`finest_d2`, stored by the
// tiler from rottger_d2()) restores it exactly: every node then has the full
// tree's d2. Without it, `finer_d2` (a bound on the children's propagated
// d2, from rottger_roughness()) keeps d2 >= the full tree's at every node, at
// the cost of more triangles. Either way the reduced patch never stops
// where the full one would refine.
// Across a seam with a coarser patch, the finer one can only share vertices
// the coarser one has: set_seam_ratio() keeps the finer patch's nodes along
// that edge from being subdivided into nodes smaller than the coarser
// patch's finest ones, so its edge vertices lie on the coarser grid and the
// recursive edge rule above stitches both sides (Röttger's one-level rule
// carried across patches of different sample spacing).
#include "core/MeshArrays.h"
#include "core/Terrain.h"
#include "lod/Frustum.h"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace overflight {

// c of Röttger's criterion for a screen-space error of error_px pixels and a
// focal length of focal_px pixels (see above): fp / (tau * C).
double rottger_c(double error_px, double focal_px, double min_resolution);

// Roughness of a (2^k+1)^2 patch per node size: entry j (0 .. k-1) is the
// largest d2 before propagation (max |dh| / d at the six check points) over
// the nodes of half-size 2^j. Stored per tile by the tiler, so that a tile's
// level of detail can be chosen before it is loaded.
std::vector<float> rottger_roughness(const Terrain& patch);
// Upper bound on the propagated d2 of any node of half-size 2^j given the
// roughness above: e_0 = r_0, e_j = max(r_j, K e_(j-1)), K = C / (2 (C - 1))
// (Röttger sec. 3.3 applied to the per-level maxima).
double propagated_d2_bound(const std::vector<float>& roughness, int j, double min_resolution);
// The propagated d2 of every node of a (2^k+1)^2 patch, at its centre sample
// (0 where no node is centred): Röttger's quadtree matrix for min_resolution C.
std::vector<float> rottger_d2(const Terrain& patch, double min_resolution);

class RottgerQuadtree {
public:
    enum Side { North, South, West, East }; // row - 1, row + 1, col - 1, col + 1

    // `samples` is the square (2^k+1)^2 patch (k >= 1) with one color per
    // sample; `normals` one unit normal per sample (row-major, same size);
    // (origin_row, origin_col) is the global sample index of the patch's
    // sample (0, 0), so that world X = hs * (origin_col + j) is identical in
    // every patch that shares a sample. min_resolution is Röttger's C (> 1).
    // A reduced patch holds every `step`-th sample (a power of two; its
    // h_scale is step times the full grid's, origins stay in full-grid
    // indices) and `finer_d2` bounds the propagated d2 of the full tree's
    // nodes of half-size step / 2 (see above; 0 for a full patch), unless
    // `finest_d2` gives the full tree's d2 at each sample of the reduced
    // patch (only read while constructing).
    // Throws Error("quadtree", ...) for a patch that is not (2^k+1)^2 or
    // normals of the wrong size. Both are referenced, not copied: they must
    // outlive the quadtree.
    RottgerQuadtree(const Terrain& samples, const std::vector<glm::vec3>& normals, int origin_row, int origin_col,
                    double min_resolution = 4.0, int step = 1, double finer_d2 = 0.0,
                    const std::vector<float>* finest_d2 = nullptr);

    int size() const { return n_; }
    int origin_row() const { return origin_row_; }
    int origin_col() const { return origin_col_; }
    int step() const { return step_; }
    double min_resolution() const { return C_; }
    // Propagated d2 of the node centred at (row, col) (0 where no node is centred).
    float d2(int row, int col) const { return d2_[idx(row, col)]; }

    // Neighbouring patches, or nullptr where there is none or it is not drawn
    // this frame (the patch then keeps its own edge midpoints there, as at
    // the terrain border). Must be set before append_fans(); neighbours must have been
    // refine()d for the same frame.
    void set_neighbour(Side side, const RottgerQuadtree* q) { neighbours_[side] = q; }
    // The patch across `side` keeps every ratio-th of this patch's samples
    // (1: as fine or finer). Set before refine(); see "Reduced patches".
    void set_seam_ratio(Side side, int ratio) { seam_ratio_[side] = ratio; }

    // Top-down evaluation of f from the root (Röttger sec. 3.2) for an eye
    // in world coordinates; starts a new frame. With a frustum, a node whose
    // bounding box (its XZ square, its samples' Y range) lies wholly outside
    // it is not subdivided: Zamri's culling carried from tiles down to
    // nodes, so the minimum-resolution term does not refine the ground
    // beside and behind the viewer. Such a node is still drawn, coarsely, so
    // its visible neighbours keep a conforming mesh.
    void refine(const glm::dvec3& eye, double c, const Frustum* frustum = nullptr);
    // Whether the node centred at (row, col) was subdivided by the last refine().
    bool subdivided(int row, int col) const { return stamp_[idx(row, col)] == frame_; }

    // Appends one triangle fan per leaf (as a triangle list, counter-clockwise
    // seen from above) with world positions, the given normals and the
    // patch's colors. Vertices are shared within the patch. Returns the
    // number of triangles appended.
    std::size_t append_fans(MeshArrays& out);

    // Bytes held by the quadtree matrix and its per-frame buffers.
    std::size_t memory_bytes() const;
    // Bytes of the matrix alone for an n x n patch (an estimate before building one).
    static std::size_t matrix_bytes(int n);

private:
    std::size_t idx(int row, int col) const { return std::size_t(row) * std::size_t(n_) + std::size_t(col); }
    float world_y(int row, int col) const { return terrain_->sample_height(row, col); }
    friend std::vector<float> rottger_d2(const Terrain& patch, double min_resolution);
    static void build_matrix(const Terrain& t, double C, const std::vector<float>* finest, double finer_d2,
                             std::vector<float>& d2, std::vector<std::uint16_t>& lo, std::vector<std::uint16_t>& hi);
    void refine_node(int ci, int cj, int h, bool inside);
    void emit_leaves(int ci, int cj, int h);
    struct NodeRef {
        const RottgerQuadtree* patch;
        int ci, cj, h;
    };
    NodeRef locate(int ci, int cj, int h) const;
    bool has_patch(int ci, int cj) const;
    bool node_reached(int ci, int cj, int h) const;
    bool node_subdivided(int ci, int cj, int h) const;
    void collect_edge(int ci, int cj, int h, Side towards, bool same_size, std::vector<std::array<int, 2>>& out) const;
    std::uint32_t vertex(int row, int col);

    const Terrain* terrain_;
    const std::vector<glm::vec3>* normals_;
    int n_ = 0;
    int origin_row_ = 0, origin_col_ = 0;
    int step_ = 1;
    double hs_full_ = 1.0; // h_scale of the full grid: world X = hs_full_ * (origin_col_ + step_ * col)
    double C_ = 4.0;
    std::array<int, 4> seam_ratio_{1, 1, 1, 1};
    std::vector<float> d2_;
    std::vector<std::uint16_t> lo_, hi_; // per node: raw height range of its samples
    std::vector<std::uint32_t> stamp_;     // == frame_: subdivided this frame
    std::vector<std::uint32_t> vertex_id_; // valid where vertex_stamp_ == emit_frame_
    std::vector<std::uint32_t> vertex_stamp_;
    std::uint32_t frame_ = 1;
    std::uint32_t emit_frame_ = 0;
    std::array<const RottgerQuadtree*, 4> neighbours_{};
    // Per-frame state of refine()/append_fans(), kept to avoid allocating per frame.
    glm::dvec3 eye_{0.0};
    double c_ = 1.0;
    const Frustum* frustum_ = nullptr;
    MeshArrays* out_ = nullptr;
    std::vector<std::array<int, 2>> ring_; // fan boundary of one leaf
    std::vector<std::array<int, 2>> edge_;
};

} // namespace overflight
