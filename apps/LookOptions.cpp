// Based on: DESIGN sec. 6.1 (looks and effects). See LookOptions.h.
#include "LookOptions.h"

#include "OptionValues.h"
#include "core/Error.h"
#include "core/SunLight.h"

#include <cstdio>
#include <string>

namespace overflight::app {

void add_look_options(CLI::App& cmd, LookArgs& args, const char* what) {
    cmd.add_flag("--atmosphere", args.atmosphere,
                 std::string("aerial perspective (extinction and in-scattering that depend on altitude and sun angle) "
                             "and a sky whose color follows the sun, instead of GL_EXP fog") +
                     what);
    cmd.add_option("--lighting", args.lighting,
                   "sun: sun and ambient light on every method (the default); baked: the terrain's colors as they are "
                   "(the papers' look)")
        ->capture_default_str();
    cmd.add_option("--sun", args.sun,
                   "sun position AZIMUTH,ELEVATION in degrees (azimuth clockwise from north, 0..360; elevation "
                   "-90..90, at or below 0: night, ambient light only); default: the data set's sun");
    cmd.add_flag("--shadows", args.shadows, "the terrain casts the sun's shadows (on itself and on the objects)");
}

Environment with_looks(const LookArgs& args, Environment env) {
    if (args.atmosphere) env.atmosphere = true;
    if (args.lighting == "baked") bake_lighting(env);
    else if (args.lighting != "sun") throw Error("--lighting", "unknown mode '" + args.lighting + "' (known: sun|baked)");
    if (!args.sun.empty()) {
        const std::vector<double> v = parse_list(args.sun, "--sun", 2, "AZIMUTH,ELEVATION (two numbers, degrees)");
        if (v[0] < 0 || v[0] > 360)
            throw Error("--sun", "azimuth " + args.sun.substr(0, args.sun.find(',')) + " is outside 0..360");
        if (v[1] < -90 || v[1] > 90)
            throw Error("--sun", "elevation " + args.sun.substr(args.sun.find(',') + 1) + " is outside -90..90");
        env.sun_dir = sun_direction(v[0], v[1]);
        if (v[1] <= 0)
            std::fprintf(stderr, "overflight: --sun: warning: elevation %g is at or below the horizon: ambient light only\n",
                         v[1]);
    }
    if (args.shadows) env.shadows = true;
    return env;
}

} // namespace overflight::app
