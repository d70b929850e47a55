#pragma once
// Plain image buffers shared by every renderer: row 0 is the top row of the
// picture, as in the camera contract (DESIGN sec. 2) and in PNG files. (OpenGL
// stores row 0 at the bottom; the GL layer flips when it uploads or reads back.)
#include "core/HugePages.h"

#include <cstddef>
#include <cstdint>
#include <new>
#include <vector>

namespace overflight {

struct Rgb8 {
    std::uint8_t r = 0, g = 0, b = 0;
    friend bool operator==(const Rgb8&, const Rgb8&) = default;
};

// An image's storage: it starts a cache line, so that the renderers' runs of
// pixels that start a line in one row start one in every row whose width
// allows it (a block of 32 columns of a 3840-pixel depth image writes each
// row's two lines whole, sharing none with the next block); and where an
// image spans whole 2 MiB pages, they are advised for huge pages before they
// are first touched (HugePages.h).
template <typename T>
struct ImageAllocator {
    using value_type = T;
    static constexpr std::align_val_t kAlign{64};
    ImageAllocator() = default;
    template <typename U>
    ImageAllocator(const ImageAllocator<U>&) noexcept {}
    T* allocate(std::size_t n) {
        void* p = ::operator new(n * sizeof(T), kAlign);
        advise_huge_pages(p, n * sizeof(T));
        return static_cast<T*>(p);
    }
    void deallocate(T* p, std::size_t) noexcept { ::operator delete(p, kAlign); }
    friend bool operator==(const ImageAllocator&, const ImageAllocator&) { return true; }
};

template <typename T>
using ImagePixels = std::vector<T, ImageAllocator<T>>;

template <typename T>
struct Image2D {
    int width = 0;
    int height = 0;
    ImagePixels<T> pixels; // row-major, row 0 = top

    Image2D() = default;
    Image2D(int w, int h, T fill = T{}) : width(w), height(h) { pixels.assign(std::size_t(w) * std::size_t(h), fill); }

    T& at(int col, int row) { return pixels[std::size_t(row) * std::size_t(width) + std::size_t(col)]; }
    const T& at(int col, int row) const { return pixels[std::size_t(row) * std::size_t(width) + std::size_t(col)]; }
    void resize(int w, int h, T fill = T{}) {
        width = w;
        height = h;
        pixels.assign(std::size_t(w) * std::size_t(h), fill);
    }
};

using ColorImage = Image2D<Rgb8>;
// OpenGL window depth in [0,1] for the camera's near/far; 1.0 where nothing was hit (sky).
using DepthImage = Image2D<float>;

} // namespace overflight
