// Names of the ray caster options (see RaycastOptions.h).
#include "raycast/RaycastOptions.h"

#include "core/Error.h"

namespace overflight {

const char* to_string(SurfaceModel s) { return s == SurfaceModel::Blocks ? "blocks" : "bilinear"; }
const char* to_string(TiltMethod t) { return t == TiltMethod::Exact ? "exact" : "guedes"; }

SurfaceModel parse_surface_model(const std::string& name, const std::string& option) {
    if (name == "blocks") return SurfaceModel::Blocks;
    if (name == "bilinear") return SurfaceModel::Bilinear;
    throw Error(option, "'" + name + "' is not a surface model (blocks or bilinear)");
}

TiltMethod parse_tilt_method(const std::string& name, const std::string& option) {
    if (name == "exact") return TiltMethod::Exact;
    if (name == "guedes") return TiltMethod::Guedes;
    throw Error(option, "'" + name + "' is not a tilt method (exact or guedes)");
}

} // namespace overflight
