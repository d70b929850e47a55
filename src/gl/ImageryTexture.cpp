// Based on: the OpenGL 4.5 core specification (DSA textures, mipmaps) and
// EXT_texture_filter_anisotropic. See ImageryTexture.h.
#include "gl/ImageryTexture.h"

#include <algorithm>

namespace overflight::gl {

void ImageryTexture::upload(const ImageryPyramid& imagery) {
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    int first = 0;
    while (first + 1 < imagery.levels() &&
           std::max(imagery.level(first).width, imagery.level(first).height) > max_size)
        ++first;
    const int levels = imagery.levels() - first;
    texture_ = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(texture_.get(), levels, GL_RGBA8, imagery.level(first).width, imagery.level(first).height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    for (int l = 0; l < levels; ++l) {
        const Image2D<Rgba8>& img = imagery.level(first + l);
        glTextureSubImage2D(texture_.get(), l, 0, 0, img.width, img.height, GL_RGBA, GL_UNSIGNED_BYTE, img.pixels.data());
    }
    glTextureParameteri(texture_.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(texture_.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture_.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture_.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    if (epoxy_has_gl_extension("GL_EXT_texture_filter_anisotropic")) {
        GLfloat most = 1.0f;
        glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY_EXT, &most);
        glTextureParameterf(texture_.get(), GL_TEXTURE_MAX_ANISOTROPY_EXT, std::min(most, 16.0f));
    }
    uniform_ = glm::vec4(float(1.0 / imagery.extent_x()), float(1.0 / imagery.extent_z()), float(imagery.x0()),
                         float(imagery.z0()));
    bind();
}

void ImageryTexture::bind() const {
    if (texture_.get()) glBindTextureUnit(kUnit, texture_.get());
}

} // namespace overflight::gl
