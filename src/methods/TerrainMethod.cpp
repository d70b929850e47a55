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

MethodOutput MethodOutput::images(const ColorImage& color, const DepthImage& depth) {
    MethodOutput out;
    out.color = &color;
    out.depth = &depth;
    return out;
}

MethodOutput MethodOutput::of_mesh(const MeshArrays& mesh) {
    MethodOutput out;
    out.kind = MethodOutputKind::Mesh;
    out.mesh = &mesh;
    return out;
}

MethodOutput MethodOutput::resident(ResidentSurface surface) {
    MethodOutput out;
    out.kind = MethodOutputKind::Resident;
    out.surface = surface;
    return out;
}

void MethodStats::add_step_since(const char* name, std::chrono::steady_clock::time_point start) {
    steps.push_back({name, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count()});
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
