// Floating Horizon speed (Szenberg, Gattass, Carvalho, "An Algorithm for the
// Visualization of a Terrain with Objects", SIBGRAPI 1997, Table 1's
// "Floating Horizon" step): the fast caster against the literal Algorithm 1
// in the same run, on the demo island, at 1920x1080 with the far plane 2048
// cells away, with fog and with the atmosphere. Counters:
// ns per ray sample (columns x slices up to far) and frames per second.
//   bench_raycast_bench --benchmark_filter=. [--benchmark_min_time=1]
// Environment OVERFLIGHT_BENCH_DEMO_SIZE (default 4097) sets the island size.
// BM_VoxelImagery* drape imagery at twice the island's resolution
// (raycast/ImageryTexels.h): their ratio to BM_Voxel* is the imagery's cost;
// BM_VoxelAllLooks adds the sun's light, shadows and the atmosphere.
// BM_VoxelLod4K: the distance LOD at 3840x2160, far 16384 cells.
#include "core/DemoIsland.h"
#include "core/ImageryPyramid.h"
#include "core/SunLight.h"
#include "raycast/Atmosphere.h"
#include "raycast/FloatingHorizon.h"
#include "raycast/FloatingHorizonLiteral.h"
#include "raycast/ShearResolve.h"

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cstdlib>
#include <memory>

using namespace overflight;

