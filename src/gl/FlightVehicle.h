#pragma once
// The hovercraft itself in the chase view of `fly` (CMSC 23700 project 2a sec. 3: the
// camera sits behind the vehicle and follows it): ObjectGeometry's built-in
// `vehicle` shape, built once, placed every frame where the simulation put the
// vehicle, hovering just above the ground and tilted to the local slope so
// that it neither sinks into nor floats over a hillside. Drawn lit and fogged
// with the Z-buffer like every other object.
#include "core/MeshArrays.h"
#include "core/ScreenRect.h"
#include "core/Terrain.h"
#include "gl/StreamedMesh.h"

namespace overflight::gl {

class FlightVehicle {
public:
    static constexpr double kLength = 5.0, kWidth = 3.0, kHeight = 2.0; // metres, like the demo's vehicle
    static constexpr double kHover = 0.3;                               // skirt above the ground

    // Builds the shape and its GL buffers (a GL context must be current).
    // `terrain` must outlive this object.
    explicit FlightVehicle(const Terrain& terrain);

    // Places the vehicle at world (x, z) facing `heading` (degrees, DESIGN
    // sec. 1) and draws it (Frame uniforms bound). Returns triangles drawn.
    long long draw(double x, double z, double heading);

    // A world box holding every vertex draw(x, z, heading) places: where a
    // composite needs the terrain's depth for the vehicle. No GL: any thread.
    WorldBox bounds(double x, double z, double heading) const;

private:
    // The body's frame on the ground at (x, z): origin and axes (right, up, forward).
    struct Frame {
        glm::dvec3 origin, ax, ay, az;
    };
    Frame frame_at(double x, double z, double heading) const;

    const Terrain& terrain_;
    MeshArrays model_;  // local frame: base centre at the origin, +Z forward
    MeshArrays placed_; // world, reused every frame
    WorldBox model_box_; // of model_
    StreamedMesh mesh_;
};

} // namespace overflight::gl
