// Based on: Szenberg et al. 1997 sec. 5 (objects drawn with the Z-buffer).
#include "gl/ObjectRenderer.h"

#include "gl/ObjectGeometry.h"

namespace overflight::gl {

void ObjectRenderer::set_scene(const Scene& scene, const Terrain& terrain) {
    const ObjectGeometry g = build_object_geometry(scene, terrain);
    solids_.upload(g.triangles);
    lines_.upload(g.line_points, g.line_colors);
    bounds_ = g.bounds;
    casters_ = g.casters;
}

long long ObjectRenderer::draw() const {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    const long long n = solids_.draw();
    lines_.draw();
    return n;
}

} // namespace overflight::gl
