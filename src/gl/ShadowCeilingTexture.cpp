// Based on: the OpenGL 4.5 core specification (DSA textures). See ShadowCeilingTexture.h.
#include "gl/ShadowCeilingTexture.h"

#include <glm/vec2.hpp>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <vector>

namespace overflight::gl {

namespace {

int stride(int rows, int cols) {
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    return std::max({1, (cols + max_size - 1) / max_size, (rows + max_size - 1) / max_size});
}

float texels_per_unit(const Terrain& t, int k) { return 1.0f / (t.h_scale() * float(k)); }

} // namespace

SnapGrid ShadowCeilingTexture::grid(const Terrain& t) {
    const int k = stride(t.rows(), t.cols());
    return {&t, k, texels_per_unit(t, k)};
}

void ShadowCeilingTexture::upload(const ShadowCeiling& c, const Terrain& t) {
    const int k = stride(c.rows, c.cols);
    const int w = (c.cols - 1) / k + 1, h = (c.rows - 1) / k + 1;
    std::vector<glm::vec2> texels(std::size_t(w) * std::size_t(h));
    tbb::parallel_for(0, h, [&](int r) {
        for (int col = 0; col < w; ++col) {
            const float y = t.sample_height(r * k, col * k);
            texels[std::size_t(r) * std::size_t(w) + std::size_t(col)] = glm::vec2(c.at(r * k, col * k) - y, y);
        }
    });
    if (!texture_.get() || w != width_ || h != height_) {
        texture_ = make_texture(GL_TEXTURE_2D);
        glTextureStorage2D(texture_.get(), 1, GL_RG32F, w, h);
        glTextureParameteri(texture_.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(texture_.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTextureParameteri(texture_.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(texture_.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        width_ = w;
        height_ = h;
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage2D(texture_.get(), 0, 0, 0, w, h, GL_RG, GL_FLOAT, texels.data());
    uniform_ = glm::vec4(1.0f, texels_per_unit(t, k), 0.0f, 0.0f);
    bind();
}

void ShadowCeilingTexture::bind() const {
    if (texture_.get()) glBindTextureUnit(kUnit, texture_.get());
}

} // namespace overflight::gl
