// `overflight sim TERRAIN --steps N [--at X,Z] [--heading D] [--press KEY:FROM-TO ...]`
// (DESIGN sec. 6): the hovercraft physics of CMSC 23700 project 2a sec. 3.2 alone, no GL.
// Prints CSV `step,x,z,y,velocity,heading` with one row per 10 ms step: row k
// is the state after step k (k = 0 .. N-1), the step that saw the keys held
// "during step k" of --press.
#include "Commands.h"
#include "OptionValues.h"
#include "StandardOutput.h"
#include "TerrainOptions.h"
#include "core/Error.h"
#include "sim/Hovercraft.h"
#include "sim/KeyScript.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace overflight::app {

namespace {

struct SimOptions {
    TerrainArgs terrain;
    long long steps = 0;
    std::string at;
    std::optional<double> heading;
    std::vector<std::string> presses;
    std::string slope = "ahead";
};

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

void run_sim(const SimOptions& o) {
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

    const DataSet ds = load_terrain(o.terrain);
    const Terrain& t = ds.terrain;
    // Start: --at, else the data set's [vehicle] start, else the terrain centre.
    double x = t.width() * 0.5, z = t.depth() * 0.5, heading = 0;
    if (ds.start.given) {
        x = ds.start.x;
        z = ds.start.z;
        heading = ds.start.heading;
    }
    if (!o.at.empty() && !parse_xz(o.at, x, z))
        throw Error("--at", "'" + o.at + "' is not X,Z (two numbers, world units)");
    if (o.heading) heading = *o.heading;
    Hovercraft hc(t, x, z, heading, params);
    const KeyScript script(std::move(presses));

    // Rows are formatted into one reused buffer and written in blocks, each
    // write checked: a full disk or a closed stdout stops the run at once.
    std::string out = "step,x,z,y,velocity,heading\n";
    char line[192];
    for (long long k = 0; k < o.steps; ++k) {
        hc.step(script.controls_at(k));
        const HovercraftState& s = hc.state();
        const int n = std::snprintf(line, sizeof line, "%lld,%.6f,%.6f,%.6f,%.6f,%.6f\n", k, s.x, s.z, s.y,
                                    s.velocity, s.heading);
        out.append(line, std::size_t(n));
        if (out.size() > (1u << 16)) {
            write_stdout(out);
            out.clear();
        }
    }
    write_stdout(out);
}

} // namespace

void add_sim_command(CLI::App& app) {
    auto o = std::make_shared<SimOptions>();
    CLI::App* sub = app.add_subcommand("sim", "Run the hovercraft physics alone (no GL) and print CSV "
                                              "step,x,z,y,velocity,heading after each 10 ms step");
    add_terrain_options(*sub, o->terrain);
    sub->add_option("--steps", o->steps, "Number of 10 ms steps (decimal)")
        ->required()
        ->transform(decimal<long long>());
    sub->add_option("--at", o->at, "Start X,Z in world units (default: the data set's start, else the centre)");
    sub->add_option("--heading", o->heading, "Start heading, degrees (0 south, 90 east)");
    sub->add_option("--press", o->presses,
                    "KEY:FROM-TO holds KEY (accelerate, brake, left, right) during steps FROM..TO-1")
        ->take_all();
    sub->add_option("--slope", o->slope, "Slope method of the physics: ahead (default) or triangle-normal");
    sub->callback([o] { run_sim(*o); });
}

} // namespace overflight::app
