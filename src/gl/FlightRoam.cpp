// `roam` flight method: split-only ROAM rebuilt every frame for the chase
// camera, the vehicle's triangles first (its focus), drawn lit and fogged like
// the full mesh. + / _ step the triangle budget by sqrt 2 (roam_scale_budget).
//
// Based on: seed 003 sec. 5 and 5.1 (split-only ROAM, triangle budget, view
// wedge, the vehicle's triangle at maximum priority) and sec. 3.1 (+ / _).
#include "gl/FlightMethods.h"
#include "gl/StreamedFlightMethod.h"
#include "lod/RoamMesh.h"

#include <cmath>
#include <string>

namespace overflight::gl {

namespace {

class RoamFlightMethod final : public StreamedFlightMethod {
public:
    static constexpr int kDefaultBudget = 65536; // as `render --method roam`

    explicit RoamFlightMethod(const DataSet& data) : roam_(data.terrain) {}
    const char* name() const override { return "roam"; }

    const char* build_step() const override { return "tessellate"; }
    void build(const FlightView& view, MeshArrays& mesh) override {
        roam_.tessellate(view.camera, budget_, view.focus);
        roam_.write_mesh(mesh);
    }

    void scale_detail(double factor) override {
        // One step of the sqrt 2 ladder per factor of sqrt 2.
        budget_ = roam_scale_budget(budget_, int(std::lround(2.0 * std::log2(factor))));
    }
    std::string detail() const override { return "budget " + std::to_string(budget_); }

private:
    RoamMesh roam_;
    int budget_ = kDefaultBudget;
};

} // namespace

std::unique_ptr<FlightMethod> make_roam_flight_method(const DataSet& data) {
    return std::make_unique<RoamFlightMethod>(data);
}

} // namespace overflight::gl
