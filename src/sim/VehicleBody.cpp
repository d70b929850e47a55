// Based on: CMSC 23700 project 2a sec. 3 (the vehicle and its chase camera).
#include "sim/VehicleBody.h"

#include "sim/Hovercraft.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>

namespace overflight {

BodyFrame vehicle_frame(const Terrain& terrain, double x, double z, double heading) {
    constexpr double kLength = VehicleBody::kLength, kWidth = VehicleBody::kWidth;
    const double h = glm::radians(heading);
    const glm::dvec3 fwd{std::sin(h), 0, std::cos(h)}, side{std::cos(h), 0, -std::sin(h)};
    const auto ground = [&](const glm::dvec3& offset) { return ground_height(terrain, x + offset.x, z + offset.z); };
    const double front = ground(0.5 * kLength * fwd), back = ground(-0.5 * kLength * fwd);
    const double left = ground(0.5 * kWidth * side), right = ground(-0.5 * kWidth * side);
    const glm::dvec3 up{0, 1, 0};
    BodyFrame f;
    f.az = glm::normalize(fwd + up * ((front - back) / kLength));
    const glm::dvec3 ax0 = glm::normalize(side + up * ((left - right) / kWidth));
    f.ay = glm::normalize(glm::cross(f.az, ax0));
    f.ax = glm::cross(f.ay, f.az);
    const double centre = std::max(ground_height(terrain, x, z), 0.25 * (front + back + left + right));
    f.origin = {x, centre + VehicleBody::kHover, z};
    return f;
}

WorldBox vehicle_local_box() {
    const double w = VehicleBody::kWidth / 2, d = VehicleBody::kLength / 2;
    return {glm::vec3(-w, 0, -d), glm::vec3(w, VehicleBody::kHeight, d)};
}

WorldBox placed_box(const BodyFrame& frame, const WorldBox& local, double margin) {
    glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
    for (int k = 0; k < 8; ++k) {
        const glm::dvec3 p{(k & 1) ? local.hi.x : local.lo.x, (k & 2) ? local.hi.y : local.lo.y,
                           (k & 4) ? local.hi.z : local.lo.z};
        const glm::dvec3 w = frame.place(p);
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
    }
    return {glm::vec3(lo - margin), glm::vec3(hi + margin)};
}

} // namespace overflight
