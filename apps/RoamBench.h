#pragma once
// The ROAM figures of `overflight bench` beyond frame times: the best of
// `frames` rebuilds (tessellation and output arrays) at 100000 and 65536
// triangles, the rate at 65536 (triangles per second) and the
// error-versus-budget curve for budgets 4k .. 256k:
// {"ms_tessellate_100000":ms,"triangles_per_s":R,"ms_tessellate_65536":ms,
//  "curve":[{"budget":4096,"triangles":..,"ms_tessellate":..,"max_error_px":..,"mean_error_px":..},...]}
//
// Based on: CMSC 23700 hovercraft project sec. 5 (split-only ROAM, triangle budget).
#include "core/Camera.h"
#include "core/Terrain.h"

#include <nlohmann/json.hpp>

namespace overflight::app {

nlohmann::json roam_bench(const Terrain& terrain, const Camera& camera, int frames = 10);

} // namespace overflight::app
