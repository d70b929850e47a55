// `raymarch`: the brute-force per-pixel ray marcher, the reference the Floating
// Horizon is checked against (slow, but every pixel is traced on its own).
//
// Based on: Szenberg, Gattass, Carvalho, "An Algorithm for the Visualization of
// a Terrain with Objects" (SIBGRAPI 1997), sec. 4 (the plain ray casting the
// Floating Horizon speeds up); DESIGN sec. 8 (reference implementations).
#include "core/SunLight.h"
#include "methods/MethodTable.h"
#include "raycast/RayMarcher.h"
#include "raycast/WaterPass.h"

#include <chrono>

namespace overflight {

namespace {

class RayMarchMethod final : public TerrainMethod {
public:
    explicit RayMarchMethod(const MethodContext& c)
        : marcher_(c.terrain, env_),
          lighting_(c.terrain, c.terrain.imagery() ? LightOutput::Light : LightOutput::Colors, c.sun_shadow),
          water_(c.terrain, c.sun_shadow),
          surface_(c.settings.raycast.surface) {
        marcher_.set_imagery(c.terrain.imagery());
    }
    MethodOutputKind output_kind() const override { return MethodOutputKind::Images; }
    MethodOutput produce(const MethodView& view, MethodStats& stats) override {
        stats.clear();
        env_ = view.environment;
        const auto t0 = std::chrono::steady_clock::now();
        const std::vector<Rgb8>* colors = lighting_.colors(env_);
        marcher_.set_colors(colors);
        marcher_.render(view.camera, surface_, color_, depth_);
        stats.add_step_since("raymarch", t0);
        stats.rays = (long long)view.camera.width * view.camera.height;
        if (view.environment.water) {
            const auto tw = std::chrono::steady_clock::now();
            water_.set_colors(colors, view.environment);
            water_.apply(view.camera, view.environment, surface_, color_, depth_);
            stats.add_step_since("water", tw);
        }
        return MethodOutput::images(color_, depth_);
    }

private:
    Environment env_; // before marcher_, which reads it every frame
    RayMarcher marcher_;
    TerrainLighting lighting_;
    WaterPass water_;
    SurfaceModel surface_;
    ColorImage color_;
    DepthImage depth_;
};

} // namespace

std::unique_ptr<TerrainMethod> make_raymarch_method(const MethodContext& c) {
    return std::make_unique<RayMarchMethod>(c);
}

} // namespace overflight
