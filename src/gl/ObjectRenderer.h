#pragma once
// Draws a Scene's objects with OpenGL's Z-buffer: lit solids through
// StreamedMesh, towers and cables as GL lines. Geometry is built and uploaded
// once per scene (set_scene), so drawing a frame allocates nothing.
//
// Based on: Szenberg et al. 1997 sec. 5 (Fig. 5: objects by Z-buffer over the
// terrain's color and depth) and Table 1 ("Objects" step).
#include "core/Scene.h"
#include "core/ScreenRect.h"
#include "core/Terrain.h"
#include "gl/StreamedMesh.h"

namespace overflight::gl {

class ObjectRenderer {
public:
    ObjectRenderer() = default;
    // Builds and uploads the scene's geometry on `terrain`. Throws what
    // build_object_geometry throws (model files).
    void set_scene(const Scene& scene, const Terrain& terrain);
    // Draws with depth test on (Frame block must be bound). Returns triangles drawn.
    long long draw() const;
    long long triangle_count() const { return solids_.triangle_count(); }
    // The pixels the objects can cover for `camera` (core screen_rect of their
    // bounds): where a composite needs the ray caster's depth.
    PixelRect screen_rect(const Camera& camera) const { return overflight::screen_rect(bounds_, camera); }
    const std::vector<WorldBox>& bounds() const { return bounds_; }
    // ObjectGeometry::casters: what casts the objects' shadows, finer than bounds().
    const std::vector<std::vector<glm::vec3>>& casters() const { return casters_; }

private:
    StreamedMesh solids_;
    LineBatch lines_;
    std::vector<WorldBox> bounds_;
    std::vector<std::vector<glm::vec3>> casters_;
};

} // namespace overflight::gl
