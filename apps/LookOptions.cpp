// Based on: DESIGN sec. 6.1 (looks and effects). See LookOptions.h.
#include "LookOptions.h"

#include <string>

namespace overflight::app {

void add_look_options(CLI::App& cmd, LookArgs& args, const char* what) {
    cmd.add_flag("--atmosphere", args.atmosphere,
                 std::string("aerial perspective (extinction and in-scattering that depend on altitude and sun angle) "
                             "and a sky whose color follows the sun, instead of GL_EXP fog") +
                     what);
}

Environment with_looks(const LookArgs& args, Environment env) {
    if (args.atmosphere) env.atmosphere = true;
    return env;
}

} // namespace overflight::app
