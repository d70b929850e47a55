// Based on: CMSC 23700 project 2a sec. 3 (the vehicle and its chase camera) and Szenberg et
// al. 1997 sec. 5 (objects drawn with the Z-buffer over any terrain).
#include "gl/FlightVehicle.h"

#include "gl/ObjectGeometry.h"
#include "sim/Hovercraft.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>
#include <limits>

namespace overflight::gl {

FlightVehicle::FlightVehicle(const Terrain& terrain) : terrain_(terrain) {
    Scene scene;
    SceneObject v;
    v.kind = ObjectKind::Vehicle;
    v.y = 0.0;
    v.width = kWidth;
    v.height = kHeight;
    v.depth = kLength;
    v.color = Rgb8{215, 75, 35};
    scene.objects.push_back(v);
    model_ = build_object_geometry(scene, terrain).triangles;
    placed_ = model_;
    model_box_ = {glm::vec3(HUGE_VALF), glm::vec3(-HUGE_VALF)};
    for (const glm::vec3& p : model_.positions) {
        model_box_.lo = glm::min(model_box_.lo, p);
        model_box_.hi = glm::max(model_box_.hi, p);
    }
}

FlightVehicle::Frame FlightVehicle::frame_at(double x, double z, double heading) const {
    // The ground under the craft's four sides gives its slope along and across
    // the heading; the body is rotated onto that plane.
    const double h = glm::radians(heading);
    const glm::dvec3 fwd{std::sin(h), 0, std::cos(h)}, side{std::cos(h), 0, -std::sin(h)};
    const auto ground = [&](const glm::dvec3& offset) { return ground_height(terrain_, x + offset.x, z + offset.z); };
    const double front = ground(0.5 * kLength * fwd), back = ground(-0.5 * kLength * fwd);
    const double left = ground(0.5 * kWidth * side), right = ground(-0.5 * kWidth * side);
    const glm::dvec3 up{0, 1, 0};
    Frame f;
    f.az = glm::normalize(fwd + up * ((front - back) / kLength));
    const glm::dvec3 ax0 = glm::normalize(side + up * ((left - right) / kWidth));
    f.ay = glm::normalize(glm::cross(f.az, ax0));
    f.ax = glm::cross(f.ay, f.az);
    const double centre = std::max(ground_height(terrain_, x, z), 0.25 * (front + back + left + right));
    f.origin = {x, centre + kHover, z};
    return f;
}

bool FlightVehicle::place(double x, double z, double heading) {
    if (placed_once_ && x == px_ && z == pz_ && heading == pheading_) return false;
    placed_once_ = true;
    px_ = x;
    pz_ = z;
    pheading_ = heading;
    const Frame f = frame_at(x, z, heading);
    WorldBox box{glm::vec3(std::numeric_limits<float>::max()), glm::vec3(-std::numeric_limits<float>::max())};
    for (std::size_t i = 0; i < model_.positions.size(); ++i) {
        const glm::dvec3 p(model_.positions[i]), n(model_.normals[i]);
        placed_.positions[i] = glm::vec3(f.origin + p.x * f.ax + p.y * f.ay + p.z * f.az);
        placed_.normals[i] = glm::vec3(n.x * f.ax + n.y * f.ay + n.z * f.az);
        box.lo = glm::min(box.lo, placed_.positions[i]);
        box.hi = glm::max(box.hi, placed_.positions[i]);
    }
    mesh_.upload(placed_);
    bounds_.assign(1, box);
    return true;
}

WorldBox FlightVehicle::bounds_at(double x, double z, double heading) const {
    // The placed model box's corners bound the placed vertices (an affine map
    // keeps them in the image of the box); float rounding of place()'s
    // positions is covered by half a metre of margin.
    const Frame f = frame_at(x, z, heading);
    glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
    for (int k = 0; k < 8; ++k) {
        const glm::dvec3 p{(k & 1) ? model_box_.hi.x : model_box_.lo.x, (k & 2) ? model_box_.hi.y : model_box_.lo.y,
                           (k & 4) ? model_box_.hi.z : model_box_.lo.z};
        const glm::dvec3 w = f.origin + p.x * f.ax + p.y * f.ay + p.z * f.az;
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
    }
    return {glm::vec3(lo - 0.5), glm::vec3(hi + 0.5)};
}

} // namespace overflight::gl
