#pragma once
// View-frustum culling of terrain tiles.
//
// Based on: Gribb & Hartmann, "Fast Extraction of Viewing Frustum Planes from
// the World-View-Projection Matrix" (2001), and Zamri, "Real-time terrain
// rendering and visualization based on hierarchical method" (Zamri,
// "Run-Time Processing"): combine projection x modelview, extract the six
// planes, normalise them, then test each tile's bounding sphere (Fig. 4.1).
//
// Planes here point INTO the frustum (a point p is inside a plane when
// dot(n, p) + d >= 0), which is what Gribb-Hartmann's row sums give for
// OpenGL's clip volume -w <= x,y,z <= w. Zamri's Fig. 4.1 is written for
// outward normals and returns INTERSECT at the first straddled plane; that
// misses a sphere that straddles one plane but lies wholly outside a later
// one, so classify() keeps testing after a straddle and reports INTERSECT
// only when no plane rejects the sphere.
#include "core/Camera.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <array>

namespace overflight {

struct Plane {
    glm::dvec3 normal{0.0, 0.0, 1.0}; // unit, pointing into the frustum
    double d = 0.0;
    // Signed distance of p to the plane (positive inside).
    double distance(const glm::dvec3& p) const { return normal.x * p.x + normal.y * p.y + normal.z * p.z + d; }
};

enum class Containment { AllOutside, Intersect, AllInside };

const char* to_string(Containment c);

struct Frustum {
    enum Side { Left, Right, Bottom, Top, Near, Far };
    std::array<Plane, 6> planes; // indexed by Side

    // Gribb-Hartmann extraction from a clip matrix M = projection x modelview
    // (column-vector convention, as GLM and OpenGL use): with r_i the rows of
    // M, left = r4 + r1, right = r4 - r1, bottom = r4 + r2, top = r4 - r2,
    // near = r4 + r3, far = r4 - r3; each plane is then divided by |(a,b,c)|
    // so that distance() is a true Euclidean distance, which the sphere test
    // needs. Planes are in the space M maps from (world space for P x V).
    static Frustum from_matrix(const glm::dmat4& clip);

    // The frustum of the shared camera (DESIGN sec. 2): from_matrix(P x V).
    static Frustum from_camera(const Camera& camera);

    // Zamri Fig. 4.1 with inward normals: ALL-OUTSIDE when the sphere lies
    // entirely on the outer side of some plane, ALL-INSIDE when it lies
    // entirely on the inner side of all six, INTERSECT otherwise. Conservative:
    // a sphere reported ALL-OUTSIDE cannot touch the frustum.
    Containment classify(const glm::dvec3& centre, double radius) const;

    // The same three outcomes for an axis-aligned box [lo, hi] (lo <= hi),
    // tested per plane at its farthest and nearest corners along the normal
    // (the "p- and n-vertex" test). Tighter than a sphere for the flat boxes
    // of terrain quadtree nodes; conservative in the same way.
    Containment classify_box(const glm::dvec3& lo, const glm::dvec3& hi) const;
};

} // namespace overflight
