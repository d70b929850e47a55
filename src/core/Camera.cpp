#include "core/Camera.h"

#include "core/Error.h"

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>
#include <string>

namespace overflight {

const char* to_string(Projection p) { return p == Projection::Shear ? "shear" : "tilt"; }

void Camera::validate() const {
    auto bad = [](const std::string& what) { throw Error("camera", what); };
    if (!std::isfinite(eye.x) || !std::isfinite(eye.y) || !std::isfinite(eye.z)) bad("eye is not a finite point");
    if (!std::isfinite(heading)) bad("heading is not a number");
    if (!(std::abs(pitch) < 89.0)) bad("pitch " + std::to_string(pitch) + " is outside (-89, 89) degrees");
    if (!(fov > 0.0 && fov < 180.0)) bad("fov " + std::to_string(fov) + " is outside (0, 180) degrees");
    if (width < 1 || height < 1 || width > 16384 || height > 16384)
        bad("image size " + std::to_string(width) + "x" + std::to_string(height) + " is outside 1..16384");
    if (!(near > 0.0) || !std::isfinite(near)) bad("near must be > 0");
    if (!(far > near) || !std::isfinite(far)) bad("far must be greater than near");
}

glm::dvec3 Camera::forward() const {
    const double h = glm::radians(heading);
    return {std::sin(h), 0.0, std::cos(h)};
}

glm::dvec3 Camera::right() const { return glm::cross(forward(), glm::dvec3(0, 1, 0)); }

glm::dvec3 Camera::view_axis() const {
    if (projection == Projection::Shear) return forward();
    const double p = glm::radians(pitch);
    return std::cos(p) * forward() + std::sin(p) * glm::dvec3(0, 1, 0);
}

glm::dvec3 Camera::view_up() const {
    if (projection == Projection::Shear) return {0, 1, 0};
    const double p = glm::radians(pitch);
    return -std::sin(p) * forward() + std::cos(p) * glm::dvec3(0, 1, 0);
}

double Camera::focal_px() const { return (width * 0.5) / std::tan(glm::radians(fov) * 0.5); }

glm::dvec3 Camera::ray(double u, double v) const {
    const double fp = focal_px();
    if (projection == Projection::Shear)
        return forward() + (u / fp) * right() + ((v + fp * std::tan(glm::radians(pitch))) / fp) * glm::dvec3(0, 1, 0);
    return view_axis() + (u / fp) * right() + (v / fp) * view_up();
}

glm::dmat4 Camera::view_matrix() const { return glm::lookAt(eye, eye + view_axis(), view_up()); }

glm::dmat4 Camera::projection_matrix() const {
    const double t = std::tan(glm::radians(fov) * 0.5);
    const double aspect = double(height) / double(width);
    const double shift = projection == Projection::Shear ? std::tan(glm::radians(pitch)) : 0.0;
    return glm::frustum(-near * t, near * t, near * (-aspect * t + shift), near * (aspect * t + shift), near, far);
}

double Camera::view_depth(const glm::dvec3& world) const { return glm::dot(world - eye, view_axis()); }

Camera::Projected Camera::project(const glm::dvec3& world) const {
    const glm::dvec3 d = world - eye;
    const double z = glm::dot(d, view_axis());
    const double fp = focal_px();
    const double u = fp * glm::dot(d, right()) / z;
    double v = fp * glm::dot(d, view_up()) / z;
    if (projection == Projection::Shear) v -= fp * std::tan(glm::radians(pitch));
    return {u + width * 0.5, height * 0.5 - v, window_depth(z), z > 0};
}

} // namespace overflight
