#pragma once
// The hovercraft itself in the chase view of `fly` (CMSC 23700 project 2a sec. 3: the
// camera sits behind the vehicle and follows it): ObjectGeometry's built-in
// `vehicle` shape, built once, placed every frame where the simulation put the
// vehicle, hovering just above the ground and tilted to the local slope so
// that it neither sinks into nor floats over a hillside. Drawn lit and fogged
// with the Z-buffer like every other object, and into its own shadow map from
// the sun (gl/ObjectShadowMap.h) so that it casts a shadow like them.
#include "core/MeshArrays.h"
#include "core/ScreenRect.h"
#include "core/Terrain.h"
#include "gl/StreamedMesh.h"
#include "sim/VehicleBody.h"

#include <vector>

namespace overflight::gl {

class FlightVehicle {
public:
    // Builds the shape and its GL buffers (a GL context must be current).
    // `terrain` must outlive this object.
    explicit FlightVehicle(const Terrain& terrain);

    // Places the vehicle at world (x, z) facing `heading` (degrees, DESIGN
    // sec. 1), uploading its triangles when the pose changed. Returns true
    // when it did (the vehicle moved since the last call).
    bool place(double x, double z, double heading);
    // The placed vehicle's world bounds (one box; empty before place()).
    const std::vector<WorldBox>& bounds() const { return bounds_; }
    // A world box holding every vertex place(x, z, heading) would place:
    // where a composite needs the terrain's depth for the vehicle before it is
    // placed. No GL: any thread.
    WorldBox bounds_at(double x, double z, double heading) const;
    // Draws the placed vehicle (Frame uniforms bound). Returns triangles drawn.
    long long draw() const { return mesh_.draw(); }

private:
    const Terrain& terrain_;
    MeshArrays model_;  // local frame: base centre at the origin, +Z forward
    MeshArrays placed_; // world, reused every frame
    WorldBox model_box_; // of model_
    StreamedMesh mesh_;
    std::vector<WorldBox> bounds_;
    bool placed_once_ = false;
    double px_ = 0, pz_ = 0, pheading_ = 0;
};

} // namespace overflight::gl
