// Based on: CMSC 23700 project 2a sec. 3 (the vehicle and its chase camera) and Szenberg et
// al. 1997 sec. 5 (objects drawn with the Z-buffer over any terrain).
#include "gl/FlightVehicle.h"

#include "gl/ObjectGeometry.h"

#include <glm/common.hpp>

#include <cmath>
#include <limits>

namespace overflight::gl {

FlightVehicle::FlightVehicle(const Terrain& terrain) : terrain_(terrain) {
    model_ = player_vehicle_model();
    placed_ = model_;
    model_box_ = {glm::vec3(HUGE_VALF), glm::vec3(-HUGE_VALF)};
    for (const glm::vec3& p : model_.positions) {
        model_box_.lo = glm::min(model_box_.lo, p);
        model_box_.hi = glm::max(model_box_.hi, p);
    }
}

bool FlightVehicle::place(double x, double z, double heading) {
    if (placed_once_ && x == px_ && z == pz_ && heading == pheading_) return false;
    placed_once_ = true;
    px_ = x;
    pz_ = z;
    pheading_ = heading;
    const BodyFrame f = vehicle_frame(terrain_, x, z, heading);
    WorldBox box{glm::vec3(std::numeric_limits<float>::max()), glm::vec3(-std::numeric_limits<float>::max())};
    for (std::size_t i = 0; i < model_.positions.size(); ++i) {
        const glm::dvec3 n(model_.normals[i]);
        placed_.positions[i] = glm::vec3(f.place(glm::dvec3(model_.positions[i])));
        placed_.normals[i] = glm::vec3(n.x * f.ax + n.y * f.ay + n.z * f.az);
        box.lo = glm::min(box.lo, placed_.positions[i]);
        box.hi = glm::max(box.hi, placed_.positions[i]);
    }
    mesh_.upload(placed_);
    bounds_.assign(1, box);
    return true;
}

WorldBox FlightVehicle::bounds_at(double x, double z, double heading) const {
    // Float rounding of place()'s positions is covered by half a metre of margin.
    return placed_box(vehicle_frame(terrain_, x, z, heading), model_box_, 0.5);
}

} // namespace overflight::gl