namespace {

const DataSet& island() {
    static const DataSet ds = [] {
        const char* env = std::getenv("OVERFLIGHT_BENCH_DEMO_SIZE");
        return make_demo_island({env ? std::atoi(env) : 4097});
    }();
    return ds;
}

// The default view of `overflight bench` (apps/CameraOptions.cpp): aerial,
// 150 cells behind the vehicle start, 14 degrees down, far 2048 cells.
Camera bench_camera(const DataSet& ds, Projection proj) {
    const Terrain& t = ds.terrain;
    const double relief = std::max(double(t.max_height() - t.min_height()), 10.0 * t.h_scale());
    Camera cam;
    cam.width = 1920;
    cam.height = 1080;
    cam.fov = 60;
    cam.pitch = -14;
    cam.projection = proj;
    cam.heading = ds.start.heading;
    const glm::dvec3 F = cam.forward();
    const double x = std::clamp(ds.start.x - 150 * t.h_scale() * F.x, 0.0, double(t.width()));
    const double z = std::clamp(ds.start.z - 150 * t.h_scale() * F.z, 0.0, double(t.depth()));
    const double ground = std::max(t.height_bilinear(float(x), float(z)), t.height_bilinear(float(ds.start.x), float(ds.start.z)));
    cam.eye = {x, std::max(ground + 15.0 * t.h_scale(), double(t.min_height()) + 0.9 * relief), z};
    cam.near = 1;
    cam.far = 2048 * t.h_scale();
    return cam;
}

// Imagery over the island at twice its resolution: its colors, a pattern
// of texels brightened and darkened in turn so that no two neighbours agree.
const ImageryPyramid& island_imagery() {
    static const ImageryPyramid p = [] {
        const Terrain& t = island().terrain;
        Image2D<Rgba8> img(2 * t.cols(), 2 * t.rows());
        for (int r = 0; r < img.height; ++r)
            for (int c = 0; c < img.width; ++c) {
                const Rgb8 s = t.color(std::min(r / 2, t.rows() - 1), std::min(c / 2, t.cols() - 1));
                const int k = (r + c) % 2 ? 20 : -20;
                auto ch = [k](int v) { return std::uint8_t(std::clamp(v + k, 0, 255)); };
                img.at(c, r) = Rgba8{ch(s.r), ch(s.g), ch(s.b), 255};
            }
        const double hs = t.h_scale();
        return ImageryPyramid(std::move(img), -0.5 * hs, -0.5 * hs, hs * t.cols(), hs * t.rows());
    }();
    return p;
}

// atmosphere: the aerial perspective (Environment::atmosphere) instead of fog.
// imagery: draped over the painted samples (FloatingHorizon::set_imagery).
// shadows: sun-lit colors with the terrain's shadows of a low sun and their
// light mask (front faces change light where the mesh does: FrontFace.h).
// uhd: the view of the distance LOD's speed goal, 3840x2160 with far 16384
// cells (`bench --size 3840x2160 --far 163840 --lod`).
void run_fast(benchmark::State& state, Projection proj, RaycastOptions opt, bool atmosphere = false,
              bool imagery = false, bool shadows = false, bool uhd = false) {
    const DataSet& ds = island();
    const int threads = int(state.range(0));
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    FloatingHorizon fh(ds.terrain);
    if (imagery) fh.set_imagery(&island_imagery());
    Camera cam = bench_camera(ds, proj);
    if (uhd) {
        cam.width = 3840;
        cam.height = 2160;
        cam.far = 16384 * ds.terrain.h_scale();
    }
    Environment env = ds.environment;
    env.atmosphere = atmosphere;
    TerrainLighting lighting(ds.terrain);
    if (shadows) {
        env.sun_dir = sun_direction(250.0, 12.0);
        env.shadows = true;
        fh.set_colors(lighting.colors(env), lighting.light_mask());
    }
    ColorImage color;
    DepthImage depth;
    RaycastStats stats;
    fh.render(cam, env, opt, color, depth, &stats); // warm-up
    double ms_setup = 0, ms_cast = 0, ms_resolve = 0;
    for (auto _ : state) {
        fh.render(cam, env, opt, color, depth, &stats);
        ms_setup += stats.ms_setup;
        ms_cast += stats.ms_cast;
        ms_resolve += stats.ms_resolve;
    }
    state.counters["setup_ms"] = ms_setup / double(state.iterations());
    state.counters["cast_ms"] = ms_cast / double(state.iterations());
    state.counters["resolve_ms"] = ms_resolve / double(state.iterations());
    state.counters["ns_per_sample"] = benchmark::Counter(double(stats.samples) * 1e-9 * double(state.iterations()),
                                                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    state.counters["samples"] = double(stats.samples);
    state.counters["visited"] = double(stats.samples_visited);
    state.counters["fps"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_Voxel(benchmark::State& s) { run_fast(s, Projection::Shear, {}); }
// Without run skipping (SliceRunBound): what the max-height pyramid saves.
void BM_VoxelAtmosphere(benchmark::State& s) { run_fast(s, Projection::Shear, {}, true); }
void BM_VoxelImagery(benchmark::State& s) { run_fast(s, Projection::Shear, {}, false, true); }
void BM_VoxelImageryAtmosphere(benchmark::State& s) { run_fast(s, Projection::Shear, {}, true, true); }
void BM_VoxelShadows(benchmark::State& s) { run_fast(s, Projection::Shear, {}, false, false, true); }
// Every look of the speed target at once: its ratio to BM_Voxel is what
// imagery, sun light, shadows and the atmosphere cost together.
void BM_VoxelAllLooks(benchmark::State& s) { run_fast(s, Projection::Shear, {}, true, true, true); }

// The aerial perspective's per-frame tables for an eye that climbs every
// frame, as in a flight (the direction and sky tables are rebuilt).
void BM_AerialTables(benchmark::State& state) {
    Environment env;
    env.atmosphere = true;
    AerialTables tables;
    double eye_y = 100.0;
    for (auto _ : state) {
        eye_y += 0.5;
        tables.build(aerial_frame(env, eye_y), float(-eye_y), float(3000.0 - eye_y));
        benchmark::DoNotOptimize(tables.haze());
    }
}

void BM_VoxelNoSkip(benchmark::State& s) {
    RaycastOptions o;
    o.skip_runs = false;
    run_fast(s, Projection::Shear, o);
}
// The scalar block cast compiled for x86-64-v3 (CastKernel): beside
// BM_Voxel / BM_VoxelNoSkip, which run the x86-64-v4 kernel (columns in
// lockstep) where the CPU has it, in one run
// (--benchmark_enable_random_interleaving on a busy machine).
void BM_VoxelV3(benchmark::State& s) {
    RaycastOptions o;
    o.kernel = CastKernel::X86_64_v3;
    run_fast(s, Projection::Shear, o);
}
void BM_VoxelNoSkipV3(benchmark::State& s) {
    RaycastOptions o;
    o.skip_runs = false;
    o.kernel = CastKernel::X86_64_v3;
    run_fast(s, Projection::Shear, o);
}
// The AVX2 resolve and drape reading their tables with gathers, with scalar
// loads and through windows (ResolveKernel::Avx2, Avx2Loads, Avx2Window:
// raycast/LaneLookup.h), plain and with every look (the imagery's drape);
// Auto (BM_Voxel, BM_VoxelAllLooks) resolves through windows and drapes with
// the loads where gathers are slow, and runs the AVX-512 kernels where the
// CPU has them.
void run_resolve(benchmark::State& s, ResolveKernel kernel, bool all_looks) {
    if (!resolve_kernel_available(kernel)) {
        s.SkipWithError("no AVX2 on this CPU");
        return;
    }
    RaycastOptions o;
    o.resolve = kernel;
    run_fast(s, Projection::Shear, o, all_looks, all_looks, all_looks);
}
void BM_VoxelGathers(benchmark::State& s) { run_resolve(s, ResolveKernel::Avx2, false); }
void BM_VoxelLoads(benchmark::State& s) { run_resolve(s, ResolveKernel::Avx2Loads, false); }
void BM_VoxelWindow(benchmark::State& s) { run_resolve(s, ResolveKernel::Avx2Window, false); }
void BM_VoxelAllLooksGathers(benchmark::State& s) { run_resolve(s, ResolveKernel::Avx2, true); }
void BM_VoxelAllLooksLoads(benchmark::State& s) { run_resolve(s, ResolveKernel::Avx2Loads, true); }
void BM_VoxelAllLooksWindow(benchmark::State& s) { run_resolve(s, ResolveKernel::Avx2Window, true); }
void BM_VoxelBilinear(benchmark::State& s) {
    RaycastOptions o;
    o.surface = SurfaceModel::Bilinear;
    run_fast(s, Projection::Shear, o);
}
void BM_VoxelLod(benchmark::State& s) {
    RaycastOptions o;
    o.lod = true;
    run_fast(s, Projection::Shear, o);
}
void BM_VoxelLod4K(benchmark::State& s) {
    RaycastOptions o;
    o.lod = true;
    run_fast(s, Projection::Shear, o, false, false, false, true);
}
void BM_VoxelNearStep(benchmark::State& s) {
    RaycastOptions o;
    o.near_step_pixels = 0.5;
    run_fast(s, Projection::Shear, o);
}
void BM_VoxelTiltExact(benchmark::State& s) { run_fast(s, Projection::Tilt, {}); }
void BM_VoxelTiltGuedes(benchmark::State& s) {
    RaycastOptions o;
    o.tilt = TiltMethod::Guedes;
    run_fast(s, Projection::Tilt, o);
}

void BM_VoxelLiteral(benchmark::State& state) {
    const DataSet& ds = island();
    const Camera cam = bench_camera(ds, Projection::Shear);
    ColorImage color;
    DepthImage depth;
    RaycastStats stats;
    for (auto _ : state)
        render_floating_horizon_literal(ds.terrain, ds.environment, cam, SurfaceModel::Blocks, color, depth, &stats);
    state.counters["ns_per_sample"] = benchmark::Counter(double(stats.samples) * 1e-9 * double(state.iterations()),
                                                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    state.counters["fps"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}

} // namespace

BENCHMARK(BM_Voxel)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_VoxelAtmosphere)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_VoxelImagery)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_VoxelImageryAtmosphere)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_VoxelShadows)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_VoxelAllLooks)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_AerialTables)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_VoxelNoSkip)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_VoxelV3)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_VoxelNoSkipV3)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_VoxelGathers)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_VoxelLoads)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_VoxelWindow)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_VoxelAllLooksGathers)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_VoxelAllLooksLoads)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_VoxelAllLooksWindow)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_VoxelBilinear)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_VoxelLod)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_VoxelLod4K)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_VoxelNearStep)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_VoxelTiltExact)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_VoxelTiltGuedes)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_VoxelLiteral)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
