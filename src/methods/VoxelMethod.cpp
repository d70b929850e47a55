// `voxel`: the Floating Horizon ray caster, parallel and exact, producing the
// terrain's color and window depth for the compositor.
//
// Based on: Szenberg, Gattass, Carvalho, "An Algorithm for the Visualization of
// a Terrain with Objects" (SIBGRAPI 1997), sec. 4-6 (Algorithm 1, exact conic
// projection, depth vector); Guedes, "Integrating Polygonal Objects on Voxel
// Based Terrain Models" (pitched view planes).
#include "core/SunLight.h"
#include "methods/MethodTable.h"
#include "raycast/FloatingHorizon.h"
#include "raycast/WaterPass.h"

#include <chrono>
#include <utility>

namespace overflight {

namespace {

class VoxelMethod final : public TerrainMethod {
public:
    explicit VoxelMethod(const MethodContext& c)
        : caster_(c.terrain),
          lighting_(c.terrain, c.terrain.imagery() ? LightOutput::Light : LightOutput::Colors, c.sun_shadow),
          water_(c.terrain, c.sun_shadow),
          options_(c.settings.raycast) {
        // Imagery finer than the samples: the cast paints light, the imagery the albedo.
        caster_.set_imagery(c.terrain.imagery());
    }
    MethodOutputKind output_kind() const override { return MethodOutputKind::Images; }
    MethodOutput produce(const MethodView& view, MethodStats& stats) override {
        stats.clear();
        const auto t0 = std::chrono::steady_clock::now();
        const std::vector<Rgb8>* colors = lighting_.colors(view.environment);
        if (lighting_.version() != painted_) {
            caster_.set_colors(colors, lighting_.light_mask());
            painted_ = lighting_.version();
            stats.add_step_since("light", t0);
        }
        RaycastStats s;
        caster_.render(view.camera, view.environment, options_, color_, depth_, &s);
        stats.steps.push_back({"raycast", s.ms_total});
        stats.raycast = s;
        if (view.environment.water) {
            const auto tw = std::chrono::steady_clock::now();
            water_.set_colors(colors, view.environment);
            water_.apply(view.camera, view.environment, options_.surface, color_, depth_);
            stats.add_step_since("water", tw);
        }
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
    FloatingHorizon caster_;
    TerrainLighting lighting_;
    WaterPass water_;
    std::uint64_t painted_ = 0; // the lighting's version the caster paints
    RaycastOptions options_;
    ColorImage color_;
    DepthImage depth_;
};

} // namespace

std::unique_ptr<TerrainMethod> make_voxel_method(const MethodContext& c) { return std::make_unique<VoxelMethod>(c); }

} // namespace overflight
