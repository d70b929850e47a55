#pragma once
// The view frustum of the shared camera reduced to a wedge in the XZ plane,
// for ROAM's priorities: a triangle whose footprint lies outside the wedge
// cannot be seen and gets the minimum priority.
//
// Based on: CMSC 23700 project 2a sec. 5.1 ("Since the view is mostly horizontal, you can
// approximate the view frustum as a triangle in the XZ plane ... compute the
// line equations for the sides of the frustum"), with the camera of DESIGN
// sec. 2. For `shear` every pixel column lies in a vertical plane, so the two
// side lines at +-fov/2 are exact; for `tilt` the side lines are the XZ
// shadows of the four corner rays, and when a corner ray points backwards in
// XZ (camera looking steeply down) no wedge exists and nothing is culled.
#include "core/Camera.h"

#include <glm/vec2.hpp>

#include <cstdint>

namespace overflight {

struct RoamViewWedge {
    bool enabled = false;   // false: everything counts as visible
    glm::dvec2 eye{0.0};    // camera XZ
    glm::dvec2 forward{0.0, 1.0};
    glm::dvec2 inner_left{0.0}, inner_right{0.0}; // side-line normals pointing into the wedge
    double far_forward = 0; // beyond this forward XZ distance no point can be nearer than `far`

    // Wedge of `camera` over a terrain whose world heights lie in [min_y, max_y]
    // (the far cut of a tilted camera depends on height).
    static RoamViewWedge from_camera(const Camera& camera, double min_y, double max_y);

    // The lines a point in XZ lies strictly beyond, as a bit mask (Cohen-
    // Sutherland style): kBehindLeft, kBehindRight, kBehindEye, kBeyondFar.
    // Always 0 when the wedge is disabled. ROAM computes it once per vertex.
    enum Outcode : std::uint8_t { kBehindLeft = 1, kBehindRight = 2, kBehindEye = 4, kBeyondFar = 8 };
    std::uint8_t outcode(const glm::dvec2& p) const;

    // True when the triangle (a, b, c) in XZ certainly lies outside the view:
    // all three corners behind one side line, behind the eye or beyond far,
    // i.e. their outcodes share a bit. Half-plane tests, so a triangle inside
    // an outside one is outside too.
    static bool outside(std::uint8_t a, std::uint8_t b, std::uint8_t c) { return (a & b & c) != 0; }
    bool outside(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) const {
        return outside(outcode(a), outcode(b), outcode(c));
    }
};

} // namespace overflight
