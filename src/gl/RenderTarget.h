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
// objects and glTextureSubImage2D instead of glDrawPixels.
#include "core/Image.h"
#include "core/ScreenRect.h"
#include "gl/GlProgram.h"

#include <cstdint>
#include <optional>
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

    // Copies a core image into the color / depth attachment (through a PBO).
    // The image must have the target's size; depth is window depth, 1.0 = sky.
    // Offscreen targets only: a window target draws the images with a
    // full-screen pass writing gl_FragDepth instead (upload_fullscreen).
    // upload_depth loads only the pixels of `rect` (core rows, row 0 at the
    // top; default the whole image) and leaves the rest of the attachment as
    // it was: a composite needs depth only where objects can be drawn
    // (ObjectRenderer::screen_rect). Within the rect, the rows above the
    // topmost one holding terrain are cleared to 1.0 without a transfer.
    void upload_color(const ColorImage& color);
    void upload_depth(const DepthImage& depth, std::optional<PixelRect> rect = std::nullopt);
    // Window targets (or any target): draws previously uploaded textures of an
    // offscreen target `src` into this target's color and depth (gl_FragDepth).
    void draw_from(const RenderTarget& src) const;

    // Reads the attachments back into core images (resized to the target).
    void read_color(ColorImage& color) const;
    void read_depth(DepthImage& depth) const;

private:
    RenderTarget() = default;
    int width_ = 0, height_ = 0;
    Framebuffer fbo_;
    Texture color_tex_, depth_tex_;
    Buffer color_pbo_, depth_pbo_;
    mutable Program copy_;        // full-screen gl_FragDepth pass, built on first use
    mutable VertexArray copy_vao_;
    mutable std::vector<std::uint8_t> readback_; // reused between frames (no per-frame allocation)
};

} // namespace overflight::gl
