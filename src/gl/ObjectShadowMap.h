#pragma once
// The objects' cast shadows: a depth map of the scene's objects seen from the
// sun (orthographic, fitted to the objects' bounds), read by
// object_sun_visible() in shade() (kFrameGlsl), so that every lit program
// (terrain meshes, block representations, objects) darkens what lies behind
// an object from the sun; the ray casters' images get the same through
// ShadowScreenPass. Rendered again only when the sun moves or what casts
// changed. Two maps are kept (gl/Compositor.h): the scene's objects' (unit
// 8, block 3, rendered when the sun moves) and the vehicle's (unit 11, block
// 4, fitted to the vehicle alone and rendered whenever it moved), so that a
// 5 m hovercraft anywhere on the terrain gets texels of centimetres instead
// of one map stretched from the objects to wherever it flies.
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

// std140 mirror of the GLSL blocks ObjectShadow (binding 3) and VehicleShadow
// (binding 4) in kFrameGlsl.
struct ObjectShadowBlock {
    glm::mat4 sun_proj{1.0f}; // multiplies (world - origin): clip space of the sun's view
    glm::vec4 origin{0.0f};
    glm::vec4 params{0.0f};   // x: 1 = objects cast shadows; y: depth bias (window depth units)
};

class ObjectShadowMap {
public:
    // The scene's objects: `object_shadow_map`, block ObjectShadow in kFrameGlsl.
    static constexpr GLuint kUnit = 8, kBinding = 3;
    static constexpr int kSize = 2048; // texels per side
    // The vehicle: `vehicle_shadow_map`, block VehicleShadow in kFrameGlsl.
    static constexpr GLuint kVehicleUnit = 11, kVehicleBinding = 4;
    static constexpr int kVehicleSize = 512;

    // A map of `size` texels per side read through texture unit `unit` and
    // uniform block binding `binding`.
    ObjectShadowMap(GLuint unit = kUnit, GLuint binding = kBinding, int size = kSize);

    // Makes the map current for a frame: with `on` and a sun above the
    // horizon, renders what `draw` draws (with depth test on, the Frame
    // block bound), which lies inside `boxes`, from the sun `sun_dir` (unit)
    // when the sun moved since the last render or `changed` (`frame`: the
    // frame's block, whose view the pass replaces by the sun's); otherwise
    // (also with no boxes) turns these shadows off. May leave the sun's
    // framebuffer bound: the caller binds its target next.
    template <class Draw>
    void update(bool on, const glm::vec3& sun_dir, const std::vector<WorldBox>& boxes, bool changed, Draw&& draw,
                const FrameBlock& frame) {
        if (begin_pass(on, sun_dir, boxes, changed, frame)) {
            draw();
            end_pass(sun_dir);
        }
    }
    // The scene's objects, rendered when the sun moves.
    void update(bool on, const glm::vec3& sun_dir, const ObjectRenderer& objects, const FrameBlock& frame) {
        update(on, sun_dir, objects.bounds(), false, [&] { objects.draw(); }, frame);
    }
    // Binds the block to its binding and the map to its unit.
    void bind() const;
    bool active() const { return block_.params.x > 0.0f; }
    const ObjectShadowBlock& block() const { return block_; }

    // The world boxes that hold every point an object's shadow may fall on:
    // each of `objects` extended along the sun's rays down to `floor`.
    static std::vector<WorldBox> reach(const std::vector<WorldBox>& objects, const glm::vec3& sun_dir, float floor);
    // A world length no texel of a map of `size` texels fitted to `boxes`
    // exceeds, whatever the sun: the filtered lookup reads the texels within
    // one of a point, so a shadow reaches that far past its caster's bounds.
    static float texel_bound(const std::vector<WorldBox>& boxes, int size);

private:
    // Whether to draw into the map now (its framebuffer bound, its own
    // shadows off); turns the shadows off or on as `update` says.
    bool begin_pass(bool on, const glm::vec3& sun_dir, const std::vector<WorldBox>& boxes, bool changed,
                    const FrameBlock& frame);
    void end_pass(const glm::vec3& sun_dir);

    GLuint unit_, binding_;
    int size_;
    Texture depth_;
    Framebuffer fbo_;
    Buffer ubo_, pass_frame_, off_ubo_;
    ObjectShadowBlock block_;
    bool rendered_ = false;
    glm::vec3 rendered_for_{0.0f};
};

} // namespace overflight::gl
