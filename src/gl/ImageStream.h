#pragma once
// The ray casters' color and depth images on their way into a RenderTarget:
// pixel-unpack buffers mapped once, persistently and coherently
// (ARB_buffer_storage), in kSlots slots. The CPU half of a load (copying the
// image into a slot, flipping rows) calls no GL and may run on any thread, so
// that a flight casts and stages frame N+1 while the GL thread loads and
// draws frame N from the other slot; the GL half (glTextureSubImage2D from
// the slot) then only hands the driver a buffer it already owns. A fence
// after each load tells when GL has read a slot, so a slot is never
// rewritten while a transfer from it may still be in flight, and nothing is
// mapped, orphaned or reallocated per frame.
//
// The color is staged as 4 bytes per pixel in the order GL stores the
// target's RGBA8 texture (GL_TEXTURE_IMAGE_FORMAT: RGBA or BGRA), alpha 255,
// so that the load is a copy: a 3-byte RGB load made GL widen every pixel on
// the GL thread, where staging widens it beside the cast.
//
// What a slot keeps of the depth: only the rows of a rectangle (where objects
// can be depth-tested, Szenberg et al. 1997 sec. 5 and Table 1 "Z-buffer
// load") from its topmost row holding terrain down; the rows above it are sky
// (window depth 1.0) and are cleared in the target without a transfer.
//
// Based on: Szenberg et al. 1997 sec. 5 and 7 (color and Z-buffer load);
// Hrabcak and Masserann, "Asynchronous Buffer Transfers", OpenGL Insights
// (2012) ch. 28 (persistent, fenced, multi-buffered pixel transfers).
#include "core/Image.h"
#include "core/ScreenRect.h"
#include "gl/GlProgram.h"

#include <array>
#include <cstddef>

namespace overflight::gl {

class RenderTarget;

class ImageStream {
public:
    static constexpr int kSlots = 2;

    ImageStream() = default;
    ~ImageStream();
    ImageStream(const ImageStream&) = delete;
    ImageStream& operator=(const ImageStream&) = delete;

    // GL thread. Gives every slot room for width x height images (storage is
    // recreated, after GL has finished with the old one, when the size
    // changes; staged contents are then lost).
    void reserve(int width, int height);
    int width() const { return width_; }
    int height() const { return height_; }

    // GL thread: waits until GL has read the slot's last load, so that it can
    // be staged again.
    void acquire(int slot);

    // Any thread, no GL: copies an image of the reserved size into the slot,
    // between acquire(slot) and the load from it. `rect` (core rows, row 0 at
    // the top, inside the image) is the part of the depth to be loaded.
    // Throws Error("opengl", ...) for a size that is not the reserved one.
    void stage_color(int slot, const ColorImage& color);
    void stage_depth(int slot, const DepthImage& depth, const PixelRect& rect);

    // GL thread: loads what the slot holds into `target` (offscreen, of the
    // reserved size): the color, and the depth of the staged rectangle (the
    // rest of the depth attachment is left as it was). Each fences the slot.
    void load_color(int slot, RenderTarget& target);
    void load_depth(int slot, RenderTarget& target);

private:
    struct Slot {
        Buffer buffer;             // color bytes, then depth floats
        void* mapped = nullptr;    // persistent, coherent write mapping
        GLsync fence = nullptr;    // after the last load from the slot
        PixelRect depth_rect;      // staged depth rectangle
        int terrain_row = 0;       // its first row holding terrain (rows above: sky)
    };
    void release();
    void fence(Slot& s);

    int width_ = 0, height_ = 0;
    GLenum color_format_ = GL_RGBA; // the staged color's byte order (reserve())
    std::size_t color_bytes_ = 0;
    std::array<Slot, kSlots> slots_;
};

} // namespace overflight::gl
