// Based on: Williams 1978 (shadow depth maps). See ShadowPixels.h.
#include "core/ShadowPixels.h"

#include "core/Parallel.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

namespace overflight {

namespace {

// A caster seen along the sun: its extents across the sun along the frame's
// a, b and along its own direction d and normal n (in a, b coordinates),
// and its highest point along the sun.
struct SunExtent {
    double u0, u1, v0, v1, w1;
    double du, dv; // d = (du, dv); n = (-dv, du)
    double d0, d1, n0, n1;
};

} // namespace

std::vector<PixelRect> shadow_pixels(const DepthImage& depth, const Camera& camera, const SnapGrid& grid,
                                     const glm::vec3& sun, std::span<const ShadowCaster> casters,
                                     std::span<const PixelRect> rects) {
    const int width = camera.width, height = camera.height;
    // The sun's frame: a, b across the sun, s towards it.
    const glm::dvec3 s = glm::normalize(glm::dvec3(sun));
    const glm::dvec3 a = glm::normalize(glm::cross(s, std::abs(s.y) > 0.99 ? glm::dvec3(0, 0, 1) : glm::dvec3(0, 1, 0)));
    const glm::dvec3 b = glm::cross(a, s);
    std::vector<SunExtent> extent(casters.size());
    for (std::size_t i = 0; i < casters.size(); ++i) {
        SunExtent& e = extent[i];
        const auto points = casters[i].points;
        const double g = casters[i].margin;
        e = {HUGE_VAL, -HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL, 1, 0, HUGE_VAL, -HUGE_VAL, HUGE_VAL, -HUGE_VAL};
        if (points.empty()) continue;
        // Eye-relative, as the pixels' points.
        const auto uvw = [&](const glm::vec3& p) {
            const glm::dvec3 q = glm::dvec3(p) - camera.eye;
            return glm::dvec3(glm::dot(q, a), glm::dot(q, b), glm::dot(q, s));
        };
        const glm::dvec3 first = uvw(points.front()), last = uvw(points.back());
        const double len = std::hypot(last.x - first.x, last.y - first.y);
        if (len > 0) {
            e.du = (last.x - first.x) / len;
            e.dv = (last.y - first.y) / len;
        }
        for (const glm::vec3& p : points) {
            const glm::dvec3 q = uvw(p);
            e.u0 = std::min(e.u0, q.x - g);
            e.u1 = std::max(e.u1, q.x + g);
            e.v0 = std::min(e.v0, q.y - g);
            e.v1 = std::max(e.v1, q.y + g);
            e.w1 = std::max(e.w1, q.z + g);
            const double d = q.x * e.du + q.y * e.dv, n = q.y * e.du - q.x * e.dv;
            e.d0 = std::min(e.d0, d - g);
            e.d1 = std::max(e.d1, d + g);
            e.n0 = std::min(e.n0, n - g);
            e.n1 = std::max(e.n1, n + g);
        }
    }
    const double near = camera.near;
    const Terrain* terrain = grid.terrain;
    const int grid_cols = terrain ? (terrain->cols() - 1) / grid.stride + 1 : 0;
    const int grid_rows = terrain ? (terrain->rows() - 1) / grid.stride + 1 : 0;
    const double per_unit = grid.texels_per_unit;
    const double cell = per_unit > 0 ? 1.0 / per_unit : 1.0;
    // The pass's float eye: an error of a few units in its last place,
    // besides the depth's (relative to the distance, `rel` below).
    const double absolute = 1e-3 * cell + 1e-6 * (std::abs(camera.eye.x) + std::abs(camera.eye.y) + std::abs(camera.eye.z));

    // Whether the pixel (col, row) may be darkened by one of the `active`
    // casters; ray0 + col dray is the row's ray through the pixel (Camera::ray).
    const auto shadowed = [&](int col, int row, const glm::dvec3& ray0, const glm::dvec3& dray,
                              std::span<const int> active) {
        const double d = depth.at(col, row);
        if (d >= 1.0) return false; // sky: the pass discards it
        // The ray through the pixel centre, of unit length along the view
        // axis, linear along the row, times the view depth: the point the
        // pass rebuilds from the depth through the inverse matrices.
        const glm::dvec3 r = (ray0 + double(col) * dray) * camera.view_depth_of_window(d);
        const double dist = glm::length(r);
        if (!(dist < HUGE_VAL)) return true;
        const double rel = 1e-5 + 4e-7 * dist / near;
        const double slack = rel * dist + absolute;
        // The ray parameters of the points the pass may test: the point
        // itself, or the top it moves the point to. The hull of those.
        double t0 = HUGE_VAL, t1 = -HUGE_VAL;
        const auto keep = [&](double t) {
            t0 = std::min(t0, t);
            t1 = std::max(t1, t);
        };
        if (terrain && r.y < slack) {
            if (r.y > -slack) return true; // too level to say whether the pass moves the point
            // The samples that may be nearest to a point (x, z) known to
            // within `err`, as the pass rounds it.
            const auto span = [&](double x, double err, int last) {
                const double p = x * per_unit + 0.5, wiggle = err * per_unit + 1e-4;
                return std::pair(std::clamp(int(std::floor(p - wiggle)), 0, last),
                                 std::clamp(int(std::floor(p + wiggle)), 0, last));
            };
            const auto height_at = [&](int x, int z) { return terrain->sample_height(z * grid.stride, x * grid.stride); };
            const auto [x0, x1] = span(camera.eye.x + r.x, slack, grid_cols - 1);
            const auto [z0, z1] = span(camera.eye.z + r.z, slack, grid_rows - 1);
            for (int z = z0; z <= z1; ++z)
                for (int x = x0; x <= x1; ++x) {
                    // The top of that sample's height along the ray: the
                    // pass moves the point there iff the sample nearest to
                    // the top has the same height.
                    const float h = height_at(x, z);
                    const double t = (double(h) - camera.eye.y) / r.y;
                    const double err = rel * dist * std::abs(t) + absolute;
                    const auto [u0, u1] = span(camera.eye.x + t * r.x, err, grid_cols - 1);
                    const auto [v0, v1] = span(camera.eye.z + t * r.z, err, grid_rows - 1);
                    bool same = false, other = false;
                    for (int v = v0; v <= v1; ++v)
                        for (int u = u0; u <= u1; ++u) (height_at(u, v) == h ? same : other) = true;
                    if (same) keep(t);
                    if (other) keep(1.0);
                }
        } else {
            keep(1.0);
        }
        const double m = rel * dist * std::max(std::abs(t0), std::abs(t1)) + absolute;
        const double ur = glm::dot(r, a), vr = glm::dot(r, b), wr = glm::dot(r, s);
        const double u0 = std::min(t0 * ur, t1 * ur) - m, u1 = std::max(t0 * ur, t1 * ur) + m;
        const double v0 = std::min(t0 * vr, t1 * vr) - m, v1 = std::max(t0 * vr, t1 * vr) + m;
        const double w0 = std::min(t0 * wr, t1 * wr) - m;
        // The segment's ends across the sun: (pu, pv) and (qu, qv).
        const double pu = t0 * ur, pv = t0 * vr, qu = t1 * ur, qv = t1 * vr;
        for (const int i : active) {
            const SunExtent& x = extent[std::size_t(i)];
            if (!(u1 >= x.u0 && u0 <= x.u1 && v1 >= x.v0 && v0 <= x.v1 && w0 <= x.w1)) continue;
            const double pd = pu * x.du + pv * x.dv, qd = qu * x.du + qv * x.dv;
            const double pn = pv * x.du - pu * x.dv, qn = qv * x.du - qu * x.dv;
            if (std::max(pd, qd) + m >= x.d0 && std::min(pd, qd) - m <= x.d1 && std::max(pn, qn) + m >= x.n0 &&
                std::min(pn, qn) - m <= x.n1)
                return true;
        }
        return false;
    };

    // Each row's runs [col0, col1) of pixels to keep.
    std::vector<std::vector<std::pair<int, int>>> runs(std::size_t(std::max(height, 0)));
    parallel::for_each_range(0, height, 16, [&](int first, int last) {
        std::vector<int> active, here, cuts;
        for (int row = first; row < last; ++row) {
            active.clear();
            cuts.clear();
            for (std::size_t i = 0; i < rects.size(); ++i) {
                const PixelRect& rect = rects[i];
                if (rect.empty() || row < rect.row0 || row >= rect.row1) continue;
                active.push_back(int(i));
                cuts.insert(cuts.end(), {rect.col0, rect.col1});
            }
            std::sort(cuts.begin(), cuts.end());
            cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
            auto& out = runs[std::size_t(row)];
            const glm::dvec3 ray0 = camera.ray(camera.u_of(0), camera.v_of(row));
            const glm::dvec3 dray = camera.ray(camera.u_of(1), camera.v_of(row)) - ray0;
            // Between consecutive cuts the same casters' rectangles hold the pixels.
            for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
                const int c0 = cuts[k], c1 = cuts[k + 1];
                here.clear();
                for (const int i : active)
                    if (rects[std::size_t(i)].col0 <= c0 && rects[std::size_t(i)].col1 >= c1) here.push_back(i);
                if (here.empty()) continue;
                for (int col = c0; col < c1; ++col) {
                    if (!shadowed(col, row, ray0, dray, here)) continue;
                    if (!out.empty() && out.back().second == col)
                        out.back().second = col + 1;
                    else
                        out.emplace_back(col, col + 1);
                }
            }
        }
    });

    // A row's runs extend the rectangles of the row above when they are the same.
    std::vector<PixelRect> out;
    std::size_t above = 0; // the first rectangle of the row above
    for (int row = 0; row < height; ++row) {
        const auto& rr = runs[std::size_t(row)];
        const bool same = row > 0 && rr == runs[std::size_t(row - 1)];
        if (same) {
            for (std::size_t k = above; k < out.size(); ++k) out[k].row1 = row + 1;
            continue;
        }
        above = out.size();
        for (const auto& [col0, col1] : rr) out.push_back({col0, row, col1, row + 1});
    }
    return out;
}

} // namespace overflight
