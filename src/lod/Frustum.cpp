// Based on: Gribb & Hartmann 2001 (plane extraction); Zamri,
// "Run-Time Processing", Fig. 4.1 (plane / bounding-sphere test).
#include "lod/Frustum.h"

#include <glm/geometric.hpp>

namespace overflight {

const char* to_string(Containment c) {
    switch (c) {
    case Containment::AllOutside: return "all-outside";
    case Containment::Intersect: return "intersect";
    case Containment::AllInside: return "all-inside";
    }
    return "?";
}

Frustum Frustum::from_matrix(const glm::dmat4& m) {
    // GLM is column-major: m[col][row]. Row i of M is (m[0][i], m[1][i], m[2][i], m[3][i]).
    auto row = [&](int i) { return glm::dvec4(m[0][i], m[1][i], m[2][i], m[3][i]); };
    const glm::dvec4 r1 = row(0), r2 = row(1), r3 = row(2), r4 = row(3);
    const glm::dvec4 raw[6] = {r4 + r1, r4 - r1, r4 + r2, r4 - r2, r4 + r3, r4 - r3};
    Frustum f;
    for (int i = 0; i < 6; ++i) {
        const glm::dvec3 n(raw[i]);
        const double len = glm::length(n);
        f.planes[std::size_t(i)] = Plane{n / len, raw[i].w / len};
    }
    return f;
}

Frustum Frustum::from_camera(const Camera& camera) {
    return from_matrix(camera.projection_matrix() * camera.view_matrix());
}

Containment Frustum::classify(const glm::dvec3& centre, double radius) const {
    Containment result = Containment::AllInside;
    for (const Plane& p : planes) {
        const double dist = p.distance(centre);
        if (dist < -radius) return Containment::AllOutside;
        if (dist < radius) result = Containment::Intersect;
    }
    return result;
}

Containment Frustum::classify_box(const glm::dvec3& lo, const glm::dvec3& hi) const {
    Containment result = Containment::AllInside;
    for (const Plane& p : planes) {
        const glm::dvec3 far_corner(p.normal.x >= 0 ? hi.x : lo.x, p.normal.y >= 0 ? hi.y : lo.y,
                                    p.normal.z >= 0 ? hi.z : lo.z);
        if (p.distance(far_corner) < 0) return Containment::AllOutside;
        const glm::dvec3 near_corner(p.normal.x >= 0 ? lo.x : hi.x, p.normal.y >= 0 ? lo.y : hi.y,
                                     p.normal.z >= 0 ? lo.z : hi.z);
        if (p.distance(near_corner) < 0) result = Containment::Intersect;
    }
    return result;
}

} // namespace overflight
