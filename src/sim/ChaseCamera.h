#pragma once
// Based on: CMSC 23700 project 2a sec. 3.2, last paragraph: the
// camera follows the vehicle; looking parallel to the XZ plane "can leave you
// staring at steep slopes", a look-at point ahead "can be quite jerky", so the
// change in view direction is damped. Here the eye sits behind and above the
// vehicle, the target pitch aims at a point ahead on the terrain, and the pitch
// follows the target by exponential smoothing with time constant tau:
//     pitch += (target - pitch) * (1 - exp(-dt / tau))
// which is frame-rate independent (two frames of dt/2 equal one of dt).
#include "core/Camera.h"
#include "core/Terrain.h"
#include "sim/Hovercraft.h"

namespace overflight {

struct ChaseParams {
    double behind = 12.0;      // eye distance behind the vehicle, world units
    double above = 4.0;        // eye height above the vehicle
    double clearance = 1.0;    // eye kept at least this far above the terrain under it
    double look_ahead = 30.0;  // the look-at point, ahead of the vehicle
    double smoothing = 0.25;   // tau, seconds; 0 = no damping
    double max_pitch = 60.0;   // |pitch| limit, degrees (the camera contract needs < 89)
};

class ChaseCamera {
public:
    explicit ChaseCamera(const ChaseParams& params = {}) : params_(params) {}

    // The undamped pitch (degrees) that looks from the eye at the point
    // look_ahead in front of the vehicle, `altitude` above the terrain there.
    double target_pitch(const Terrain& terrain, const HovercraftState& s, double altitude = 2.0) const;

    // Sets camera.eye, heading and pitch for vehicle state s; the pitch jumps
    // straight to the target (first frame, teleport). Other camera fields
    // (fov, size, near, far, projection) are left as the caller set them.
    void reset(const Terrain& terrain, const HovercraftState& s, Camera& camera);

    // Same, with the pitch moved towards the target by exponential smoothing
    // over dt seconds of real time.
    void update(const Terrain& terrain, const HovercraftState& s, double dt, Camera& camera);

    const ChaseParams& params() const { return params_; }
    double pitch() const { return pitch_; }

private:
    void place_eye(const Terrain& terrain, const HovercraftState& s, Camera& camera) const;

    ChaseParams params_;
    double pitch_ = 0;
    bool started_ = false;
};

} // namespace overflight
