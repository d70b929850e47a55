// Based on: Szenberg et al. 1997 sec. 5 and 7 (Tables 1 and 2); DESIGN sec. 6.
#include "GlMethods.h"

#include "core/Error.h"

namespace overflight::app {

namespace {
bool is_voxel(const std::string& m) { return m == "voxel" || m == "voxel+objects" || m == "voxel+present"; }
} // namespace

bool is_gl_method(const std::string& method) {
    return is_voxel(method) || gl::parse_terrain_method(method).has_value();
}

GlMethods::GlMethods(const DataSet& data, const Scene* extra_scene) {
    Scene scene = data.scene;
    if (extra_scene) scene.append(*extra_scene);
    gl_ = std::make_unique<gl::HeadlessRenderer>(data, scene);
}

void GlMethods::render(const std::string& method, const Camera& camera, const GlRenderOptions& options,
                       ColorImage& color, DepthImage& depth, nlohmann::json* stats) {
    gl::FrameTimings t;
    DepthImage* want_depth = options.want_depth ? &depth : nullptr;
    if (is_voxel(method)) {
        if (!options.raycast_color || !options.raycast_depth)
            throw Error("--method", method + " needs the ray caster's color and depth");
        gl_->composite(*options.raycast_color, *options.raycast_depth, camera, method != "voxel+present", color,
                       want_depth, stats ? &t : nullptr);
    } else if (const auto m = gl::parse_terrain_method(method)) {
        gl_->render(*m, camera, color, want_depth, stats ? &t : nullptr);
    } else {
        throw Error("--method", "unknown method '" + method + "'");
    }
    if (!stats) return;
    (*stats)["gl_renderer"] = gl_->renderer_name();
    for (const auto& [name, ms] : t.steps_ms) (*stats)["ms_" + name] = ms;
    (*stats)["ms_gl_total"] = t.total_ms;
    (*stats)["triangles"] = t.terrain_primitives;
    (*stats)["object_triangles"] = t.object_triangles;
    if (method == "mesh") {
        (*stats)["chunks_drawn"] = t.chunks_drawn;
        (*stats)["chunks_total"] = t.chunks_total;
    }
}

void render_gl(const std::string& method, const DataSet& data, const Camera& camera, const GlRenderOptions& options,
               ColorImage& color, DepthImage& depth, nlohmann::json* stats) {
    GlMethods gl(data, options.extra_scene);
    gl.render(method, camera, options, color, depth, stats);
}

} // namespace overflight::app
