#pragma once
// Plain image buffers shared by every renderer: row 0 is the top row of the
// picture, as in the camera contract (DESIGN sec. 2) and in PNG files. (OpenGL
// stores row 0 at the bottom; the GL layer flips when it uploads or reads back.)
#include "core/HugePages.h"

#include <cstdint>
#include <vector>

namespace overflight {

struct Rgb8 {
    std::uint8_t r = 0, g = 0, b = 0;
    friend bool operator==(const Rgb8&, const Rgb8&) = default;
};

template <typename T>
struct Image2D {
    int width = 0;
    int height = 0;
    std::vector<T> pixels; // row-major, row 0 = top

    Image2D() = default;
    Image2D(int w, int h, T fill = T{}) : width(w), height(h) {
        assign_on_huge_pages(pixels, std::size_t(w) * std::size_t(h), fill);
    }

    T& at(int col, int row) { return pixels[std::size_t(row) * std::size_t(width) + std::size_t(col)]; }
    const T& at(int col, int row) const { return pixels[std::size_t(row) * std::size_t(width) + std::size_t(col)]; }
    void resize(int w, int h, T fill = T{}) {
        width = w;
        height = h;
        assign_on_huge_pages(pixels, std::size_t(w) * std::size_t(h), fill);
    }
};

using ColorImage = Image2D<Rgb8>;
// OpenGL window depth in [0,1] for the camera's near/far; 1.0 where nothing was hit (sky).
using DepthImage = Image2D<float>;

} // namespace overflight
