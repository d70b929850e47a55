#pragma once
// `--method roam` of `overflight render` and the roam rows of `overflight
// bench` (issue 5): split-only ROAM tessellation for one camera, returned as
// plain MeshArrays for the GL layer to draw, with its statistics as JSON.
// Thin: the algorithm is lod/RoamMesh.
//
// Based on: seed 003 sec. 5 (split-only ROAM, triangle budget), DESIGN sec. 6
// (`--triangles N`, `--stats` as one JSON object).
#include "core/Camera.h"
#include "core/MeshArrays.h"
#include "core/Terrain.h"
#include "lod/RoamMesh.h"

#include <glm/vec2.hpp>

#include <optional>
#include <string>

namespace overflight::app {

constexpr int kRoamDefaultTriangles = 65536;
constexpr int kRoamMaxTriangles = 1 << 24;

struct RoamMethodOptions {
    int triangles = kRoamDefaultTriangles; // `--triangles N`
    std::optional<glm::dvec2> focus;       // world (x, z) of the vehicle, if any
};

struct RoamMethodResult {
    MeshArrays mesh;
    RoamStats stats;
    double ms_tessellate = 0; // tessellation and array output, wall clock
    // {"method":"roam","triangles":T,"vertices":V,"ms_tessellate":ms,
    //  "max_error_px":e,"mean_error_px":m,"budget":N,"splits":S,"forced_splits":F}
    // The caller adds "ms_draw" (gl) before printing.
    std::string stats_json;
};

// Builds the variance tree once; keep the RoamMesh for every frame of a
// terrain (`terrain` must outlive it). Throws Error("roam", ...).
RoamMesh make_roam(const Terrain& terrain);

// One frame. Throws Error("--triangles", ...) for a budget outside
// 2 .. kRoamMaxTriangles and Error("camera", ...) for an invalid camera.
RoamMethodResult roam_method(RoamMesh& roam, const Camera& camera, const RoamMethodOptions& options = {});

// `overflight bench` rows for roam: the best of `frames` rebuilds (tessellation
// and output arrays) at 100000 and 65536 triangles, the rate at 65536
// (triangles per second) and the error-versus-budget curve for budgets
// 4k .. 256k, as one JSON object:
// {"method":"roam","ms_tessellate_100000":ms,"triangles_per_s":R,"ms_tessellate_65536":ms,
//  "curve":[{"budget":4096,"triangles":..,"ms_tessellate":..,"max_error_px":..,"mean_error_px":..},...]}
std::string roam_bench_json(RoamMesh& roam, const Camera& camera, int frames = 10);

} // namespace overflight::app
