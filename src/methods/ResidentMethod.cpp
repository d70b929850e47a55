// `mesh` and Szenberg's Table 2 representations (`points`, `top-faces`,
// `front-faces`, `segments`, `blocks`): the terrain's samples at full
// resolution, uploaded once by the renderer and drawn with the Z-buffer every
// frame. There is nothing to compute per frame, so the method only names the
// representation; the renderer reports the primitives it drew.
//
// Based on: Szenberg, Gattass, Carvalho, "An Algorithm for the Visualization of
// a Terrain with Objects" (SIBGRAPI 1997), sec. 3 (representations a-e) and
// sec. 7, Table 2; DESIGN sec. 3 (the `mesh` surface).
#include "methods/MethodTable.h"

namespace overflight {

namespace {

class ResidentMethod final : public TerrainMethod {
public:
    explicit ResidentMethod(ResidentSurface surface) : surface_(surface) {}
    MethodOutputKind output_kind() const override { return MethodOutputKind::Resident; }
    MethodOutput produce(const MethodView& view, MethodStats& stats) override {
        view.camera.validate();
        stats.clear();
        return MethodOutput::resident(surface_);
    }

private:
    ResidentSurface surface_;
};

} // namespace

std::unique_ptr<TerrainMethod> make_resident_mesh_method(const MethodContext&) {
    return std::make_unique<ResidentMethod>(ResidentSurface::Mesh);
}
std::unique_ptr<TerrainMethod> make_points_method(const MethodContext&) {
    return std::make_unique<ResidentMethod>(ResidentSurface::Points);
}
std::unique_ptr<TerrainMethod> make_top_faces_method(const MethodContext&) {
    return std::make_unique<ResidentMethod>(ResidentSurface::TopFaces);
}
std::unique_ptr<TerrainMethod> make_front_faces_method(const MethodContext&) {
    return std::make_unique<ResidentMethod>(ResidentSurface::FrontFaces);
}
std::unique_ptr<TerrainMethod> make_segments_method(const MethodContext&) {
    return std::make_unique<ResidentMethod>(ResidentSurface::Segments);
}
std::unique_ptr<TerrainMethod> make_blocks_method(const MethodContext&) {
    return std::make_unique<ResidentMethod>(ResidentSurface::Blocks);
}

} // namespace overflight
