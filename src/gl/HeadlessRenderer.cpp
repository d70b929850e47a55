// Based on: Szenberg et al. 1997 sec. 5 and 7 (Tables 1 and 2).
#include "gl/HeadlessRenderer.h"

#include "core/Error.h"

#include <string_view>

namespace overflight::gl {

double FrameTimings::step(const char* name) const {
    for (const auto& [n, ms] : steps_ms)
        if (std::string_view(n) == name) return ms;
    return 0;
}

double FrameTimings::total_ms() const {
    double t = 0;
    for (const auto& s : steps_ms) t += s.second;
    return t;
}

HeadlessRenderer::HeadlessRenderer(const Terrain& terrain, const Scene& scene)
    : context_(std::make_unique<HeadlessContext>()), compositor_(std::make_unique<Compositor>(terrain, scene)) {}

HeadlessRenderer::~HeadlessRenderer() {
    // GL deletes objects in whichever context is current, and another
    // renderer may have drawn last on this thread: delete in our own. (A
    // context current on another thread cannot be taken; EGL refuses, and the
    // caller was told to release it first.)
    try {
        context_->make_current();
    } catch (const Error&) {
    }
    target_.reset();
    compositor_.reset();
}

void HeadlessRenderer::render(const MethodOutput& out, const Camera& camera, const Environment& environment,
                              const CompositeOptions& options, ColorImage& color, DepthImage* depth,
                              FrameTimings* timings) {
    camera.validate();
    context_->make_current();
    if (!target_ || target_->width() != camera.width || target_->height() != camera.height)
        target_ = std::make_unique<RenderTarget>(camera.width, camera.height);
    // Uploads of a resident representation finish before the first timed step.
    if (out.kind == MethodOutputKind::Resident) compositor_->prepare(out.surface);
    CompositeOptions o = options;
    o.full_depth = o.full_depth || depth != nullptr;
    timer_.begin_frame();
    const CompositeCounts counts = compositor_->draw(out, camera, environment, *target_, timer_, o);
    timer_.begin_gl("present");
    target_->read_color(color);
    timer_.end_gl();
    if (depth) {
        timer_.begin_gl("depth_readback");
        if (out.kind == MethodOutputKind::Images && !o.objects) *depth = *out.depth;
        else target_->read_depth(*depth);
        timer_.end_gl();
    }
    if (timings) {
        timings->steps_ms = timer_.steps();
        timings->counts = counts;
    }
}

} // namespace overflight::gl
