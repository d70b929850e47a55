#pragma once
// World-space geometry of a Scene (DESIGN sec. 5) on a terrain: solid objects
// (box, house, vehicle, model) as one lit triangle mesh, towers and cables as
// GL line segments. Y of an object defaults to Terrain::height_bilinear at its
// (x, z). CPU only; ObjectRenderer uploads the result.
//
// Shapes (local frame: base centred at the origin, +Z rotated to the heading
// direction (sin h, 0, cos h), +X to (cos h, 0, -sin h)):
//   box      width x height x depth
//   house    walls of 0.6 height, gable roof with its ridge along Z at `height`
//   vehicle  a hovercraft: dark skirt (0.35 height) under a body, a cabin on top
//   tower    a lattice tower of `height` (legs, rings, bracing, cross-arm) in lines
//   model    the OBJ/glTF mesh scaled by `scale`, base at y
// A transmission line puts a tower at each point (cross-arm across the line)
// and hangs three cables between consecutive towers' cross-arm ends and top
// as catenaries with the line's sag (Catenary.h).
//
// Based on: Szenberg et al. 1997 sec. 5 and 7 (Fig. 9-11: houses, vehicles,
// transmission lines drawn with OpenGL over the terrain).
#include "core/MeshArrays.h"
#include "core/Scene.h"
#include "core/ScreenRect.h"
#include "core/Terrain.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <vector>

namespace overflight::gl {

struct ObjectGeometry {
    MeshArrays triangles;                 // lit solids
    std::vector<glm::vec3> line_points;   // segment k = points 2k, 2k+1
    std::vector<Rgb8> line_colors;        // one per point
    // World bounds of each object, each tower of a line and each span of its
    // cables: every vertex above lies in one of them (screen_rect).
    std::vector<WorldBox> bounds;
    // Point sets whose convex hulls hold every vertex above, finer than
    // `bounds` for the objects' shadows (core/ShadowPixels.h): each object's
    // and tower's bounds' corners, and each cable's runs of
    // kCasterSegments pieces (a span's box holds a slab of air the thin
    // cables' shadows hardly touch).
    std::vector<std::vector<glm::vec3>> casters;
};

// Number of straight pieces per cable span.
inline constexpr int kCableSegments = 32;
// Cable pieces per caster: a run of them bends less than a metre for the sags of real lines.
inline constexpr int kCasterSegments = 8;

// Half-length of a tower's cross-arm for a tower of `height`.
inline double tower_arm(double height) { return 0.22 * height; }

// Builds the geometry of every object and line of `scene`. Model files are
// read with io load_model (Error(path, problem) when missing or malformed).
ObjectGeometry build_object_geometry(const Scene& scene, const Terrain& terrain);

// The player's hovercraft of `fly` in its local frame (base centred at the
// origin, +Z forward): the `vehicle` shape of sim/VehicleBody.h's size (it
// fills vehicle_local_box()), orange. gl/FlightVehicle.h draws it natively;
// `overflight web` writes it into the site for the page.
MeshArrays player_vehicle_model();

// World corners of a `box` object (base y resolved against the terrain), in
// the order of bits 1 = +X, 2 = top, 4 = +Z of its local frame. For tests and
// analytic projections.
std::vector<glm::dvec3> box_corners(const SceneObject& box, const Terrain& terrain);

} // namespace overflight::gl
