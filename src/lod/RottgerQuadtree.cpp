// Based on: Röttger, Heidrich, Slusallek, Seidel 1998, sec. 3 (quadtree
// matrix, criterion f, d2 and its propagation, fans); Zamri.
#include "lod/RottgerQuadtree.h"

#include "core/Error.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace overflight {

double rottger_c(double error_px, double focal_px, double min_resolution) {
    if (!(error_px > 0) || !std::isfinite(error_px)) throw Error("screen-space error", "must be a positive number of pixels");
    return focal_px / (error_px * min_resolution);
}

namespace {

// Röttger's dh at the six check points of the node centred at (ci, cj) with
// half-size h (Fig. 5): four edge midpoints against their edge, the centre
// against both diagonals.
double node_dh(const Terrain& t, int ci, int cj, int h) {
    auto y = [&](int i, int j) { return double(t.sample_height(i, j)); };
    const double nw = y(ci - h, cj - h), ne = y(ci - h, cj + h);
    const double sw = y(ci + h, cj - h), se = y(ci + h, cj + h);
    const double c = y(ci, cj);
    double dh = std::abs(y(ci - h, cj) - 0.5 * (nw + ne));
    dh = std::max(dh, std::abs(y(ci + h, cj) - 0.5 * (sw + se)));
    dh = std::max(dh, std::abs(y(ci, cj - h) - 0.5 * (nw + sw)));
    dh = std::max(dh, std::abs(y(ci, cj + h) - 0.5 * (ne + se)));
    dh = std::max(dh, std::abs(c - 0.5 * (nw + se)));
    dh = std::max(dh, std::abs(c - 0.5 * (ne + sw)));
    return dh;
}

double propagation_k(double C) { return C / (2.0 * (C - 1.0)); }

} // namespace

std::vector<float> rottger_roughness(const Terrain& patch) {
    const int n = patch.rows();
    if (n != patch.cols() || !is_pow2_plus1(n) || n < 3) throw Error("quadtree", "roughness needs a (2^k+1)^2 patch");
    std::vector<float> r;
    for (int h = 1; 2 * h < n; h *= 2) {
        const double d = 2.0 * h * patch.h_scale();
        double v = 0;
        for (int ci = h; ci < n; ci += 2 * h)
            for (int cj = h; cj < n; cj += 2 * h) v = std::max(v, node_dh(patch, ci, cj, h) / d);
        r.push_back(float(v));
    }
    return r;
}

double propagated_d2_bound(const std::vector<float>& roughness, int j, double min_resolution) {
    const double K = propagation_k(min_resolution);
    double e = 0;
    for (int i = 0; i <= j && i < int(roughness.size()); ++i) e = std::max(double(roughness[std::size_t(i)]), K * e);
    return e;
}

RottgerQuadtree::RottgerQuadtree(const Terrain& samples, const std::vector<glm::vec3>& normals, int origin_row,
                                 int origin_col, double min_resolution, int step, double finer_d2,
                                 const std::vector<float>* finest_d2)
    : terrain_(&samples), normals_(&normals), n_(samples.rows()), origin_row_(origin_row), origin_col_(origin_col),
      step_(step), hs_full_(double(samples.h_scale()) / step), C_(min_resolution) {
    if (samples.rows() != samples.cols() || !is_pow2_plus1(samples.rows()) || samples.rows() < 3)
        throw Error("quadtree", "patch of " + std::to_string(samples.rows()) + "x" + std::to_string(samples.cols()) +
                                    " samples is not (2^k+1)^2 with k >= 1");
    if (normals.size() != samples.heights().size()) throw Error("quadtree", "one normal per sample is needed");
    if (!(min_resolution > 1)) throw Error("quadtree", "minimum resolution C must be greater than 1");
    if (step < 1 || (step & (step - 1)) != 0) throw Error("quadtree", "sample step must be a power of two");
    if (finest_d2 && finest_d2->size() != samples.heights().size()) throw Error("quadtree", "one d2 per sample is needed");
    const std::size_t count = std::size_t(n_) * std::size_t(n_);
    d2_.assign(count, 0.0f);
    lo_.assign(count, 0);
    hi_.assign(count, 0);
    stamp_.assign(count, 0);
    vertex_id_.assign(count, 0);
    vertex_stamp_.assign(count, 0);
    build_matrix(samples, C_, finest_d2, finer_d2, d2_, lo_, hi_);
}

