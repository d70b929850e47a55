// See ImageryTexels.h.
#include "raycast/ImageryTexels.h"

namespace overflight {

void ImageryTexels::bind(const ImageryPyramid* pyramid) {
    pyramid_ = pyramid;
    levels_.clear();
    if (!pyramid) return;
    x0_ = float(pyramid->x0());
    z0_ = float(pyramid->z0());
    for (int l = 0; l < pyramid->levels(); ++l) {
        const Image2D<Rgba8>& img = pyramid->level(l);
        levels_.push_back(Level{img.pixels.data(), img.width, img.height, float(1.0 / pyramid->texel_x(l)),
                                float(1.0 / pyramid->texel_z(l))});
    }
}

void drape_column(const DrapeFrame& f, float dir_x, float dir_z, std::uint32_t* color, const std::uint32_t* slice,
                  int jend, std::ptrdiff_t row_stride) {
    int j = 0;
    while (j < jend) {
        const std::uint32_t k = slice[j * row_stride];
        int top = j + 1;
        while (top < jend && slice[top * row_stride] == k) ++top;
        const float dk = f.slice_d[k];
        const float d_prev = k > 0 ? f.slice_d[k - 1] : f.d_before_first;
        const float m_top = f.row_m[top - 1];
        const int level = f.imagery->slice_level(int(k));
        for (; j < top; ++j) {
            const float m = f.row_m[j];
            // Rays looking down meet the sample's height in front of slice k; others hit its face at d_k.
            const float d = m_top < 0.0f && m < 0.0f ? std::clamp(dk * (m_top / m), d_prev, dk) : dk;
            std::uint32_t& c = color[j * row_stride];
            c = modulate_light(c, f.imagery->at(f.eye_x + d * dir_x, f.eye_z + d * dir_z, level));
        }
    }
}

void ImageryTexels::prepare_slices(const float* slice_d, int slices, double focal_px) {
    slice_level_.resize(std::size_t(std::max(slices, 0)));
    if (!pyramid_) return;
    const double texel = pyramid_->texel_size(0);
    for (int k = 0; k < slices; ++k)
        slice_level_[std::size_t(k)] =
            std::uint8_t(mip_level_for_footprint(double(slice_d[k]) / focal_px, texel, pyramid_->levels()));
}

} // namespace overflight
