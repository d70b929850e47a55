// Röttger quadtree over overlapping 257^2 tiles (Zamri):
// per-frame CPU cost of building the mesh (select + cull + load + refine +
// fans, the tile cache warm) and Zamri's metrics beside it -- triangles per
// frame, reduction against the full-resolution mesh of the whole terrain,
// share of terrain pixels whose depth is within 3 % of the full mesh (CPU
// Z-buffer, lod/QuadtreeAccuracy), and the geometric screen-space error in
// pixels (max, 99th percentile, mean over the samples in view). Zamri reports
// 80.53 fps at 22,370 triangles and 95.34 % accuracy.
//
// Terrains: the 2049^2 demo island (20 km across) and the SRTM tile of Mt
// Rainier (../shared/data, reprojected to UTM by io; the 1025^2 island when
// the data is absent). Views, at 1280x720 and 1920x1080, 60 degree fov:
//   low    -- looking south, pitch -12, far 800 samples (8 km on the
//             island): on the island 150 m above its highest point off its
//             north edge (tests/cpu/tileset_test's view); on a mountain
//             (Rainier, 80 m cells) 300 m above the ground a tenth of the way
//             in from the north edge, towards the summit;
//   aerial -- `overflight bench`'s default for a terrain without a vehicle
//             start: above the south edge at the highest point + 1/4 of the
//             relief, looking north, pitch -12, far 2048 samples.
#include "BenchTerrains.h"
#include "lod/QuadtreeAccuracy.h"
#include "lod/TileSet.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <string>

using namespace overflight;

namespace {

enum Which { Demo = 0, Rainier = 1 };
enum View { Low = 0, Aerial = 1 };

const Terrain& terrain(int which) {
    return which == Rainier ? bench::rainier_or_demo(1025) : bench::demo_island(2049);
}

Camera view(int which, const Terrain& t, int v, int width, int height) {
    Camera c;
    c.fov = 60;
    c.pitch = -12;
    c.near = 1;
    c.width = width;
    c.height = height;
    if (v == Low) {
        const double x = t.width() / 2, z = 0.1 * t.depth();
        c.eye = which == Demo ? glm::dvec3(x, t.max_height() + 150, -300)
                              : glm::dvec3(x, t.height_bilinear(float(x), float(z)) + 300, z);
        c.heading = 0;
        c.far = 800.0 * t.h_scale();
    } else {
        const double relief = std::max(double(t.max_height() - t.min_height()), 10.0 * t.h_scale());
        const double extent = std::max(t.width(), t.depth());
        c.eye = {t.width() * 0.5, t.max_height() + 0.25 * relief, t.depth() + 0.02 * extent};
        c.heading = 180;
        c.far = 2048.0 * t.h_scale();
    }
    return c;
}

void BM_Quadtree(benchmark::State& state, int which, int v, int width, int height, double error_px) {
    const Terrain& t = terrain(which);
    const TileGrid g = terrain_tile_grid(t, 257);
    TileSet set(g, terrain_tile_loader(t, g), std::size_t(1) << 30);
    const Camera cam = view(which, t, v, width, height);
    MeshArrays m;
    // Accuracy once, outside the timed loop; it also warms the tile cache.
    const TileFrameStats first = set.build_mesh(cam, error_px, m);
    const MeshArrays full = full_resolution_mesh(t);
    const DepthAgreement a = compare_depth(rasterize_depth(m, cam), rasterize_depth(full, cam), cam, 0.03);
    const ScreenError e = screen_space_error(m, t, cam);
    for (auto _ : state) {
        set.build_mesh(cam, error_px, m);
        benchmark::DoNotOptimize(m.indices.data());
    }
    state.counters["fps"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
    state.counters["triangles"] = double(first.triangles);
    state.counters["reduction"] = double(full.triangle_count()) / double(first.triangles);
    state.counters["tiles_visible"] = first.visible;
    state.counters["depth_within_3pct"] = a.share();
    state.counters["err_max_px"] = e.max_px;
    state.counters["err_p99_px"] = e.p99_px;
    state.counters["err_mean_px"] = e.mean_px;
    state.counters["samples_in_view"] = double(e.samples);
    state.counters["terrain_pixels"] = double(a.terrain_pixels);
}

BENCHMARK_CAPTURE(BM_Quadtree, demo_low_1280x720, Demo, Low, 1280, 720, 1.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Quadtree, demo_low_1920x1080, Demo, Low, 1920, 1080, 1.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Quadtree, demo_aerial_1280x720, Demo, Aerial, 1280, 720, 1.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Quadtree, demo_aerial_1920x1080, Demo, Aerial, 1920, 1080, 1.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Quadtree, rainier_low_1280x720, Rainier, Low, 1280, 720, 1.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Quadtree, rainier_low_1920x1080, Rainier, Low, 1920, 1080, 1.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Quadtree, rainier_aerial_1280x720, Rainier, Aerial, 1280, 720, 1.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Quadtree, rainier_aerial_1920x1080, Rainier, Aerial, 1920, 1080, 1.0)->Unit(benchmark::kMillisecond);
// The error target against triangles on the demo's low view.
BENCHMARK_CAPTURE(BM_Quadtree, demo_low_1280x720_2px, Demo, Low, 1280, 720, 2.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Quadtree, demo_low_1280x720_4px, Demo, Low, 1280, 720, 4.0)->Unit(benchmark::kMillisecond);

} // namespace
