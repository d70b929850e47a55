#pragma once
// Renders frames of any terrain method into core images without a window: a
// headless EGL context, the Compositor and an offscreen target of the
// camera's size (recreated when the size changes), with each step timed on the
// CPU clock between glFinish() calls (FinishStepTimer). The GL side of
// `overflight render`, `bench` and `fly --replay`.
//
// Based on: Szenberg et al. 1997 sec. 5 (Fig. 5 strategy) and sec. 7 (Tables 1, 2).
#include "gl/Compositor.h"
#include "gl/FinishStepTimer.h"
#include "gl/GlContext.h"

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace overflight::gl {

struct FrameTimings {
    std::vector<std::pair<const char*, double>> steps_ms; // GL steps in execution order
    CompositeCounts counts;
    double step(const char* name) const; // 0 when absent
    double total_ms() const;
};

class HeadlessRenderer {
public:
    // Creates the context (Error("opengl", ...) if impossible) and uploads the
    // objects of `scene` on `terrain` (which must outlive the renderer).
    HeadlessRenderer(const Terrain& terrain, const Scene& scene);
    // Deletes the GL objects in this renderer's context (made current).
    ~HeadlessRenderer();
    HeadlessRenderer(const HeadlessRenderer&) = delete;
    HeadlessRenderer& operator=(const HeadlessRenderer&) = delete;

    // Composites `out` (Compositor::draw), then reads back the color
    // ("present") and, when `depth` is not null, the depth ("depth_readback";
    // for an Images frame drawn without objects, the method's own depth).
    void render(const MethodOutput& out, const Camera& camera, const Environment& environment,
                const CompositeOptions& options, ColorImage& color, DepthImage* depth,
                FrameTimings* timings = nullptr);

    std::string renderer_name() const { return Context::renderer(); }
    // Makes the renderer's context current on the calling thread: a caller
    // rendering from several threads releases it on the others before
    // destroying the renderer, whose GL objects are deleted in that context.
    void make_current() { context_->make_current(); }
    Compositor& compositor() { return *compositor_; }

private:
    std::unique_ptr<HeadlessContext> context_; // first member: destroyed last
    std::unique_ptr<Compositor> compositor_;
    std::unique_ptr<RenderTarget> target_;
    FinishStepTimer timer_;
};

} // namespace overflight::gl
