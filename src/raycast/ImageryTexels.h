#pragma once
// The imagery (core/ImageryPyramid.h) as the ray casters read it: the albedo
// of a painted sample is the texel under the sample's exact ground position
// (x, z of the ray at its slice, not the cell's corner) on the mip level of
// the pixel's footprint there (Williams, "Pyramidal Parametrics", SIGGRAPH
// 1983, sec. 3: level = log2(footprint / texel)), nearest texel at that level.
// The footprint is the world size of a pixel at view depth d, d / fp (fp the
// focal length in pixels): the level is one per slice for the whole frame.
//
// With imagery, the casts paint the light of each sample instead of its
// color (core/SunLight.h, LightOutput::Light: 128 is a light of 1), and the
// albedo multiplies it here, before fog or aerial perspective: the sun, the
// shadows and the atmosphere stay as they are without imagery.
#include "core/ImageryPyramid.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace overflight {

class ImageryTexels {
public:
    // The pyramid to read (it must outlive its use); null: none.
    void bind(const ImageryPyramid* pyramid);
    bool bound() const { return pyramid_ != nullptr; }

    // The mip level of every slice from its view depth slice_d[k], for a
    // camera of focal length focal_px (pixels).
    void prepare_slices(const float* slice_d, int slices, double focal_px);
    int slice_level(int k) const { return slice_level_[std::size_t(k)]; }

    // The texel of `level` under world (x, z), clamped to the imagery's edge.
    Rgba8 at(float x, float z, int level) const {
        const Level& l = levels_[std::size_t(level)];
        const int col = std::clamp(int((x - x0_) * l.inv_x), 0, l.w - 1);
        const int row = std::clamp(int((z - z0_) * l.inv_z), 0, l.h - 1);
        return l.texels[std::size_t(row) * std::size_t(l.w) + std::size_t(col)];
    }

private:
    struct Level {
        const Rgba8* texels = nullptr;
        int w = 1, h = 1;
        float inv_x = 1, inv_z = 1; // texels per world unit
    };
    const ImageryPyramid* pyramid_ = nullptr;
    std::vector<Level> levels_;
    float x0_ = 0, z0_ = 0;
    std::vector<std::uint8_t> slice_level_;
};

// One cast column of a floating horizon over vertical planes, as the cast
// left it: pixel j (bottom-up) at color[j * row_stride], painted from slice
// slice[j * row_stride] while j < jend. Each painted pixel's light becomes
// light x the texel under the point where its ray meets the surface: a run
// of rows painted by the sample of slice k, whose top row's ray passes
// (within a pixel) over the sample's height, sees that height at view depth
// d_k m_top / m_j along row j's ray (slope m_j per unit view depth, negative
// downwards), clamped to [d_{k-1}, d_k], the cell the sample stands for;
// the point is eye + d (dir_x, dir_z), dir the plane's horizontal direction
// per unit view depth. Without that clamp every row of the run would show
// the texel at slice k, stretching one texel over a cell's depth.
struct DrapeFrame {
    const ImageryTexels* imagery = nullptr;
    const float* slice_d = nullptr; // view depth of slice k
    float d_before_first = 0;       // the view depth before slice 0 (the near plane)
    const float* row_m = nullptr;   // slope of row j, bottom-up
    float eye_x = 0, eye_z = 0;
};
void drape_column(const DrapeFrame& f, float dir_x, float dir_z, std::uint32_t* color, const std::uint32_t* slice,
                  int jend, std::ptrdiff_t row_stride);

// light (128 = 1) x albedo per channel, rounded, clamped to 255.
inline Rgb8 modulate_light(Rgb8 light, Rgba8 albedo) {
    auto m = [](unsigned l, unsigned a) { return std::uint8_t(std::min<unsigned>((l * a + 64) >> 7, 255)); };
    return Rgb8{m(light.r, albedo.r), m(light.g, albedo.g), m(light.b, albedo.b)};
}

// light (packed 0x00BBGGRR, 128 = 1, up to 255) x albedo, rounded, clamped to 255.
inline std::uint32_t modulate_light(std::uint32_t light, Rgba8 albedo) {
    const std::uint32_t r = std::min<std::uint32_t>(((light & 0xFFu) * albedo.r + 64) >> 7, 255);
    const std::uint32_t g = std::min<std::uint32_t>((((light >> 8) & 0xFFu) * albedo.g + 64) >> 7, 255);
    const std::uint32_t b = std::min<std::uint32_t>((((light >> 16) & 0xFFu) * albedo.b + 64) >> 7, 255);
    return r | (g << 8) | (b << 16);
}

} // namespace overflight
