// Split-only ROAM (CMSC 23700 project 2a sec. 5): tessellation rate, variance-tree build
// and the error-versus-budget curve, on the SRTM tile of Mt Rainier
// (../shared/data, reprojected by io's load_terrain: 1201^2 padded to 2049^2)
// and on the 4097^2 demo island. The target is >= 15 million triangles per
// second at 262144 triangles; `items_per_second` is that rate. The quality counters
// (max / mean projected error in pixels, share of terrain pixels whose depth
// is within 5 % of the full-resolution mesh) are per budget.
#include "BenchTerrains.h"
#include "lod/QuadtreeAccuracy.h"
#include "lod/RoamMesh.h"
#include "lod/RoamViewWedge.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <string>

using namespace overflight;

namespace {

// 0: Mt Rainier SRTM (or the 1025^2 island when the data is absent), 1: 4097^2 island,
// 2: 257^2 island, whose node pool, variance tree and heights stay in the caches
// at 16384 triangles (what a split costs without its misses).
const Terrain& terrain(int which) {
    if (which == 2) return bench::demo_island(257);
    return which == 0 ? bench::rainier_or_demo(1025) : bench::demo_island(4097);
}

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

// A flight: the camera moves a quarter cell and turns a quarter degree per
// frame (the vehicle at 60 fps), back and forth along 240 frames, so that
// each frame starts from the previous frame's order-free threshold as in
// `fly`. `refined_again`: the share of frames whose threshold did not hold
// (found again by a pass in order, then refined a second time); `ordered`:
// the share of splits made in priority order.
void BM_RoamFlight(benchmark::State& state) {
    const int which = int(state.range(0));
    const int budget = int(state.range(1));
    RoamMesh& r = roam(which);
    const Terrain& t = terrain(which);
    const Camera start = flight_camera(t);
    MeshArrays mesh;
    std::size_t triangles = 0, frames = 0, again = 0, splits = 0, ordered = 0;
    for (auto _ : state) {
        const int k = int(frames % 480);
        const double step = k < 240 ? k : 480 - k;
        Camera cam = start;
        cam.heading += 0.25 * step;
        const double a = cam.heading * std::acos(-1.0) / 180.0;
        cam.eye.x += 0.25 * t.h_scale() * step * std::sin(a);
        cam.eye.z -= 0.25 * t.h_scale() * step * std::cos(a);
        const RoamStats s = r.tessellate(cam, budget);
        r.write_mesh(mesh);
        benchmark::DoNotOptimize(mesh.indices.data());
        triangles += s.triangles;
        again += s.passes == 2;
        splits += s.splits;
        ordered += s.ordered_splits;
        ++frames;
    }
    state.SetItemsProcessed(std::int64_t(triangles));
    state.counters["refined_again"] = double(again) / double(frames);
    state.counters["ordered"] = double(ordered) / double(std::max<std::size_t>(splits, 1));
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

// The split loop's floor: the greedy refinement of the same bintree with the
// same priorities (variance bound over distance, nested), buckets and view
// wedge, but each triangle split alone: no base neighbour, no forced splits,
// no links, no output arrays. The mesh is not conforming. What is left is
// what every split of split-only ROAM does (the midpoint's height and
// outcode, two children's priorities, two bucket pushes, one pop), so the
// gap between this rate and BM_RoamFrame's is what keeping the mesh
// conforming and writing it out costs. Rate: triangles (2 + splits) per
// second, as BM_RoamFrame's.
void BM_RoamSplitFloor(benchmark::State& state) {
    const int which = int(state.range(0));
    const int budget = int(state.range(1));
    RoamMesh& r = roam(which);
    const Terrain& g = r.grid();
    const RoamVarianceTree& var = r.variance();
    const Camera cam = flight_camera(terrain(which));
    const RoamViewWedge wedge = RoamViewWedge::from_camera(cam, g.min_height(), g.max_height());
    struct Tri {
        std::uint16_t r[3], c[3], raw[3];
        std::uint8_t out[3];
        std::uint8_t level;
        std::uint32_t node;
        float error;
    };
    const int n = g.rows() - 1, finest = var.finest_level();
    const double hs = g.h_scale();
    const float half_hs = 0.5f * float(hs), half_vs = 0.5f * g.v_scale(), y0 = g.y_offset();
    const float ex = float(cam.eye.x), ey = float(cam.eye.y), ez = float(cam.eye.z);
    const float focal = float(cam.focal_px()), near = float(cam.near);
    std::vector<float> radius(std::size_t(finest) + 1);
    for (int level = 0; level <= finest; ++level)
        radius[std::size_t(level)] = float(0.5 * hs * n * std::sqrt(2.0) / std::pow(std::sqrt(2.0), level));
    const std::uint16_t* heights = g.heights().data();
    const std::size_t cols = std::size_t(g.cols());
    std::vector<std::vector<Tri>> buckets(kRoamBuckets);
    // RoamMesh's priority, without the focus and padding cases.
    auto priority = [&](const Tri& t, float parent) {
        if (RoamViewWedge::outside(t.out[0], t.out[1], t.out[2]) || t.level >= finest) return -1.0f;
        const float mx = half_hs * float(t.c[1] + t.c[2]) - ex, mz = half_hs * float(t.r[1] + t.r[2]) - ez;
        const float my = half_vs * float(t.raw[1] + t.raw[2]) + y0 - ey;
        return roam_projected_error(var.world(var.stored_node(t.node, t.level)), mx, my, mz, radius[t.level], near,
                                    focal, parent);
    };
    int max_bucket = 0;
    auto push = [&](const Tri& t) {
        if (t.error < 0) return;
        const int b = roam_bucket(t.error);
        buckets[std::size_t(b)].push_back(t);
        max_bucket = std::max(max_bucket, b);
    };
    auto corner = [&](int row, int col) {
        return std::pair{heights[std::size_t(row) * cols + std::size_t(col)], wedge.outcode({hs * col, hs * row})};
    };
    long long splits = 0;
    for (auto _ : state) {
        for (auto& b : buckets) b.clear();
        max_bucket = 0;
        const auto [nw_raw, nw_out] = corner(0, 0);
        const auto [ne_raw, ne_out] = corner(0, n);
        const auto [sw_raw, sw_out] = corner(n, 0);
        const auto [se_raw, se_out] = corner(n, n);
        const std::uint16_t N = std::uint16_t(n);
        Tri roots[2] = {{{0, 0, N}, {N, 0, N}, {ne_raw, nw_raw, se_raw}, {ne_out, nw_out, se_out}, 0, 2, 0},
                        {{N, N, 0}, {0, N, 0}, {sw_raw, se_raw, nw_raw}, {sw_out, se_out, nw_out}, 0, 3, 0}};
        for (Tri& t : roots) {
            t.error = priority(t, std::numeric_limits<float>::max());
            push(t);
        }
        splits = 0;
        while (2 + splits < budget) {
            while (max_bucket > 0 && buckets[std::size_t(max_bucket)].empty()) --max_bucket;
            if (buckets[std::size_t(max_bucket)].empty()) break;
            const Tri t = buckets[std::size_t(max_bucket)].back();
            buckets[std::size_t(max_bucket)].pop_back();
            ++splits;
            const int mr = (t.r[1] + t.r[2]) / 2, mc = (t.c[1] + t.c[2]) / 2;
            const auto [m_raw, m_out] = corner(mr, mc);
            const std::uint8_t level = std::uint8_t(t.level + 1);
            Tri c0{{std::uint16_t(mr), t.r[0], t.r[1]}, {std::uint16_t(mc), t.c[0], t.c[1]},
                   {m_raw, t.raw[0], t.raw[1]}, {m_out, t.out[0], t.out[1]}, level, 2 * t.node, 0};
            Tri c1{{std::uint16_t(mr), t.r[2], t.r[0]}, {std::uint16_t(mc), t.c[2], t.c[0]},
                   {m_raw, t.raw[2], t.raw[0]}, {m_out, t.out[2], t.out[0]}, level, 2 * t.node + 1, 0};
            c0.error = priority(c0, t.error);
            c1.error = priority(c1, t.error);
            push(c0);
            push(c1);
        }
    }
    state.SetItemsProcessed(std::int64_t(state.iterations()) * (2 + splits));
    state.counters["triangles"] = double(2 + splits);
}

void BM_RoamVarianceTree(benchmark::State& state) {
    const Terrain& t = terrain(int(state.range(0)));
    for (auto _ : state) {
        RoamVarianceTree v(t.rows() == t.cols() && is_pow2_plus1(t.rows()) ? t : pad_to_pow2_plus1(t));
        benchmark::DoNotOptimize(v.raw(2));
    }
}

} // namespace

BENCHMARK(BM_RoamFrame)
    ->ArgsProduct({{0, 1}, {16384, 65536, 100000, 262144}})
    ->Args({2, 16384})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RoamFlight)->ArgsProduct({{0, 1}, {65536, 262144}})->Iterations(240)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RoamSplitFloor)->ArgsProduct({{0, 1}, {65536, 262144}})->Args({2, 16384})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RoamTessellate)->ArgsProduct({{0, 1}, {65536, 100000}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RoamErrorCurve)
    ->ArgsProduct({{0}, {4096, 8192, 16384, 32768, 65536, 131072, 262144}})
    ->Iterations(3)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RoamVarianceTree)->Arg(0)->Arg(1)->Iterations(2)->Unit(benchmark::kMillisecond);
