// `overflight bench TERRAIN [--json] [--markdown] [--size WxH] [--frames N] [--methods a,b]`
// (DESIGN sec. 6, sec. 8): renders the same view with each method N times in
// one run and reports the median, so methods are compared as ratios measured
// on the same machine at the same moment (the papers' Tables 1 and 2).
#include "CameraOptions.h"
#include "Commands.h"
#include "TerrainOptions.h"
#include "core/Error.h"

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <sstream>

namespace overflight::app {

void add_bench_command(CLI::App& app) {
    struct Args {
        TerrainArgs terrain;
        CameraArgs camera;
        RenderSettings settings;
        std::string methods;
        int frames = 10;
        int threads = 0;
        bool json = false, markdown = false;
    };
    auto args = std::make_shared<Args>();
    CLI::App* cmd = app.add_subcommand(
        "bench", "Time the terrain renderers on one view (default: 1920x1080, far 2048 cells, the overview camera)");
    add_terrain_options(*cmd, args->terrain);
    add_camera_options(*cmd, args->camera);
    add_render_settings(*cmd, args->settings);
    cmd->add_option("--frames", args->frames, "timed frames per method (after one warm-up frame)")->capture_default_str();
    cmd->add_option("--methods", args->methods, "comma-separated methods (default: all benchmarked ones; known: " +
                                                   render_method_names() + ")");
    cmd->add_option("--threads", args->threads, "worker threads (default: all cores)");
    cmd->add_flag("--json", args->json, "print one JSON object {\"runs\": [...]}");
    cmd->add_flag("--markdown", args->markdown, "print a Markdown table (the default without --json)");
    cmd->callback([args] {
        if (args->frames < 1 || args->frames > 100000) throw Error("--frames", "must be in 1..100000");
        if (args->threads < 0 || args->threads > 1024) throw Error("--threads", "must be in 1..1024");
        std::vector<const RenderMethod*> methods;
        if (args->methods.empty()) {
            for (const auto& m : render_methods())
                if (m.bench_by_default) methods.push_back(&m);
        } else {
            std::stringstream ss(args->methods);
            std::string name;
            while (std::getline(ss, name, ',')) methods.push_back(&find_render_method(name, "--methods"));
        }
        std::unique_ptr<tbb::global_control> limit;
        if (args->threads > 0)
            limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, args->threads);
        const DataSet data = load_terrain(args->terrain);
        CameraArgs cam_args = args->camera;
        if (!cam_args.far) cam_args.far = 2048.0 * data.terrain.h_scale(); // "far 2048 samples"
        const Camera camera = make_camera(cam_args, data, 1920, 1080);

        nlohmann::json runs = nlohmann::json::array();
        ColorImage color;
        DepthImage depth;
        for (const RenderMethod* m : methods) {
            std::unique_ptr<ViewRenderer> r = m->create(data, args->settings);
            nlohmann::json stats;
            r->render(camera, color, depth, stats); // warm-up: first-touch of buffers and pyramids
            std::vector<double> ms;
            for (int f = 0; f < args->frames; ++f) {
                const auto t0 = std::chrono::steady_clock::now();
                r->render(camera, color, depth, stats);
                ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
            }
            std::sort(ms.begin(), ms.end());
            const double median = ms.size() % 2 ? ms[ms.size() / 2] : 0.5 * (ms[ms.size() / 2 - 1] + ms[ms.size() / 2]);
            nlohmann::json run = {{"method", m->name},   {"width", camera.width}, {"height", camera.height},
                                  {"frames", args->frames}, {"ms_median", median},  {"ms_min", ms.front()},
                                  {"fps", 1000.0 / median}};
            if (stats.contains("samples")) {
                const double samples = stats["samples"].get<double>();
                run["samples"] = stats["samples"];
                run["samples_visited"] = stats["samples_visited"];
                run["ns_per_sample"] = median * 1e6 / samples;
            }
            run["stats"] = stats;
            runs.push_back(run);
        }
        const int threads = args->threads > 0 ? args->threads : tbb::info::default_concurrency();
        if (args->json) {
            const nlohmann::json out = {{"terrain", data.info.source.empty() ? args->terrain.terrain : data.info.source},
                                        {"rows", data.terrain.rows()},
                                        {"cols", data.terrain.cols()},
                                        {"threads", threads},
                                        {"far", camera.far},
                                        {"projection", to_string(camera.projection)},
                                        {"runs", runs}};
            const std::string text = out.dump() + "\n";
            std::fwrite(text.data(), 1, text.size(), stdout);
        }
        if (args->markdown || !args->json) {
            const double base = runs.empty() ? 1.0 : runs[0]["ms_median"].get<double>();
            std::printf("%s %dx%d samples, %d threads, %dx%d image, far %g, %s\n\n", args->terrain.terrain.c_str(),
                        data.terrain.cols(), data.terrain.rows(), threads, camera.width, camera.height, camera.far,
                        to_string(camera.projection));
            std::printf("| method | ms (median) | fps | ns / sample | x %s |\n|---|---:|---:|---:|---:|\n",
                        runs.empty() ? "" : runs[0]["method"].get<std::string>().c_str());
            for (const auto& r : runs) {
                const double med = r["ms_median"].get<double>();
                std::printf("| %s | %.2f | %.1f | %s | %.2f |\n", r["method"].get<std::string>().c_str(), med, 1000.0 / med,
                            r.contains("ns_per_sample") ? std::to_string(r["ns_per_sample"].get<double>()).c_str() : "-",
                            med / base);
            }
        }
    });
}

} // namespace overflight::app
