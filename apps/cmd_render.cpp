// `overflight render TERRAIN -o out.png [--method M] [camera options] [--scene FILE]
//                   [--depth depth.tif] [--save-camera view.json] [--stats] [--triangles N] [--error PX]
//                   [--lighting sun|baked] [--sun AZ,EL] [--shadows]`
// (DESIGN sec. 6): one view of a terrain, written as PNG (+ float32 window
// depth TIFF), with timings and counts as one JSON object on stdout.
#include "CameraOptions.h"
#include "Commands.h"
#include "LookOptions.h"
#include "OptionValues.h"
#include "RenderSession.h"
#include "StandardOutput.h"
#include "TerrainOptions.h"
#include "core/Error.h"
#include "io/CameraFile.h"
#include "io/Files.h"
#include "io/ImageWriters.h"
#include "io/TileDirectory.h"

#include <chrono>
#include <cstdio>
#include <memory>

namespace overflight::app {

namespace {
double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}
} // namespace

void add_render_command(CLI::App& app) {
    struct Args {
        TerrainArgs terrain;
        CameraArgs camera;
        MethodOptions methods;
        LookArgs looks;
        std::string out, depth, save_camera, method = "voxel";
        bool stats = false;
    };
    auto args = std::make_shared<Args>();
    CLI::App* cmd = app.add_subcommand("render", "Render one view of a terrain to a PNG (and its depth to a TIFF)");
    add_terrain_options(*cmd, args->terrain);
    add_max_direct_size_option(*cmd, args->terrain);
    cmd->add_option("-o,--output", args->out, "output PNG")->required();
    cmd->add_option("--method", args->method, "terrain renderer: " + terrain_method_names())->capture_default_str();
    add_camera_options(*cmd, args->camera);
    add_method_options(*cmd, args->methods);
    add_look_options(*cmd, args->looks);
    cmd->add_option("--depth", args->depth, "also write the OpenGL window depth (float32 TIFF, 1.0 = sky)");
    cmd->add_option("--save-camera", args->save_camera, "also write the camera of this view (JSON, read by --camera)");
    cmd->add_flag("--stats", args->stats, "print timings and counts as one JSON object on stdout");
    cmd->callback([args, cmd] {
        reject_empty_names(*cmd, {"-o", "--depth", "--scene", "--color", "--save-camera", "--camera"});
        // A bad output name is refused before the work, not after it.
        check_output_folder(args->out);
        if (!args->depth.empty()) check_output_folder(args->depth);
        if (!args->save_camera.empty()) check_output_folder(args->save_camera);
        const MethodEntry* row = find_terrain_method(args->method);
        if (!row) throw Error("--method", "unknown method '" + args->method + "' (known: " + terrain_method_names() + ")");
        auto t0 = std::chrono::steady_clock::now();
        const bool tiles = is_tile_directory(args->terrain.terrain);
        DataSet data = row->reads_tiles ? load_terrain_lazily(args->terrain) : load_terrain(args->terrain);
        const double ms_load = ms_since(t0);
        const Camera camera = make_camera(args->camera, data, 1280, 720);
        RenderSession session(data, args->methods, tiles ? args->terrain.terrain : std::string());
        session.set_environment(with_looks(args->looks, data.environment, data.terrain));
        // A user's `voxel` view shows the objects: Szenberg's composite.
        if (args->method == "voxel" && session.has_objects()) row = find_terrain_method("voxel+objects");
        std::unique_ptr<TerrainMethod> method = session.create(*row);
        RenderedView view;
        t0 = std::chrono::steady_clock::now();
        session.render(*row, *method, camera, !args->depth.empty(), view);
        const double ms_render = ms_since(t0);
        t0 = std::chrono::steady_clock::now();
        // The depth first: if it fails, -o has not been touched; if the PNG
        // fails, the new depth goes too (no half of a result left behind).
        if (!args->depth.empty()) write_depth_tiff(args->depth, *view.depth);
        bool camera_written = false;
        try {
            if (!args->save_camera.empty()) {
                write_camera_file(args->save_camera, camera, camera_map_of(camera, data));
                camera_written = true;
            }
            write_png(args->out, *view.color);
        } catch (...) {
            if (!args->depth.empty()) std::remove(args->depth.c_str());
            if (camera_written) std::remove(args->save_camera.c_str());
            throw;
        }
        const double ms_write = ms_since(t0);
        if (args->stats) {
            nlohmann::json stats = view_stats_json(session.settings(), camera, view);
            stats["method"] = args->method;
            stats["width"] = camera.width;
            stats["height"] = camera.height;
            stats["projection"] = to_string(camera.projection);
            stats["ms"]["terrain_load"] = ms_load; // quadtree has its own "load" (tiles)
            stats["ms"]["render"] = ms_render;
            stats["ms"]["write"] = ms_write;
            stats["sun_sweeps"] = session.sun_sweeps();
            write_stdout(stats.dump() + "\n");
        }
    });
}

} // namespace overflight::app
