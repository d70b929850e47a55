#pragma once
// The terrain's imagery (core/ImageryPyramid.h) as a mipmapped RGBA texture
// on texture unit 6, read by terrain_albedo() in shade() for every terrain
// fragment (mesh, ROAM, quadtree, the block representations) at its world
// (x, z): trilinear between the core's box-filtered levels, anisotropic
// where the GL offers GL_EXT_texture_filter_anisotropic. Only uploads: the
// levels and the fallback colors where the source does not cover the
// terrain are the core's (ImageryFallback.h). Levels wider than the GL's
// largest texture are left out (the texture starts at the first that fits).
#include "core/ImageryPyramid.h"
#include "gl/GlProgram.h"

#include <glm/vec4.hpp>

namespace overflight::gl {

class ImageryTexture {
public:
    static constexpr GLuint kUnit = 10; // `imagery_texture` in kFrameGlsl

    // Uploads every level of `imagery` and binds it to kUnit.
    void upload(const ImageryPyramid& imagery);
    // Binds the upload to kUnit (nothing without one).
    void bind() const;
    // The `imagery` vector of the frame block: 1 / extent x and z, origin x
    // and z of the texture's world rectangle; 0 without an upload.
    glm::vec4 uniform() const { return uniform_; }

private:
    Texture texture_;
    glm::vec4 uniform_{0.0f};
};

} // namespace overflight::gl
