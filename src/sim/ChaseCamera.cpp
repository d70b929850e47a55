#include "sim/ChaseCamera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace overflight {

namespace {
constexpr double kDeg = 180.0 / std::numbers::pi;

// Eye position behind and above the vehicle, never inside the terrain.
glm::dvec3 eye_of(const Terrain& t, const HovercraftState& s, const ChaseParams& p) {
    const double h = s.heading / kDeg;
    const double x = s.x - p.behind * std::sin(h);
    const double z = s.z - p.behind * std::cos(h);
    const double ground = ground_height(t, x, z);
    return {x, std::max(s.y + p.above, ground + p.clearance), z};
}
} // namespace

double ChaseCamera::target_pitch(const Terrain& terrain, const HovercraftState& s, double altitude) const {
    const double h = s.heading / kDeg;
    const double lx = s.x + params_.look_ahead * std::sin(h);
    const double lz = s.z + params_.look_ahead * std::cos(h);
    const double ly = ground_height(terrain, lx, lz) + altitude;
    const glm::dvec3 eye = eye_of(terrain, s, params_);
    const double pitch = std::atan2(ly - eye.y, params_.behind + params_.look_ahead) * kDeg;
    return std::clamp(pitch, -params_.max_pitch, params_.max_pitch);
}

void ChaseCamera::place_eye(const Terrain& terrain, const HovercraftState& s, Camera& camera) const {
    camera.eye = eye_of(terrain, s, params_);
    camera.heading = s.heading;
    camera.pitch = pitch_;
}

void ChaseCamera::reset(const Terrain& terrain, const HovercraftState& s, Camera& camera) {
    pitch_ = target_pitch(terrain, s);
    started_ = true;
    place_eye(terrain, s, camera);
}

void ChaseCamera::update(const Terrain& terrain, const HovercraftState& s, double dt, Camera& camera) {
    if (!started_) {
        reset(terrain, s, camera);
        return;
    }
    const double target = target_pitch(terrain, s);
    const double k = params_.smoothing > 0 ? 1.0 - std::exp(-std::max(0.0, dt) / params_.smoothing) : 1.0;
    pitch_ += (target - pitch_) * k;
    place_eye(terrain, s, camera);
}

} // namespace overflight
