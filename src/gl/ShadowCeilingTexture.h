#pragma once
// The terrain's shadow ceiling (core/HorizonSweep.h) as a float texture on
// texture unit 7, one texel per sample, read by sun_visible() (four texels,
// percentage-closer filtered) in shade() in
// every lit program (terrain meshes, block representations, objects), so
// that the mesh methods and the objects receive the same cast shadows as the
// ray casters' samples. A grid larger than the GL's largest texture is
// uploaded every k-th sample.
#include "core/HorizonSweep.h"
#include "core/ShadowPixels.h"
#include "gl/GlProgram.h"

#include <glm/vec4.hpp>

namespace overflight::gl {

class ShadowCeilingTexture {
public:
    static constexpr GLuint kUnit = 7; // `shadow_ceiling` in kFrameGlsl

    // Uploads `ceiling` of `terrain` (texels: ceiling - height, height) and binds it to kUnit.
    void upload(const ShadowCeiling& ceiling, const Terrain& terrain);
    // The samples of `terrain` its uploads hold (every k-th), as the frame
    // block's `shadow.y` scales world positions to them. Needs a GL context.
    static SnapGrid grid(const Terrain& terrain);
    // Binds the last upload to kUnit.
    void bind() const;
    // The `shadow` vector of the frame block for the last upload.
    glm::vec4 uniform() const { return uniform_; }

private:
    Texture texture_;
    int width_ = 0, height_ = 0;
    glm::vec4 uniform_{0.0f};
};

} // namespace overflight::gl
