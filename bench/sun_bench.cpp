// The cost of a new sun direction on the demo island (default 4097², as the
// speed target's; environment OVERFLIGHT_BENCH_DEMO_SIZE sets it): the
// horizon sweep writing float ceilings (what the GL methods upload), the
// shadow mask alone (what the ray casters' lighting reads) or both in one
// pass (what `fly` shares between the two), and the light of
// every sample from either (core/HorizonSweep.h, core/SunLight.h). The suns
// are a day's arc, one per iteration, as the time-of-day keys move it.
//   bench_sun_bench --benchmark_repetitions=5 (compare the minima on a busy machine)
#include "core/DemoIsland.h"
#include "core/HorizonSweep.h"
#include "core/SunLight.h"

#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <tbb/global_control.h>

#include <cstdlib>

using namespace overflight;

namespace {

const DataSet& island() {
    static const DataSet ds = [] {
        const char* env = std::getenv("OVERFLIGHT_BENCH_DEMO_SIZE");
        return make_demo_island({env ? std::atoi(env) : 4097});
    }();
    return ds;
}

const PackedNormals& normals() {
    static const PackedNormals n = pack_normals(island().terrain);
    return n;
}

// CPU time of the whole process (every thread's, oneTBB's workers
// included), reported per iteration as the counter "cpu_ms": on a busy
// machine it varies less than the wall time, though contention (and a
// virtual machine's stolen time) still inflates it; callgrind's instruction
// counts are the load-independent check.
double process_cpu_ms() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return 1e3 * double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-3 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// Runs `step(i)` per iteration and reports its process CPU time per iteration.
template <class Step> void timed(benchmark::State& state, Step step) {
    long long i = 0;
    const double cpu0 = process_cpu_ms();
    for (auto _ : state) step(i++);
    state.counters["cpu_ms"] = benchmark::Counter(process_cpu_ms() - cpu0, benchmark::Counter::kAvgIterations);
}

// The sun of iteration i: 7:00 to 17:00 in steps of 1.25 h, round and round.
glm::vec3 sun_of(long long i) { return sun_at_hour(7.0 + 1.25 * double(i % 9)); }

void BM_SweepCeiling(benchmark::State& state) {
    const Terrain& t = island().terrain;
    ShadowCeiling c;
    timed(state, [&](long long i) { sweep_shadow_ceiling(t, sun_of(i), c); });
}

void BM_SweepMask(benchmark::State& state) {
    const Terrain& t = island().terrain;
    std::vector<std::uint8_t> mask;
    timed(state, [&](long long i) { sweep_shadow_mask(t, sun_of(i), mask); });
}

// Both in one pass (what `fly` sweeps per sun direction for the ray caster's
// lighting and the compositor's ceiling together, core/SharedSunShadow.h).
void BM_SweepBoth(benchmark::State& state) {
    const Terrain& t = island().terrain;
    ShadowCeiling c;
    std::vector<std::uint8_t> mask;
    timed(state, [&](long long i) { sweep_shadow(t, sun_of(i), c, mask); });
}

// The one pass for a sun that moves in elevation alone (azimuth 135, from 10
// to 50 degrees up) and for one that moves in small azimuth steps (0.5
// degrees, 30 up): the sweep costs what a new direction costs either way.
void BM_SweepBothNewElevation(benchmark::State& state) {
    const Terrain& t = island().terrain;
    ShadowCeiling c;
    std::vector<std::uint8_t> mask;
    timed(state, [&](long long i) { sweep_shadow(t, sun_direction(135.0, 10.0 + 5.0 * double(i % 9)), c, mask); });
}

void BM_SweepBothSmallAzimuthStep(benchmark::State& state) {
    const Terrain& t = island().terrain;
    ShadowCeiling c;
    std::vector<std::uint8_t> mask;
    timed(state, [&](long long i) { sweep_shadow(t, sun_direction(135.0 + 0.5 * double(i % 9), 30.0), c, mask); });
}

// The light alone, for one sun (its sweep done before timing).
void BM_LightFromCeiling(benchmark::State& state) {
    const Terrain& t = island().terrain;
    Environment env = island().environment;
    env.sun_dir = sun_of(3);
    env.shadows = true;
    ShadowCeiling c;
    sweep_shadow_ceiling(t, env.sun_dir, c);
    std::vector<Rgb8> out;
    for (auto _ : state) light_colors(t, normals(), env, &c, out);
}

void BM_LightFromMask(benchmark::State& state) {
    const Terrain& t = island().terrain;
    Environment env = island().environment;
    env.sun_dir = sun_of(3);
    env.shadows = true;
    std::vector<std::uint8_t> mask;
    sweep_shadow_mask(t, env.sun_dir, mask);
    std::vector<Rgb8> out;
    for (auto _ : state) light_colors(t, normals(), env, mask, out);
}

// What the ray casters' lighting pays for a new sun direction: mask and light.
void BM_NewSunMaskAndLight(benchmark::State& state) {
    const Terrain& t = island().terrain;
    Environment env = island().environment;
    env.shadows = true;
    std::vector<std::uint8_t> mask;
    std::vector<Rgb8> out;
    long long i = 0;
    for (auto _ : state) {
        env.sun_dir = sun_of(i++);
        sweep_shadow_mask(t, env.sun_dir, mask);
        light_colors(t, normals(), env, mask, out);
    }
}

} // namespace

BENCHMARK(BM_SweepCeiling)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SweepMask)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SweepBoth)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SweepBothNewElevation)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SweepBothSmallAzimuthStep)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_LightFromCeiling)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_LightFromMask)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_NewSunMaskAndLight)->Unit(benchmark::kMillisecond)->UseRealTime();
