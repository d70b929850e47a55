// `roam`: split-only ROAM rebuilt for every frame within a triangle budget, the
// vehicle's triangles first when one is flying; the mesh goes out as plain
// arrays. The level-of-detail knob steps the budget by sqrt 2.
//
// Based on: Duchaineau et al., "ROAMing Terrain: Real-time Optimally Adapting
// Meshes" (1997), split-only with a variance tree, forced splits and priority
// buckets as in the CMSC 23700 hovercraft project (sec. 5 and 5.1; sec. 3.1
// for the + / _ keys).
#include "core/Error.h"
#include "methods/MethodTable.h"

#include <chrono>
#include <cmath>
#include <string>

namespace overflight {

namespace {

class RoamMethod final : public TerrainMethod {
public:
    explicit RoamMethod(const MethodContext& c) : roam_(c.terrain), budget_(c.settings.triangles) {}
    MethodOutputKind output_kind() const override { return MethodOutputKind::Mesh; }
    MethodOutput produce(const MethodView& view, MethodStats& stats) override {
        stats.clear();
        const auto t0 = std::chrono::steady_clock::now();
        stats.roam = roam_.tessellate(view.camera, budget_, view.focus);
        roam_.write_mesh(mesh_);
        stats.add_step_since("tessellate", t0);
        stats.triangles = (long long)mesh_.triangle_count();
        return MethodOutput::of_mesh(mesh_);
    }
    void scale_detail(double factor) override {
        // One step of the sqrt 2 ladder per factor of sqrt 2.
        budget_ = roam_scale_budget(budget_, int(std::lround(2.0 * std::log2(factor))));
    }
    std::string detail() const override { return "budget " + std::to_string(budget_); }

private:
    RoamMesh roam_;
    int budget_;
    MeshArrays mesh_;
};

} // namespace

std::unique_ptr<TerrainMethod> make_roam_method(const MethodContext& c) { return std::make_unique<RoamMethod>(c); }

} // namespace overflight
