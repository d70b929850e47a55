// `overflight bench TERRAIN [--json] [--markdown] [--size WxH] [--frames N] [--methods a,b]`
// (DESIGN sec. 6, sec. 8): renders the same view with each method in one run
// and reports medians, so methods are compared as ratios measured on the same
// machine at the same moment: Szenberg's Table 1 (steps of the composite) and
// Table 2 (Z-buffer representations), ROAM's tessellation rate and error curve
// (CMSC 23700 project 2a), Zamri's accuracy of the LOD meshes against the full mesh, and
// the ray caster's distance LOD against its exact cast (sky mask, silhouette rows).
#include "CameraOptions.h"
#include "ClassicBench.h"
#include "Commands.h"
#include "LookOptions.h"
#include "OptionValues.h"
#include "RenderSession.h"
#include "RoamBench.h"
#include "TerrainOptions.h"
#include "core/Error.h"
#include "core/HorizonSweep.h"
#include "core/SunLight.h"
#include "io/TileDirectory.h"
#include "lod/QuadtreeAccuracy.h"
#include "raycast/FloatingHorizon.h"
#include "raycast/LodAccuracy.h"

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <functional>
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string_view>

namespace overflight::app {

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n == 0 ? 0.0 : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// A slow baseline (seconds per frame on llvmpipe) stops after this much time
// once it has three timed frames; the row says how many frames it timed.
constexpr double kMethodBudgetMs = 15000.0;

void add_accuracy(nlohmann::json& run, const MethodEntry& m, RenderSession& session, const Camera& camera,
                  const DepthImage& mesh_depth);

// The distance LOD's outline against the exact cast of the same camera at
// 1920x1080, whatever size the run times (the measure's resolution is fixed
// so that its pixel tolerance means the same at every size): the share of
// pixels whose sky mask agrees and of columns whose topmost terrain row is
// within one pixel.
nlohmann::json lod_accuracy(const DataSet& data, RaycastOptions options, Camera camera) {
    camera.width = 1920;
    camera.height = 1080;
    FloatingHorizon caster(data.terrain);
    ColorImage color;
    DepthImage exact, lod;
    options.lod = false;
    caster.render(camera, data.environment, options, color, exact);
    options.lod = true;
    caster.render(camera, data.environment, options, color, lod);
    const SilhouetteAgreement a = compare_silhouettes(lod, exact, 1);
    return {{"width", camera.width},
            {"height", camera.height},
            {"sky_mask_agreement", a.sky_share()},
            {"silhouette_within_1px", a.column_share()},
            {"max_silhouette_rows", a.max_row_difference}};
}

// What the timed frames of one environment gave: wall-clock ms and each
// step's ms per frame, and the last frame's stats.
struct TimedFrames {
    std::vector<double> ms;
    std::map<std::string, std::vector<double>> steps;
    nlohmann::json stats;
};

// A run's JSON row from its frames (medians).
nlohmann::json run_row(const std::string& name, const TimedFrames& t, const Camera& camera) {
    const double med = median(t.ms);
    nlohmann::json run = {{"method", name},
                          {"width", camera.width},
                          {"height", camera.height},
                          {"frames", int(t.ms.size())},
                          {"ms_median", med},
                          {"ms_min", *std::min_element(t.ms.begin(), t.ms.end())},
                          {"fps", 1000.0 / med}};
    for (const auto& [step, v] : t.steps) run["steps_ms"][step] = median(v);
    if (t.stats.contains("samples")) {
        run["samples"] = t.stats["samples"];
        run["samples_visited"] = t.stats["samples_visited"];
        const double cast = run["steps_ms"].value("raycast", med);
        run["ns_per_sample"] = cast * 1e6 / t.stats["samples"].get<double>();
    }
    if (t.stats.contains("triangles")) run["triangles"] = t.stats["triangles"];
    run["stats"] = t.stats;
    return run;
}

// Times `frames` frames of `m` after a warm-up, one row per environment of
// `envs`: the session's own, then with the looks asked for (METHOD+looks,
// with its ratio to the first). The environments take turns frame by frame,
// so that a shared machine's load weighs on both alike. A mesh method is also
// measured against the full mesh's depth when `full_mesh_depth` gives one.
std::vector<nlohmann::json> bench_method(const MethodEntry& m, RenderSession& session, const Camera& camera,
                                         int frames, const std::function<const DepthImage*()>& full_mesh_depth,
                                         const std::vector<Environment>& envs) {
    // One method per environment: a method keeps what it derives from the
    // environment (the ray casters' lit colors) while it stays the same, as
    // it does through a flight, so interleaved frames must not share one.
    std::vector<std::unique_ptr<TerrainMethod>> methods;
    for (std::size_t e = 0; e < envs.size(); ++e) methods.push_back(session.create(m));
    TerrainMethod& method = *methods.front();
    RenderedView view;
    for (std::size_t e = 0; e < envs.size(); ++e) { // warm-up: first-touch of buffers, pyramids, uploads, tables
        session.set_environment(envs[e]);
        session.render(m, *methods[e], camera, false, view);
    }
    std::vector<TimedFrames> timed(envs.size());
    double spent = 0;
    for (int f = 0; f < frames && (f < 3 || spent < kMethodBudgetMs); ++f)
        for (std::size_t e = 0; e < envs.size(); ++e) {
            session.set_environment(envs[e]);
            TimedFrames& t = timed[e];
            const auto t0 = std::chrono::steady_clock::now();
            session.render(m, *methods[e], camera, false, view); // timed frames do not read the depth back
            t.ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
            spent += t.ms.back();
            t.stats = view_stats_json(session.settings(), camera, view);
            for (const auto& [step, v] : t.stats["ms"].items()) t.steps[step].push_back(v.get<double>());
        }
    session.set_environment(envs.front());
    std::vector<nlohmann::json> runs;
    for (std::size_t e = 0; e < envs.size(); ++e) {
        runs.push_back(run_row(e ? std::string(m.name) + "+looks" : std::string(m.name), timed[e], camera));
        if (e) runs.back()["x_without_looks"] = median(timed[e].ms) / median(timed[0].ms);
    }
    nlohmann::json& run = runs.front();
    if (view.method.roam) {
        const nlohmann::json roam = roam_bench(session.data().terrain, camera);
        run["triangles_per_s"] = roam["triangles_per_s"];
        run["ms_tessellate_100000"] = roam["ms_tessellate_100000"];
        run["error_curve"] = roam["curve"];
    }
    if (std::string_view(m.name) == "voxel" && session.settings().raycast.lod)
        run["lod_accuracy"] = lod_accuracy(session.data(), session.settings().raycast, camera);
    if (method.output_kind() == MethodOutputKind::Mesh)
        if (const DepthImage* depth = full_mesh_depth()) add_accuracy(run, m, session, camera, *depth);
    return runs;
}

// The sun's cost, measured in the same run as the methods: the horizon sweep
// and the relighting of every sample for new sun directions (a moving sun,
// as the time-of-day keys of `fly` move it), medians over a day's arc; and
// the packing of the normals that the relighting reads, done once per terrain.
// The ray casters' lighting sweeps the shadow mask alone and lights from it
// (TerrainLighting); the GL methods sweep the ceiling, which their objects
// read too.
nlohmann::json bench_sun(const Terrain& t, const Environment& env) {
    std::vector<double> sweep, mask_sweep, light;
    ShadowCeiling ceiling;
    std::vector<std::uint8_t> mask;
    std::vector<Rgb8> colors;
    const auto t_pack = std::chrono::steady_clock::now();
    const PackedNormals normals = pack_normals(t);
    const double ms_pack = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t_pack).count();
    Environment e = env;
    e.shadows = true;
    for (double hour = 7.0; hour <= 17.0; hour += 1.25) {
        e.sun_dir = sun_at_hour(hour);
        auto t0 = std::chrono::steady_clock::now();
        sweep_shadow_ceiling(t, e.sun_dir, ceiling);
        sweep.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        t0 = std::chrono::steady_clock::now();
        sweep_shadow_mask(t, e.sun_dir, mask);
        mask_sweep.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        t0 = std::chrono::steady_clock::now();
        light_colors(t, normals, e, mask, colors);
        light.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
    return {{"sun_directions", int(sweep.size())},
            {"ms_shadow_sweep", median(sweep)},
            {"ms_shadow_mask_sweep", median(mask_sweep)},
            {"ms_light", median(light)},
            {"ms_pack_normals_once", ms_pack}};
}

// Zamri's figures for a LOD mesh against full resolution (the terrain in
// memory): how many fewer triangles than two per cell, the screen-space error,
// and the share of the full mesh's terrain pixels whose view depth the
// method's image matches within 3 % (and 5 %, the ROAM target).
void add_accuracy(nlohmann::json& run, const MethodEntry& m, RenderSession& session, const Camera& camera,
                  const DepthImage& mesh_depth) {
    std::unique_ptr<TerrainMethod> method = session.create(m);
    RenderedView view;
    session.render(m, *method, camera, true, view);
    run["depth_within_3pct"] = compare_depth(*view.depth, mesh_depth, camera, 0.03).share();
    run["depth_within_5pct"] = compare_depth(*view.depth, mesh_depth, camera, 0.05).share();
    const MeshArrays* mesh = view.output.mesh;
    const Terrain& t = session.data().terrain;
    const double full = 2.0 * double(t.rows() - 1) * double(t.cols() - 1);
    const ScreenError e = screen_space_error(*mesh, t, camera);
    run["full_resolution_triangles"] = full;
    run["triangle_reduction"] = full / double(std::max<std::size_t>(1, mesh->triangle_count()));
    run["max_error_px"] = e.max_px;
    run["mean_error_px"] = e.mean_px;
    run["p99_error_px"] = e.p99_px;
}

const nlohmann::json* find_run(const nlohmann::json& runs, const std::string& method) {
    for (const auto& r : runs)
        if (r["method"] == method) return &r;
    return nullptr;
}

template <class T>
std::string fmt(const char* format, T value) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, value);
    return buf;
}

