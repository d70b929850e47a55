// `overflight fly TERRAIN [--scene FILE] [--method M] [--record path.csv]
//                  [--frames N --press KEY:FROM-TO ... --screenshot FILE]
//                  [--replay path.csv [--frames N] --out DIR [--video out.mp4] [--save-cameras]]`
// (DESIGN sec. 6). Interactive: a resizable window flying the
// hovercraft (gl/FlightWindow). With --frames: an unattended run of N frames
// with scripted keys (FROM-TO in frames). With --replay: the recorded cameras
// rendered headless to DIR/frame_00000.png ... (and to a video through ffmpeg).
// Methods: any row of the method table (methods/MethodTable.h) is shown
// first; Tab cycles the table's fly rows (mesh, voxel, roam, quadtree).
// TERRAIN may be a tile directory larger than memory: the quadtree then reads
// its full-resolution tiles lazily within --cache-mib, while the vehicle,
// the chase camera and the other methods use its overview (at most 2049
// samples per side: every f-th sample, exact when the terrain is no larger).
// Prints one CSV line per method used:
//   method,frames,fps,triangles_per_frame,object_triangles_per_frame,ms_per_step
// the last column as "step:ms;step:ms;..." (mean over the timed frames).
#include "CameraOptions.h"
#include "Commands.h"
#include "LookOptions.h"
#include "OptionValues.h"
#include "RenderSession.h"
#include "TerrainOptions.h"
#include "core/Error.h"
#include "core/SunLight.h"
#include "gl/FlightWindow.h"
#include "io/CameraFile.h"
#include "io/Files.h"
#include "io/FlightRecordFile.h"
#include "io/ImageWriters.h"
#include "io/SceneFile.h"
#include "io/Subprocess.h"
#include "io/TileDirectory.h"
#include "sim/FlightSession.h"
#include "sim/KeyScript.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace overflight::app {

namespace {

struct FlyOptions {
    TerrainArgs terrain;
    LookArgs looks;
    std::string scene, method = "mesh", record, replay, out, screenshot, video, size = "1280x720";
    long long frames = 0;
    int cache_mib = MethodSettings::kDefaultCacheMib;
    std::vector<std::string> presses;
    double fov = 60;
    bool no_hud = false, hidden = false;
    bool save_cameras = false; // --replay: a camera file beside each frame
};

void parse_size(const std::string& s, int& w, int& h) {
    char x = 0;
    char extra = 0;
    if (std::sscanf(s.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w < 16 || h < 16 || w > 16384 ||
        h > 16384)
        throw Error("--size", "'" + s + "' is not WxH with sides 16..16384");
}

void print_stats(const std::vector<gl::FlightMethodStats>& stats) {
    std::printf("method,frames,fps,triangles_per_frame,object_triangles_per_frame,ms_per_step\n");
    for (const gl::FlightMethodStats& s : stats)
        std::printf("%s,%lld,%.2f,%lld,%lld,%s\n", s.method.c_str(), s.frames, s.fps(),
                    s.frames ? s.triangles / s.frames : 0, s.frames ? s.object_triangles / s.frames : 0,
                    s.steps_text().c_str());
}

std::string frame_name(long long i) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "frame_%05lld.png", i);
    return buf;
}

// Encodes DIR/frame_%05d.png into `video` with `ffmpeg`, run without a shell
// (io/Subprocess.h), through a temporary name so a failed encode leaves
// nothing behind. ffmpeg reads '%' in the input name as its frame-number
// pattern ("%%" is a literal '%') and "PROTOCOL:" at the start of a name as a
// protocol, so the folder's '%' are doubled and both names say "file:".
void encode_video(const std::string& ffmpeg, const std::string& dir, const std::string& video) {
    std::string pattern;
    for (char c : dir) pattern += c == '%' ? std::string("%%") : std::string(1, c);
    pattern += "/frame_%05d.png";
    write_atomically(video, [&](const std::string& temp) {
        const ProcessResult r = run_program(ffmpeg,
                                            {"-nostdin", "-loglevel", "error", "-y", "-framerate", "60", "-i",
                                             "file:" + pattern, "-pix_fmt", "yuv420p", "-vf",
                                             "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-f", "mp4", "file:" + temp},
                                            video);
        if (!r.succeeded()) throw Error(video, "ffmpeg could not encode the frames (" + r.describe() + ")");
    });
}

