#pragma once
// The looks and effects of DESIGN sec. 6.1 that `render`, `bench` and `fly`
// share: `--atmosphere` (aerial perspective and a sky that follows the sun,
// core/AerialPerspective.h, in place of the GL_EXP fog).
#include "core/DataSet.h"

#include <CLI/CLI.hpp>

namespace overflight::app {

struct LookArgs {
    bool atmosphere = false; // --atmosphere
    // Whether any look was asked for.
    bool any() const { return atmosphere; }
};

// Adds the switches to `cmd`; `what` ends each one's help (e.g. ", also timed
// without it" for bench).
void add_look_options(CLI::App& cmd, LookArgs& args, const char* what = "");

// The data set's environment with the looks asked for.
Environment with_looks(const LookArgs& args, Environment env);

} // namespace overflight::app
