// Based on: Szenberg et al. 1997 sec. 5 and 7; Hrabcak and Masserann, OpenGL
// Insights ch. 28. See ImageStream.h.
#include "gl/ImageStream.h"

#include "core/Error.h"
#include "gl/RenderTarget.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>

namespace overflight::gl {

namespace {

// Copies `rows` rows of `row_bytes` from src (rows `src_stride` bytes apart)
// to packed rows of dst in reverse order (core row 0 is the top, GL row 0 the
// bottom).
void copy_flipped(void* dst, const void* src, int rows, std::size_t row_bytes, std::size_t src_stride) {
    auto* d = static_cast<std::uint8_t*>(dst);
    const auto* s = static_cast<const std::uint8_t*>(src);
    for (int r = 0; r < rows; ++r)
        std::memcpy(d + std::size_t(rows - 1 - r) * row_bytes, s + std::size_t(r) * src_stride, row_bytes);
}

static_assert(std::endian::native == std::endian::little, "pixels are composed as little-endian words");

// Widens the RGB rows of `color` to 4-byte pixels (red at byte 0 or, with
// kBgra, at byte 2; alpha 255) into packed rows of dst in reverse order, a
// whole 32-bit word per pixel (a mapped buffer may be write-combined).
template <bool kBgra>
void copy_flipped_wide(void* dst, const ColorImage& color) {
    const int w = color.width, h = color.height;
    auto* d = static_cast<std::uint8_t*>(dst);
    for (int row = 0; row < h; ++row) {
        const Rgb8* s = color.pixels.data() + std::size_t(row) * std::size_t(w);
        std::uint8_t* o = d + std::size_t(h - 1 - row) * std::size_t(w) * 4;
        for (int c = 0; c < w; ++c) {
            const std::uint32_t r = s[c].r, g = s[c].g, b = s[c].b;
            const std::uint32_t word = (kBgra ? b | r << 16 : r | b << 16) | g << 8 | 0xff000000u;
            std::memcpy(o + std::size_t(c) * 4, &word, 4); // little-endian: byte 0 first
        }
    }
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

// Waits for a fence and deletes it (1 s per wait, until it is signalled).
void wait_and_delete(GLsync& fence) {
    if (!fence) return;
    while (glClientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, 1'000'000'000) == GL_TIMEOUT_EXPIRED) {
    }
    glDeleteSync(fence);
    fence = nullptr;
}

} // namespace

ImageStream::~ImageStream() { release(); }

void ImageStream::release() {
    for (Slot& s : slots_) {
        wait_and_delete(s.fence);
        if (s.buffer) glUnmapNamedBuffer(s.buffer.get());
        s.buffer.reset();
        s.mapped = nullptr;
    }
}

void ImageStream::reserve(int width, int height) {
    if (width == width_ && height == height_ && slots_[0].buffer) return;
    if (width < 1 || height < 1) throw Error("opengl", "image stream size must be positive");
    release();
    width_ = width;
    height_ = height;
    // The byte order GL keeps an RGBA8 texture in: loads in it are copies.
    GLint order = GL_RGBA;
    glGetInternalformativ(GL_TEXTURE_2D, GL_RGBA8, GL_TEXTURE_IMAGE_FORMAT, 1, &order);
    color_format_ = order == GL_BGRA ? GL_BGRA : GL_RGBA;
    // The depth after the color (4-aligned for its floats, as 4-byte pixels are).
    color_bytes_ = std::size_t(width) * std::size_t(height) * 4;
    const std::size_t bytes = color_bytes_ + std::size_t(width) * std::size_t(height) * 4;
    const GLbitfield flags = GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
    for (Slot& s : slots_) {
        s.buffer = make_buffer();
        glNamedBufferStorage(s.buffer.get(), GLsizeiptr(bytes), nullptr, flags);
        s.mapped = glMapNamedBufferRange(s.buffer.get(), 0, GLsizeiptr(bytes), flags);
        if (!s.mapped) throw Error("opengl", "cannot map a pixel buffer persistently");
        s.depth_rect = {};
        s.terrain_row = 0;
    }
}

void ImageStream::acquire(int slot) { wait_and_delete(slots_.at(std::size_t(slot)).fence); }

void ImageStream::fence(Slot& s) {
    if (s.fence) glDeleteSync(s.fence);
    s.fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
}

void ImageStream::stage_color(int slot, const ColorImage& color) {
    Slot& s = slots_.at(std::size_t(slot));
    if (color.width != width_ || color.height != height_ || !s.mapped)
        throw Error("opengl", "color image size does not match the image stream");
    if (color_format_ == GL_BGRA) copy_flipped_wide<true>(s.mapped, color);
    else copy_flipped_wide<false>(s.mapped, color);
}

void ImageStream::stage_depth(int slot, const DepthImage& depth, const PixelRect& rect) {
    Slot& s = slots_.at(std::size_t(slot));
    if (depth.width != width_ || depth.height != height_ || !s.mapped)
        throw Error("opengl", "depth image size does not match the image stream");
    if (rect.col0 < 0 || rect.row0 < 0 || rect.col1 > width_ || rect.row1 > height_)
        throw Error("opengl", "depth upload rectangle is outside the image");
    s.depth_rect = rect;
    if (rect.empty()) return;
    // Above the horizon the ray caster's depth is 1.0 everywhere: a clear
    // costs no transfer.
    s.terrain_row = first_terrain_row(depth, rect);
    const int rows = rect.row1 - s.terrain_row;
    const std::size_t row_bytes = std::size_t(rect.col1 - rect.col0) * 4;
    copy_flipped(static_cast<std::uint8_t*>(s.mapped) + color_bytes_,
                 depth.pixels.data() + std::size_t(s.terrain_row) * std::size_t(width_) + std::size_t(rect.col0), rows,
                 row_bytes, std::size_t(width_) * 4);
}

void ImageStream::load_color(int slot, RenderTarget& target) {
    Slot& s = slots_.at(std::size_t(slot));
    target.load_color(s.buffer.get(), 0, color_format_);
    fence(s);
}

void ImageStream::load_depth(int slot, RenderTarget& target) {
    Slot& s = slots_.at(std::size_t(slot));
    if (s.depth_rect.empty()) return;
    target.load_depth(s.buffer.get(), color_bytes_, s.depth_rect, s.terrain_row);
    fence(s);
}

} // namespace overflight::gl
