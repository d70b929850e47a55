#pragma once
// The terrain methods of `overflight render --method` and `overflight bench`
// (DESIGN sec. 6), as one table. Each entry makes a ViewRenderer that turns a
// camera into a color image and an OpenGL window-depth image (1.0 = sky) plus
// its own statistics. The CPU methods (ray caster and its references) need no
// GL; the others share one headless EGL context created on first use.
//
//   voxel          Floating Horizon ray cast alone (Szenberg sec. 4-6)
//   voxel+present  ray cast + color upload + present (Table 1, without objects)
//   voxel+objects  ray cast + color and depth upload + Z-buffered objects (Table 1, Fig. 5)
//   voxel-literal  Algorithm 1 as printed, single-threaded (reference)
//   raymarch       brute-force per-pixel ray marcher (reference)
//   mesh           full-resolution triangulation (the Z-buffer baseline)
//   points, top-faces, front-faces, segments, blocks   Table 2 representations
//   roam           split-only ROAM, --triangles N (seed 003 sec. 5)
//   quadtree       Roettger quadtree over overlapping tiles, --error PX (seed 001)
//
// Every GL-drawn method draws the objects (data set map + --scene); `render
// --method voxel` composites them too (cmd_render picks voxel+objects when
// there are objects), while `bench` keeps `voxel` the ray cast alone as in
// Table 1.
#include "GlMethods.h"
#include "core/Camera.h"
#include "core/DataSet.h"
#include "core/Image.h"
#include "raycast/RaycastOptions.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace overflight::app {

// The renderer options beyond the camera.
struct RenderSettings {
    std::string surface = "blocks";    // --surface (voxel)
    std::string tilt_method = "exact"; // --tilt-method (voxel, tilt projection)
    bool lod = false;                  // --lod (voxel)
    double near_step = RaycastOptions{}.near_step_pixels; // --near-step (voxel)
    int triangles = 65536;             // --triangles (roam)
    double error_px = 1.0;             // --error (quadtree)
    int cache_mib = 1024;              // --cache-mib (quadtree): memory bound of loaded tiles
    std::string scene;                 // --scene FILE

    RaycastOptions raycast() const; // throws Error("--surface" | "--tilt-method" | "--near-step", ...)
    // Throws Error("--triangles" | "--error" | "--cache-mib", ...) for values outside their range.
    void validate() const;
};
void add_render_settings(CLI::App& cmd, RenderSettings& settings);

// What the methods of one command share: the data set, the settings, the
// --scene objects, the tile directory TERRAIN names (if it is one), and one
// GL context created on first use.
class RenderSession {
public:
    // Loads settings.scene (Error(path, ...) for a bad scene file).
    RenderSession(const DataSet& data, const RenderSettings& settings, std::string tile_dir = {});
    ~RenderSession();

    const DataSet& data() const { return data_; }
    const RenderSettings& settings() const { return settings_; }
    const Scene& extra_scene() const { return extra_scene_; }
    bool has_objects() const { return !data_.scene.empty() || !extra_scene_.empty(); }
    const std::string& tile_dir() const { return tile_dir_; }
    // The headless GL renderer with the data set's and --scene's objects
    // (Error("opengl", ...) when no context can be made).
    GlMethods& gl();

    bool want_depth = true; // GL methods read the depth back (render --depth, accuracy in bench)

private:
    const DataSet& data_;
    RenderSettings settings_;
    Scene extra_scene_;
    std::string tile_dir_;
    std::unique_ptr<GlMethods> gl_;
};

class ViewRenderer {
public:
    virtual ~ViewRenderer() = default;
    // Renders `camera` into color and window depth and sets `stats` to the
    // method's counts and its per-step times under "ms" (milliseconds).
    virtual void render(const Camera& camera, ColorImage& color, DepthImage& depth, nlohmann::json& stats) = 0;
    // Measurements `bench` adds to this method's row beyond frame times
    // (ROAM: tessellation rate and the error-versus-budget curve).
    virtual void bench_extras(const Camera& /*camera*/, nlohmann::json& /*run*/) {}
};

struct RenderMethod {
    std::string name;
    std::string help;
    bool bench_by_default = false;
    std::function<std::unique_ptr<ViewRenderer>(RenderSession&)> create; // throws Error
};
const std::vector<RenderMethod>& render_methods();
// Throws Error(option, "unknown method ...") listing the known ones.
const RenderMethod& find_render_method(const std::string& name, const std::string& option = "--method");
std::string render_method_names(); // "voxel|voxel+present|..."

} // namespace overflight::app
