// Based on: CMSC 23700 project 2a sec. 3 and 4.1-4.2; Fiedler, "Fix your timestep".
#include "sim/FlightSession.h"

#include "core/SunLight.h"
#include "core/WaterSurface.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace overflight {

namespace {

constexpr std::size_t kMaxCommands = 64; // per frame; more are dropped (no allocation per frame)

// Chase distances grow with the grid spacing: on a 10 m or 90 m grid the
// paper's few-metre offsets would fill the view with a single cell. The eye
// stays low enough (above / behind = 0.2, about 11 degrees down) that the
// vehicle is in the lower part of the view while the camera aims at the
// look-ahead point (60 degrees horizontal fov at 16:9 sees 18 degrees down).
ChaseParams chase_params(const Terrain& t) {
    ChaseParams p;
    const double hs = t.h_scale();
    p.behind = std::max(p.behind, 3.0 * hs);
    p.above = std::max(p.above, 0.6 * hs);
    p.look_ahead = std::max(p.look_ahead, 8.0 * hs);
    return p;
}

Hovercraft place_vehicle(const Terrain& t, const VehicleStart& start) {
    const double x = start.given ? start.x : t.width() * 0.5;
    const double z = start.given ? start.z : t.depth() * 0.5;
    return Hovercraft(t, x, z, start.given ? start.heading : 0.0);
}

} // namespace

Camera flight_camera(const Terrain& t, double fov) {
    Camera cam;
    cam.fov = fov;
    cam.near = 0.5;
    const double span = std::hypot(double(t.width()), double(t.depth()), double(t.max_height() - t.min_height()));
    cam.far = std::max(1000.0, 1.1 * span);
    cam.projection = Projection::Shear;
    return cam;
}

FogMode next_fog_mode(FogMode mode) {
    switch (mode) {
    case FogMode::Off: return FogMode::Exp;
    case FogMode::Exp: return FogMode::Atmosphere;
    default: return FogMode::Off;
    }
}

const char* to_string(FogMode mode) {
    switch (mode) {
    case FogMode::Exp: return "GL_EXP";
    case FogMode::Atmosphere: return "atmosphere";
    default: return "off";
    }
}

FogMode fog_mode_of(const Environment& env) {
    if (env.atmosphere) return FogMode::Atmosphere;
    return env.fog_density > 0 ? FogMode::Exp : FogMode::Off;
}

Environment view_environment(const Environment& env, const Terrain& t, FogMode fog, bool lighting) {
    Environment e = env;
    e.atmosphere = fog == FogMode::Atmosphere;
    if (fog != FogMode::Exp) e.fog_density = 0;
    else if (!(e.fog_density > 0))
        e.fog_density = float(2.0 / std::max(1.0, std::hypot(double(t.width()), double(t.depth()))));
    if (!lighting) bake_lighting(e);
    return e;
}

FlightSession::FlightSession(const Terrain& terrain, const Environment& environment,
                             const FlightSessionOptions& options)
    : terrain_(terrain), environment_(environment), options_(options),
      hovercraft_(place_vehicle(terrain, options.start)), chase_(chase_params(terrain)),
      camera_(flight_camera(terrain, options.fov)), clock_(hovercraft_.params().step) {
    chase_.reset(terrain_, hovercraft_.state(), camera_);
    toggles_.fog = fog_mode_of(environment);
    toggles_.hud = options.hud;
    toggles_.lighting = options.lighting;
    toggles_.shadows = environment.shadows;
    toggles_.water = environment.water;
    const double level = environment.water ? double(environment.water_level)
                                           : default_water_level(terrain, environment);
    if (water_level_problem(terrain, level).empty()) water_level_ = level;
    pending_.reserve(kMaxCommands);
    commands_.reserve(kMaxCommands);
    if (options.record) record_.frames.reserve(unattended() ? std::size_t(options.frames) : 4096);
}

void FlightSession::press(Key key) {
    if (is_vehicle_key(key)) keys_.press(key);
    else if (pending_.size() < kMaxCommands) pending_.push_back(key);
}

void FlightSession::release(Key key) {
    if (is_vehicle_key(key)) keys_.release(key);
}

const std::vector<Key>& FlightSession::begin_frame() {
    ++frame_;
    // Scripted keys act exactly like events arriving before this frame.
    for (int k = 0; k < 4; ++k) {
        const bool held = options_.script.held_at(Key(k), frame_);
        const bool was = (scripted_held_ >> k) & 1u;
        if (held && !was) keys_.press(Key(k));
        if (!held && was) keys_.release(Key(k));
        scripted_held_ = held ? scripted_held_ | (1u << k) : scripted_held_ & ~(1u << k);
    }
    for (int k = 4; k < kKeyCount; ++k)
        if (options_.script.starts_at(Key(k), frame_)) press(Key(k));

    commands_.clear();
    for (Key k : pending_) {
        switch (k) {
        case Key::Fog: toggles_.fog = next_fog_mode(toggles_.fog); break;
        case Key::Lighting: toggles_.lighting = !toggles_.lighting; break;
        case Key::Wireframe: toggles_.wireframe = !toggles_.wireframe; break;
        case Key::Hud: toggles_.hud = !toggles_.hud; break;
        case Key::Shadows: toggles_.shadows = !toggles_.shadows; break;
        case Key::Water: toggles_.water = !toggles_.water && water_level_; break;
        case Key::SunLater:
        case Key::SunEarlier:
            if (!sun_moved_) sun_hour_ = hour_of_sun(environment_.sun_dir);
            sun_moved_ = true;
            sun_hour_ = std::fmod(sun_hour_ + (k == Key::SunLater ? 0.5 : 23.5), 24.0);
            break;
        default: commands_.push_back(k); break;
        }
    }
    pending_.clear();
    return commands_;
}

void FlightSession::advance(double wall_seconds) {
    const double dt = unattended() ? options_.frame_time : std::min(0.25, wall_seconds);
    sim_time_ += dt;
    const int steps = clock_.advance(dt);
    seen_ = Controls{};
    const auto t0 = std::chrono::steady_clock::now();
    hovercraft_.set_water_level(toggles_.water ? water_level_ : std::nullopt);
    for (int i = 0; i < steps; ++i) {
        const Controls c = keys_.sample();
        hovercraft_.step(c);
        seen_.accelerate |= c.accelerate;
        seen_.brake |= c.brake;
        seen_.left |= c.left;
        seen_.right |= c.right;
    }
    if (steps > 0)
        ms_per_step_ =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() / steps;
    physics_steps_ += steps;
    chase_.update(terrain_, hovercraft_.state(), dt, camera_);
}

void FlightSession::end_frame() {
    if (!options_.record) return;
    const HovercraftState& s = hovercraft_.state();
    FlightFrame rec;
    rec.frame = frame_;
    rec.time = sim_time_;
    rec.eye = camera_.eye;
    rec.heading = camera_.heading;
    rec.pitch = camera_.pitch;
    rec.x = s.x;
    rec.z = s.z;
    rec.velocity = s.velocity;
    rec.vehicle_heading = s.heading;
    rec.keys = seen_;
    record_.frames.push_back(rec);
}

Environment FlightSession::environment() const {
    Environment e = view_environment(environment_, terrain_, toggles_.fog, toggles_.lighting);
    e.shadows = toggles_.shadows;
    if (sun_moved_) e.sun_dir = sun_at_hour(sun_hour_);
    e.water = toggles_.water;
    if (water_level_) e.water_level = float(*water_level_);
    e.water_time = sim_time_;
    return e;
}

} // namespace overflight