std::size_t RottgerQuadtree::matrix_bytes(int n) {
    return std::size_t(n) * std::size_t(n) * (sizeof(float) + 3 * sizeof(std::uint32_t) + 2 * sizeof(std::uint16_t));
}

std::size_t RottgerQuadtree::memory_bytes() const {
    return d2_.size() * sizeof(float) + stamp_.size() * sizeof(std::uint32_t) * 3 +
           (lo_.size() + hi_.size()) * sizeof(std::uint16_t) +
           (ring_.capacity() + edge_.capacity()) * sizeof(std::array<int, 2>);
}

// The quadtree matrix (Röttger sec. 3.3): d2 bottom-up over the levels so
// that each parent sees its children's final (already propagated) values,
// and each node's raw height range. For a reduced patch, the finest nodes
// take the full tree's d2 from `finest` (exact) or, without it, are raised
// by K * finer_d2 (a bound on the full-resolution children it dropped).
void RottgerQuadtree::build_matrix(const Terrain& t, double C, const std::vector<float>* finest, double finer_d2,
                                   std::vector<float>& d2, std::vector<std::uint16_t>& lo_out,
                                   std::vector<std::uint16_t>& hi_out) {
    const int n = t.rows();
    auto at = [n](int i, int j) { return std::size_t(i) * std::size_t(n) + std::size_t(j); };
    const double K = propagation_k(C);
    const int root = (n - 1) / 2;
    for (int h = 1; h <= root; h *= 2) {
        const double d = 2.0 * h * t.h_scale();
        for (int ci = h; ci < n; ci += 2 * h)
            for (int cj = h; cj < n; cj += 2 * h) {
                double v = node_dh(t, ci, cj, h) / d;
                std::uint16_t lo = t.raw(ci, cj), hi = lo;
                if (h > 1) {
                    const int q = h / 2;
                    for (const std::size_t k : {at(ci - q, cj - q), at(ci - q, cj + q), at(ci + q, cj - q),
                                                at(ci + q, cj + q)}) {
                        v = std::max(v, K * d2[k]);
                        lo = std::min(lo, lo_out[k]);
                        hi = std::max(hi, hi_out[k]);
                    }
                } else {
                    v = finest ? std::max(v, double((*finest)[at(ci, cj)])) : std::max(v, K * finer_d2);
                    for (int i = ci - 1; i <= ci + 1; ++i)
                        for (int j = cj - 1; j <= cj + 1; ++j) {
                            lo = std::min(lo, t.raw(i, j));
                            hi = std::max(hi, t.raw(i, j));
                        }
                }
                d2[at(ci, cj)] = float(v);
                lo_out[at(ci, cj)] = lo;
                hi_out[at(ci, cj)] = hi;
            }
    }
}

std::vector<float> rottger_d2(const Terrain& patch, double min_resolution) {
    const int n = patch.rows();
    if (n != patch.cols() || !is_pow2_plus1(n) || n < 3) throw Error("quadtree", "d2 needs a (2^k+1)^2 patch");
    const std::size_t count = std::size_t(n) * std::size_t(n);
    std::vector<float> d2(count, 0.0f);
    std::vector<std::uint16_t> lo(count), hi(count);
    RottgerQuadtree::build_matrix(patch, min_resolution, nullptr, 0.0, d2, lo, hi);
    return d2;
}

void RottgerQuadtree::refine(const glm::dvec3& eye, double c, const Frustum* frustum) {
    ++frame_;
    if (frame_ == 0) { // wrapped: stale stamps could alias the new frame
        std::fill(stamp_.begin(), stamp_.end(), 0u);
        frame_ = 1;
    }
    eye_ = eye;
    c_ = c;
    frustum_ = frustum;
    const int root = (n_ - 1) / 2;
    refine_node(root, root, root, frustum == nullptr);
}

