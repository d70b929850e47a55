// Out-of-core rendering of a tile directory (Zamri,
// "Run-Time Processing"): a flight across a terrain larger than the memory
// bound, each frame selecting and culling the tiles around the viewer,
// reading the missing tiles lazily, far ones at reduced levels, into the LRU
// cache (1 GiB bound; rows streamed within a frame beyond it), refining their Röttger quadtrees at 1 px and drawing the mesh with
// OpenGL (headless EGL). The camera is placed on the directory's overview
// (io load_tile_directory_overview), never on the whole terrain.
//
//   overflight tile demo --demo-size 16385 -o DIR --tile-size 513
//   OVERFLIGHT_TILE_DIR=DIR /usr/bin/time -v bench_tile_stream_bench
//
// Without OVERFLIGHT_TILE_DIR the benchmark reports an error and does nothing.
// OVERFLIGHT_TILE_BOUND_MIB=N sets another memory bound (default 1024);
// OVERFLIGHT_TILE_PNG=FILE also writes the last frame. Counters: triangles
// and tiles loaded per frame, tiles evicted, tiles streamed within frames,
// cache MiB (largest), peak RSS MiB of the process (getrusage).
#include "core/Camera.h"
#include "gl/HeadlessRenderer.h"
#include "io/ImageWriters.h"
#include "io/TileDirectory.h"
#include "lod/TileSet.h"

#include <benchmark/benchmark.h>

#include <sys/resource.h>

#include <algorithm>
#include <cstdlib>
#include <string>

using namespace overflight;

namespace {

double peak_rss_mib() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_maxrss) / 1024.0; // kilobytes on Linux
}

void BM_TileStream(benchmark::State& state) {
    const char* dir = std::getenv("OVERFLIGHT_TILE_DIR");
    if (!dir) {
        state.SkipWithError("set OVERFLIGHT_TILE_DIR to a directory written by `overflight tile`");
        return;
    }
    const DataSet overview = load_tile_directory_overview(dir);
    const TileIndex index = read_tile_index(dir);
    const char* bound_mib = std::getenv("OVERFLIGHT_TILE_BOUND_MIB");
    const std::size_t bound = std::size_t(bound_mib ? std::max(1L, std::atol(bound_mib)) : 1024L) << 20;
    TileSet tiles(index.grid, tile_directory_loader(dir, index), bound);
    gl::HeadlessRenderer gl(overview.terrain, Scene{});
    const Terrain& t = overview.terrain;

    // Eastwards across the middle, 300 m above the ground, half a tile per frame.
    Camera cam;
    cam.fov = 60;
    cam.pitch = -12;
    cam.heading = 90;
    cam.width = 1280;
    cam.height = 720;
    cam.near = 1;
    cam.far = 2048.0 * index.grid.h_scale;
    const double step = 0.5 * index.grid.tile_world_size();
    double x = 0.1 * t.width();
    const double z = 0.5 * t.depth();

    MeshArrays mesh;
    ColorImage color;
    double triangles = 0, loaded = 0, evicted = 0, streamed = 0, cache_mib = 0;
    for (auto _ : state) {
        if (x > 0.9 * t.width()) x = 0.1 * t.width();
        cam.eye = {x, t.height_bilinear(float(x), float(z)) + 300.0, z};
        const TileFrameStats s = tiles.build_mesh(cam, 1.0, mesh);
        gl.render(MethodOutput::of_mesh(mesh), cam, overview.environment, {}, color, nullptr);
        triangles += double(s.triangles);
        loaded += s.loaded;
        evicted += s.evicted;
        streamed += s.streamed;
        cache_mib = std::max(cache_mib, double(s.cache_bytes) / (1024.0 * 1024.0));
        x += step;
    }
    if (const char* png = std::getenv("OVERFLIGHT_TILE_PNG")) write_png(png, color);
    const double frames = double(state.iterations());
    state.counters["fps"] = benchmark::Counter(frames, benchmark::Counter::kIsRate);
    state.counters["triangles"] = triangles / frames;
    state.counters["loaded_per_frame"] = loaded / frames;
    state.counters["evicted"] = evicted;
    state.counters["streamed"] = streamed;
    state.counters["cache_mib"] = cache_mib;
    state.counters["peak_rss_mib"] = peak_rss_mib();
    state.counters["terrain_samples"] = double(index.grid.source_rows) * double(index.grid.source_cols);
}
BENCHMARK(BM_TileStream)->Unit(benchmark::kMillisecond)->Iterations(40);

} // namespace
