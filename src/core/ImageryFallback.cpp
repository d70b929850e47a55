// See ImageryFallback.h.
#include "core/ImageryFallback.h"

#include "core/Parallel.h"

#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace overflight {

namespace {

// The terrain's color bilinear at world (x, z), clamped to the grid.
glm::vec3 terrain_color(const Terrain& t, double x, double z) {
    const double u = std::clamp(x / t.h_scale(), 0.0, double(t.cols() - 1));
    const double v = std::clamp(z / t.h_scale(), 0.0, double(t.rows() - 1));
    const int c0 = std::min(int(u), t.cols() - 2), r0 = std::min(int(v), t.rows() - 2);
    const float fu = float(u - c0), fv = float(v - r0);
    auto rgb = [&](int r, int c) {
        const Rgb8 p = t.color(r, c);
        return glm::vec3(p.r, p.g, p.b);
    };
    return (rgb(r0, c0) * (1 - fu) + rgb(r0, c0 + 1) * fu) * (1 - fv) +
           (rgb(r0 + 1, c0) * (1 - fu) + rgb(r0 + 1, c0 + 1) * fu) * fv;
}

// Summed-area table of the alphas, (w + 1) x (h + 1).
std::vector<std::int64_t> alpha_sums(const Image2D<Rgba8>& img) {
    const std::size_t w1 = std::size_t(img.width) + 1;
    std::vector<std::int64_t> s(w1 * (std::size_t(img.height) + 1), 0);
    for (int r = 0; r < img.height; ++r) {
        std::int64_t row = 0;
        for (int c = 0; c < img.width; ++c) {
            row += img.at(c, r).a;
            s[std::size_t(r + 1) * w1 + std::size_t(c + 1)] = s[std::size_t(r) * w1 + std::size_t(c + 1)] + row;
        }
    }
    return s;
}

} // namespace

void blend_over_terrain_colors(ImageryPyramid& imagery, const Terrain& terrain, int feather) {
    Image2D<Rgba8>& img = imagery.level(0);
    const std::vector<std::int64_t> sums = alpha_sums(img);
    const std::size_t w1 = std::size_t(img.width) + 1;
    const double tx = imagery.texel_x(0), tz = imagery.texel_z(0);
    parallel::for_each_index(0, img.height, [&](int row) {
        const int r0 = std::max(row - feather, 0), r1 = std::min(row + feather + 1, img.height);
        for (int col = 0; col < img.width; ++col) {
            Rgba8& t = img.at(col, row);
            const int c0 = std::max(col - feather, 0), c1 = std::min(col + feather + 1, img.width);
            const std::int64_t box = sums[std::size_t(r1) * w1 + std::size_t(c1)] - sums[std::size_t(r0) * w1 + std::size_t(c1)] -
                                     sums[std::size_t(r1) * w1 + std::size_t(c0)] + sums[std::size_t(r0) * w1 + std::size_t(c0)];
            const double mean = double(box) / double((r1 - r0) * (c1 - c0));
            const float w = float(std::min(double(t.a), mean) / 255.0);
            if (w >= 1.0f) continue;
            const glm::vec3 fb = terrain_color(terrain, imagery.x0() + (col + 0.5) * tx, imagery.z0() + (row + 0.5) * tz);
            auto mix = [&](std::uint8_t a, float b) { return std::uint8_t(std::lround(float(a) * w + b * (1.0f - w))); };
            t.r = mix(t.r, fb.r);
            t.g = mix(t.g, fb.g);
            t.b = mix(t.b, fb.b);
        }
    });
    imagery.rebuild_mips();
}

void colors_from_imagery(const ImageryPyramid& imagery, Terrain& terrain) {
    const int level = mip_level_for_footprint(terrain.h_scale(), imagery.texel_size(0), imagery.levels());
    const float hs = terrain.h_scale();
    parallel::for_each_index(0, terrain.rows(), [&](int row) {
        for (int col = 0; col < terrain.cols(); ++col) {
            const Rgba8 t = imagery.bilinear(double(hs) * col, double(hs) * row, level);
            terrain.color(row, col) = Rgb8{t.r, t.g, t.b};
        }
    });
}

} // namespace overflight
