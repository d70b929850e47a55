#pragma once
// Renders one frame of any GL method into core images with a per-step time
// breakdown: the driver behind `overflight render --method M` and `overflight
// bench` (Szenberg Table 1 steps for the composite, Table 2 for the Z-buffer
// baselines). Owns a headless EGL context, the Renderer and an offscreen
// target of the camera's size (recreated when the size changes).
//
// Steps are timed on the CPU clock between glFinish() calls, so each step's
// time includes the GL work it queued (as the paper's wall-clock timings do).
//
// Based on: Szenberg et al. 1997 sec. 5 (Fig. 5 strategy) and sec. 7 (Tables 1, 2).
#include "core/DataSet.h"
#include "gl/GlContext.h"
#include "gl/Renderer.h"

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace overflight::gl {

struct FrameTimings {
    std::vector<std::pair<std::string, double>> steps_ms; // in execution order
    double total_ms = 0;
    long long terrain_primitives = 0;
    long long object_triangles = 0;
    int chunks_total = 0, chunks_drawn = 0;
    double step(const std::string& name) const; // 0 when absent
};

class HeadlessRenderer {
public:
    // Creates the context (Error("opengl", ...) if impossible) and uploads the
    // objects of `scene` (Error(path, ...) for a bad model file).
    HeadlessRenderer(const DataSet& data, const Scene& scene);

    // Draws terrain method m, then the objects, and reads back the color
    // (and the depth when `depth` is not null). Steps: terrain, objects, present[, depth_readback].
    void render(TerrainMethod m, const Camera& camera, ColorImage& color, DepthImage* depth,
                FrameTimings* timings = nullptr);
    // The same for a per-frame mesh of a LOD method (ROAM, quadtree): its
    // upload is part of the "terrain" step, as it is every frame.
    void render_mesh(const MeshArrays& mesh, const Camera& camera, ColorImage& color, DepthImage* depth,
                     FrameTimings* timings = nullptr);

    // Szenberg's composite: loads a ray-cast color image (and, with objects,
    // its window depth) into the target, draws the objects with the depth
    // test, and reads back. Steps: color_upload[, depth_upload, objects], present[, depth_readback].
    // Without objects the depth upload is skipped (voxel+present); a requested
    // depth output is then the ray caster's own depth.
    void composite(const ColorImage& raycast_color, const DepthImage& raycast_depth, const Camera& camera,
                   bool with_objects, ColorImage& color, DepthImage* depth, FrameTimings* timings = nullptr);

    std::string renderer_name() const { return Context::renderer(); }
    Renderer& renderer() { return *renderer_; }

private:
    RenderTarget& target_for(const Camera& camera);
    // begin_frame, draw_terrain() (one "terrain" step), objects, read-back.
    void draw_frame(const Camera& camera, const std::function<TerrainDrawStats()>& draw_terrain, ColorImage& color,
                    DepthImage* depth, FrameTimings* timings);
    std::unique_ptr<HeadlessContext> context_; // first member: destroyed last
    std::unique_ptr<Renderer> renderer_;
    std::unique_ptr<RenderTarget> target_;
};

} // namespace overflight::gl
