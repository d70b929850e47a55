// Based on: Szenberg et al. 1997 sec. 5 (objects drawn by Z-buffer over the
// ray-cast depth); DESIGN sec. 2 (camera).
#include "core/ScreenRect.h"

#include <algorithm>
#include <cmath>

namespace overflight {

PixelRect screen_rect(std::span<const WorldBox> boxes, const Camera& camera) {
    const PixelRect whole{0, 0, camera.width, camera.height};
    double c0 = HUGE_VAL, r0 = HUGE_VAL, c1 = -HUGE_VAL, r1 = -HUGE_VAL;
    for (const WorldBox& b : boxes) {
        glm::dvec3 corner[8];
        int behind = 0;
        for (int k = 0; k < 8; ++k) {
            corner[k] = {(k & 1) ? b.hi.x : b.lo.x, (k & 2) ? b.hi.y : b.lo.y, (k & 4) ? b.hi.z : b.lo.z};
            behind += !(camera.view_depth(corner[k]) > camera.near);
        }
        if (behind == 8) continue; // wholly clipped by the near plane
        // Convex and wholly in front: its corners bound its projection. Cut by
        // the near plane, its projection is unbounded.
        if (behind > 0) return whole;
        for (const glm::dvec3& p : corner) {
            const Camera::Projected q = camera.project(p);
            c0 = std::min(c0, q.col);
            c1 = std::max(c1, q.col);
            r0 = std::min(r0, q.row);
            r1 = std::max(r1, q.row);
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

} // namespace overflight
