#pragma once
// The hovercraft simulator as `sim` runs it (DESIGN sec. 6), shared with the
// Python module: the options (`--steps N --at POSITION --heading D --press
// KEY:FROM-TO ... --slope M`) and the run, one 10 ms step at a time.
#include "core/DataSet.h"
#include "sim/Hovercraft.h"

#include <CLI/CLI.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace overflight::app {

struct SimArgs {
    long long steps = 0;
    std::string at;  // a position (CameraOptions.h parse_position): engine X,Z, lonlat:, crs:
    std::optional<double> heading;
    std::vector<std::string> presses;
    std::string slope = "ahead";
};

// Adds --steps (required), --at, --heading, --press, --slope to `cmd`.
void add_sim_options(CLI::App& cmd, SimArgs& args);

// Runs args.steps steps on `data`, from --at (else the data set's start,
// else the terrain's centre), calling on_step(k, state) after step k.
// Throws Error naming the option (--steps, --press, --slope, --at).
void run_simulator(const SimArgs& args, const DataSet& data,
                   const std::function<void(long long step, const HovercraftState& state)>& on_step);

} // namespace overflight::app
