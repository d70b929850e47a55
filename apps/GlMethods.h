#pragma once
// The GL side of `overflight render` and `overflight bench` (DESIGN sec. 6):
// terrain methods mesh, points, top-faces, front-faces, segments, blocks drawn
// by OpenGL with the objects, and Szenberg's composite of the ray-cast image
// (voxel+objects, voxel+present). Thin: the work is in src/gl.
#include "core/Camera.h"
#include "core/DataSet.h"
#include "core/Image.h"
#include "gl/HeadlessRenderer.h"

#include <nlohmann/json.hpp>

#include <memory>
#include <string>

namespace overflight::app {

struct GlRenderOptions {
    const Scene* extra_scene = nullptr;          // --scene objects, drawn with data.scene
    const ColorImage* raycast_color = nullptr;   // voxel methods: the ray caster's output
    const DepthImage* raycast_depth = nullptr;
    bool want_depth = false;                     // fill `depth` (--depth)
};

// True for the method names render_gl accepts: mesh, points, top-faces,
// front-faces, segments, blocks, voxel (= voxel+objects), voxel+objects, voxel+present.
bool is_gl_method(const std::string& method);

// Keeps the headless context and the uploaded terrain between frames (bench).
class GlMethods {
public:
    // Creates the context and uploads the objects; throws Error.
    GlMethods(const DataSet& data, const Scene* extra_scene = nullptr);
    // Renders one frame. For voxel methods options.raycast_color/depth must be
    // set (Error("--method", ...) otherwise). Adds to *stats (when given):
    // "gl_renderer", per-step "ms_<step>", "ms_gl_total", "triangles",
    // "object_triangles", "chunks_drawn", "chunks_total".
    void render(const std::string& method, const Camera& camera, const GlRenderOptions& options, ColorImage& color,
                DepthImage& depth, nlohmann::json* stats);

private:
    std::unique_ptr<gl::HeadlessRenderer> gl_;
};

// One-shot convenience: a GlMethods for this call only.
void render_gl(const std::string& method, const DataSet& data, const Camera& camera, const GlRenderOptions& options,
               ColorImage& color, DepthImage& depth, nlohmann::json* stats);

} // namespace overflight::app
