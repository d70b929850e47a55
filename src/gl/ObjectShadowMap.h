#pragma once
// The objects' cast shadows: a depth map of the scene's objects seen from the
// sun (orthographic, fitted to the objects' bounds), read by
// object_sun_visible() in shade() (kFrameGlsl), so that every lit program
// (terrain meshes, block representations, objects) darkens what lies behind
// an object from the sun; the ray casters' images get the same through
// ShadowScreenPass. Rendered again only when the sun moves.
//
// Based on: L. Williams, "Casting Curved Shadows on Curved Surfaces"
// (SIGGRAPH 1978): a point is in shadow iff it lies farther from the light
// than the depth the light's view stores at its position; the comparison is
// filtered over the 2x2 nearest texels (percentage-closer filtering: Reeves,
// Salesin, Cook, SIGGRAPH 1987).
#include "core/ScreenRect.h"
#include "gl/FrameUniforms.h"
#include "gl/GlProgram.h"
#include "gl/ObjectRenderer.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <vector>

namespace overflight::gl {

// std140 mirror of the GLSL block ObjectShadow (binding 3) in kFrameGlsl.
struct ObjectShadowBlock {
    glm::mat4 sun_proj{1.0f}; // multiplies (world - origin): clip space of the sun's view
    glm::vec4 origin{0.0f};
    glm::vec4 params{0.0f};   // x: 1 = objects cast shadows; y: depth bias (window depth units)
};

class ObjectShadowMap {
public:
    static constexpr GLuint kUnit = 8;    // `object_shadow_map` in kFrameGlsl
    static constexpr GLuint kBinding = 3; // uniform block ObjectShadow
    static constexpr int kSize = 2048;    // texels per side

    ObjectShadowMap();

    // Makes the map current for a frame: with `on` and a sun above the
    // horizon, renders `objects` from the sun `sun_dir` (unit) when the sun
    // moved since the last render (`frame`: the frame's block, whose view the
    // pass replaces by the sun's); otherwise turns the objects' shadows off.
    // Leaves the sun's framebuffer bound: the caller binds its target next.
    void update(bool on, const glm::vec3& sun_dir, const ObjectRenderer& objects, const FrameBlock& frame);
    // Binds the block to kBinding and the map to kUnit.
    void bind() const;
    bool active() const { return block_.params.x > 0.0f; }
    const ObjectShadowBlock& block() const { return block_; }

    // The world boxes that hold every point an object's shadow may fall on:
    // each of `objects` extended along the sun's rays down to `floor`.
    static std::vector<WorldBox> reach(const std::vector<WorldBox>& objects, const glm::vec3& sun_dir, float floor);

private:
    Texture depth_;
    Framebuffer fbo_;
    Buffer ubo_, pass_frame_;
    ObjectShadowBlock block_;
    bool rendered_ = false;
    glm::vec3 rendered_for_{0.0f};
};

} // namespace overflight::gl
