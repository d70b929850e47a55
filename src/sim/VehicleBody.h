#pragma once
// The hovercraft's body as `fly` draws it (CMSC 23700 project 2a sec. 3: the
// chase camera follows a vehicle on the terrain): its size, and where the
// body sits for a simulated position, hovering just above the ground and
// tilted to the local slope so that it neither sinks into nor floats over a
// hillside. No GL: the native compositor (gl/FlightVehicle.h) and the web
// page's engine (web/WebEngine.h) place the same body the same way.
#include "core/ScreenRect.h"
#include "core/Terrain.h"

#include <glm/vec3.hpp>

namespace overflight {

struct VehicleBody {
    static constexpr double kLength = 5.0, kWidth = 3.0, kHeight = 2.0; // metres, like the demo's vehicle
    static constexpr double kHover = 0.3;                               // skirt above the ground
};

// The body's frame on the ground: the origin (the base's centre) and unit
// axes right, up and forward, in world coordinates. A point p of the local
// frame (base centre at the origin, +Z forward) is placed at
// origin + p.x ax + p.y ay + p.z az.
struct BodyFrame {
    glm::dvec3 origin, ax, ay, az;
    glm::dvec3 place(const glm::dvec3& p) const { return origin + p.x * ax + p.y * ay + p.z * az; }
};

// The frame of the body at world (x, z) facing `heading` (degrees, DESIGN
// sec. 1): the ground under its four sides (sim/Hovercraft.h ground_height)
// gives the slope along and across the heading; the base rides kHover above
// the higher of the ground under its centre and the sides' mean.
BodyFrame vehicle_frame(const Terrain& terrain, double x, double z, double heading);

// The local box the body's shape fills: kWidth x kHeight x kLength, base
// centred at the origin (gl/ObjectGeometry.h's `vehicle` shape of that size).
WorldBox vehicle_local_box();

// A world box holding every point of `local` placed by `frame` (an affine map
// keeps them in the image of the box's corners), `margin` wider on every side
// (the float rounding of placed vertices).
WorldBox placed_box(const BodyFrame& frame, const WorldBox& local, double margin);

} // namespace overflight
