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

// The first row of `rect` at or below which `depth` holds terrain (a value
// below 1.0) within the rect's columns; rect.row1 when it is all sky.
int first_terrain_row(const DepthImage& depth, const PixelRect& rect) {
    for (int r = rect.row0; r < rect.row1; ++r) {
        const float* row = depth.pixels.data() + std::size_t(r) * std::size_t(depth.width);
        float nearest = 1.0f;
        for (int c = rect.col0; c < rect.col1; ++c) nearest = std::min(nearest, row[c]);
        if (nearest < 1.0f) return r;
    }
    return rect.row1;
}

const char* const kCopyVs = R"(
out vec2 uv;
void main() {
    // One triangle covering the viewport.
    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    uv = p;
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

const char* const kCopyFs = R"(
in vec2 uv;
layout(binding = 0) uniform sampler2D color_tex;
layout(binding = 1) uniform sampler2D depth_tex;
out vec4 frag;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    frag = texelFetch(color_tex, p, 0);
    gl_FragDepth = texelFetch(depth_tex, p, 0).r;
}
)";

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
    color_pbo_ = make_buffer();
    depth_pbo_ = make_buffer();
    glNamedBufferData(color_pbo_.get(), GLsizeiptr(width) * height * 3, nullptr, GL_STREAM_DRAW);
    glNamedBufferData(depth_pbo_.get(), GLsizeiptr(width) * height * 4, nullptr, GL_STREAM_DRAW);
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

void RenderTarget::upload_color(const ColorImage& color) {
    if (!offscreen()) throw Error("opengl", "color upload needs an offscreen target");
    if (color.width != width_ || color.height != height_)
        throw Error("opengl", "color image size does not match the render target");
    const std::size_t row = std::size_t(width_) * 3;
    // Invalidating the whole buffer lets the driver hand out fresh storage while
    // the previous frame's transfer may still be in flight.
    void* dst = glMapNamedBufferRange(color_pbo_.get(), 0, GLsizeiptr(row * height_),
                                      GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_BUFFER_BIT);
    if (!dst) throw Error("opengl", "cannot map the color pixel buffer");
    copy_flipped(dst, color.pixels.data(), height_, row);
    glUnmapNamedBuffer(color_pbo_.get());
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, color_pbo_.get());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(color_tex_.get(), 0, 0, 0, width_, height_, GL_RGB, GL_UNSIGNED_BYTE, nullptr);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
}

void RenderTarget::upload_depth(const DepthImage& depth, std::optional<PixelRect> rect) {
    if (!offscreen()) throw Error("opengl", "depth upload needs an offscreen target");
    if (depth.width != width_ || depth.height != height_)
        throw Error("opengl", "depth image size does not match the render target");
    const PixelRect r = rect.value_or(PixelRect{0, 0, width_, height_});
    if (r.col0 < 0 || r.row0 < 0 || r.col1 > width_ || r.row1 > height_)
        throw Error("opengl", "depth upload rectangle is outside the render target");
    if (r.empty()) return;
    const int w = r.col1 - r.col0;
    // Above the horizon the ray caster's depth is 1.0 everywhere: a clear
    // costs no transfer.
    const int terrain = first_terrain_row(depth, r);
    if (terrain > r.row0) {
        const float far = 1.0f;
        glClearTexSubImage(depth_tex_.get(), 0, r.col0, height_ - terrain, 0, w, terrain - r.row0, 1,
                           GL_DEPTH_COMPONENT, GL_FLOAT, &far);
    }
    const int rows = r.row1 - terrain;
    if (rows == 0) return;
    const std::size_t row_bytes = std::size_t(w) * 4;
    void* dst = glMapNamedBufferRange(depth_pbo_.get(), 0, GLsizeiptr(row_bytes * std::size_t(rows)),
                                      GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_BUFFER_BIT);
    if (!dst) throw Error("opengl", "cannot map the depth pixel buffer");
    copy_flipped(dst, depth.pixels.data() + std::size_t(terrain) * std::size_t(width_) + std::size_t(r.col0), rows,
                 row_bytes, std::size_t(width_) * 4);
    glUnmapNamedBuffer(depth_pbo_.get());
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, depth_pbo_.get());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    // The ray caster's values are already GL window depth for the same camera
    // (Szenberg eq. 7), so they go straight into the depth attachment.
    glTextureSubImage2D(depth_tex_.get(), 0, r.col0, height_ - r.row1, w, rows, GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
}

void RenderTarget::draw_from(const RenderTarget& src) const {
    if (!src.offscreen()) throw Error("opengl", "full-screen copy needs an offscreen source");
    if (!copy_) copy_ = make_program("fullscreen-copy", kCopyVs, kCopyFs);
    if (!copy_vao_) copy_vao_ = make_vertex_array();
    bind();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    glDepthMask(GL_TRUE);
    glUseProgram(copy_.get());
    glBindTextureUnit(0, src.color_tex_.get());
    glBindTextureUnit(1, src.depth_tex_.get());
    glBindVertexArray(copy_vao_.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDepthFunc(GL_LESS);
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
