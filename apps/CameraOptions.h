#pragma once
// The camera options of DESIGN sec. 6 shared by `render` and `bench`, the
// ray caster options, and the table of rendering methods both commands use.
//
//   --eye X,Y,Z | --at X,Z [--agl M]   where the eye is (world units)
//   --heading D --pitch D              DESIGN sec. 1 convention, pitch > 0 looks up
//   --projection shear|tilt --fov D --size WxH --near N --far F
//
// Without --eye/--at the camera is the data set's overview (see
// default_camera); without --heading an eye given by the user looks at the
// terrain's centre. Bad values throw overflight::Error naming the option.
#include "core/Camera.h"
#include "core/DataSet.h"
#include "core/Image.h"
#include "raycast/RaycastOptions.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace overflight::app {

struct CameraArgs {
    std::string eye;        // "X,Y,Z"
    std::string at;         // "X,Z"
    std::optional<double> agl, heading, pitch, fov, near, far;
    std::string projection = "shear";
    std::string size;       // "WxH"
};

// Adds the options above to `cmd`; `args` must outlive the parse.
void add_camera_options(CLI::App& cmd, CameraArgs& args);

// The overview a user gets without camera options: from the vehicle's start
// (behind it along its heading, at 80 % of the relief) when the data set has one,
// else above the terrain's south edge looking north across it; pitched down
// 12 degrees, far enough to see the whole terrain.
Camera default_camera(const DataSet& data, int width, int height);

// The camera of `args` for `data` (default size when --size is absent),
// validated. Throws Error("--fov", ...), Error("--size", ...), Error("--eye", ...) etc.
Camera make_camera(const CameraArgs& args, const DataSet& data, int default_width, int default_height);

// "WxH" with 1 <= W, H <= 16384; throws Error(option, ...).
void parse_size(const std::string& text, const std::string& option, int& width, int& height);

// Options of the terrain renderers (--surface, --lod, --tilt-method, --near-step).
struct RenderSettings {
    std::string surface = "blocks";
    std::string tilt_method = "exact";
    bool lod = false;
    double near_step = RaycastOptions{}.near_step_pixels;
    RaycastOptions raycast() const; // throws Error("--surface" | "--tilt-method", ...)
};
void add_render_settings(CLI::App& cmd, RenderSettings& settings);

// One way of drawing a terrain view. Created once per command (so per-terrain
// precomputation and buffers are reused over the frames of `bench`).
class ViewRenderer {
public:
    virtual ~ViewRenderer() = default;
    // Renders `camera` into color and window depth (1.0 = sky) and fills
    // `stats` with the method's own timings and counts.
    virtual void render(const Camera& camera, ColorImage& color, DepthImage& depth, nlohmann::json& stats) = 0;
};

// The rendering methods of `render --method` and `bench`: a name, a line of
// help, whether `bench` runs it by default, and a factory. New renderers (the
// GL ones) are one more entry in render_methods().
struct RenderMethod {
    std::string name;
    std::string help;
    bool bench_by_default = false;
    std::function<std::unique_ptr<ViewRenderer>(const DataSet&, const RenderSettings&)> create;
};
const std::vector<RenderMethod>& render_methods();
// Throws Error(option, "unknown method ...") listing the known ones.
const RenderMethod& find_render_method(const std::string& name, const std::string& option = "--method");
std::string render_method_names(); // "voxel|voxel-literal|raymarch"

} // namespace overflight::app
