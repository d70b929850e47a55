// `voxel-literal`: Szenberg's Algorithm 1 as printed, single-threaded: the
// reference the fast ray caster is measured against (shear cameras only).
//
// Based on: Szenberg, Gattass, Carvalho, "An Algorithm for the Visualization of
// a Terrain with Objects" (SIBGRAPI 1997), sec. 4, Algorithm 1.
#include "core/Error.h"
#include "core/SunLight.h"
#include "methods/MethodTable.h"
#include "raycast/FloatingHorizonLiteral.h"
#include "raycast/WaterPass.h"

#include <chrono>

namespace overflight {

namespace {

class VoxelLiteralMethod final : public TerrainMethod {
public:
    explicit VoxelLiteralMethod(const MethodContext& c)
        : terrain_(c.terrain),
          lighting_(c.terrain, c.terrain.imagery() ? LightOutput::Light : LightOutput::Colors, c.sun_shadow),
          water_(c.terrain, c.sun_shadow),
          options_(c.settings.raycast) {
        if (options_.lod) throw Error("distance LOD", "voxel-literal has none (it is Algorithm 1 as printed)");
    }
    MethodOutputKind output_kind() const override { return MethodOutputKind::Images; }
    MethodOutput produce(const MethodView& view, MethodStats& stats) override {
        stats.clear();
        const auto t0 = std::chrono::steady_clock::now();
        const std::uint64_t before = lighting_.version();
        const std::vector<Rgb8>* colors = lighting_.colors(view.environment);
        if (lighting_.version() != before) stats.add_step_since("light", t0);
        RaycastStats s;
        render_floating_horizon_literal(terrain_, view.environment, view.camera, options_.surface, color_, depth_, &s,
                                        colors, terrain_.imagery(), lighting_.light_mask());
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

private:
    const Terrain& terrain_;
    TerrainLighting lighting_;
    WaterPass water_;
    RaycastOptions options_;
    ColorImage color_;
    DepthImage depth_;
};

} // namespace

std::unique_ptr<TerrainMethod> make_voxel_literal_method(const MethodContext& c) {
    return std::make_unique<VoxelLiteralMethod>(c);
}

} // namespace overflight
