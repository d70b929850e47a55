// `voxel-literal`: Szenberg's Algorithm 1 as printed, single-threaded: the
// reference the fast ray caster is measured against (shear cameras only).
//
// Based on: Szenberg, Gattass, Carvalho, "An Algorithm for the Visualization of
// a Terrain with Objects" (SIBGRAPI 1997), sec. 4, Algorithm 1.
#include "core/Error.h"
#include "methods/MethodTable.h"
#include "raycast/FloatingHorizonLiteral.h"

namespace overflight {

namespace {

class VoxelLiteralMethod final : public TerrainMethod {
public:
    explicit VoxelLiteralMethod(const MethodContext& c) : terrain_(c.terrain), options_(c.settings.raycast) {
        if (options_.lod) throw Error("distance LOD", "voxel-literal has none (it is Algorithm 1 as printed)");
    }
    MethodOutputKind output_kind() const override { return MethodOutputKind::Images; }
    MethodOutput produce(const MethodView& view, MethodStats& stats) override {
        stats.clear();
        RaycastStats s;
        render_floating_horizon_literal(terrain_, view.environment, view.camera, options_.surface, color_, depth_, &s);
        stats.steps.push_back({"raycast", s.ms_total});
        stats.raycast = s;
        return MethodOutput::images(color_, depth_);
    }

private:
    const Terrain& terrain_;
    RaycastOptions options_;
    ColorImage color_;
    DepthImage depth_;
};

} // namespace

std::unique_ptr<TerrainMethod> make_voxel_literal_method(const MethodContext& c) {
    return std::make_unique<VoxelLiteralMethod>(c);
}

} // namespace overflight
