// Based on: Szenberg et al. 1997 sec. 5 and 7 (color and Z-buffer load into OpenGL).
#include "gl/RenderTarget.h"

#include "core/Error.h"

#include <algorithm>
#include <cstring>
#include <string>

namespace overflight::gl {

namespace {

// Copies `rows` rows of `row_bytes` from src (rows `src_stride` bytes apart,
// default packed) to packed rows of dst in reverse order (core row 0 is the
// top, GL row 0 the bottom).
void copy_flipped(void* dst, const void* src, int rows, std::size_t row_bytes, std::size_t src_stride = 0) {
    auto* d = static_cast<std::uint8_t*>(dst);
    const auto* s = static_cast<const std::uint8_t*>(src);
    const std::size_t stride = src_stride ? src_stride : row_bytes;
    for (int r = 0; r < rows; ++r)
        std::memcpy(d + std::size_t(rows - 1 - r) * row_bytes, s + std::size_t(r) * stride, row_bytes);
}

} // namespace

RenderTarget::RenderTarget(int width, int height) : width_(width), height_(height) {
    if (width < 1 || height < 1) throw Error("opengl", "render target size must be positive");
    color_tex_ = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(color_tex_.get(), 1, GL_RGBA8, width, height);
    depth_tex_ = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(depth_tex_.get(), 1, GL_DEPTH_COMPONENT32F, width, height);
    for (GLuint t : {color_tex_.get(), depth_tex_.get()}) {
        glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    fbo_ = make_framebuffer();
    glNamedFramebufferTexture(fbo_.get(), GL_COLOR_ATTACHMENT0, color_tex_.get(), 0);
    glNamedFramebufferTexture(fbo_.get(), GL_DEPTH_ATTACHMENT, depth_tex_.get(), 0);
    const GLenum status = glCheckNamedFramebufferStatus(fbo_.get(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw Error("opengl", "framebuffer " + std::to_string(width) + "x" + std::to_string(height) +
                                  " is incomplete (status " + std::to_string(status) + ")");
    color_fbo_ = make_framebuffer();
    glNamedFramebufferTexture(color_fbo_.get(), GL_COLOR_ATTACHMENT0, color_tex_.get(), 0);
}

RenderTarget RenderTarget::default_framebuffer(int width, int height) {
    RenderTarget t;
    t.width_ = width;
    t.height_ = height;
    return t;
}

void RenderTarget::bind() const {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
    glViewport(0, 0, width_, height_);
}

void RenderTarget::load_color(GLuint buffer, std::size_t offset, GLenum format) {
    if (!offscreen()) throw Error("opengl", "color upload needs an offscreen target");
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, buffer);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage2D(color_tex_.get(), 0, 0, 0, width_, height_, format, GL_UNSIGNED_BYTE,
                        reinterpret_cast<const void*>(offset));
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
}

void RenderTarget::load_depth(GLuint buffer, std::size_t offset, const PixelRect& r, int terrain_row) {
    if (!offscreen()) throw Error("opengl", "depth upload needs an offscreen target");
    if (r.col0 < 0 || r.row0 < 0 || r.col1 > width_ || r.row1 > height_ || terrain_row < r.row0 ||
        terrain_row > r.row1)
        throw Error("opengl", "depth upload rectangle is outside the render target");
    if (r.empty()) return;
    const int w = r.col1 - r.col0;
    if (terrain_row > r.row0) {
        const float far = 1.0f;
        glClearTexSubImage(depth_tex_.get(), 0, r.col0, height_ - terrain_row, 0, w, terrain_row - r.row0, 1,
                           GL_DEPTH_COMPONENT, GL_FLOAT, &far);
    }
    const int rows = r.row1 - terrain_row;
    if (rows == 0) return;
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, buffer);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    // The ray caster's values are already GL window depth for the same camera
    // (Szenberg eq. 7), so they go straight into the depth attachment.
    glTextureSubImage2D(depth_tex_.get(), 0, r.col0, height_ - r.row1, w, rows, GL_DEPTH_COMPONENT, GL_FLOAT,
                        reinterpret_cast<const void*>(offset));
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
}

void RenderTarget::blit_color_to(const RenderTarget& dst) const {
    if (!offscreen()) throw Error("opengl", "a blit needs an offscreen source");
    glBlitNamedFramebuffer(fbo_.get(), dst.fbo_.get(), 0, 0, width_, height_, 0, 0, width_, height_,
                           GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

void RenderTarget::bind_color_only() const {
    if (!offscreen()) throw Error("opengl", "a color-only framebuffer needs an offscreen target");
    glBindFramebuffer(GL_FRAMEBUFFER, color_fbo_.get());
    glViewport(0, 0, width_, height_);
}

void RenderTarget::read_color(ColorImage& color) const {
    color.resize(width_, height_);
    const std::size_t row = std::size_t(width_) * 3;
    readback_.resize(row * std::size_t(height_));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_.get());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width_, height_, GL_RGB, GL_UNSIGNED_BYTE, readback_.data());
    copy_flipped(color.pixels.data(), readback_.data(), height_, row);
}

void RenderTarget::read_depth(DepthImage& depth) const {
    depth.resize(width_, height_);
    const std::size_t row = std::size_t(width_) * 4;
    readback_.resize(row * std::size_t(height_));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_.get());
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, width_, height_, GL_DEPTH_COMPONENT, GL_FLOAT, readback_.data());
    copy_flipped(depth.pixels.data(), readback_.data(), height_, row);
}

} // namespace overflight::gl