double step_ms(const nlohmann::json* run, const char* step) {
    return run && run->contains("steps_ms") ? (*run)["steps_ms"].value(step, 0.0) : 0.0;
}

void print_markdown(const nlohmann::json& out, const std::string& terrain, const Camera& camera) {
    const nlohmann::json& runs = out["runs"];
    std::printf("%s %dx%d samples, %d threads, %dx%d image, far %g, %s\n\n", terrain.c_str(), out["cols"].get<int>(),
                out["rows"].get<int>(), out["threads"].get<int>(), camera.width, camera.height, camera.far,
                to_string(camera.projection));
    const nlohmann::json* voxel = find_run(runs, "voxel");
    const double base = voxel ? (*voxel)["ms_median"].get<double>() : runs[0]["ms_median"].get<double>();
    std::printf("| method | ms (median) | fps | x %s | triangles | ns / sample | depth within 3 %% of mesh |\n"
                "|---|---:|---:|---:|---:|---:|---:|\n",
                voxel ? "voxel" : runs[0]["method"].get<std::string>().c_str());
    for (const auto& r : runs) {
        const double med = r["ms_median"].get<double>();
        std::printf("| %s | %.2f | %.2f | %.2f | %s | %s | %s |\n", r["method"].get<std::string>().c_str(), med,
                    1000.0 / med, med / base, r.contains("triangles") ? fmt("%lld", r["triangles"].get<long long>()).c_str() : "-",
                    r.contains("ns_per_sample") ? fmt("%.2f", r["ns_per_sample"].get<double>()).c_str() : "-",
                    r.contains("depth_within_3pct") ? fmt("%.2f %%", 100.0 * r["depth_within_3pct"].get<double>()).c_str()
                                                    : "-");
    }
    for (const auto& r : runs)
        if (r.contains("lod_accuracy")) {
            const nlohmann::json& a = r["lod_accuracy"];
            std::printf("\n%s distance LOD against the exact cast at %dx%d: sky mask agrees on %.2f %% of pixels, "
                        "silhouette within 1 px on %.2f %% of columns (largest difference %d rows)\n",
                        r["method"].get<std::string>().c_str(), a["width"].get<int>(), a["height"].get<int>(),
                        100.0 * a["sky_mask_agreement"].get<double>(), 100.0 * a["silhouette_within_1px"].get<double>(),
                        a["max_silhouette_rows"].get<int>());
        }
    for (const auto& r : runs)
        if (r.contains("x_without_looks"))
            std::printf("%s / without = %.3fx\n", r["method"].get<std::string>().c_str(),
                        r["x_without_looks"].get<double>());
    if (out.contains("sun")) {
        const nlohmann::json& s = out["sun"];
        std::printf("\nSun: lighting %s, shadows %s, sun azimuth %.1f elevation %.1f\n\n",
                    out["look"]["lighting"].get<std::string>().c_str(), out["look"]["shadows"].get<bool>() ? "on" : "off",
                    out["look"]["sun_azimuth"].get<double>(), out["look"]["sun_elevation"].get<double>());
        std::printf("| step for a new sun direction (median of %d) | ms |\n|---|---:|\n| horizon sweep (shadow ceiling, GL) | %.2f "
                    "|\n| horizon sweep (shadow mask, ray casters) | %.2f |\n| light of every sample (from the mask) | %.2f "
                    "|\n\nOnce per terrain: packing the normals %.2f ms\n",
                    s["sun_directions"].get<int>(), s["ms_shadow_sweep"].get<double>(),
                    s["ms_shadow_mask_sweep"].get<double>(), s["ms_light"].get<double>(),
                    s["ms_pack_normals_once"].get<double>());
    }
    const nlohmann::json* with = find_run(runs, "voxel+objects");
    const nlohmann::json* without = find_run(runs, "voxel+present");
    if (with || without) {
        // Szenberg Table 1, PC Pentium 166 column (seconds).
        std::printf("\nSzenberg Table 1: ms per step (paper: PC Pentium 166, seconds)\n\n"
                    "| step | with objects | paper | without objects | paper |\n|---|---:|---:|---:|---:|\n");
        const struct {
            const char* label;
            const char* step;
            const char* paper_with;
            const char* paper_without;
        } rows[] = {{"Floating Horizon", "raycast", "0.05", "0.04"},
                    {"Z-Buffer load", "depth_upload", "0.11", "-"},
                    {"Color Buffer load", "color_upload", "0.04", "0.04"},
                    {"Objects", "objects", "0.02", "-"},
                    {"Present (read-back)", "present", "-", "-"}};
        for (const auto& row : rows)
            std::printf("| %s | %.2f | %s | %.2f | %s |\n", row.label, step_ms(with, row.step), row.paper_with,
                        step_ms(without, row.step), row.paper_without);
        auto total = [](const nlohmann::json* r) { return r ? (*r)["ms_median"].get<double>() : 0.0; };
        std::printf("| Total | %.2f | 0.22 | %.2f | 0.08 |\n| Frames/sec. | %.1f | 4.6 | %.1f | 14.1 |\n", total(with),
                    total(without), with ? 1000.0 / total(with) : 0.0, without ? 1000.0 / total(without) : 0.0);
        if (with && without)
            std::printf("\nvoxel+objects / voxel+present = %.2fx (paper: 2.75x)\n", total(with) / total(without));
    }
    const struct {
        const char* method;
        const char* label;
        const char* paper;
    } table2[] = {{"points", "(a) Points on top faces", "0.62"}, {"top-faces", "(b) Top faces", "0.28"},
                  {"front-faces", "(c) Frontal faces", "0.24"},    {"segments", "(d) Straight line segments", "0.43"},
                  {"blocks", "(e) Blocks", "0.07"},                {"mesh", "full-resolution mesh", "-"}};
    bool header = false;
    for (const auto& row : table2) {
        const nlohmann::json* r = find_run(runs, row.method);
        if (!r) continue;
        if (!header) {
            std::printf("\nSzenberg Table 2: fps of the Z-buffer representations with objects (paper: PC)\n\n"
                        "| terrain represented by | fps | paper | x slower than voxel+objects |\n|---|---:|---:|---:|\n");
            header = true;
        }
        const double med = (*r)["ms_median"].get<double>();
        std::printf("| %s | %.3f | %s | %s |\n", row.label, 1000.0 / med, row.paper,
                    with ? fmt("%.1f", med / (*with)["ms_median"].get<double>()).c_str() : "-");
    }
    if (const nlohmann::json* q = find_run(runs, "quadtree"); q && q->contains("triangle_reduction")) {
        std::printf("\nZamri: Roettger quadtree at %g px against full resolution (paper: 1 px)\n\n"
                    "| | fps | triangles | x fewer than full | depth within 3 %% | max / mean error px |\n"
                    "|---|---:|---:|---:|---:|---:|\n"
                    "| measured | %.1f | %lld | %.1f | %s | %.2f / %.3f |\n"
                    "| paper | 80.53 | 22370 | - | 95.34 %% | - |\n",
                    (*q)["stats"].value("error_px", 1.0), 1000.0 / (*q)["ms_median"].get<double>(),
                    (*q)["triangles"].get<long long>(), (*q)["triangle_reduction"].get<double>(),
                    q->contains("depth_within_3pct")
                        ? fmt("%.2f %%", 100.0 * (*q)["depth_within_3pct"].get<double>()).c_str()
                        : "-",
                    (*q)["max_error_px"].get<double>(),
                    (*q)["mean_error_px"].get<double>());
    }
    if (const nlohmann::json* roam = find_run(runs, "roam"); roam && roam->contains("error_curve")) {
        std::printf("\nROAM: %.2f M triangles/s tessellated at 64k, a 100k mesh in %.2f ms; error versus budget\n\n"
                    "| budget | triangles | ms tessellate | max error px | mean error px |\n|---:|---:|---:|---:|---:|\n",
                    (*roam)["triangles_per_s"].get<double>() * 1e-6, (*roam)["ms_tessellate_100000"].get<double>());
        for (const auto& p : (*roam)["error_curve"])
            std::printf("| %d | %lld | %.2f | %.3f | %.3f |\n", p["budget"].get<int>(), p["triangles"].get<long long>(),
                        p["ms_tessellate"].get<double>(), p["max_error_px"].get<double>(),
                        p["mean_error_px"].get<double>());
    }
}

} // namespace

