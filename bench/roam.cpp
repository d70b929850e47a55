// Split-only ROAM (CMSC 23700 project 2a sec. 5): tessellation rate, variance-tree build
// and the error-versus-budget curve, on the SRTM tile of Mt Rainier
// (../shared/data, reprojected by io's load_terrain: 1201^2 padded to 2049^2)
// and on the 4097^2 demo island. The target is >= 10 million triangles per
// second per core; `items_per_second` is that rate. The quality counters
// (max / mean projected error in pixels, share of terrain pixels whose depth
// is within 5 % of the full-resolution mesh) are per budget.
#include "BenchTerrains.h"
#include "lod/QuadtreeAccuracy.h"
#include "lod/RoamMesh.h"

#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>

using namespace overflight;

namespace {

// 0: Mt Rainier SRTM (or the 1025^2 island when the data is absent), 1: 4097^2 island.
const Terrain& terrain(int which) { return which == 0 ? bench::rainier_or_demo(1025) : bench::demo_island(4097); }

RoamMesh& roam(int which) {
    static std::map<int, std::unique_ptr<RoamMesh>> cache;
    auto& r = cache[which];
    if (!r) r = std::make_unique<RoamMesh>(terrain(which));
    return *r;
}

// A low flight from the west third of the terrain looking east, 1280x720.
Camera flight_camera(const Terrain& t) {
    Camera c;
    const double x = t.width() * 0.3, z = t.depth() * 0.5;
    c.eye = {x, t.height_bilinear(float(x), float(z)) + 20.0 * t.h_scale(), z};
    c.heading = 80;
    c.pitch = -8;
    c.fov = 60;
    c.width = 1280;
    c.height = 720;
    c.near = t.h_scale() * 0.5;
    c.far = 2.0 * std::max(t.width(), t.depth());
    return c;
}

// Per-frame work of the renderer: tessellate from scratch and write the arrays.
void BM_RoamFrame(benchmark::State& state) {
    const int which = int(state.range(0));
    const int budget = int(state.range(1));
    RoamMesh& r = roam(which);
    const Camera cam = flight_camera(terrain(which));
    MeshArrays mesh;
    std::size_t triangles = 0;
    for (auto _ : state) {
        triangles = r.tessellate(cam, budget).triangles;
        r.write_mesh(mesh);
        benchmark::DoNotOptimize(mesh.indices.data());
    }
    state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(triangles));
    state.counters["triangles"] = double(triangles);
}

// Tessellation alone (the split loop with its priority buckets).
void BM_RoamTessellate(benchmark::State& state) {
    const int which = int(state.range(0));
    const int budget = int(state.range(1));
    RoamMesh& r = roam(which);
    const Camera cam = flight_camera(terrain(which));
    std::size_t triangles = 0;
    for (auto _ : state) triangles = r.tessellate(cam, budget).triangles;
    state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(triangles));
}

// Error versus budget, 4k .. 256k: projected error and depth agreement with
// the full-resolution mesh (CPU rasteriser, 640x360 to keep it short).
void BM_RoamErrorCurve(benchmark::State& state) {
    const int which = int(state.range(0));
    const int budget = int(state.range(1));
    const Terrain& t = terrain(which);
    RoamMesh& r = roam(which);
    Camera cam = flight_camera(t);
    RoamStats s;
    for (auto _ : state) s = r.tessellate(cam, budget);
    cam.width = 640;
    cam.height = 360;
    static std::map<int, DepthImage> reference;
    if (!reference.count(which)) reference[which] = rasterize_depth(full_resolution_mesh(t), cam);
    r.tessellate(cam, budget);
    MeshArrays mesh;
    r.write_mesh(mesh);
    const DepthAgreement a = compare_depth(rasterize_depth(mesh, cam), reference[which], cam, 0.05);
    state.counters["triangles"] = double(s.triangles);
    state.counters["max_err_px"] = s.max_error_px;
    state.counters["mean_err_px"] = s.mean_error_px;
    state.counters["depth_within_5pct"] = a.share();
}

void BM_RoamVarianceTree(benchmark::State& state) {
    const Terrain& t = terrain(int(state.range(0)));
    for (auto _ : state) {
        RoamVarianceTree v(t.rows() == t.cols() && is_pow2_plus1(t.rows()) ? t : pad_to_pow2_plus1(t));
        benchmark::DoNotOptimize(v.raw(2));
    }
}

} // namespace

BENCHMARK(BM_RoamFrame)->ArgsProduct({{0, 1}, {16384, 65536, 100000, 262144}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RoamTessellate)->ArgsProduct({{0, 1}, {65536, 100000}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RoamErrorCurve)
    ->ArgsProduct({{0}, {4096, 8192, 16384, 32768, 65536, 131072, 262144}})
    ->Iterations(3)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RoamVarianceTree)->Arg(0)->Arg(1)->Iterations(2)->Unit(benchmark::kMillisecond);
