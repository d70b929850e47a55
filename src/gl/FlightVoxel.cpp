// `voxel` flight method: Szenberg's composite at interactive rates. Every frame
// the Floating Horizon casts the chase camera on the CPU (all cores, oneTBB);
// its color and window depth go through pixel buffer objects into the
// textures of an offscreen target of the camera's size (Table 1: "color buffer
// load", "Z-buffer load"), and a full-screen pass writes both into the frame's
// target (gl_FragDepth), where the objects are then drawn with the Z-buffer.
//
// The ray caster's colors are the terrain's own (the papers shade nothing at
// run time), so the lighting toggle leaves the voxel terrain unchanged; fog
// and sky follow the frame's environment, computed as the GL shaders do
// (raycast/Atmosphere.h).
//
// Based on: Szenberg et al. 1997 sec. 4-6 (Algorithm 1, exact conic
// projection, depth vector) and sec. 5, Fig. 5 (composite with objects).
#include "gl/FlightMethods.h"
#include "raycast/FloatingHorizon.h"

#include <chrono>
#include <memory>

namespace overflight::gl {

namespace {

class VoxelFlightMethod final : public FlightMethod {
public:
    explicit VoxelFlightMethod(const DataSet& data) : caster_(data.terrain) {}
    const char* name() const override { return "voxel"; }
    bool covers_frame() const override { return true; }

    long long draw(const FlightView& view) override {
        const Camera& cam = view.camera;
        auto t0 = std::chrono::steady_clock::now();
        caster_.render(cam, view.environment, options_, color_, depth_); // fog toggle: per frame
        view.timer.cpu_step_since("raycast", t0);

        t0 = std::chrono::steady_clock::now();
        if (!images_ || images_->width() != cam.width || images_->height() != cam.height)
            images_ = std::make_unique<RenderTarget>(cam.width, cam.height);
        images_->upload_color(color_);
        images_->upload_depth(depth_);
        view.timer.cpu_step_since("upload", t0);

        view.timer.begin_gl("composite");
        view.target.draw_from(*images_);
        view.timer.end_gl();
        return 0;
    }

private:
    FloatingHorizon caster_;
    RaycastOptions options_; // blocks surface, exact: the papers' voxels
    ColorImage color_;
    DepthImage depth_;
    std::unique_ptr<RenderTarget> images_; // textures the ray-cast images are loaded into
};

} // namespace

std::unique_ptr<FlightMethod> make_voxel_flight_method(const DataSet& data) {
    return std::make_unique<VoxelFlightMethod>(data);
}

} // namespace overflight::gl
