#pragma once
// The GL side of the render methods (RenderMethods.h): one headless context
// with the objects uploaded, drawing a terrain three ways -- a resident GL
// representation (mesh and Szenberg's Table 2 baselines), a per-frame mesh
// from a LOD method (ROAM, quadtree), or Szenberg's composite of a ray-cast
// image (sec. 5, Fig. 5) -- and reporting each step's time under stats["ms"].
// Thin: the work is in src/gl.
//
// Based on: Szenberg et al. 1997 sec. 5 and 7 (Tables 1 and 2).
#include "core/Camera.h"
#include "core/DataSet.h"
#include "core/Image.h"
#include "core/MeshArrays.h"
#include "gl/HeadlessRenderer.h"

#include <nlohmann/json.hpp>

#include <memory>

namespace overflight::app {

class GlMethods {
public:
    // Creates the context (Error("opengl", ...)) and uploads the objects of
    // data.scene and `extra_scene` (Error(path, ...) for a bad model file).
    GlMethods(const DataSet& data, const Scene& extra_scene);

    // `depth` may be null when the caller does not need it (no read-back).
    // Steps: terrain, objects, present[, depth_readback].
    void render_terrain(gl::TerrainMethod method, const Camera& camera, ColorImage& color, DepthImage* depth,
                        nlohmann::json& stats);
    // Steps as render_terrain; "terrain" includes uploading `mesh`.
    void render_mesh(const MeshArrays& mesh, const Camera& camera, ColorImage& color, DepthImage* depth,
                     nlohmann::json& stats);
    // Steps: color_upload[, depth_upload, objects], present[, depth_readback].
    void composite(const ColorImage& raycast_color, const DepthImage& raycast_depth, const Camera& camera,
                   bool with_objects, ColorImage& color, DepthImage* depth, nlohmann::json& stats);

private:
    void add_stats(const gl::FrameTimings& t, nlohmann::json& stats) const;
    std::unique_ptr<gl::HeadlessRenderer> gl_;
};

} // namespace overflight::app
