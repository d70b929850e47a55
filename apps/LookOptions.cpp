// Based on: DESIGN sec. 6.1 (looks and effects). See LookOptions.h.
#include "LookOptions.h"

#include "OptionValues.h"
#include "core/Error.h"
#include "core/SunLight.h"
#include "core/WaterSurface.h"

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
    cmd.add_option("--time", args.time,
                   "time of day HH:MM setting the sun as fly's time-of-day keys (t / T) do: rising due east at "
                   "06:00, due south at 12:00 at 60 degrees, setting due west at 18:00, night (ambient light only) "
                   "between; instead of --sun");
    cmd.add_flag("--shadows", args.shadows, "the terrain casts the sun's shadows (on itself and on the objects)");
    cmd.add_flag("--water", args.water,
                 "reflective water at the data set's sea level (the map's sea_level; else 0 when the terrain spans "
                 "it; else just above its lowest height)");
    cmd.add_option("--water-level", args.water_level, "reflective water at height H (world units)");
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
    if (!args.time.empty()) {
        if (!args.sun.empty()) throw Error("--time", "give the sun's position by --sun or by --time, not both");
        const std::string& t = args.time;
        const std::size_t colon = t.find(':');
        const auto digits = [](const std::string& s) {
            return !s.empty() && s.size() <= 2 && s.find_first_not_of("0123456789") == std::string::npos;
        };
        const std::string hh = colon == std::string::npos ? "" : t.substr(0, colon);
        const std::string mm = colon == std::string::npos ? "" : t.substr(colon + 1);
        if (!digits(hh) || mm.size() != 2 || !digits(mm) || std::stoi(hh) > 23 || std::stoi(mm) > 59)
            throw Error("--time", "'" + t + "' is not a time of day HH:MM (00:00..23:59)");
        const double hour = std::stoi(hh) + std::stoi(mm) / 60.0;
        env.sun_dir = sun_at_hour(hour);
        if (!(env.sun_dir.y > 0.0f))
            std::fprintf(stderr, "overflight: --time: warning: the sun is at or below the horizon at %s: ambient light only\n",
                         t.c_str());
    }
    if (args.shadows) env.shadows = true;
    return env;
}

Environment with_looks(const LookArgs& args, Environment env, const Terrain& terrain) {
    env = with_looks(args, env);
    if (!args.water && args.water_level.empty()) return env;
    const char* subject = args.water_level.empty() ? "--water" : "--water-level";
    const double level = args.water_level.empty()
                             ? default_water_level(terrain, env)
                             : parse_list(args.water_level, "--water-level", 1, "a height (world units)")[0];
    if (const std::string problem = water_level_problem(terrain, level); !problem.empty()) throw Error(subject, problem);
    env.water = true;
    env.water_level = float(level);
    return env;
}

} // namespace overflight::app
