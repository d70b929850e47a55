// The ray casters' water pass (raycast/WaterPass.h): the mirrored rays
// marched through every cell against the same rays skipping the blocks of
// the max-height pyramid they pass above (identical pixels), in the same run,
// on the demo island flooded half-way up its relief, 1280x720, from above
// the vehicle start looking 14 degrees down. Counter: frames per second.
//   bench_water_bench [--benchmark_min_time=1]
// Environment OVERFLIGHT_BENCH_DEMO_SIZE (default 1025) sets the island size.
#include "core/DemoIsland.h"
#include "raycast/RayMarcher.h"
#include "raycast/WaterPass.h"

#include <benchmark/benchmark.h>

#include <cstdlib>

using namespace overflight;

namespace {

struct Flooded {
    DataSet ds;
    Camera camera;
    ColorImage color;
    DepthImage depth;
    Flooded() : ds(make_demo_island({std::getenv("OVERFLIGHT_BENCH_DEMO_SIZE")
                                         ? std::atoi(std::getenv("OVERFLIGHT_BENCH_DEMO_SIZE"))
                                         : 1025})) {
        const Terrain& t = ds.terrain;
        ds.environment.water = true;
        ds.environment.water_level = 0.5f * (t.min_height() + t.max_height());
        camera.heading = ds.start.heading;
        camera.pitch = -14;
        camera.eye = {ds.start.x, double(t.max_height()), ds.start.z};
        camera.far = 2048 * t.h_scale();
        RayMarcher(t, ds.environment).render(camera, SurfaceModel::Blocks, color, depth);
    }
};

const Flooded& flooded() {
    static const Flooded f;
    return f;
}

void BM_Water(benchmark::State& state) {
    const Flooded& f = flooded();
    WaterPass pass(f.ds.terrain);
    pass.set_skipping(state.range(0) != 0);
    long long pixels = 0;
    for (auto _ : state) {
        ColorImage color = f.color;
        DepthImage depth = f.depth;
        pixels = pass.apply(f.camera, f.ds.environment, SurfaceModel::Blocks, color, depth);
        benchmark::DoNotOptimize(color.pixels.data());
    }
    state.counters["water_pixels"] = double(pixels);
    state.counters["fps"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}

} // namespace

// Arg 0: the plain cell march; 1: skipping with the pyramid.
BENCHMARK(BM_Water)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
