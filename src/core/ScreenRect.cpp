// Based on: Szenberg et al. 1997 sec. 5 (objects drawn by Z-buffer over the
// ray-cast depth); DESIGN sec. 2 (camera).
#include "core/ScreenRect.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace overflight {

PixelRect screen_rect(std::span<const WorldBox> boxes, const Camera& camera) {
    double c0 = HUGE_VAL, r0 = HUGE_VAL, c1 = -HUGE_VAL, r1 = -HUGE_VAL;
    const auto add = [&](const glm::dvec3& p) {
        const Camera::Projected q = camera.project(p);
        c0 = std::min(c0, q.col);
        c1 = std::max(c1, q.col);
        r0 = std::min(r0, q.row);
        r1 = std::max(r1, q.row);
    };
    for (const WorldBox& b : boxes) {
        glm::dvec3 corner[8];
        double depth[8];
        int behind = 0;
        for (int k = 0; k < 8; ++k) {
            corner[k] = {(k & 1) ? b.hi.x : b.lo.x, (k & 2) ? b.hi.y : b.lo.y, (k & 4) ? b.hi.z : b.lo.z};
            depth[k] = camera.view_depth(corner[k]) - camera.near;
            behind += !(depth[k] > 0);
        }
        if (behind == 8) continue; // wholly clipped by the near plane
        // The box's part in front of the near plane is convex, with the
        // corners in front and the points where edges cross the plane as its
        // vertices; a perspective projection keeps lines straight, so the
        // projections of those vertices bound it.
        for (int k = 0; k < 8; ++k) {
            if (depth[k] > 0) add(corner[k]);
            for (int axis = 1; axis < 8; axis <<= 1) {
                const int m = k | axis;
                if (m == k || (depth[k] > 0) == (depth[m] > 0)) continue;
                const double t = depth[k] / (depth[k] - depth[m]);
                glm::dvec3 p = corner[k] + t * (corner[m] - corner[k]);
                // On the plane up to rounding: nudged to just in front of it.
                const glm::dvec3 axis_dir = camera.view_axis();
                const double off = camera.view_depth(p) - camera.near;
                if (!(off > 0)) p += axis_dir * (std::abs(off) + 1e-9 * std::max(1.0, camera.near));
                add(p);
            }
        }
    }
    if (!(c1 >= c0)) return {};
    auto clip = [](double v, int hi) { return int(std::clamp(v, 0.0, double(hi))); };
    return {clip(std::floor(c0) - 1, camera.width), clip(std::floor(r0) - 1, camera.height),
            clip(std::ceil(c1) + 1, camera.width), clip(std::ceil(r1) + 1, camera.height)};
}

PixelRect bounding_union(const PixelRect& a, const PixelRect& b) {
    if (a.empty()) return b;
    if (b.empty()) return a;
    return {std::min(a.col0, b.col0), std::min(a.row0, b.row0), std::max(a.col1, b.col1), std::max(a.row1, b.row1)};
}

std::vector<PixelRect> disjoint_cover(std::span<const PixelRect> rects) {
    std::vector<int> edges;
    for (const PixelRect& r : rects)
        if (!r.empty()) edges.insert(edges.end(), {r.row0, r.row1});
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    std::vector<PixelRect> out;
    std::size_t above = 0; // the previous band's first rectangle in `out`
    std::vector<std::pair<int, int>> runs;
    for (std::size_t e = 0; e + 1 < edges.size(); ++e) {
        const int row0 = edges[e], row1 = edges[e + 1];
        runs.clear();
        for (const PixelRect& r : rects)
            if (!r.empty() && r.row0 <= row0 && r.row1 >= row1) runs.emplace_back(r.col0, r.col1);
        std::sort(runs.begin(), runs.end());
        std::size_t merged = 0;
        for (const auto& run : runs) {
            if (merged > 0 && run.first <= runs[merged - 1].second)
                runs[merged - 1].second = std::max(runs[merged - 1].second, run.second);
            else
                runs[merged++] = run;
        }
        runs.resize(merged);
        // The band continues the one above when it has the same runs and touches it.
        const std::size_t band = out.size();
        bool same = band - above == runs.size() && (band == above || out[above].row1 == row0);
        for (std::size_t i = 0; same && i < runs.size(); ++i)
            same = out[above + i].col0 == runs[i].first && out[above + i].col1 == runs[i].second;
        if (same) {
            for (std::size_t i = above; i < band; ++i) out[i].row1 = row1;
            continue;
        }
        above = band;
        for (const auto& [c0, c1] : runs) out.push_back({c0, row0, c1, row1});
    }
    return out;
}

} // namespace overflight
