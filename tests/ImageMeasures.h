#pragma once
// Measures of a rendered frame (any type with `color` and `depth` images of
// the same size) shared by the imagery tests: high-frequency energy, mean
// difference between two frames' terrain, and black terrain pixels.
#include "core/Image.h"

#include <cstdlib>

namespace overflight::test {

// Mean squared 4-neighbour Laplacian of the luminance over the pixels whose
// neighbours are all terrain: the image's high-frequency energy.
template <class Frame>
double laplacian_energy(const Frame& f) {
    const int w = f.color.width, h = f.color.height;
    auto lum = [&](int x, int y) {
        const Rgb8 p = f.color.at(x, y);
        return 0.299 * p.r + 0.587 * p.g + 0.114 * p.b;
    };
    auto terrain = [&](int x, int y) { return f.depth.at(x, y) < 1.0f; };
    double sum = 0;
    long long n = 0;
    for (int y = 1; y + 1 < h; ++y)
        for (int x = 1; x + 1 < w; ++x) {
            if (!terrain(x, y) || !terrain(x - 1, y) || !terrain(x + 1, y) || !terrain(x, y - 1) || !terrain(x, y + 1))
                continue;
            const double l = 4 * lum(x, y) - lum(x - 1, y) - lum(x + 1, y) - lum(x, y - 1) - lum(x, y + 1);
            sum += l * l;
            ++n;
        }
    return n ? sum / double(n) : 0.0;
}

// Mean per-channel difference over the pixels that are terrain in both.
template <class Frame>
double mean_difference(const Frame& a, const Frame& b) {
    double diff = 0;
    long long n = 0;
    for (std::size_t i = 0; i < a.color.pixels.size(); ++i) {
        if (!(a.depth.pixels[i] < 1.0f && b.depth.pixels[i] < 1.0f)) continue;
        const Rgb8 p = a.color.pixels[i], q = b.color.pixels[i];
        diff += (std::abs(p.r - q.r) + std::abs(p.g - q.g) + std::abs(p.b - q.b)) / 3.0;
        ++n;
    }
    return n ? diff / double(n) : 0.0;
}

// Terrain pixels darker than 6 levels in every channel.
template <class Frame>
long long black_pixels(const Frame& f) {
    long long n = 0;
    for (std::size_t i = 0; i < f.color.pixels.size(); ++i) {
        const Rgb8 p = f.color.pixels[i];
        n += f.depth.pixels[i] < 1.0f && p.r < 6 && p.g < 6 && p.b < 6;
    }
    return n;
}

} // namespace overflight::test
