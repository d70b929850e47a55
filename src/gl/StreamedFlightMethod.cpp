// Based on: DESIGN sec. 7 (LOD selection produces plain arrays the renderer only uploads).
#include "gl/StreamedFlightMethod.h"

namespace overflight::gl {

long long StreamedFlightMethod::draw(const FlightView& view) {
    auto t0 = std::chrono::steady_clock::now();
    build(view, mesh_);
    view.timer.cpu_step_since(build_step(), t0);
    t0 = std::chrono::steady_clock::now();
    streamed_.upload(mesh_);
    view.timer.cpu_step_since("upload", t0);
    view.timer.begin_gl("terrain");
    if (view.wireframe) glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    const long long n = streamed_.draw();
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    view.timer.end_gl();
    return n;
}

} // namespace overflight::gl
