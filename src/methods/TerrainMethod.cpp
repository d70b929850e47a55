#include "methods/TerrainMethod.h"

namespace overflight {

const char* to_string(ResidentSurface s) {
    switch (s) {
    case ResidentSurface::Mesh: return "mesh";
    case ResidentSurface::Points: return "points";
    case ResidentSurface::TopFaces: return "top-faces";
    case ResidentSurface::FrontFaces: return "front-faces";
    case ResidentSurface::Segments: return "segments";
    case ResidentSurface::Blocks: return "blocks";
    }
    return "mesh";
}

void MethodStats::clear() {
    steps.clear();
    triangles = 0;
    raycast.reset();
    rays = 0;
    roam.reset();
    tiles.reset();
}

double MethodStats::step_ms(const char* name) const {
    for (const MethodStep& s : steps)
        if (std::string_view(s.name) == name) return s.ms;
    return 0;
}

} // namespace overflight
