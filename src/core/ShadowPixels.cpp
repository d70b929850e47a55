// Based on: Williams 1978 (shadow depth maps). See ShadowPixels.h.
#include "core/ShadowPixels.h"

#include "core/HeightBounds.h"
#include "core/Parallel.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
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
                                     std::span<const PixelRect> rects, bool per_tile) {
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
    // casters whose rectangle holds its column (they all hold its row);
    // ray0 + col dray is the row's ray through the pixel (Camera::ray).
    const auto holds = [&](int i, int col) { return rects[std::size_t(i)].col0 <= col && col < rects[std::size_t(i)].col1; };
    const auto shadowed = [&](int col, int row, const glm::dvec3& ray0, const glm::dvec3& dray,
                              std::span<const int> active) {
        if (std::none_of(active.begin(), active.end(), [&](int i) { return holds(i, col); })) return false;
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
            if (!holds(i, col)) continue;
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

    // The heights the pass may move a point to, over any rectangle of the grid.
    std::optional<HeightBounds> own_bounds;
    const HeightBounds* bounds = grid.bounds;
    if (terrain && !bounds) bounds = &own_bounds.emplace(*terrain, grid.stride);

    // Every point a tile's pixels may test lies in the convex hull of a few
    // points (eye-relative), grown by `margin`: the corner rays at the
    // tile's nearest and farthest depth, and, where the pass may move points
    // onto sample tops, the corner rays at the lowest and highest top near
    // them. `known` false: some pixel keeps itself whatever the casters
    // (a ray too level, a depth too far to trust).
    struct TileHull {
        bool known = false;
        int count = 0;
        std::array<glm::dvec3, 16> uvw; // the points' sun coordinates
        double u0 = HUGE_VAL, u1 = -HUGE_VAL, v0 = HUGE_VAL, v1 = -HUGE_VAL, w0 = HUGE_VAL; // their extents
        double margin = 0;
    };
    const auto tile_hull = [&](const std::array<glm::dvec3, 4>& corner, double zlo, double zhi) {
        TileHull hull;
        if (!(zhi < HUGE_VAL)) return hull;
        double reach = 0, ylo = HUGE_VAL, yhi = -HUGE_VAL;
        for (const glm::dvec3& c : corner) {
            reach = std::max(reach, glm::length(c) * zhi);
            ylo = std::min(ylo, c.y);
            yhi = std::max(yhi, c.y);
        }
        // The per-pixel test's tolerances at the tile's farthest pixel,
        // a little wider than any of its pixels' (their rounding apart).
        const double rel = 1e-5 + 4e-7 * reach / near;
        const double slack = (rel * reach + absolute) * (1.0 + 1e-6);
        std::array<glm::dvec3, 16> points;
        int count = 0;
        for (const glm::dvec3& c : corner) {
            points[std::size_t(count++)] = c * zlo;
            points[std::size_t(count++)] = c * zhi;
        }
        if (terrain && !(ylo * zlo > slack)) {
            if (!(yhi * zlo < -slack)) return hull; // a ray may be too level, or rise
            // The samples that may be nearest to the tile's points.
            double x0 = HUGE_VAL, x1 = -HUGE_VAL, z0 = HUGE_VAL, z1 = -HUGE_VAL;
            for (int k = 0; k < count; ++k) {
                x0 = std::min(x0, points[std::size_t(k)].x);
                x1 = std::max(x1, points[std::size_t(k)].x);
                z0 = std::min(z0, points[std::size_t(k)].z);
                z1 = std::max(z1, points[std::size_t(k)].z);
            }
            const double wiggle = slack * per_unit + 1e-3;
            const auto index = [&](double x, int last) {
                return std::clamp(int(std::floor(std::clamp(x * per_unit + 0.5, -1.0, double(last) + 1.0))), 0, last);
            };
            const auto [hlo, hhi] = bounds->range(index(camera.eye.x + x0 - wiggle * cell, grid_cols - 1),
                                                   index(camera.eye.z + z0 - wiggle * cell, grid_rows - 1),
                                                   index(camera.eye.x + x1 + wiggle * cell, grid_cols - 1),
                                                   index(camera.eye.z + z1 + wiggle * cell, grid_rows - 1));
            for (const glm::dvec3& c : corner) {
                points[std::size_t(count++)] = c * ((double(hlo) - camera.eye.y) / c.y);
                points[std::size_t(count++)] = c * ((double(hhi) - camera.eye.y) / c.y);
            }
        }
        double far_point = 0;
        for (int k = 0; k < count; ++k) {
            const glm::dvec3& p = points[std::size_t(k)];
            far_point = std::max(far_point, glm::length(p));
            const glm::dvec3 q(glm::dot(p, a), glm::dot(p, b), glm::dot(p, s));
            hull.uvw[std::size_t(k)] = q;
            hull.u0 = std::min(hull.u0, q.x);
            hull.u1 = std::max(hull.u1, q.x);
            hull.v0 = std::min(hull.v0, q.y);
            hull.v1 = std::max(hull.v1, q.y);
            hull.w0 = std::min(hull.w0, q.z);
        }
        hull.known = true;
        hull.count = count;
        hull.margin = (rel * far_point + absolute) * (1.0 + 1e-6);
        return hull;
    };
    // Whether caster `x` may shadow some point of `hull`: the per-pixel
    // test's comparisons, on the hull's extents.
    const auto may_shadow = [](const TileHull& hull, const SunExtent& x) {
        const double m = hull.margin;
        if (!(hull.u1 + m >= x.u0 && hull.u0 - m <= x.u1 && hull.v1 + m >= x.v0 && hull.v0 - m <= x.v1 &&
              hull.w0 - m <= x.w1))
            return false;
        double d0 = HUGE_VAL, d1 = -HUGE_VAL, n0 = HUGE_VAL, n1 = -HUGE_VAL;
        for (int k = 0; k < hull.count; ++k) {
            const glm::dvec3& p = hull.uvw[std::size_t(k)];
            const double d = p.x * x.du + p.y * x.dv, n = p.y * x.du - p.x * x.dv;
            d0 = std::min(d0, d);
            d1 = std::max(d1, d);
            n0 = std::min(n0, n);
            n1 = std::max(n1, n);
        }
        return d1 + m >= x.d0 && d0 - m <= x.d1 && n1 + m >= x.n0 && n0 - m <= x.n1;
    };

    // Each row's runs [col0, col1) of pixels to keep, found per tile of
    // kTile x kTile pixels: a tile whose hull no caster over it may shadow
    // is passed over whole, so that the per-pixel test's cost follows the
    // shadows' area rather than the casters' screen rectangles'.
    constexpr int kTile = 8;
    std::vector<std::vector<std::pair<int, int>>> runs(std::size_t(std::max(height, 0)));
    const int bands = (height + kTile - 1) / kTile;
    parallel::for_each_range(0, bands, 1, [&](int first, int last) {
        std::vector<int> active, candidates, here;
        std::array<glm::dvec3, kTile> ray0, dray;
        for (int band = first; band < last; ++band) {
            const int row0 = band * kTile, row1 = std::min(row0 + kTile, height);
            active.clear();
            int col_lo = width, col_hi = 0;
            for (std::size_t i = 0; i < rects.size(); ++i) {
                const PixelRect& rect = rects[i];
                if (rect.empty() || rect.row1 <= row0 || rect.row0 >= row1) continue;
                active.push_back(int(i));
                col_lo = std::min(col_lo, rect.col0);
                col_hi = std::max(col_hi, rect.col1);
            }
            if (active.empty()) continue;
            for (int row = row0; row < row1; ++row) {
                ray0[std::size_t(row - row0)] = camera.ray(camera.u_of(0), camera.v_of(row));
                dray[std::size_t(row - row0)] = camera.ray(camera.u_of(1), camera.v_of(row)) - ray0[std::size_t(row - row0)];
            }
            for (int c0 = col_lo / kTile * kTile; c0 < col_hi; c0 += kTile) {
                const int c1 = std::min(c0 + kTile, width);
                candidates.clear();
                for (const int i : active)
                    if (rects[std::size_t(i)].col0 < c1 && rects[std::size_t(i)].col1 > c0) candidates.push_back(i);
                if (candidates.empty()) continue;
                float dlo = 1.0f, dhi = 0.0f;
                for (int row = row0; row < row1; ++row)
                    for (int col = c0; col < c1; ++col) {
                        const float d = depth.at(col, row);
                        if (d >= 1.0f) continue;
                        dlo = std::min(dlo, d);
                        dhi = std::max(dhi, d);
                    }
                if (dlo > dhi) continue; // all sky
                const std::array<glm::dvec3, 4> corner{
                    ray0[0] + double(c0) * dray[0], ray0[0] + double(c1 - 1) * dray[0],
                    ray0[std::size_t(row1 - 1 - row0)] + double(c0) * dray[std::size_t(row1 - 1 - row0)],
                    ray0[std::size_t(row1 - 1 - row0)] + double(c1 - 1) * dray[std::size_t(row1 - 1 - row0)]};
                const TileHull hull =
                    tile_hull(corner, camera.view_depth_of_window(dlo), camera.view_depth_of_window(dhi));
                if (hull.known && per_tile)
                    std::erase_if(candidates, [&](int i) { return !may_shadow(hull, extent[std::size_t(i)]); });
                if (candidates.empty()) continue;
                for (int row = row0; row < row1; ++row) {
                    here.clear();
                    for (const int i : candidates)
                        if (rects[std::size_t(i)].row0 <= row && rects[std::size_t(i)].row1 > row) here.push_back(i);
                    if (here.empty()) continue;
                    auto& out = runs[std::size_t(row)];
                    for (int col = c0; col < c1; ++col) {
                        if (!shadowed(col, row, ray0[std::size_t(row - row0)], dray[std::size_t(row - row0)], here))
                            continue;
                        if (!out.empty() && out.back().second == col)
                            out.back().second = col + 1;
                        else
                            out.emplace_back(col, col + 1);
                    }
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
