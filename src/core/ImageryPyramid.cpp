// Based on: Williams, "Pyramidal Parametrics" (SIGGRAPH 1983), sec. 2-3 (box
// filtered levels, level chosen from the pixel's footprint). See ImageryPyramid.h.
#include "core/ImageryPyramid.h"

#include "core/Parallel.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace overflight {

ImageryPyramid::ImageryPyramid(Image2D<Rgba8> level0, double x0, double z0, double extent_x, double extent_z)
    : x0_(x0), z0_(z0), extent_x_(extent_x), extent_z_(extent_z) {
    if (level0.width < 1 || level0.height < 1 ||
        level0.pixels.size() != std::size_t(level0.width) * std::size_t(level0.height))
        throw std::invalid_argument("imagery: empty or inconsistent level 0");
    if (!(extent_x > 0) || !(extent_z > 0) || !std::isfinite(extent_x) || !std::isfinite(extent_z) ||
        !std::isfinite(x0) || !std::isfinite(z0))
        throw std::invalid_argument("imagery: extent is not a positive finite rectangle");
    levels_.push_back(std::move(level0));
    rebuild_mips();
}

void ImageryPyramid::rebuild_mips() {
    levels_.resize(1);
    while (levels_.back().width > 1 || levels_.back().height > 1) levels_.push_back(box_filter_half(levels_.back()));
}

double ImageryPyramid::texel_size(int l) const { return std::max(texel_x(l), texel_z(l)); }

Rgba8 ImageryPyramid::nearest(double x, double z, int l) const {
    const Image2D<Rgba8>& img = level(l);
    const int col = std::clamp(int(std::floor((x - x0_) / texel_x(l))), 0, img.width - 1);
    const int row = std::clamp(int(std::floor((z - z0_) / texel_z(l))), 0, img.height - 1);
    return img.at(col, row);
}

Rgba8 ImageryPyramid::bilinear(double x, double z, int l) const {
    const Image2D<Rgba8>& img = level(l);
    // Texel centres sit at half-texel offsets.
    const double u = std::clamp((x - x0_) / texel_x(l) - 0.5, 0.0, double(img.width - 1));
    const double v = std::clamp((z - z0_) / texel_z(l) - 0.5, 0.0, double(img.height - 1));
    const int c0 = int(u), r0 = int(v);
    const int c1 = std::min(c0 + 1, img.width - 1), r1 = std::min(r0 + 1, img.height - 1);
    const double fu = u - c0, fv = v - r0;
    const Rgba8 p[4] = {img.at(c0, r0), img.at(c1, r0), img.at(c0, r1), img.at(c1, r1)};
    auto mix = [&](auto channel) {
        const double top = channel(p[0]) * (1 - fu) + channel(p[1]) * fu;
        const double bottom = channel(p[2]) * (1 - fu) + channel(p[3]) * fu;
        return std::uint8_t(std::lround(top * (1 - fv) + bottom * fv));
    };
    return Rgba8{mix([](Rgba8 t) { return double(t.r); }), mix([](Rgba8 t) { return double(t.g); }),
                 mix([](Rgba8 t) { return double(t.b); }), mix([](Rgba8 t) { return double(t.a); })};
}

double ImageryPyramid::coverage() const {
    if (levels_.empty()) return 0.0;
    double sum = 0;
    for (const Rgba8& t : levels_[0].pixels) sum += t.a;
    return sum / (255.0 * double(levels_[0].pixels.size()));
}

Image2D<Rgba8> box_filter_half(const Image2D<Rgba8>& src) {
    const int w = std::max(1, src.width / 2), h = std::max(1, src.height / 2);
    Image2D<Rgba8> out(w, h);
    parallel::for_each_index(0, h, [&](int row) {
        // Box rows [row * H / h, (row + 1) * H / h): two source rows, three
        // for the last one of an odd side, one when the side is 1.
        const int r0 = int(std::int64_t(row) * src.height / h), r1 = int(std::int64_t(row + 1) * src.height / h);
        for (int col = 0; col < w; ++col) {
            const int c0 = int(std::int64_t(col) * src.width / w), c1 = int(std::int64_t(col + 1) * src.width / w);
            unsigned sum[4] = {0, 0, 0, 0};
            for (int r = r0; r < r1; ++r)
                for (int c = c0; c < c1; ++c) {
                    const Rgba8 t = src.at(c, r);
                    sum[0] += t.r;
                    sum[1] += t.g;
                    sum[2] += t.b;
                    sum[3] += t.a;
                }
            const unsigned n = unsigned((r1 - r0) * (c1 - c0));
            out.at(col, row) = Rgba8{std::uint8_t((sum[0] + n / 2) / n), std::uint8_t((sum[1] + n / 2) / n),
                                     std::uint8_t((sum[2] + n / 2) / n), std::uint8_t((sum[3] + n / 2) / n)};
        }
    });
    return out;
}

int mip_level_for_footprint(double footprint, double texel_size, int levels) {
    if (levels <= 1 || !(footprint > texel_size) || !(texel_size > 0)) return 0;
    const double level = std::log2(footprint / texel_size);
    if (!std::isfinite(level)) return levels - 1;
    return std::clamp(int(std::lround(level)), 0, levels - 1);
}

} // namespace overflight
