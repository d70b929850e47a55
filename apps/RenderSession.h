#pragma once
// What `render` and `bench` share: the method options of the command line,
// the data set with its objects (the data set's and --scene's), and one
// headless GL renderer created when a method first needs it. Any row of the
// method table (methods/MethodTable.h) is rendered the same way: the method
// produces its output for the camera, and unless it is an image method run
// alone (Composite::None), the compositor draws it with the objects and reads
// the picture back.
#include "core/Camera.h"
#include "core/DataSet.h"
#include "core/Image.h"
#include "gl/HeadlessRenderer.h"
#include "methods/MethodTable.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <memory>
#include <string>

namespace overflight::app {

// The method knobs as given on the command line; defaults from MethodSettings.
struct MethodOptions {
    std::string surface = "blocks";    // --surface (voxel)
    std::string tilt_method = "exact"; // --tilt-method (voxel, tilt projection)
    bool lod = false;                  // --lod (voxel)
    double near_step = RaycastOptions{}.near_step_pixels; // --near-step (voxel)
    int triangles = MethodSettings::kDefaultTriangles;    // --triangles (roam)
    double error_px = MethodSettings::kDefaultErrorPx;    // --error (quadtree)
    int cache_mib = MethodSettings::kDefaultCacheMib;      // --cache-mib (quadtree)
    std::string scene;                 // --scene FILE

    // Validated settings; throws Error in the methods' terms (OptionErrors.h).
    MethodSettings settings() const;
};
void add_method_options(CLI::App& cmd, MethodOptions& options);

// The tiles of a directory written by `overflight tile`, read lazily within
// `memory_bound` bytes (throws as read_tile_index).
std::unique_ptr<TileSet> tile_directory_tiles(const std::string& tile_dir, std::size_t memory_bound);

// One rendered view: the images (the method's own for an image method run
// alone, else the read-back), what the method and the GL steps cost.
struct RenderedView {
    const ColorImage* color = nullptr;
    const DepthImage* depth = nullptr; // null when not asked for
    MethodOutput output; // what the method produced (valid until its next produce)
    MethodStats method;
    gl::FrameTimings gl;
    bool composited = false; // drawn by the GL compositor
};

class RenderSession {
public:
    // Loads options.scene (Error(path, ...) for a bad scene file). `tile_dir`:
    // TERRAIN when it is a tile directory (the quadtree reads it lazily).
    RenderSession(const DataSet& data, const MethodOptions& options, std::string tile_dir = {});
    ~RenderSession();

    const DataSet& data() const { return data_; }
    // The environment the views are rendered in (the data set's unless set).
    const Environment& environment() const { return environment_; }
    void set_environment(const Environment& env) { environment_ = env; }
    const MethodSettings& settings() const { return settings_; }
    bool has_objects() const { return !scene_.empty(); }
    const std::string& tile_dir() const { return tile_dir_; }

    // Builds the method of `row`; throws what the method's factory throws.
    std::unique_ptr<TerrainMethod> create(const MethodEntry& row);
    // Renders `camera` with `method` as `row` composites it, reading the depth
    // back when `want_depth`. The view's images live until the next call.
    void render(const MethodEntry& row, TerrainMethod& method, const Camera& camera, bool want_depth,
                RenderedView& view);
    // Hands the images of `view`, the last render() with `method`, to the
    // caller without copying them where it can: swaps their buffers with
    // `color` and, when the view read the depth back and `depth` is not null,
    // with `*depth` (a read-back into the session's images, or the method's
    // own images if it lends them, TerrainMethod::swap_images); else copies.
    // What the session or the method receives may hold anything of any size:
    // the next render() draws over it. `view`'s image pointers are invalid
    // afterwards.
    void take_images(TerrainMethod& method, RenderedView& view, ColorImage& color, DepthImage* depth);
    // Makes the GL renderer's context (if one was created) current on the
    // calling thread, as the session's destruction needs when another thread rendered last.
    void make_gl_current() {
        if (gl_) gl_->make_current();
    }
    // How many horizon sweeps the session's renderers have run between them.
    long long sun_sweeps() const { return sun_shadow_->sweeps(); }

private:
    void make_gl(); // the headless GL renderer, created once, sharing the sun's sweep

    const DataSet& data_;
    Environment environment_;
    MethodSettings settings_;
    Scene scene_;
    std::string tile_dir_;
    // One horizon sweep per sun direction for the methods' lighting, their
    // water and the compositor's shadow ceiling, as in `fly`.
    std::unique_ptr<SharedSunShadow> sun_shadow_;
    MethodContext context_;
    std::unique_ptr<gl::HeadlessRenderer> gl_;
    ColorImage color_;
    DepthImage depth_;
};

// --stats of one view: the method's figures, its steps under "ms" (CPU and
// GL, milliseconds) and, when composited, the GL renderer's name.
nlohmann::json view_stats_json(const MethodSettings& settings, const Camera& camera,
                               const RenderedView& view);

} // namespace overflight::app
