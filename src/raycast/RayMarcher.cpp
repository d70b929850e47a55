// Based on: Szenberg 1997 sec. 4 (plain ray casting), OpenGL unprojection.
// See RayMarcher.h. Deliberately simple and slow: it is the reference.
#include "raycast/RayMarcher.h"

#include "core/Parallel.h"
#include "raycast/Atmosphere.h"
#include "raycast/CellTraversal.h"
#include "raycast/ImageryTexels.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace overflight {

namespace {

// Clips the segment a + t (b - a), t in [0,1], to lo <= x <= hi on one axis.
bool clip_axis(double a, double d, double lo, double hi, double& t0, double& t1) {
    if (d == 0.0) return a >= lo && a <= hi;
    double ta = (lo - a) / d, tb = (hi - a) / d;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    return t0 <= t1;
}

} // namespace

RayMarcher::Frame RayMarcher::frame(const Camera& camera) const {
    Frame f;
    f.view_projection = camera.projection_matrix() * camera.view_matrix();
    f.inverse_view_projection = glm::inverse(f.view_projection);
    f.air = aerial_frame(env_, camera.eye.y);
    return f;
}

RayMarcher::Hit RayMarcher::intersect(const glm::dvec3& a, const glm::dvec3& b, SurfaceModel surface) const {
    return surface == SurfaceModel::Blocks ? intersect_blocks(a, b) : intersect_bilinear(a, b);
}

RayMarcher::Hit RayMarcher::intersect_blocks(const glm::dvec3& a, const glm::dvec3& b) const {
    const Terrain& t = terrain_;
    const double hs = t.h_scale();
    const glm::dvec3 d = b - a;
    double t0 = 0.0, t1 = 1.0;
    if (!clip_axis(a.x, d.x, 0.0, t.width(), t0, t1) || !clip_axis(a.z, d.z, 0.0, t.depth(), t0, t1)) return {};
    // Cell space: cell (i, j) = [i, i+1) x [j, j+1) holds the sample at its centre.
    CellTraversal cells(a, d, hs, t.cols(), t.rows(), t0);
    // A rising segment is nowhere lower in a block than where it enters it:
    // the block holds no hit while that height is above the block's highest
    // sample (its pyramid height), and the traversal jumps over it.
    const bool skip = pyramid_ && pyramid_->levels() > 0 && d.y > 0.0 && t.v_scale() > 0.0f;
    int level = 0;
    double s = t0;
    for (;;) {
        if (skip) {
            const double ya = a.y + s * d.y;
            // The coarsest block below the segment, from the last one's level.
            while (level < pyramid_->levels() && ya > block_height(level + 1, cells.iz, cells.ix)) ++level;
            while (level > 0 && !(ya > block_height(level, cells.iz, cells.ix))) --level;
            if (level > 0) {
                const int x0 = cells.ix >> level << level, z0 = cells.iz >> level << level;
                const int x1 = std::min(x0 + (1 << level), t.cols()), z1 = std::min(z0 + (1 << level), t.rows());
                // Both sides the segment can leave through are the grid's
                // edges (always so for the whole grid's block: the segment
                // above every sample): it leaves the grid, or ends, unhit.
                if ((cells.sx > 0 ? x1 == t.cols() : x0 == 0) && (cells.sz > 0 ? z1 == t.rows() : z0 == 0)) return {};
                const double e = cells.leave_block(x0, x1, z0, z1);
                if (e >= t1) return {};
                s = e;
                if (cells.ix < 0 || cells.iz < 0 || cells.ix >= t.cols() || cells.iz >= t.rows()) return {};
                continue;
            }
        }
        const double e = std::min({cells.next_x, cells.next_z, t1});
        const double h = t.sample_height(cells.iz, cells.ix);
        const double ya = a.y + s * d.y, yb = a.y + e * d.y;
        double hit_s = -1.0;
        if (ya <= h) hit_s = s;                                  // front face (or starts inside)
        else if (yb <= h) hit_s = s + (ya - h) / (ya - yb) * (e - s); // top face
        if (hit_s >= 0.0) return {true, a + hit_s * d, color_at(cells.iz, cells.ix)};
        if (e >= t1) return {};
        s = e;
        cells.advance();
        if (cells.ix < 0 || cells.iz < 0 || cells.ix >= t.cols() || cells.iz >= t.rows()) return {};
    }
}

