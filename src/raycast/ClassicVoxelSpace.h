#pragma once
// The classic Voxel Space inner loop, kept as a yardstick: `overflight bench
// --compare` times it beside the Floating Horizon at the same image size and
// the same samples per column, so that the exact caster's lead is measured in
// every run rather than quoted.
//
// Based on: the Voxel Space renderer of NovaLogic's Comanche (1992) as
// described by S. Macke, "Voxel Space: terrain rendering algorithm in less
// than 20 lines of code" (front-to-back lines across the view, a y-buffer per
// column, vertical spans); A. LaMothe, "Tricks of the Game-Programming Gurus"
// (1994) and M. Freese's voxel landscape notes, whose ray step grows with
// distance.
//
// What makes it the classic and not the Floating Horizon (Szenberg, Gattass,
// Carvalho, SIBGRAPI 1997): the screen line of sample s at distance z is
// `horizon - (h_s - eye_y) * focal / z` with z the distance along the view
// axis, each column takes the nearest sample on its line (truncated, no
// surface model), the image is painted in vertical spans into a row-major
// frame, and nothing is written but colour: no depth, no fog, no objects.
// The projection of the sample's top is the shear camera's (DESIGN sec. 2),
// so its silhouettes land where the exact caster's do when the step is one
// cell; with a growing step they thin out with distance, as in the originals.
#include "core/Camera.h"
#include "core/Image.h"
#include "core/Terrain.h"

#include <cstdint>

namespace overflight {

struct ClassicVoxelSpaceOptions {
    // Distance between the first two lines, in samples (h_scale units).
    double first_step = 1.0;
    // Each next step is the previous one times this factor: 1 keeps one
    // sample per line (the Floating Horizon's slice spacing); the originals
    // grow it (about 1.005 to 1.02 per line).
    double step_growth = 1.0;
    Rgb8 sky{184, 204, 230};
};

struct ClassicVoxelSpaceStats {
    std::uint64_t samples = 0; // columns x lines, every line to the camera's far
    int lines = 0;             // lines (samples per column)
};

// Paints `color` (resized to the camera) for a shear `camera` (throws
// Error("camera", ...) for an invalid or tilt camera, or options that do not
// step forward). Lines run from camera.near to camera.far inclusive; samples outside
// the terrain paint nothing. Columns are cast in parallel bands (oneTBB),
// each band with the whole loop over lines, so per-core figures compare with
// the Floating Horizon's.
ClassicVoxelSpaceStats render_classic_voxel_space(const Terrain& terrain, const Camera& camera,
                                                  const ClassicVoxelSpaceOptions& options, ColorImage& color);

} // namespace overflight
