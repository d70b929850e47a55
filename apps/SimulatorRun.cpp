// The simulator's options and run. See SimulatorRun.h.
#include "SimulatorRun.h"

#include "CameraOptions.h"
#include "OptionValues.h"
#include "core/Error.h"
#include "sim/KeyScript.h"

#include <charconv>
#include <cmath>

namespace overflight::app {

namespace {

// "X,Z" in world units.
bool parse_xz(const std::string& s, double& x, double& z) {
    const auto comma = s.find(',');
    if (comma == std::string::npos) return false;
    const char* b = s.data();
    const char* e = s.data() + s.size();
    auto r1 = std::from_chars(b, b + comma, x);
    auto r2 = std::from_chars(b + comma + 1, e, z);
    return r1.ec == std::errc() && r1.ptr == b + comma && r2.ec == std::errc() && r2.ptr == e &&
           std::isfinite(x) && std::isfinite(z);
}

} // namespace

void add_sim_options(CLI::App& sub, SimArgs& o) {
    sub.add_option("--steps", o.steps, "Number of 10 ms steps (decimal)")
        ->required()
        ->transform(decimal<long long>());
    sub.add_option("--at", o.at,
                   "Start X,Z in world units, lonlat:LON,LAT or crs:E,N (default: the data set's start, else the centre)");
    sub.add_option("--heading", o.heading, "Start heading, degrees (0 south, 90 east)");
    sub.add_option("--press", o.presses,
                   "KEY:FROM-TO holds KEY (accelerate, brake, left, right) during steps FROM..TO-1")
        ->take_all();
    sub.add_option("--slope", o.slope, "Slope method of the physics: ahead (default) or triangle-normal");
}

void run_simulator(const SimArgs& o, const DataSet& ds,
                   const std::function<void(long long step, const HovercraftState& state)>& on_step) {
    if (o.steps < 1) throw Error("--steps", "must be at least 1");
    std::vector<ScriptedPress> presses;
    for (const std::string& spec : o.presses) {
        const ScriptedPress p = parse_press(spec);
        if (!is_vehicle_key(p.key))
            throw Error("--press", std::string("'") + key_name(p.key) +
                                       "' is not a vehicle key; sim takes accelerate, brake, left, right");
        presses.push_back(p);
    }
    HovercraftParams params;
    if (o.slope == "ahead") params.slope = SlopeMethod::Ahead;
    else if (o.slope == "triangle-normal") params.slope = SlopeMethod::TriangleNormal;
    else throw Error("--slope", "'" + o.slope + "' is not ahead or triangle-normal");

    const Terrain& t = ds.terrain;
    // Start: --at, else the data set's [vehicle] start, else the terrain centre.
    double x = t.width() * 0.5, z = t.depth() * 0.5, heading = 0;
    if (ds.start.given) {
        x = ds.start.x;
        z = ds.start.z;
        heading = ds.start.heading;
    }
    if (o.at.find(':') != std::string::npos) {
        const Position p = parse_position(o.at, "--at", EngineForm::XZ, "", ds);
        x = p.x;
        z = p.z;
    } else if (!o.at.empty() && !parse_xz(o.at, x, z)) {
        throw Error("--at", "'" + o.at + "' is not X,Z (two numbers, world units)");
    }
    if (o.heading) heading = *o.heading;
    Hovercraft hc(t, x, z, heading, params);
    const KeyScript script(std::move(presses));
    for (long long k = 0; k < o.steps; ++k) {
        hc.step(script.controls_at(k));
        on_step(k, hc.state());
    }
}

} // namespace overflight::app
