#pragma once
// Cameras shared by the tests (DESIGN sec. 2 conventions).
#include "core/Camera.h"
#include "core/Terrain.h"

#include <glm/trigonometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>

namespace overflight::test {

// A 160x100 view from a third of the way in, looking across the terrain at
// `heading`, eye 15 % of the relief plus two cells above the ground.
inline Camera across_terrain(const Terrain& t, double heading, double pitch, Projection proj) {
    Camera cam;
    cam.heading = heading;
    cam.pitch = pitch;
    cam.projection = proj;
    cam.width = 160;
    cam.height = 100;
    cam.fov = 60;
    const double extent = std::max(t.width(), t.depth());
    const glm::dvec3 F = cam.forward();
    const double x = t.width() * 0.5 - 0.3 * extent * F.x, z = t.depth() * 0.5 - 0.3 * extent * F.z;
    const double relief = std::max(1.0, double(t.max_height() - t.min_height()));
    cam.eye = {x, t.height_bilinear(float(x), float(z)) + 0.15 * relief + 2.0 * t.h_scale(), z};
    cam.near = 1.0;
    cam.far = 1.2 * extent;
    return cam;
}

// A 60-degree camera at `eye`, near 1.
inline Camera camera_at(glm::dvec3 eye, double heading, double pitch, double far, int width, int height) {
    Camera c;
    c.eye = eye;
    c.heading = heading;
    c.pitch = pitch;
    c.fov = 60;
    c.width = width;
    c.height = height;
    c.near = 1;
    c.far = far;
    return c;
}

// The hand-worked tests' camera: 2x4 pixels, fp = 2 (fov = 2 atan(1/2)),
// near 1, far 5, facing south (heading 0: F = +Z, R = -X).
inline Camera two_by_four(glm::dvec3 eye, double pitch = 0.0, Projection proj = Projection::Shear) {
    Camera c;
    c.eye = eye;
    c.pitch = pitch;
    c.projection = proj;
    c.fov = 2.0 * glm::degrees(std::atan(0.5));
    c.width = 2;
    c.height = 4;
    c.near = 1;
    c.far = 5;
    return c;
}

} // namespace overflight::test
