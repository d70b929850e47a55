#pragma once
// `overflight bench --compare`: the classic Voxel Space loop
// (raycast/ClassicVoxelSpace.h) timed beside the Floating Horizon in the
// same run, on the same camera, so the exact caster's lead is a ratio of
// one run: once stepping one sample per line (the Floating Horizon's samples
// per column) and once with the originals' growing step. Rows:
// {"method":"classic (1-sample step)"|"classic (growing step)","ms_median":..,
//  "frames":..,"samples":..,"samples_per_column":..,"ns_per_sample":..,"step_growth":..}
//
// Based on: S. Macke, "Voxel Space"; A. LaMothe, "Tricks of the
// Game-Programming Gurus" (see ClassicVoxelSpace.h).
#include "core/Camera.h"
#include "core/Terrain.h"

#include <nlohmann/json.hpp>

namespace overflight::app {

// Times `frames` frames (after one warm-up) of each step schedule, taking
// turns frame by frame so that a shared machine's load weighs on both.
nlohmann::json classic_voxel_space_bench(const Terrain& terrain, const Camera& camera, int frames);

// Prints the side-by-side table of `runs` (bench rows: voxel, voxel-literal
// and the classic rows) in ns per sample per core, with `threads` cores for
// the parallel casts and one for voxel-literal, which is single-threaded.
void print_classic_comparison(const nlohmann::json& runs, int threads);

} // namespace overflight::app
