// `mesh` flight method: the full-resolution triangulation, uploaded once.
// Based on: Szenberg et al. 1997 sec. 7 (the Z-buffer baseline), DESIGN sec. 3.
#include "gl/FlightMethods.h"
#include "gl/TerrainMesh.h"

namespace overflight::gl {

namespace {

class MeshFlightMethod final : public FlightMethod {
public:
    explicit MeshFlightMethod(const DataSet& data) : mesh_(data.terrain) {}
    const char* name() const override { return "mesh"; }
    long long draw(const FlightView& view) override {
        view.timer.begin_gl("terrain");
        if (view.wireframe) glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
        const TerrainMesh::DrawStats s = mesh_.draw(view.camera.projection_matrix() * view.camera.view_matrix());
        glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
        view.timer.end_gl();
        return s.triangles;
    }

private:
    TerrainMesh mesh_;
};

} // namespace

std::unique_ptr<FlightMethod> make_mesh_flight_method(const DataSet& data) {
    return std::make_unique<MeshFlightMethod>(data);
}

} // namespace overflight::gl
