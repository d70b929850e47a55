// `overflight web TERRAIN -o SITE/ [--scene FILE] [--color FILE] [--max-size N]`
// (DESIGN sec. 6.1): a static site that flies over the terrain in a browser,
// the core compiled to WebAssembly casting the terrain and WebGL2 drawing the
// objects over its depth (apps/WebSite.h describes the folder).
#include "Commands.h"
#include "OptionValues.h"
#include "TerrainOptions.h"
#include "WebSite.h"
#include "core/Error.h"
#include "io/SceneFile.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <initializer_list>
#include <iterator>
#include <memory>
#include <system_error>

namespace overflight::app {

namespace {

// The engine (scripts/build_web.sh) and the page's shell (web/shell/): the
// folder $OVERFLIGHT_WEB_ENGINE_DIR names for the engine (another web
// build), a `web` folder next to the `overflight` binary holding them (a
// copied build), else the first of the folders this build configured that
// holds `probe` (the last when none does: its name is in the error).
std::string web_folder(std::initializer_list<const char*> configured, const char* probe,
                       const char* variable = nullptr) {
    if (variable)
        if (const char* dir = std::getenv(variable); dir && *dir) return dir;
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec && std::filesystem::is_regular_file(exe.parent_path() / "web" / probe, ec))
        return (exe.parent_path() / "web").string();
    for (const char* dir : configured)
        if (std::filesystem::is_regular_file(std::filesystem::path(dir) / probe, ec)) return dir;
    return *std::prev(configured.end());
}

} // namespace

void add_web_command(CLI::App& app) {
    struct Args {
        TerrainArgs terrain;
        std::string out, scene;
        int max_size = 4097;
    };
    auto args = std::make_shared<Args>();
    CLI::App* cmd = app.add_subcommand(
        "web", "Write a static web site that flies over the terrain in a browser (WebAssembly ray caster, WebGL2 "
               "objects); serve it with `python3 -m http.server -d SITE`");
    add_terrain_options(*cmd, args->terrain);
    cmd->add_option("-o,--output", args->out, "the site's folder (new, or empty)")->required();
    cmd->add_option("--scene", args->scene, "objects to show besides the data set's (TOML, DESIGN sec. 5)");
    cmd->add_option("--max-size", args->max_size,
                    "samples per side the page holds at most; a larger terrain is decimated (" +
                        std::to_string(kMinWebSize) + ".." + std::to_string(kMaxWebSize) + ")")
        ->transform(decimal<int>())
        ->capture_default_str();
    cmd->callback([args, cmd] {
        reject_empty_names(*cmd, {"-o", "--scene", "--color"});
        WebSiteOptions o;
        o.out = args->out;
        o.max_size = args->max_size;
        o.engine_dir = web_folder({OVERFLIGHT_WEB_BUILD_DIR, OVERFLIGHT_WEB_ENGINE_DIR}, "overflight_engine.wasm",
                                  "OVERFLIGHT_WEB_ENGINE_DIR");
        o.shell_dir = web_folder({OVERFLIGHT_WEB_SHELL_DIR}, "overflight.js");
        // A bad SITE, --max-size or a missing engine is refused before the terrain loads.
        check_web_site(o);
        // A raster larger than the page holds is read decimated by GDAL (block means).
        args->terrain.load.max_direct_size = args->max_size;
        DataSet data = load_terrain_lazily(args->terrain);
        if (!args->scene.empty()) data.scene.append(load_scene(args->scene));
        const std::string& source = args->terrain.terrain;
        const WebSiteReport r = write_web_site(data, source, o, [&](const std::string& line) {
            std::fprintf(stderr, "overflight: %s: %s\n", source.c_str(), line.c_str());
        });
        std::printf("%s: %dx%d samples, %lld object triangles, %.1f MB; serve it with `python3 -m http.server -d %s`\n",
                    args->out.c_str(), r.cols, r.rows, r.triangles, double(r.bytes) / 1e6, args->out.c_str());
    });
}

} // namespace overflight::app