void RottgerQuadtree::refine_node(int ci, int cj, int h, bool inside) {
    if (h < 2) return; // 3x3 nodes are the finest: always leaves
    // Along a seam with a coarser patch, children must not be smaller than
    // its finest nodes (their corners would fall between its samples).
    const int m = n_ - 1;
    int finest = 1;
    if (ci - h == 0) finest = std::max(finest, seam_ratio_[North]);
    if (ci + h == m) finest = std::max(finest, seam_ratio_[South]);
    if (cj - h == 0) finest = std::max(finest, seam_ratio_[West]);
    if (cj + h == m) finest = std::max(finest, seam_ratio_[East]);
    if (h / 2 < finest) return;
    const double hs = terrain_->h_scale();
    const glm::dvec3 centre(hs_full_ * double(origin_col_ + step_ * cj), double(world_y(ci, cj)),
                            hs_full_ * double(origin_row_ + step_ * ci));
    const double l = glm::length(centre - eye_);
    const double d = 2.0 * h * hs;
    const double f = l / (d * C_ * std::max(c_ * double(d2_[idx(ci, cj)]), 1.0));
    if (f >= 1.0) return;
    if (!inside) {
        // Only after f < 1: the frustum test costs more than f.
        const double y0 = terrain_->v_scale() * double(lo_[idx(ci, cj)]) + terrain_->y_offset();
        const double y1 = terrain_->v_scale() * double(hi_[idx(ci, cj)]) + terrain_->y_offset();
        const glm::dvec3 lo(hs_full_ * double(origin_col_ + step_ * (cj - h)), std::min(y0, y1),
                            hs_full_ * double(origin_row_ + step_ * (ci - h)));
        const glm::dvec3 hi(hs_full_ * double(origin_col_ + step_ * (cj + h)), std::max(y0, y1),
                            hs_full_ * double(origin_row_ + step_ * (ci + h)));
        const Containment k = frustum_->classify_box(lo, hi);
        if (k == Containment::AllOutside) return;
        inside = k == Containment::AllInside;
    }
    stamp_[idx(ci, cj)] = frame_;
    const int q = h / 2;
    refine_node(ci - q, cj - q, q, inside);
    refine_node(ci - q, cj + q, q, inside);
    refine_node(ci + q, cj - q, q, inside);
    refine_node(ci + q, cj + q, q, inside);
}

// A node given in this patch's local frame that may lie one step across a
// seam, in an edge neighbour, expressed in that patch's frame (its origin is
// one tile away and its samples may be `step` apart); patch = nullptr when
// there is no such patch or the node falls between its samples.
RottgerQuadtree::NodeRef RottgerQuadtree::locate(int ci, int cj, int h) const {
    const int m = n_ - 1;
    const RottgerQuadtree* q = this;
    if (ci < 0) q = neighbours_[North];
    else if (ci > m) q = neighbours_[South];
    else if (cj < 0) q = neighbours_[West];
    else if (cj > m) q = neighbours_[East];
    if (q == this) return {this, ci, cj, h};
    if (!q) return {nullptr, 0, 0, 0};
    const int gi = origin_row_ + step_ * ci - q->origin_row_, gj = origin_col_ + step_ * cj - q->origin_col_;
    const int gh = step_ * h;
    if (gi % q->step_ != 0 || gj % q->step_ != 0 || gh % q->step_ != 0) return {nullptr, 0, 0, 0};
    return {q, gi / q->step_, gj / q->step_, gh / q->step_};
}

bool RottgerQuadtree::node_subdivided(int ci, int cj, int h) const {
    const NodeRef n = locate(ci, cj, h);
    return n.patch && n.h >= 2 && n.patch->subdivided(n.ci, n.cj);
}

bool RottgerQuadtree::has_patch(int ci, int cj) const {
    const int m = n_ - 1;
    if (ci < 0) return neighbours_[North] != nullptr;
    if (ci > m) return neighbours_[South] != nullptr;
    if (cj < 0) return neighbours_[West] != nullptr;
    if (cj > m) return neighbours_[East] != nullptr;
    return true;
}

bool RottgerQuadtree::node_reached(int ci, int cj, int h) const {
    const NodeRef n = locate(ci, cj, h);
    if (!n.patch) return false;
    if (2 * n.h == n.patch->n_ - 1) return true; // a root is present whenever its patch is drawn
    if (2 * n.h > n.patch->n_ - 1) return false;
    // The parent is centred on the neighbouring odd multiple of 2h.
    const int H = n.h;
    const int pi = ((n.ci - H) / (2 * H)) % 2 == 1 ? n.ci - H : n.ci + H;
    const int pj = ((n.cj - H) / (2 * H)) % 2 == 1 ? n.cj - H : n.cj + H;
    return n.patch->subdivided(pi, pj);
}

