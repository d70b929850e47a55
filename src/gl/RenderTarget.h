#pragma once
// Where a frame is drawn: an offscreen framebuffer of the camera's size with an
// RGBA8 color texture and a DEPTH32F depth texture (headless rendering and the
// compositing of Szenberg sec. 5), or a window's default framebuffer. Images
// cross the boundary in the core layout (row 0 at the top); GL keeps row 0 at
// the bottom, so every upload and read-back flips rows here and nowhere else.
//
// Based on: Szenberg et al. 1997 sec. 5 (Fig. 5: the ray caster's color and
// depth loaded into OpenGL, then objects drawn with the Z-buffer) and sec. 7,
// Table 1 (color buffer load, Z-buffer load); here through pixel buffer
// objects and glTextureSubImage2D instead of glDrawPixels, and a window is
// given the composite's color by a blit.
#include "core/Image.h"
#include "core/ScreenRect.h"
#include "gl/GlProgram.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace overflight::gl {

class RenderTarget {
public:
    // Offscreen target of width x height pixels. Throws Error("opengl", ...) if
    // the framebuffer is incomplete.
    RenderTarget(int width, int height);
    // The current context's default framebuffer (a window) of the given size.
    static RenderTarget default_framebuffer(int width, int height);

    int width() const { return width_; }
    int height() const { return height_; }
    bool offscreen() const { return bool(fbo_); }

    // Binds the target for drawing and sets the viewport to its size.
    void bind() const;

    // Loads the color / depth attachment (offscreen targets) from a
    // pixel-unpack buffer (gl/ImageStream.h) holding GL-order rows: the color
    // as packed 4-byte pixels of the whole image at `offset`, in `format`
    // (GL_RGBA or GL_BGRA, whichever the texture keeps: then a copy); the depth (window
    // depth, 1.0 = sky) as packed floats of the rows [terrain_row, rect.row1)
    // of `rect` (core rows, row 0 at the top) at `offset`, the rows of `rect`
    // above terrain_row cleared to 1.0 without a transfer, and the rest of the
    // attachment left as it was: a composite needs depth only where objects
    // can be drawn (ObjectRenderer::screen_rect).
    void load_color(GLuint buffer, std::size_t offset, GLenum format);
    void load_depth(GLuint buffer, std::size_t offset, const PixelRect& rect, int terrain_row);
    // Copies this offscreen target's color into `dst` (a window's default
    // framebuffer or another target of the same size): a blit, no shader, no
    // depth written.
    void blit_color_to(const RenderTarget& dst) const;
    // Offscreen targets: binds a framebuffer holding only the color
    // attachment (viewport set), so that a pass can sample depth_texture()
    // while it draws into the color.
    void bind_color_only() const;
    GLuint depth_texture() const { return depth_tex_.get(); }

    // Reads the attachments back into core images (resized to the target).
    void read_color(ColorImage& color) const;
    void read_depth(DepthImage& depth) const;

private:
    RenderTarget() = default;
    int width_ = 0, height_ = 0;
    Framebuffer fbo_;
    Framebuffer color_fbo_; // the color attachment alone
    Texture color_tex_, depth_tex_;
    mutable std::vector<std::uint8_t> readback_; // reused between frames (no per-frame allocation)
};

} // namespace overflight::gl
