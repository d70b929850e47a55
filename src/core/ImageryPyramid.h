#pragma once
// An orthophoto kept at its own resolution over a terrain (DESIGN sec. 1
// coordinates), as a mip pyramid: level 0 is the imagery as warped onto the
// terrain's extent, each further level halves both sides by a box filter, as
// Williams' mip map ("Pyramidal Parametrics", SIGGRAPH 1983, sec. 2) and
// OpenGL's glGenerateMipmap do. Every texel carries a coverage alpha (0:
// outside the source raster or on its no-data).
//
// Registration: level 0's width x height texels tile the world rectangle
// X in [x0, x0 + extent_x], Z in [z0, z0 + extent_z] (row 0 at Z = z0, the
// north edge), so texels per terrain cell may be any real number. A terrain
// loaded from a raster has its samples at the raster's pixel centres, so its
// imagery covers [-hs/2, width + hs/2] x [-hs/2, depth + hs/2]. Level l has
// max(1, w_{l-1} / 2) x max(1, h_{l-1} / 2) texels over the same rectangle
// (an odd side folds its last texel into the last box), down to 1 x 1.
//
// No GL, no file I/O: src/io builds level 0, the GL layer uploads the levels.
#include "core/Image.h"

#include <cstdint>
#include <vector>

namespace overflight {

struct Rgba8 {
    std::uint8_t r = 0, g = 0, b = 0, a = 0;
    friend bool operator==(const Rgba8&, const Rgba8&) = default;
};

class ImageryPyramid {
public:
    ImageryPyramid() = default;
    // Builds every level from `level0` (at least 1 x 1 with width * height
    // texels; throws std::invalid_argument otherwise or for an extent that is
    // not a positive finite number). Parallel over rows.
    ImageryPyramid(Image2D<Rgba8> level0, double x0, double z0, double extent_x, double extent_z);

    bool empty() const { return levels_.empty(); }
    int levels() const { return int(levels_.size()); }
    const Image2D<Rgba8>& level(int l) const { return levels_[std::size_t(l)]; }
    Image2D<Rgba8>& level(int l) { return levels_[std::size_t(l)]; }

    double x0() const { return x0_; }
    double z0() const { return z0_; }
    double extent_x() const { return extent_x_; }
    double extent_z() const { return extent_z_; }
    // World units per texel of level l along X and Z, and the larger of the
    // two (the footprint a mip level is chosen against).
    double texel_x(int l) const { return extent_x_ / double(level(l).width); }
    double texel_z(int l) const { return extent_z_ / double(level(l).height); }
    double texel_size(int l = 0) const;

    // The texel of level l whose square contains world (x, z), clamped to the
    // pyramid's edge.
    Rgba8 nearest(double x, double z, int l) const;
    // Bilinear between the four texel centres around (x, z) at level l,
    // clamped to the edge, rounded to 8 bits.
    Rgba8 bilinear(double x, double z, int l) const;

    // Share of level 0 covered by the source: mean alpha / 255.
    double coverage() const;

    // Recomputes levels 1.. from level 0 (after level 0 changed).
    void rebuild_mips();

private:
    std::vector<Image2D<Rgba8>> levels_;
    double x0_ = 0, z0_ = 0, extent_x_ = 1, extent_z_ = 1;
};

// The next level of a pyramid: max(1, w / 2) x max(1, h / 2) texels, each the
// rounded mean of its box of source texels (all four channels).
Image2D<Rgba8> box_filter_half(const Image2D<Rgba8>& level);

// The mip level whose texels match a pixel's footprint: log2(footprint /
// texel_size) rounded to the nearest level, clamped to [0, levels - 1];
// footprint the world size a pixel covers at its distance (distance /
// focal length in pixels, Camera::focal_px), texel_size level 0's.
int mip_level_for_footprint(double footprint, double texel_size, int levels);

} // namespace overflight
