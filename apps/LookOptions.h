#pragma once
// The looks of the terrain that `render`, `bench` and `fly` share (DESIGN
// sec. 6.1): `--lighting sun|baked`, `--sun AZIMUTH,ELEVATION`, `--shadows`.
// They set the data set's Environment, which every terrain method reads.
#include "core/DataSet.h"

#include <CLI/CLI.hpp>

#include <string>

namespace overflight::app {

struct LookArgs {
    std::string lighting = "sun"; // --lighting: sun (Lambert sun + ambient) or baked (colors as they are)
    std::string sun;              // --sun AZIMUTH,ELEVATION (degrees); empty: the data set's sun
    bool shadows = false;         // --shadows: the terrain casts the sun's shadows
};

// Adds --lighting, --sun and --shadows to `cmd` (`args` must outlive the parse).
void add_look_options(CLI::App& cmd, LookArgs& args);

// Applies `args` to `env`. Throws Error("--sun", ...) for a value that is not
// two numbers, an azimuth outside [0, 360] or an elevation outside [-90, 90],
// Error("--lighting", ...) for an unknown mode. A sun at or below the horizon
// is accepted (ambient light only, everything in the terrain's shadow) with
// a one-line warning on stderr.
void apply_look_options(const LookArgs& args, Environment& env);

} // namespace overflight::app
