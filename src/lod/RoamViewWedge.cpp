// Based on: CMSC 23700 project 2a sec. 5.1 (view wedge in XZ), DESIGN sec. 2 (camera).
#include "lod/RoamViewWedge.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>

namespace overflight {

RoamViewWedge RoamViewWedge::from_camera(const Camera& camera, double min_y, double max_y) {
    RoamViewWedge w;
    const glm::dvec3 f = camera.forward(), r = camera.right(), axis = camera.view_axis();
    // Corner rays u = +-W/2, v = +-H/2 seen from above: their forward and
    // lateral XZ components give the widest half-angle of the footprint.
    double tan_half = 0;
    for (int sv = -1; sv <= 1; sv += 2) {
        for (int su = -1; su <= 1; su += 2) {
            const double u = su * camera.width * 0.5, v = sv * camera.height * 0.5;
            const glm::dvec3 d = camera.ray(u, v);
            const double fwd = glm::dot(d, f), lat = glm::dot(d, r);
            if (fwd <= 1e-9) return w; // a ray goes backwards in XZ: no wedge
            tan_half = std::max(tan_half, std::abs(lat) / fwd);
        }
    }
    w.enabled = true;
    w.eye = {camera.eye.x, camera.eye.z};
    w.forward = {f.x, f.z};
    const glm::dvec2 right{r.x, r.z};
    // Side lines along forward -+ tan_half * right; their normals R + t F and
    // -R + t F point into the wedge (both have a positive dot with F).
    w.inner_left = right + tan_half * w.forward;
    w.inner_right = -right + tan_half * w.forward;
    // View depth = cos(a) * (forward XZ distance) + sin(a) * (y - eye.y), a the
    // elevation of the view axis (0 for shear). The smallest the height term
    // can be over the terrain gives the forward distance past which every
    // point is beyond `far`.
    const double ca = std::sqrt(axis.x * axis.x + axis.z * axis.z), sa = axis.y;
    const double least = std::min(sa * (min_y - camera.eye.y), sa * (max_y - camera.eye.y));
    w.far_forward = (camera.far - least) / std::max(ca, 1e-9);
    return w;
}

std::uint8_t RoamViewWedge::outcode(const glm::dvec2& p) const {
    if (!enabled) return 0;
    const glm::dvec2 d = p - eye;
    const double ahead = glm::dot(forward, d);
    return std::uint8_t((glm::dot(inner_left, d) < 0 ? kBehindLeft : 0) | (glm::dot(inner_right, d) < 0 ? kBehindRight : 0) |
                        (ahead < 0 ? kBehindEye : 0) | (ahead > far_forward ? kBeyondFar : 0));
}

} // namespace overflight
