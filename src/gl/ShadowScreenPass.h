#pragma once
// The objects' shadows on a ray-cast image: the ray casters paint the
// terrain's lit colors on the CPU (core/SunLight.h) and know nothing of the
// objects, so after their color and depth are in the target a full-screen
// pass, limited to the pixels an object's shadow can reach, rebuilds each
// terrain pixel's world position from its window depth (DESIGN sec. 2:
// OpenGL depth, the camera's projection), tests it against the objects'
// shadow map (object_sun_visible) and takes out the sun's share the shadow
// removes, with the light of shade(): the painted color c = fogged(albedo x
// (ambient + sun x lambert x lit)), fogged() affine in its color (fog or
// aerial perspective: fogged(x) = x T + K), becomes
//     c f + K (1 - f),  f = (ambient + sun x lambert x lit x visible) / (ambient + sun x lambert x lit),
// with lambert from the sample's normal and lit from the terrain's shadow
// ceiling texture (whose texels hold the sample heights), blended by
// dual-source blending (GL_ONE, GL_SRC1_COLOR). A pixel outside every
// object's shadow gets f = 1 and stays as it was, bit for bit.
#include "core/Camera.h"
#include "core/ScreenRect.h"
#include "gl/GlProgram.h"

#include <span>

namespace overflight::gl {

class RenderTarget;

class ShadowScreenPass {
public:
    static constexpr GLuint kUnit = 9; // the target's depth attachment

    // Darkens the pixels of `rects` (core rows; pairwise disjoint, as the
    // pass blends) of the offscreen `target` that lie in the objects'
    // shadows, reading the terrain's window depth from the target's depth
    // attachment, which must hold it within the rects (the objects not drawn
    // yet). Binds the target's color alone. Needs the frame block, the
    // terrain's shadow ceiling texture and an active ObjectShadowMap bound.
    // One instanced draw of a quad per rectangle: llvmpipe's cost is per
    // pixel covered.
    void draw(const RenderTarget& target, const Camera& camera, std::span<const PixelRect> rects);

private:
    Program program_;
    VertexArray vao_;
    Buffer rects_; // the rectangles, one ivec4 per instance
    GLsizeiptr capacity_ = 0;
};

} // namespace overflight::gl
