// Based on: Crow 1977; Everitt and Kilgard 2002 sec. 3-4. See ShadowVolume.h.
#include "core/ShadowVolume.h"

#include <glm/geometric.hpp>

#include <algorithm>

namespace overflight {

void append_shadow_volume(const WorldBox& box, const glm::vec3& sun, float floor, std::vector<glm::vec3>& triangles) {
    if (!(sun.y > 0.0f)) return;
    const float length = std::max(box.hi.y - floor, 0.0f) / sun.y;
    const glm::vec3 sweep = -sun * length;
    // Per axis, the side of the box whose face moves with the sweep: the one
    // the sweep points to (the + side when the sweep is parallel to it).
    bool moves[3][2]; // [axis][side: 0 = lo, 1 = hi]
    for (int axis = 0; axis < 3; ++axis) {
        moves[axis][1] = sweep[axis] >= 0.0f;
        moves[axis][0] = !moves[axis][1];
    }
    const auto corner = [&](int bits) {
        return glm::vec3(bits & 1 ? box.hi.x : box.lo.x, bits & 2 ? box.hi.y : box.lo.y, bits & 4 ? box.hi.z : box.lo.z);
    };
    // Any interior point: each triangle is turned to face away from it.
    const glm::vec3 inside = 0.5f * (box.lo + box.hi) + 0.5f * sweep;
    const auto add = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c) {
        if (glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0f - inside) < 0.0f) std::swap(b, c);
        triangles.insert(triangles.end(), {a, b, c});
    };
    const auto quad = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) { // a-b-c-d around
        add(a, b, c);
        add(a, c, d);
    };
    for (int axis = 0; axis < 3; ++axis) {
        const int u = 1 << ((axis + 1) % 3), v = 1 << ((axis + 2) % 3);
        for (int side = 0; side < 2; ++side) {
            const int base = side << axis;
            const glm::vec3 shift = moves[axis][side] ? sweep : glm::vec3(0.0f);
            quad(corner(base) + shift, corner(base | u) + shift, corner(base | u | v) + shift, corner(base | v) + shift);
        }
    }
    // The silhouette: each edge, along axis e, between the faces (a, sa) and
    // (b, sb) of the two other axes, of which one moves and one stays.
    for (int e = 0; e < 3; ++e) {
        const int a = (e + 1) % 3, b = (e + 2) % 3;
        for (int sa = 0; sa < 2; ++sa)
            for (int sb = 0; sb < 2; ++sb) {
                if (moves[a][sa] == moves[b][sb]) continue;
                const int bits = (sa << a) | (sb << b);
                const glm::vec3 p = corner(bits), q = corner(bits | (1 << e));
                quad(p, q, q + sweep, p + sweep);
            }
    }
}

} // namespace overflight
