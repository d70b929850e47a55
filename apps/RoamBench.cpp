// Based on: CMSC 23700 hovercraft project sec. 5.
#include "RoamBench.h"

#include "lod/RoamMesh.h"

#include <algorithm>
#include <chrono>
#include <string>

namespace overflight::app {

namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

} // namespace

nlohmann::json roam_bench(const Terrain& terrain, const Camera& camera, int frames) {
    RoamMesh roam(terrain);
    MeshArrays mesh;
    auto frame = [&](int budget, RoamStats& s) {
        const auto t0 = std::chrono::steady_clock::now();
        s = roam.tessellate(camera, budget);
        roam.write_mesh(mesh);
        return ms_since(t0);
    };
    // The rate at 64k triangles and the time of a 100k-triangle mesh, best of
    // `frames` (tessellation and output arrays, one core).
    RoamStats s;
    nlohmann::json j;
    auto best_of_frames = [&](int budget) {
        double best = 1e300;
        for (int i = 0; i < std::max(frames, 1); ++i) best = std::min(best, frame(budget, s));
        return best;
    };
    j["ms_tessellate_100000"] = best_of_frames(100000);
    const double ms_64k = best_of_frames(65536);
    j["triangles_per_s"] = double(s.triangles) / (ms_64k * 1e-3);
    j["ms_tessellate_65536"] = ms_64k;
    nlohmann::json curve = nlohmann::json::array();
    for (int budget = 4096; budget <= 262144; budget *= 2) {
        // Best of three: the first rebuild at a larger budget also grows the pools.
        double ms = 1e300;
        for (int i = 0; i < 3; ++i) ms = std::min(ms, frame(budget, s));
        curve.push_back({{"budget", budget},
                         {"triangles", s.triangles},
                         {"ms_tessellate", ms},
                         {"max_error_px", s.max_error_px},
                         {"mean_error_px", s.mean_error_px}});
    }
    j["curve"] = curve;
    return j;
}

} // namespace overflight::app
