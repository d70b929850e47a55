#pragma once
// The flight of `fly`, without a window: the hovercraft under fixed 10 ms
// physics steps, the keys that drive it (from a window's events and from a
// script), the viewer's toggles (fog, lighting, wireframe, HUD), the chase
// camera, and the record of every frame. A window only feeds it key events and
// wall-clock time and draws what it says; tests run whole flights on the CPU.
//
// Time: physics runs in fixed steps drained from a FixedStepClock. An
// interactive frame stands for the wall-clock time since the last one (at most
// 0.25 s); an unattended run (frames > 0) feeds exactly frame_time per frame,
// so a scripted flight (--press FROM-TO in frames) is the same flight on every
// machine and at any frame rate.
//
// Based on: CMSC 23700 project 2a, "sports utility hovercraft", sec. 3 (vehicle,
// controls, physics at 100 Hz, chase camera) and sec. 4.1-4.2 (sun, GL_EXP fog);
// G. Fiedler, "Fix your timestep" (2004).
#include "core/Camera.h"
#include "core/DataSet.h"
#include "sim/ChaseCamera.h"
#include "sim/FixedStepClock.h"
#include "sim/FlightRecord.h"
#include "sim/Hovercraft.h"
#include "sim/KeyScript.h"
#include "sim/KeyState.h"

#include <vector>

namespace overflight {

struct FlightSessionOptions {
    double fov = 60.0;              // horizontal, degrees
    long long frames = 0;           // > 0: an unattended run of exactly this many frames
    double frame_time = 1.0 / 60.0; // simulated seconds per frame of an unattended run
    KeyScript script;               // scripted keys, FROM-TO in frames
    VehicleStart start;             // if !given: the terrain centre, facing south
    bool hud = true;
    bool lighting = true;           // start with sun lighting (false: baked, the `1` key toggles)
    bool record = true;             // false: end_frame keeps no record (a web page flying for hours)
};

// What `f` cycles through: no fog, the hovercraft paper's GL_EXP fog, the
// atmosphere (aerial perspective and a sky that follows the sun,
// Environment::atmosphere), then no fog again.
enum class FogMode { Off, Exp, Atmosphere };
FogMode next_fog_mode(FogMode mode);
const char* to_string(FogMode mode); // "off", "GL_EXP", "atmosphere"
// The mode an environment asks for: atmosphere, else fog if it has a density.
FogMode fog_mode_of(const Environment& env);

// The viewer's state that command keys toggle.
struct ViewToggles {
    FogMode fog = FogMode::Off;
    bool lighting = true, wireframe = false, hud = true;
    bool shadows = false; // the terrain's cast shadows (s)
    bool water = false;   // the water surface (o), at FlightSession::water_level()
};

// The camera every fly frame starts from: `fov`, near 0.5, far covering the
// whole map from any point on it, shear projection (size and pose set later).
Camera flight_camera(const Terrain& terrain, double fov);

// The data set's environment with the fog (f) and lighting (1: sun or baked) toggles applied;
// a data set without fog gets a density that fades the far side of the map.
Environment view_environment(const Environment& env, const Terrain& terrain, FogMode fog, bool lighting);

class FlightSession {
public:
    // Places the vehicle (Error("vehicle start", ...) for a start off the map) and the
    // camera. `terrain` must outlive the session.
    FlightSession(const Terrain& terrain, const Environment& environment, const FlightSessionOptions& options);

    // A window's key events. Vehicle keys are sampled by the physics (a tap
    // between two steps is still seen by one step); the viewer's command keys
    // act on press, at the next begin_frame.
    void press(Key key);
    void release(Key key);

    // Starts the next frame: applies the script's keys for it and the toggles
    // of the command keys received since the last frame. Returns the commands
    // the caller acts on, in order (detail-up, detail-down, next-method,
    // screenshot, quit).
    const std::vector<Key>& begin_frame();
    // Runs the physics for the time this frame stands for (`wall_seconds`
    // since the previous frame when interactive) and moves the chase camera.
    void advance(double wall_seconds);
    // Records the frame (camera, vehicle, keys seen by its physics steps)
    // unless the options say not to.
    void end_frame();

    // True once an unattended run has begun all its frames.
    bool finished() const { return options_.frames > 0 && frame_ + 1 >= options_.frames; }
    bool unattended() const { return options_.frames > 0; }
    long long frame() const { return frame_; } // the frame begun last
    bool last_frame() const { return unattended() && frame_ + 1 == options_.frames; }

    // The camera of the frame (pose from the chase camera); the caller sets its size.
    Camera& camera() { return camera_; }
    const HovercraftState& vehicle() const { return hovercraft_.state(); }
    const ViewToggles& toggles() const { return toggles_; }
    // The environment with the current toggles (view_environment), the
    // shadows toggle and the sun the time-of-day keys moved (t / T: half an
    // hour along core/SunLight.h's day arc per press).
    Environment environment() const;
    const FlightRecord& record() const { return record_; }
    // The level the water key floods to: the environment's water level if it
    // has water, else the data set's sea level (core/WaterSurface.h); nullopt
    // when that lies outside the terrain's heights (the key does nothing).
    std::optional<double> water_level() const { return water_level_; }
    long long physics_steps() const { return physics_steps_; }
    double ms_per_physics_step() const { return ms_per_step_; } // CPU time of the last frame's steps

private:
    const Terrain& terrain_;
    Environment environment_;
    FlightSessionOptions options_;
    Hovercraft hovercraft_;
    ChaseCamera chase_;
    Camera camera_;
    FixedStepClock clock_;
    KeyState keys_;
    std::vector<Key> pending_;  // command keys received since the last frame
    std::vector<Key> commands_; // this frame's, for the caller
    unsigned scripted_held_ = 0; // vehicle keys the script holds (a bit per key)
    ViewToggles toggles_;
    std::optional<double> water_level_;
    bool sun_moved_ = false; // the time-of-day keys were used: sun_hour_ sets the sun
    double sun_hour_ = 12.0;
    FlightRecord record_;
    Controls seen_;             // vehicle keys seen by this frame's steps
    long long frame_ = -1;
    double sim_time_ = 0;
    long long physics_steps_ = 0;
    double ms_per_step_ = 0;
};

} // namespace overflight
