// `voxel`: the Floating Horizon ray caster, parallel and exact, producing the
// terrain's color and window depth for the compositor.
//
// Based on: Szenberg, Gattass, Carvalho, "An Algorithm for the Visualization of
// a Terrain with Objects" (SIBGRAPI 1997), sec. 4-6 (Algorithm 1, exact conic
// projection, depth vector); Guedes, "Integrating Polygonal Objects on Voxel
// Based Terrain Models" (pitched view planes).
#include "methods/MethodTable.h"
#include "raycast/VoxelRenderer.h"

#include <utility>

namespace overflight {

namespace {

class VoxelMethod final : public TerrainMethod {
public:
    explicit VoxelMethod(const MethodContext& c) : renderer_(c.terrain, c.settings.raycast, c.sun_shadow) {}
    MethodOutputKind output_kind() const override { return MethodOutputKind::Images; }
    MethodOutput produce(const MethodView& view, MethodStats& stats) override {
        stats.clear();
        VoxelFrameStats frame;
        renderer_.render(view.camera, view.environment, color_, depth_, frame);
        if (frame.relit) stats.steps.push_back({"light", frame.light_ms});
        stats.steps.push_back({"raycast", frame.raycast.ms_total});
        stats.raycast = frame.raycast;
        if (frame.water) stats.steps.push_back({"water", frame.water_ms});
        return MethodOutput::images(color_, depth_);
    }
    // The caster writes every pixel of both images (sky included), and resizes
    // them to the camera's size first.
    bool swap_images(ColorImage& color, DepthImage* depth) override {
        std::swap(color, color_);
        if (depth) std::swap(*depth, depth_);
        return true;
    }

private:
    VoxelRenderer renderer_;
    ColorImage color_;
    DepthImage depth_;
};

} // namespace

std::unique_ptr<TerrainMethod> make_voxel_method(const MethodContext& c) { return std::make_unique<VoxelMethod>(c); }

} // namespace overflight
