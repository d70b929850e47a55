// Based on: Szenberg et al. 1997 sec. 5 (Fig. 5) and 7 (Table 1); seed 003 sec. 3-4.
#include "gl/FlightRenderer.h"

#include "core/Error.h"

namespace overflight::gl {

FlightRenderer::FlightRenderer(const DataSet& data) : data_(data), vehicle_(data.terrain) {
    objects_.set_scene(data.scene, data.terrain);
}

FlightFrameCounts FlightRenderer::draw(FlightMethod& method, const Camera& camera, const Environment& env,
                                       const RenderTarget& target, FlightStepTimer& timer,
                                       const std::optional<VehiclePose>& vehicle, bool wireframe) {
    camera.validate();
    if (camera.width != target.width() || camera.height != target.height())
        throw Error("camera", "image size differs from the render target");
    target.bind();
    frame_.update(camera, env, data_.terrain);
    frame_.bind();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    if (!method.covers_frame()) {
        timer.begin_gl("sky");
        glClearDepth(1.0);
        glClear(GL_DEPTH_BUFFER_BIT);
        sky_.draw();
        timer.end_gl();
    }

    FlightFrameCounts counts;
    std::optional<glm::dvec2> focus;
    if (vehicle) focus = glm::dvec2(vehicle->x, vehicle->z);
    counts.terrain_triangles = method.draw(FlightView{camera, env, target, timer, focus, wireframe});

    // Objects over whatever the method left in the depth buffer (window depth
    // of the shared camera): Szenberg's composite.
    target.bind();
    frame_.bind();
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    timer.begin_gl("objects");
    counts.object_triangles = objects_.draw();
    if (vehicle) counts.object_triangles += vehicle_.draw(vehicle->x, vehicle->z, vehicle->heading);
    timer.end_gl();
    return counts;
}

} // namespace overflight::gl
