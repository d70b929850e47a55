// Based on: max-mipmaps for height-field ray casting. See HeightPyramid.h.
#include "raycast/HeightPyramid.h"

#include "core/HugePages.h"
#include "core/Parallel.h"

#include <algorithm>

namespace overflight {

HeightPyramid::HeightPyramid(const Terrain& terrain, int max_level, const std::uint32_t* colors0)
    : rows_(terrain.rows()), cols_(terrain.cols()) {
    int rows = terrain.rows(), cols = terrain.cols();
    const bool with_colors = colors0 != nullptr;
    for (int L = 1; L <= max_level && (rows > 1 || cols > 1); ++L) {
        Level next;
        next.rows = (rows + 1) / 2;
        next.cols = (cols + 1) / 2;
        assign_on_huge_pages(next.heights, std::size_t(next.rows) * std::size_t(next.cols));
        if (with_colors) assign_on_huge_pages(next.colors, next.heights.size());
        const Level* prev = levels_.empty() ? nullptr : &levels_.back();
        auto height = [&](int i, int j) -> std::uint16_t {
            return prev ? prev->heights[std::size_t(i) * std::size_t(cols) + std::size_t(j)] : terrain.raw(i, j);
        };
        auto color = [&](int i, int j) -> std::uint32_t {
            return prev ? prev->colors[std::size_t(i) * std::size_t(cols) + std::size_t(j)] : colors0[terrain.index(i, j)];
        };
        parallel::for_each_index(0, next.rows, [&](int I) {
            const int i1 = std::min(2 * I + 2, rows);
            for (int J = 0; J < next.cols; ++J) {
                const int j1 = std::min(2 * J + 2, cols);
                const std::size_t k = std::size_t(I) * std::size_t(next.cols) + std::size_t(J);
                std::uint16_t h = 0;
                for (int i = 2 * I; i < i1; ++i)
                    for (int j = 2 * J; j < j1; ++j) h = std::max(h, height(i, j));
                next.heights[k] = h;
                if (!with_colors) continue;
                std::uint32_t r = 0, g = 0, b = 0, n = 0;
                for (int i = 2 * I; i < i1; ++i)
                    for (int j = 2 * J; j < j1; ++j) {
                        const std::uint32_t c = color(i, j);
                        r += c & 0xFF;
                        g += (c >> 8) & 0xFF;
                        b += (c >> 16) & 0xFF;
                        ++n;
                    }
                next.colors[k] = ((r + n / 2) / n) | (((g + n / 2) / n) << 8) | (((b + n / 2) / n) << 16);
            }
        });
        rows = next.rows;
        cols = next.cols;
        levels_.push_back(std::move(next));
    }
}

} // namespace overflight
