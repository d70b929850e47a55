// HeightBounds (core/HeightBounds.h): every rectangle's bounds hold all its
// samples, exactly for small rectangles, on a grid read with and without a
// stride; the sizes are not powers of two, so the blocks are clipped.
#include "core/HeightBounds.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace overflight {
namespace {

Terrain bumpy(int rows, int cols) {
    Terrain t(rows, cols, 2.0f, 0.5f, -3.0f);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) t.raw(r, c) = std::uint16_t((r * 7919 + c * 104729 + r * c * 31) % 1000);
    return t;
}

TEST(HeightBounds, HoldEverySampleOfARectangle) {
    const Terrain t = bumpy(77, 100);
    for (const int stride : {1, 3}) {
        const HeightBounds bounds(t, stride);
        const int cols = (t.cols() - 1) / stride + 1, rows = (t.rows() - 1) / stride + 1;
        unsigned seed = 12345;
        const auto next = [&](int n) {
            seed = seed * 1103515245u + 12345u;
            return int((seed >> 8) % unsigned(n));
        };
        for (int k = 0; k < 2000; ++k) {
            int x0 = next(cols), x1 = next(cols), z0 = next(rows), z1 = next(rows);
            if (x0 > x1) std::swap(x0, x1);
            if (z0 > z1) std::swap(z0, z1);
            float lo = HUGE_VALF, hi = -HUGE_VALF;
            for (int z = z0; z <= z1; ++z)
                for (int x = x0; x <= x1; ++x) {
                    lo = std::min(lo, t.sample_height(z * stride, x * stride));
                    hi = std::max(hi, t.sample_height(z * stride, x * stride));
                }
            const auto [blo, bhi] = bounds.range(x0, z0, x1, z1);
            EXPECT_LE(blo, lo) << x0 << "," << z0 << " " << x1 << "," << z1;
            EXPECT_GE(bhi, hi) << x0 << "," << z0 << " " << x1 << "," << z1;
            if ((x1 - x0 + 1) * (z1 - z0 + 1) <= 64) {
                EXPECT_EQ(blo, lo);
                EXPECT_EQ(bhi, hi);
            }
        }
        // The whole grid: its lowest and highest sample.
        const auto [lo, hi] = bounds.range(0, 0, cols - 1, rows - 1);
        EXPECT_EQ(lo, -3.0f);
        EXPECT_GE(hi, 0.5f * 990.0f - 3.0f);
    }
}

} // namespace
} // namespace overflight