// Points strictly inside the edge shared with the node (ci, cj, h) that lies
// on side `towards` of a leaf of the same size, in increasing row (West/East)
// or column (North/South) order; the node is known to be present in the mesh.
// These are the corners of the neighbour side's leaves along the edge, plus
// the midpoint when that side's leaf is as large as ours: a smaller leaf
// there skips its own midpoint on this edge, because its same-size node on
// our side is not present (Röttger's rule), so we must not add it either.
void RottgerQuadtree::collect_edge(int ci, int cj, int h, Side towards, bool same_size,
                                   std::vector<std::array<int, 2>>& out) const {
    const bool along_row = towards == North || towards == South;
    // The shared edge is the node's edge facing the leaf.
    const int er = towards == North ? ci + h : towards == South ? ci - h : ci;
    const int ec = towards == West ? cj + h : towards == East ? cj - h : cj;
    if (h >= 2 && node_subdivided(ci, cj, h)) {
        const int q = h / 2;
        const int off_r = towards == North ? q : towards == South ? -q : 0;
        const int off_c = towards == West ? q : towards == East ? -q : 0;
        if (along_row) {
            collect_edge(ci + off_r, cj - q, q, towards, false, out);
            out.push_back({er, ec});
            collect_edge(ci + off_r, cj + q, q, towards, false, out);
        } else {
            collect_edge(ci - q, cj + off_c, q, towards, false, out);
            out.push_back({er, ec});
            collect_edge(ci + q, cj + off_c, q, towards, false, out);
        }
    } else if (same_size) {
        out.push_back({er, ec});
    }
}

std::uint32_t RottgerQuadtree::vertex(int row, int col) {
    const std::size_t i = idx(row, col);
    if (vertex_stamp_[i] == emit_frame_) return vertex_id_[i];
    const auto id = std::uint32_t(out_->positions.size());
    out_->positions.emplace_back(float(hs_full_ * double(origin_col_ + step_ * col)), world_y(row, col),
                                 float(hs_full_ * double(origin_row_ + step_ * row)));
    out_->normals.push_back((*normals_)[i]);
    out_->colors.push_back(terrain_->color(row, col));
    vertex_stamp_[i] = emit_frame_;
    vertex_id_[i] = id;
    return id;
}

void RottgerQuadtree::emit_leaves(int ci, int cj, int h) {
    if (h >= 2 && subdivided(ci, cj)) {
        const int q = h / 2;
        emit_leaves(ci - q, cj - q, q);
        emit_leaves(ci - q, cj + q, q);
        emit_leaves(ci + q, cj - q, q);
        emit_leaves(ci + q, cj + q, q);
        return;
    }
    // The fan boundary, counter-clockwise seen from above (X east, Z south):
    // NW, down the west edge, SW, along the south edge, SE, up the east
    // edge, NE, back along the north edge.
    ring_.clear();
    auto edge = [&](Side side, int nr, int nc, bool reverse) {
        if (!has_patch(nr, nc)) {
            // Terrain border (or a patch not drawn this frame): no one to
            // crack with, so keep the midpoint as if the neighbour were alike.
            ring_.push_back({(ci + nr) / 2, (cj + nc) / 2});
            return;
        }
        if (!node_reached(nr, nc, h)) return; // neighbour coarser: skip (Röttger)
        edge_.clear();
        collect_edge(nr, nc, h, side, true, edge_);
        if (reverse) std::reverse(edge_.begin(), edge_.end());
        ring_.insert(ring_.end(), edge_.begin(), edge_.end());
    };
    ring_.push_back({ci - h, cj - h});
    edge(West, ci, cj - 2 * h, false);
    ring_.push_back({ci + h, cj - h});
    edge(South, ci + 2 * h, cj, false);
    ring_.push_back({ci + h, cj + h});
    edge(East, ci, cj + 2 * h, true);
    ring_.push_back({ci - h, cj + h});
    edge(North, ci - 2 * h, cj, true);
    const std::uint32_t centre = vertex(ci, cj);
    std::uint32_t prev = vertex(ring_[0][0], ring_[0][1]);
    const std::uint32_t first = prev;
    for (std::size_t k = 1; k <= ring_.size(); ++k) {
        const std::uint32_t cur = k == ring_.size() ? first : vertex(ring_[k][0], ring_[k][1]);
        out_->indices.insert(out_->indices.end(), {centre, prev, cur});
        prev = cur;
    }
}

std::size_t RottgerQuadtree::append_fans(MeshArrays& out) {
    ++emit_frame_;
    if (emit_frame_ == 0) {
        std::fill(vertex_stamp_.begin(), vertex_stamp_.end(), 0u);
        emit_frame_ = 1;
    }
    out_ = &out;
    const std::size_t before = out.triangle_count();
    const int root = (n_ - 1) / 2;
    emit_leaves(root, root, root);
    out_ = nullptr;
    return out.triangle_count() - before;
}

} // namespace overflight