void run_replay(const FlyOptions& o, const DataSet& data, const MethodContext& methods) {
    namespace fs = std::filesystem;
    if (o.out.empty()) throw Error("--out", "--replay needs --out DIR for the frames");
    int w = 0, h = 0;
    parse_size(o.size, w, h);
    // Everything that can be checked is checked before the first frame: the
    // record (every line, cameras included), the folders of the other
    // outputs and ffmpeg; a bad input then leaves no folder and no frame.
    const FlightRecord record = read_flight_record(o.replay);
    std::string ffmpeg;
    if (!o.video.empty()) {
        check_output_folder(o.video);
        const std::optional<std::string> found = find_program("ffmpeg");
        if (!found) throw Error("--video", "ffmpeg is not installed (not found on PATH)");
        ffmpeg = *found;
    }
    if (!o.record.empty()) check_output_folder(o.record);
    std::error_code ec;
    const bool created = fs::create_directories(o.out, ec);
    if (ec) throw Error(o.out, "cannot create the folder: " + errno_text(ec.value()));

    // What this run wrote, removed again if it fails: a replay either
    // completes or leaves nothing of itself.
    std::vector<std::string> written;
    gl::FlightMethodStats stats;
    try {
        long long index = 0;
        FlightRecord rendered;
        stats = gl::render_flight_record(
            data, record, o.frames, *find_terrain_method(o.method), methods, w, h, o.fov,
            [&](const ColorImage& image, long long) {
                const std::string path = (fs::path(o.out) / frame_name(index)).string();
                write_png(path, image);
                written.push_back(path);
                if (o.save_cameras) {
                    // The frame's camera as a camera file (render --camera
                    // draws the same view, without the hovercraft).
                    const FlightFrame& f = record.frames[std::size_t(index)];
                    Camera cam = flight_camera(data.terrain, o.fov);
                    cam.width = w;
                    cam.height = h;
                    cam.eye = f.eye;
                    cam.heading = f.heading;
                    cam.pitch = f.pitch;
                    const std::string json = fs::path(path).replace_extension(".json").string();
                    write_camera_file(json, cam, camera_map_of(cam, data));
                    written.push_back(json);
                }
                rendered.frames.push_back(record.frames[std::size_t(index)]);
                ++index;
            });
        if (!o.video.empty()) {
            encode_video(ffmpeg, o.out, o.video);
            written.push_back(o.video);
        }
        // --record with --replay writes the camera path that was rendered.
        if (!o.record.empty()) write_flight_record(o.record, rendered);
    } catch (...) {
        for (const std::string& path : written) fs::remove(path, ec);
        if (created) fs::remove(o.out, ec); // only if empty: never someone else's files
        throw;
    }
    print_stats({stats});
}