RayMarcher::Hit RayMarcher::intersect_bilinear(const glm::dvec3& a, const glm::dvec3& b) const {
    const Terrain& t = terrain_;
    const glm::dvec3 d = b - a;
    double t0 = 0.0, t1 = 1.0;
    if (!clip_axis(a.x, d.x, 0.0, t.width(), t0, t1) || !clip_axis(a.z, d.z, 0.0, t.depth(), t0, t1)) return {};
    auto above = [&](double s) {
        const glm::dvec3 p = a + s * d;
        return p.y - double(t.height_bilinear(float(p.x), float(p.z)));
    };
    // A quarter cell horizontally per step (and at least 8 steps vertically).
    const double cells = std::hypot(d.x, d.z) * (t1 - t0) / t.h_scale();
    const int n = std::max(8, int(std::ceil(cells * 4.0)));
    double prev_s = t0, prev_f = above(t0);
    if (prev_f <= 0.0) {
        const glm::dvec3 p = a + t0 * d;
        return {true, p, color_at(std::clamp(int(std::lround(p.z / t.h_scale())), 0, t.rows() - 1),
                                 std::clamp(int(std::lround(p.x / t.h_scale())), 0, t.cols() - 1))};
    }
    for (int i = 1; i <= n; ++i) {
        const double s = t0 + (t1 - t0) * i / n;
        const double f = above(s);
        if (f <= 0.0) {
            double lo = prev_s, hi = s;
            for (int k = 0; k < 40; ++k) {
                const double mid = 0.5 * (lo + hi);
                (above(mid) > 0.0 ? lo : hi) = mid;
            }
            const glm::dvec3 p = a + hi * d;
            const int row = std::clamp(int(std::lround(p.z / t.h_scale())), 0, t.rows() - 1);
            const int col = std::clamp(int(std::lround(p.x / t.h_scale())), 0, t.cols() - 1);
            return {true, p, color_at(row, col)};
        }
        prev_s = s;
        prev_f = f;
    }
    return {};
}

void RayMarcher::shade_pixel(const Camera& camera, const Frame& frame, SurfaceModel surface, int col, int row,
                             Rgb8& color, float& depth) const {
    // Pixel centre in normalised device coordinates (GL's y points up).
    const double nx = (col + 0.5) / camera.width * 2.0 - 1.0;
    const double ny = 1.0 - (row + 0.5) / camera.height * 2.0;
    const glm::dvec4 pn = frame.inverse_view_projection * glm::dvec4(nx, ny, -1.0, 1.0);
    const glm::dvec4 pf = frame.inverse_view_projection * glm::dvec4(nx, ny, 1.0, 1.0);
    const glm::dvec3 a = glm::dvec3(pn) / pn.w, b = glm::dvec3(pf) / pf.w;
    const Hit hit = intersect(a, b, surface);
    if (!hit.hit) {
        color = env_.atmosphere ? aerial_sky_rgb(frame.air, b - a) : sky_color(env_, b - a);
        depth = 1.0f;
        return;
    }
    const glm::dvec4 clip = frame.view_projection * glm::dvec4(hit.point, 1.0);
    depth = float(std::clamp((clip.z / clip.w + 1.0) * 0.5, 0.0, 1.0));
    Rgb8 surface_color = hit.surface;
    if (imagery_) {
        // The longer side of the pixel's trace on level ground: its view depth
        // over the focal length, over the ray's slope when it looks down.
        const glm::dvec3 ray = b - a;
        const double slope = -ray.y / std::max(std::hypot(ray.x, ray.z), 1e-12);
        const double view_depth = glm::dot(hit.point - camera.eye, camera.view_axis());
        const double footprint = view_depth / (camera.focal_px() * (slope > 0 ? std::max(slope, 1.0 / 1024.0) : 1.0));
        const int level = mip_level_for_footprint(footprint, imagery_->texel_size(0), imagery_->levels());
        surface_color = modulate_light(surface_color, imagery_->nearest(hit.point.x, hit.point.z, level));
    }
    color = env_.atmosphere ? aerial_rgb(frame.air, surface_color, hit.point - camera.eye)
                            : apply_fog(env_, surface_color, fog_factor(env_, glm::length(hit.point - camera.eye)));
}

void RayMarcher::render(const Camera& camera, SurfaceModel surface, ColorImage& color, DepthImage& depth) const {
    camera.validate();
    if (color.width != camera.width || color.height != camera.height) color.resize(camera.width, camera.height);
    if (depth.width != camera.width || depth.height != camera.height) depth.resize(camera.width, camera.height);
    const Frame f = frame(camera);
    parallel::for_each_index(0, camera.height, [&](int row) {
        for (int col = 0; col < camera.width; ++col) shade_pixel(camera, f, surface, col, row, color.at(col, row), depth.at(col, row));
    });
}

} // namespace overflight