void add_bench_command(CLI::App& app) {
    struct Args {
        TerrainArgs terrain;
        CameraArgs camera;
        MethodOptions methods;
        LookArgs looks;
        std::string method_names;
        int frames = 10;
        int threads = 0;
        bool json = false, markdown = false, compare = false;
    };
    auto args = std::make_shared<Args>();
    CLI::App* cmd = app.add_subcommand(
        "bench", "Time the terrain renderers on one view (default: 1920x1080, far 2048 cells, the overview camera)");
    add_terrain_options(*cmd, args->terrain);
    add_max_direct_size_option(*cmd, args->terrain);
    add_camera_options(*cmd, args->camera);
    add_method_options(*cmd, args->methods);
    add_look_options(*cmd, args->looks, "; each method is also timed without it (METHOD and METHOD+looks rows)");
    cmd->add_option("--frames", args->frames,
                    "timed frames per method after one warm-up frame (a method slower than 15 s in all stops at 3)")
        ->transform(decimal<int>())
        ->capture_default_str();
    cmd->add_option("--methods", args->method_names, "comma-separated methods (default: all but raymarch; known: " +
                                                   terrain_method_names() + ")");
    cmd->add_option("--threads", args->threads, "worker threads (default: all cores)")->transform(decimal<int>());
    cmd->add_flag("--compare", args->compare,
                  "time voxel and voxel-literal beside the classic Voxel Space loop (no depth; one-sample and growing "
                  "steps) on the same view, in ns per sample per core");
    cmd->add_flag("--json", args->json, "print one JSON object {\"runs\": [...]}");
    cmd->add_flag("--markdown", args->markdown, "print Markdown tables (the default without --json)");
    cmd->callback([args] {
        if (args->frames < 1 || args->frames > 100000) throw Error("--frames", "must be in 1..100000");
        if (args->threads < 0 || args->threads > 1024) throw Error("--threads", "must be in 1..1024");
        std::vector<const MethodEntry*> methods;
        if (args->method_names.empty()) {
            for (const MethodEntry& m : terrain_methods())
                if (m.bench_by_default) methods.push_back(&m);
        } else {
            std::stringstream ss(args->method_names);
            std::string name;
            while (std::getline(ss, name, ',')) {
                const MethodEntry* m = find_terrain_method(name);
                if (!m) throw Error("--methods", "unknown method '" + name + "' (known: " + terrain_method_names() + ")");
                methods.push_back(m);
            }
        }
        if (args->compare)
            for (const char* name : {"voxel", "voxel-literal"}) {
                const MethodEntry* m = find_terrain_method(name);
                if (std::find(methods.begin(), methods.end(), m) == methods.end()) methods.push_back(m);
            }
        std::unique_ptr<tbb::global_control> limit;
        if (args->threads > 0)
            limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, args->threads);
        // A tile directory is read whole only when a method needs every sample
        // in memory; the quadtree alone reads it lazily (and has no full mesh
        // to be compared with).
        const bool tiles = is_tile_directory(args->terrain.terrain);
        const bool lazy = tiles && std::all_of(methods.begin(), methods.end(),
                                               [](const MethodEntry* m) { return m->reads_tiles; });
        const DataSet data = lazy ? load_terrain_lazily(args->terrain) : load_terrain(args->terrain);
        const Environment looked = with_looks(args->looks, data.environment, data.terrain); // bad values fail before the work
        CameraArgs cam_args = args->camera;
        if (!cam_args.far) cam_args.far = 2048.0 * data.terrain.h_scale(); // "far 2048 samples"
        const Camera camera = make_camera(cam_args, data, 1920, 1080);
        RenderSession session(data, args->methods, tiles ? args->terrain.terrain : std::string());

        nlohmann::json runs = nlohmann::json::array();
        std::optional<DepthImage> mesh_depth;
        // LOD meshes against the full mesh of the same samples (not of a tile
        // directory's overview).
        auto full_mesh_depth = [&]() -> const DepthImage* {
            if (lazy) return nullptr;
            if (!mesh_depth) {
                const MethodEntry& mesh = *find_terrain_method("mesh");
                std::unique_ptr<TerrainMethod> full = session.create(mesh);
                RenderedView view;
                session.render(mesh, *full, camera, true, view);
                mesh_depth = *view.depth;
            }
            return &*mesh_depth;
        };
        // With looks, each method is timed as the data set is and with them,
        // in this run: their cost is the ratio of the two rows. With
        // --shadows the rows without are the papers' baked look, so that the
        // ratio is the cost of the sun's light and shadows together.
        Environment without = data.environment;
        if (args->looks.shadows) bake_lighting(without);
        std::vector<Environment> envs{without};
        if (args->looks.any()) envs.push_back(looked);
        for (const MethodEntry* m : methods)
            for (nlohmann::json& run : bench_method(*m, session, camera, args->frames, full_mesh_depth, envs))
                runs.push_back(std::move(run));
        if (args->compare)
            for (nlohmann::json& run : classic_voxel_space_bench(data.terrain, camera, args->frames))
                runs.push_back(std::move(run));
        nlohmann::json out = {{"terrain", data.info.source.empty() ? args->terrain.terrain : data.info.source},
                                    {"rows", data.terrain.rows()},
                                    {"cols", data.terrain.cols()},
                                    {"threads", args->threads > 0 ? args->threads : tbb::info::default_concurrency()},
                                    {"far", camera.far},
                                    {"projection", to_string(camera.projection)},
                                    {"runs", runs}};
        const SunAngles sun = sun_angles(looked.sun_dir);
        out["look"] = {{"lighting", lighting_is_baked(looked) ? "baked" : "sun"},
                       {"shadows", looked.shadows},
                       {"sun_azimuth", sun.azimuth},
                       {"sun_elevation", sun.elevation}};
        if (looked.shadows) out["sun"] = bench_sun(data.terrain, looked);
        if (args->json) {
            const std::string text = out.dump() + "\n";
            std::fwrite(text.data(), 1, text.size(), stdout);
        }
        if (args->markdown || !args->json) {
            print_markdown(out, args->terrain.terrain, camera);
            if (args->compare) print_classic_comparison(out["runs"], out["threads"].get<int>());
        }
    });
}

} // namespace overflight::app
