// Looks shared by render, bench and fly (DESIGN sec. 6.1). See LookOptions.h.
#include "LookOptions.h"

#include "OptionValues.h"
#include "core/Error.h"
#include "core/SunLight.h"

#include <cstdio>

namespace overflight::app {

void add_look_options(CLI::App& cmd, LookArgs& a) {
    cmd.add_option("--lighting", a.lighting,
                   "sun: sun and ambient light on every method (the default); baked: colors as they are (the papers' look)")
        ->capture_default_str();
    cmd.add_option("--sun", a.sun,
                   "sun position AZIMUTH,ELEVATION in degrees (azimuth clockwise from north, 0..360; elevation "
                   "-90..90, at or below 0: night, ambient light only); default: the data set's sun");
    cmd.add_flag("--shadows", a.shadows, "the terrain casts the sun's shadows (on itself and on the objects)");
}

void apply_look_options(const LookArgs& a, Environment& env) {
    if (a.lighting == "baked") bake_lighting(env);
    else if (a.lighting != "sun") throw Error("--lighting", "unknown mode '" + a.lighting + "' (known: sun|baked)");
    if (!a.sun.empty()) {
        const std::vector<double> v = parse_list(a.sun, "--sun", 2, "AZIMUTH,ELEVATION (two numbers, degrees)");
        if (v[0] < 0 || v[0] > 360) throw Error("--sun", "azimuth " + a.sun.substr(0, a.sun.find(',')) + " is outside 0..360");
        if (v[1] < -90 || v[1] > 90)
            throw Error("--sun", "elevation " + a.sun.substr(a.sun.find(',') + 1) + " is outside -90..90");
        env.sun_dir = sun_direction(v[0], v[1]);
        if (v[1] <= 0)
            std::fprintf(stderr, "overflight: --sun: warning: elevation %g is at or below the horizon: ambient light only\n",
                         v[1]);
    }
    env.shadows = a.shadows;
}

} // namespace overflight::app