void run_fly(const FlyOptions& o) {
    if (o.frames < 0) throw Error("--frames", "must be 0 or more");
    if (!o.replay.empty() && o.frames == 0 && o.out.empty()) throw Error("--replay", "needs --out DIR");
    if (o.replay.empty() && (!o.out.empty() || !o.video.empty()))
        throw Error("--out", "--out and --video render a recorded flight: add --replay path.csv");
    if (!o.screenshot.empty() && o.frames == 0)
        throw Error("--screenshot", "needs --frames N (interactively, P saves a screenshot)");
    if (!find_terrain_method(o.method))
        throw Error("--method", "'" + o.method + "' is not a terrain method (known: " + terrain_method_names(", ") + ")");
    std::vector<ScriptedPress> presses;
    for (const std::string& p : o.presses) presses.push_back(parse_press(p));

    MethodSettings settings;
    settings.cache_bytes = tile_cache_bytes(o.cache_mib);
    DataSet data = load_terrain_lazily(o.terrain);
    data.environment = with_looks(o.looks, data.environment, data.terrain);
    if (!o.scene.empty()) data.scene.append(load_scene(o.scene));
    MethodContext methods{data.terrain, settings, {}};
    if (is_tile_directory(o.terrain.terrain))
        methods.tiles = [dir = o.terrain.terrain, bound = settings.cache_bytes] {
            return tile_directory_tiles(dir, bound);
        };
    if (!o.replay.empty()) return run_replay(o, data, methods);
    // `--lighting baked` is where the `1` key starts.
    const bool lit = !lighting_is_baked(data.environment);
    data.environment.baked = false;

    gl::FlightWindowOptions wo;
    parse_size(o.size, wo.width, wo.height);
    wo.method = o.method;
    wo.session.fov = o.fov;
    wo.session.frames = o.frames;
    wo.session.script = KeyScript(std::move(presses));
    wo.session.hud = !o.no_hud;
    wo.session.lighting = lit;
    wo.session.start = data.start;
    wo.visible = !o.hidden;
    const std::filesystem::path shot_base = o.screenshot.empty() ? std::filesystem::path("overflight.png")
                                                                 : std::filesystem::path(o.screenshot);
    const gl::ScreenshotSink save = [&](const ColorImage& image, const Camera& camera, int index) {
        if (index < 0) {
            if (!o.screenshot.empty()) write_png(o.screenshot, image);
            return;
        }
        // P: name-NNN.png beside --screenshot, or overflight-NNN.png here,
        char suffix[16];
        std::snprintf(suffix, sizeof suffix, "-%03d", index);
        std::filesystem::path p = shot_base;
        p.replace_filename(shot_base.stem().string() + suffix + ".png");
        write_png(p.string(), image);
        // and the frame's camera beside it, for render --camera.
        const std::string json = std::filesystem::path(p).replace_extension(".json").string();
        write_camera_file(json, camera, camera_map_of(camera, data));
        std::fprintf(stderr, "overflight: saved %s and %s\n", p.string().c_str(), json.c_str());
    };
    const gl::FlightResult result = gl::run_flight_window(data, wo, methods, save);
    if (!o.record.empty()) write_flight_record(o.record, result.record);
    print_stats(result.per_method);
}

} // namespace

void add_fly_command(CLI::App& app) {
    auto o = std::make_shared<FlyOptions>();
    CLI::App* sub = app.add_subcommand("fly", "Fly the hovercraft over a terrain in a window");
    add_terrain_options(*sub, o->terrain);
    add_max_direct_size_option(*sub, o->terrain);
    sub->add_option("--scene", o->scene, "Scene TOML with objects to add");
    add_look_options(*sub, o->looks, " (f cycles: off, GL_EXP fog, atmosphere)");
    sub->add_option("--method", o->method,
                    "Terrain method shown first (" + terrain_method_names() + "; Tab cycles " +
                        terrain_method_names(" -> ", true) + "); with --replay, the one that renders")
        ->capture_default_str();
    sub->add_option("--record", o->record, "Write the flight (per-frame camera and keys) as CSV");
    sub->add_option("--replay", o->replay, "Render a recorded flight headless instead of flying");
    sub->add_option("--out", o->out, "Folder for the replayed frames (frame_00000.png, ...)");
    sub->add_option("--video", o->video, "With --replay: also encode the frames to this MP4 (needs ffmpeg)");
    sub->add_option("--frames", o->frames, "Unattended: run exactly N frames (replay: at most N)")
        ->transform(decimal<long long>());
    sub->add_option("--press", o->presses, "KEY:FROM-TO holds KEY during frames FROM..TO-1 (keys: accelerate, brake, "
                                           "left, right, fog, lighting, wireframe, detail-up, detail-down, "
                                           "next-method, screenshot, hud, quit, shadows, sun-later, sun-earlier, water)")
        ->take_all();
    sub->add_option("--screenshot", o->screenshot, "With --frames: save the last frame as PNG");
    sub->add_option("--size", o->size, "Window / replay size WxH");
    sub->add_option("--fov", o->fov, "Horizontal field of view, degrees");
    sub->add_option("--cache-mib", o->cache_mib,
                    "quadtree over a tile directory: memory bound of the tile cache in MiB")
        ->transform(decimal<int>())
        ->capture_default_str();
    sub->add_flag("--save-cameras", o->save_cameras,
                  "With --replay: also write each frame's camera file (frame_00000.json, read by render --camera)");
    sub->add_flag("--no-hud", o->no_hud, "Start with the HUD hidden (H toggles)");
    sub->add_flag("--hidden", o->hidden, "Do not show the window (unattended runs)");
    sub->callback([o, sub] {
        reject_empty_names(*sub, {"--scene", "--record", "--replay", "--out", "--video", "--screenshot"});
        run_fly(*o);
    });
}

} // namespace overflight::app
