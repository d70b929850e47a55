// Röttger quadtree over tiles (Zamri, seed 001): per-frame cost and
// triangles per frame at 1 px error, beside the full-resolution mesh
// (Zamri reports 80.53 fps at 22,370 triangles). Counters: triangles,
// reduction (full / quadtree), depth agreement (share within 3 %).
#include "core/DemoIsland.h"
#include "lod/QuadtreeAccuracy.h"
#include "lod/TileSet.h"

#include <benchmark/benchmark.h>

using namespace overflight;

namespace {

const DataSet& island() {
    static const DataSet d = [] {
        DemoOptions o;
        o.size = 2049;
        return make_demo_island(o);
    }();
    return d;
}

Camera view(const Terrain& t) {
    Camera c;
    c.eye = {t.width() / 2, t.max_height() + 150, -300};
    c.heading = 0;
    c.pitch = -12;
    c.width = 1280;
    c.height = 720;
    c.far = 8000;
    return c;
}

void BM_QuadtreeFrame(benchmark::State& state) {
    const Terrain& t = island().terrain;
    const TileGrid g = terrain_tile_grid(t, 257);
    TileSet set(g, terrain_tile_loader(t, g), std::size_t(1) << 30);
    Camera cam = view(t);
    const double err = double(state.range(0));
    MeshArrays m;
    set.build_mesh(cam, err, m); // warm the cache: loading is not per-frame work
    std::size_t tris = 0;
    int k = 0;
    for (auto _ : state) {
        cam.heading = (k++ % 20) * 0.5; // a slowly turning camera: real re-refinement
        tris = set.build_mesh(cam, err, m).triangles;
        benchmark::DoNotOptimize(m.indices.data());
    }
    const double full = 2.0 * (t.rows() - 1) * (t.cols() - 1);
    state.counters["triangles"] = double(tris);
    state.counters["reduction"] = full / double(tris);
    state.counters["fps"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_QuadtreeFrame)->Arg(1)->Arg(2)->Arg(4)->Unit(benchmark::kMillisecond);

void BM_FullMeshBuild(benchmark::State& state) {
    const Terrain& t = island().terrain;
    for (auto _ : state) {
        MeshArrays m = full_resolution_mesh(t);
        benchmark::DoNotOptimize(m.indices.data());
    }
    state.counters["triangles"] = 2.0 * (t.rows() - 1) * (t.cols() - 1);
}
BENCHMARK(BM_FullMeshBuild)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_QuadtreeAccuracy(benchmark::State& state) {
    const Terrain& t = island().terrain;
    const TileGrid g = terrain_tile_grid(t, 257);
    TileSet set(g, terrain_tile_loader(t, g), std::size_t(1) << 30);
    Camera cam = view(t);
    cam.width = 640;
    cam.height = 360;
    const DepthImage ref = rasterize_depth(full_resolution_mesh(t), cam);
    MeshArrays m;
    DepthAgreement a;
    for (auto _ : state) {
        set.build_mesh(cam, 1.0, m);
        a = compare_depth(rasterize_depth(m, cam), ref, cam, 0.03);
    }
    state.counters["depth_within_3pct"] = a.share();
    state.counters["triangles"] = double(m.triangle_count());
}
BENCHMARK(BM_QuadtreeAccuracy)->Unit(benchmark::kMillisecond)->Iterations(1);

} // namespace
