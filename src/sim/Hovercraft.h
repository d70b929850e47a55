#pragma once
// Based on: CMSC 23700 project 2a, "sports utility hovercraft" (CMSC 23700 project 2a),
// sec. 3.2 (the physics model), with its constants and both of its slope
// methods. The vehicle state is the paper's triple (p, v, h): position in the
// X-Z plane, speed along the heading, heading in degrees (DESIGN sec. 1:
// direction (sin h, 0, cos h), h = 0 faces south, LEFT increases h). The state
// advances in fixed 10 ms steps (FixedStepClock turns frame time into steps).
#include "core/Terrain.h"
#include "sim/KeyState.h"

#include <glm/vec3.hpp>

#include <optional>

namespace overflight {

// Seed 003 sec. 3.2 offers two ways to get the unit slope vector s(p, h).
enum class SlopeMethod {
    Ahead,          // first method: height one unit ahead minus height here
    TriangleNormal, // second method: slope of the mesh triangle containing p
};

const char* to_string(SlopeMethod m);

// The constants of CMSC 23700 project 2a sec. 3.2 ("b = 0.6, f0 = 6e-4, ..."). World units
// are taken to be metres, as the paper's are.
struct HovercraftParams {
    double step = 0.01;          // seconds per step (100 Hz)
    double accel_max = 8.0;      // a = max(0, accel_max - v^2 / accel_div)
    double accel_div = 16.0;
    double brake = 0.6;          // b
    double f0 = 6e-4, f1 = 2e-4, f2 = 4e-4; // friction f = f0 + f1 v + f2 v^2
    double gravity = 9.8;        // g = (0, gravity, 0) . s(p, h)
    double turn_limit = 32.0;    // l
    double turn_factor = 24.0;   // t: heading change t / (v^2 + l) per step
    double altitude = 2.0;       // height above the terrain (footnote 2)
    double probe = 1.0;          // distance ahead for SlopeMethod::Ahead ("one metre")
    SlopeMethod slope = SlopeMethod::Ahead;
};

struct HovercraftState {
    double x = 0, z = 0;   // p, world X/Z
    double y = 0;          // altitude: ground_height(p) + params.altitude
    double velocity = 0;   // v >= 0, world units per second along the heading
    double heading = 0;    // h in degrees, kept in [0, 360)
};

// Unit slope vector s(p, h) of CMSC 23700 project 2a sec. 3.2 at world (x, z) for heading h
// (degrees). Its horizontal part points along (sin h, cos h); its y is the rise
// per unit of horizontal travel, normalised with it. Ahead: the bilinear height
// `probe` units ahead minus the height at p. TriangleNormal: the gradient of the
// mesh triangle containing p (DESIGN sec. 3 `mesh`: two triangles per cell,
// diagonals alternating as in the binary-triangle-tree split; the diagonal of
// cell (r, c) runs from (r, c) to (r+1, c+1) when r + c is even, else from
// (r, c+1) to (r+1, c)). Positions outside the map are clamped to it.
glm::dvec3 slope_vector(const Terrain& terrain, double x, double z, double heading,
                        SlopeMethod method, double probe = 1.0);

// Height of the `mesh` surface (the triangle containing (x, z), same diagonal
// rule as slope_vector), clamped to the map.
double mesh_height(const Terrain& terrain, double x, double z);

// The ground the vehicle rides on: the bilinear surface (Terrain::height_bilinear,
// CMSC 23700 project 2a footnote 2 "2 meters above the terrain"), raised to the mesh triangle
// where that is higher. On steep cells the two surfaces differ by more than the
// 2 m altitude (up to a quarter of the cell's twist h00 - h01 - h10 + h11), and
// the mesh is what the mesh/ROAM/quadtree renderers draw, so riding on the
// higher of the two keeps the vehicle above every surface the window shows.
double ground_height(const Terrain& terrain, double x, double z);

// Heading in degrees wrapped to [0, 360).
double wrap_heading(double degrees);

// The simulated vehicle on one terrain. The terrain must outlive it.
//
// Map edge: the vehicle BOUNCES (CMSC 23700 project 2a leaves teleport-or-bounce open): a
// step that would leave X in [0, width] or Z in [0, depth] is mirrored at the
// edge and the heading is reflected (h -> -h at the west/east edges,
// h -> 180 - h at the north/south edges); speed is kept. The vehicle rides
// `altitude` above ground_height(), so it is never below the bilinear or the
// mesh surface.
class Hovercraft {
public:
    // Throws Error("vehicle start", ...) if (x, z) is outside the map or not finite, and
    // Error("vehicle heading", ...) if the heading is not finite.
    Hovercraft(const Terrain& terrain, double x, double z, double heading,
               const HovercraftParams& params = {});

    // One 10 ms step of CMSC 23700 project 2a sec. 3.2:
    //   a = max(0, 8 - v^2/16),  f = f0 + f1 v + f2 v^2,  g = (0, 9.8, 0) . s(p, h)
    //   v' = v - 0.01 (f + g)
    //   v_{i+1} = max(0, v' + 0.01 a [accelerating] - 0.01 b [braking])
    //   h_{i+1} = h + t/(v_{i+1}^2 + l) [left] - t/(v_{i+1}^2 + l) [right]
    //   p_{i+1} = p + 0.01 v_{i+1} (sin h_{i+1}, cos h_{i+1})
    // The paper applies "acceleration and/or braking": with both keys down both
    // terms apply, and LEFT with RIGHT cancel.
    void step(const Controls& keys);

    const HovercraftState& state() const { return state_; }
    const HovercraftParams& params() const { return params_; }
    const Terrain& terrain() const { return *terrain_; }
    // Water at world height `level` (nullopt: none): from the next step the
    // vehicle rides on the higher of ground_height() and the water, with the
    // paper's physics otherwise unchanged; over water (ground_height() below
    // the level) the surface is level, so gravity's slope term is 0.
    void set_water_level(std::optional<double> level) { water_ = level; }
    // Number of edge bounces so far.
    long long bounces() const { return bounces_; }

private:
    const Terrain* terrain_;
    HovercraftParams params_;
    HovercraftState state_;
    long long bounces_ = 0;
    std::optional<double> water_;
};

} // namespace overflight
