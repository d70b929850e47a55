// Based on: Szenberg et al. 1997 sec. 5 and 7 (Tables 1 and 2).
#include "GlMethods.h"

namespace overflight::app {

namespace {
Scene merged(const DataSet& data, const Scene& extra) {
    Scene scene = data.scene;
    scene.append(extra);
    return scene;
}
} // namespace

GlMethods::GlMethods(const DataSet& data, const Scene& extra_scene)
    : gl_(std::make_unique<gl::HeadlessRenderer>(data, merged(data, extra_scene))) {}

void GlMethods::add_stats(const gl::FrameTimings& t, nlohmann::json& stats) const {
    stats["gl_renderer"] = gl_->renderer_name();
    for (const auto& [name, ms] : t.steps_ms) stats["ms"][name] = ms;
    stats["ms"]["gl_total"] = t.total_ms;
    stats["object_triangles"] = t.object_triangles;
}

void GlMethods::render_terrain(gl::TerrainMethod method, const Camera& camera, ColorImage& color, DepthImage* depth,
                               nlohmann::json& stats) {
    gl::FrameTimings t;
    gl_->render(method, camera, color, depth, &t);
    add_stats(t, stats);
    stats["triangles"] = t.terrain_primitives;
    if (method == gl::TerrainMethod::Mesh) {
        stats["chunks_drawn"] = t.chunks_drawn;
        stats["chunks_total"] = t.chunks_total;
    }
}

void GlMethods::render_mesh(const MeshArrays& mesh, const Camera& camera, ColorImage& color, DepthImage* depth,
                            nlohmann::json& stats) {
    gl::FrameTimings t;
    gl_->render_mesh(mesh, camera, color, depth, &t);
    add_stats(t, stats);
}

void GlMethods::composite(const ColorImage& raycast_color, const DepthImage& raycast_depth, const Camera& camera,
                          bool with_objects, ColorImage& color, DepthImage* depth, nlohmann::json& stats) {
    gl::FrameTimings t;
    gl_->composite(raycast_color, raycast_depth, camera, with_objects, color, depth, &t);
    add_stats(t, stats);
}

} // namespace overflight::app
