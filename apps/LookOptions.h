#pragma once
// The looks and effects of DESIGN sec. 6.1 that `render`, `bench` and `fly`
// share: `--atmosphere` (aerial perspective and a sky that follows the sun,
// core/AerialPerspective.h, in place of the GL_EXP fog), `--lighting
// sun|baked`, `--sun AZIMUTH,ELEVATION` or `--time HH:MM` (the sun where
// fly's time-of-day keys put it at that hour) and `--shadows` (core/SunLight.h,
// core/HorizonSweep.h). They set the data set's Environment, which every
// terrain method and the compositor read.
#include "core/DataSet.h"

#include <CLI/CLI.hpp>

#include <string>

namespace overflight::app {

struct LookArgs {
    bool atmosphere = false;      // --atmosphere
    std::string lighting = "sun"; // --lighting: sun (Lambert sun + ambient) or baked (the terrain's colors as they are)
    std::string sun;              // --sun AZIMUTH,ELEVATION (degrees); empty: the data set's sun
    std::string time;             // --time HH:MM: the sun of core/SunLight.h's day arc at that hour
    bool shadows = false;         // --shadows: the terrain casts the sun's shadows
    bool water = false;           // --water: water at the data set's sea level (core/WaterSurface.h)
    std::string water_level;      // --water-level H (world units): water at H
    // Whether any look was asked for.
    bool any() const {
        return atmosphere || lighting != "sun" || !sun.empty() || !time.empty() || shadows || water ||
               !water_level.empty();
    }
};

// Adds the switches to `cmd` (`args` must outlive the parse); `what` ends
// --atmosphere's help (e.g. ", also timed without it" for bench).
void add_look_options(CLI::App& cmd, LookArgs& args, const char* what = "");

// The data set's environment with the looks asked for. Throws
// Error("--sun", ...) for a value that is not two numbers, an azimuth outside
// [0, 360] or an elevation outside [-90, 90], Error("--time", ...) for a
// time that is not HH:MM (00:00..23:59) or one given beside --sun,
// Error("--lighting", ...) for an unknown mode. A sun at or below the horizon is accepted (ambient light
// only, everything in the terrain's shadow) with a one-line warning on stderr.
Environment with_looks(const LookArgs& args, Environment env);

// The same with the water of --water / --water-level over `terrain`
// (--water-level wins). Throws Error("--water-level", ...) for a value that
// is not a number or lies outside the terrain's heights, Error("--water", ...)
// when the data set's sea level does.
Environment with_looks(const LookArgs& args, Environment env, const Terrain& terrain);

} // namespace overflight::app
