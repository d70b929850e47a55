// `overflight sim TERRAIN --steps N [--at X,Z] [--heading D] [--press KEY:FROM-TO ...]`
// (DESIGN sec. 6): the hovercraft physics of CMSC 23700 project 2a sec. 3.2 alone, no GL.
// Prints CSV `step,x,z,y,velocity,heading` with one row per 10 ms step: row k
// is the state after step k (k = 0 .. N-1), the step that saw the keys held
// "during step k" of --press.
#include "Commands.h"
#include "SimulatorRun.h"
#include "StandardOutput.h"
#include "TerrainOptions.h"
#include "core/Error.h"

#include <cstdio>
#include <memory>
#include <string>

namespace overflight::app {

void add_sim_command(CLI::App& app) {
    struct Args {
        TerrainArgs terrain;
        SimArgs sim;
    };
    auto o = std::make_shared<Args>();
    CLI::App* sub = app.add_subcommand("sim", "Run the hovercraft physics alone (no GL) and print CSV "
                                              "step,x,z,y,velocity,heading after each 10 ms step");
    add_terrain_options(*sub, o->terrain);
    add_sim_options(*sub, o->sim);
    sub->callback([o] {
        if (o->sim.steps < 1) throw Error("--steps", "must be at least 1");
        const DataSet ds = load_terrain(o->terrain);
        // Rows are formatted into one reused buffer and written in blocks, each
        // write checked: a full disk or a closed stdout stops the run at once.
        std::string out = "step,x,z,y,velocity,heading\n";
        char line[192];
        run_simulator(o->sim, ds, [&](long long k, const HovercraftState& s) {
            const int n = std::snprintf(line, sizeof line, "%lld,%.6f,%.6f,%.6f,%.6f,%.6f\n", k, s.x, s.z, s.y,
                                        s.velocity, s.heading);
            out.append(line, std::size_t(n));
            if (out.size() > (1u << 16)) {
                write_stdout(out);
                out.clear();
            }
        });
        write_stdout(out);
    });
}

} // namespace overflight::app
