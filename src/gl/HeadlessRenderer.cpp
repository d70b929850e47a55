// Based on: Szenberg et al. 1997 sec. 5 and 7 (Tables 1 and 2).
#include "gl/HeadlessRenderer.h"

#include <chrono>

namespace overflight::gl {

namespace {

// Accumulates step times between glFinish() calls.
class StepClock {
public:
    explicit StepClock(FrameTimings* t) : t_(t) {
        if (t_) {
            glFinish();
            t_->steps_ms.clear();
            start_ = last_ = std::chrono::steady_clock::now();
        }
    }
    void lap(const char* name) {
        if (!t_) return;
        glFinish();
        const auto now = std::chrono::steady_clock::now();
        t_->steps_ms.emplace_back(name, std::chrono::duration<double, std::milli>(now - last_).count());
        last_ = now;
        t_->total_ms = std::chrono::duration<double, std::milli>(now - start_).count();
    }

private:
    FrameTimings* t_;
    std::chrono::steady_clock::time_point start_, last_;
};

} // namespace

double FrameTimings::step(const std::string& name) const {
    for (const auto& [n, ms] : steps_ms)
        if (n == name) return ms;
    return 0;
}

HeadlessRenderer::HeadlessRenderer(const DataSet& data, const Scene& scene)
    : context_(std::make_unique<HeadlessContext>()), renderer_(std::make_unique<Renderer>(data)) {
    renderer_->set_scene(scene);
}

RenderTarget& HeadlessRenderer::target_for(const Camera& camera) {
    camera.validate();
    context_->make_current();
    if (!target_ || target_->width() != camera.width || target_->height() != camera.height)
        target_ = std::make_unique<RenderTarget>(camera.width, camera.height);
    return *target_;
}

void HeadlessRenderer::render(TerrainMethod m, const Camera& camera, ColorImage& color, DepthImage* depth,
                              FrameTimings* timings) {
    target_for(camera);
    renderer_->prepare(m); // uploads are not part of a frame
    draw_frame(camera, [&] { return renderer_->draw_terrain(m); }, color, depth, timings);
}

void HeadlessRenderer::render_mesh(const MeshArrays& mesh, const Camera& camera, ColorImage& color, DepthImage* depth,
                                   FrameTimings* timings) {
    draw_frame(camera, [&] { return TerrainDrawStats{renderer_->draw_mesh(mesh)}; }, color, depth, timings);
}

void HeadlessRenderer::draw_frame(const Camera& camera, const std::function<TerrainDrawStats()>& draw_terrain,
                                  ColorImage& color, DepthImage* depth, FrameTimings* timings) {
    RenderTarget& target = target_for(camera);
    StepClock clock(timings);
    renderer_->begin_frame(camera, target);
    const TerrainDrawStats s = draw_terrain();
    clock.lap("terrain");
    const long long objects = renderer_->draw_objects();
    clock.lap("objects");
    target.read_color(color);
    clock.lap("present");
    if (depth) {
        target.read_depth(*depth);
        clock.lap("depth_readback");
    }
    if (timings) {
        timings->terrain_primitives = s.primitives;
        timings->object_triangles = objects;
        timings->chunks_total = s.chunks_total;
        timings->chunks_drawn = s.chunks_drawn;
    }
}

void HeadlessRenderer::composite(const ColorImage& raycast_color, const DepthImage& raycast_depth,
                                 const Camera& camera, bool with_objects, ColorImage& color, DepthImage* depth,
                                 FrameTimings* timings) {
    RenderTarget& target = target_for(camera);
    StepClock clock(timings);
    renderer_->begin_composite(camera, target);
    target.upload_color(raycast_color);
    clock.lap("color_upload");
    long long objects = 0;
    if (with_objects) {
        // Objects only test depth inside their screen rectangle; the whole
        // buffer is loaded only when the caller reads the final depth back.
        target.upload_depth(raycast_depth, depth ? std::nullopt
                                                 : std::optional<PixelRect>(renderer_->objects().screen_rect(camera)));
        clock.lap("depth_upload");
        objects = renderer_->draw_objects();
        clock.lap("objects");
    }
    target.read_color(color);
    clock.lap("present");
    if (depth) {
        if (with_objects) target.read_depth(*depth);
        else *depth = raycast_depth;
        clock.lap("depth_readback");
    }
    if (timings) {
        timings->terrain_primitives = 0;
        timings->object_triangles = objects;
    }
}

} // namespace overflight::gl
