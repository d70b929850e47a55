#pragma once
// The `voxel` method's whole frame on the CPU, shared by every front end that
// shows it (the methods table of `render`, `bench` and `fly`, and the
// WebAssembly engine): the terrain's colors lit for the frame's sun
// (core/SunLight.h, relit only when the light changes), the Floating Horizon
// cast of color and window depth (FloatingHorizon.h), and the water surface
// over them (WaterPass.h) when the environment has water.
//
// Based on: Szenberg, Gattass, Carvalho, "An Algorithm for the Visualization
// of a Terrain with Objects" (SIBGRAPI 1997), sec. 4-6.
#include "core/Camera.h"
#include "core/DataSet.h"
#include "core/Image.h"
#include "core/SharedSunShadow.h"
#include "core/SunLight.h"
#include "core/Terrain.h"
#include "raycast/FloatingHorizon.h"
#include "raycast/RaycastOptions.h"
#include "raycast/WaterPass.h"

#include <cstdint>

namespace overflight {

// What one frame cost, in the order of its steps.
struct VoxelFrameStats {
    bool relit = false;   // the colors were lit anew for this frame's light
    double light_ms = 0;  // that lighting (0 when !relit)
    RaycastStats raycast; // the cast
    bool water = false;   // the water pass ran
    double water_ms = 0;
};

class VoxelRenderer {
public:
    // Keeps references to `terrain` and `sun_shadow` (null: the lighting
    // sweeps its own shadow), which must outlive this object.
    VoxelRenderer(const Terrain& terrain, const RaycastOptions& options, SharedSunShadow* sun_shadow = nullptr);

    // Renders `camera` (validated: throws Error("camera", ...)) under `env`
    // into `color` (row 0 at the top) and `depth` (OpenGL window depth, 1.0
    // for sky), resizing them to the camera's size; writes every pixel.
    void render(const Camera& camera, const Environment& env, ColorImage& color, DepthImage& depth,
                VoxelFrameStats& stats);

private:
    FloatingHorizon caster_;
    TerrainLighting lighting_;
    WaterPass water_;
    std::uint64_t painted_ = 0; // the lighting's version the caster paints
    RaycastOptions options_;
};

} // namespace overflight
