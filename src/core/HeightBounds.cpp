// Based on: Tevs, Ihrke, Seidel 2008 (min-max mipmaps). See HeightBounds.h.
#include "core/HeightBounds.h"

#include "core/Parallel.h"

#include <algorithm>
#include <cmath>

namespace overflight {

namespace {

std::pair<float, float> widen(std::pair<float, float> a, std::pair<float, float> b) {
    return {std::min(a.first, b.first), std::max(a.second, b.second)};
}

} // namespace

HeightBounds::HeightBounds(const Terrain& terrain, int stride) : terrain_(&terrain), stride_(stride) {
    const int cols = (terrain.cols() - 1) / stride + 1, rows = (terrain.rows() - 1) / stride + 1;
    constexpr int block = 1 << kFirstLevel;
    Level first{(cols + block - 1) / block, (rows + block - 1) / block, {}};
    first.range.resize(std::size_t(first.cols) * std::size_t(first.rows));
    parallel::for_each_index(0, first.rows, [&](int br) {
        for (int bc = 0; bc < first.cols; ++bc) {
            std::pair<float, float> r{HUGE_VALF, -HUGE_VALF};
            for (int z = br * block; z < std::min((br + 1) * block, rows); ++z)
                for (int x = bc * block; x < std::min((bc + 1) * block, cols); ++x) {
                    const float h = terrain.sample_height(z * stride, x * stride);
                    r = widen(r, {h, h});
                }
            first.range[std::size_t(br) * std::size_t(first.cols) + std::size_t(bc)] = r;
        }
    });
    levels_.push_back(std::move(first));
    while (levels_.back().cols > 1 || levels_.back().rows > 1) {
        const Level& fine = levels_.back();
        Level coarse{(fine.cols + 1) / 2, (fine.rows + 1) / 2, {}};
        coarse.range.assign(std::size_t(coarse.cols) * std::size_t(coarse.rows), {HUGE_VALF, -HUGE_VALF});
        for (int r = 0; r < fine.rows; ++r)
            for (int c = 0; c < fine.cols; ++c) {
                auto& into = coarse.range[std::size_t(r / 2) * std::size_t(coarse.cols) + std::size_t(c / 2)];
                into = widen(into, fine.range[std::size_t(r) * std::size_t(fine.cols) + std::size_t(c)]);
            }
        levels_.push_back(std::move(coarse));
    }
}

std::pair<float, float> HeightBounds::range(int x0, int z0, int x1, int z1) const {
    std::pair<float, float> r{HUGE_VALF, -HUGE_VALF};
    if ((x1 - x0 + 1) * (z1 - z0 + 1) <= kExact) {
        for (int z = z0; z <= z1; ++z)
            for (int x = x0; x <= x1; ++x) {
                const float h = terrain_->sample_height(z * stride_, x * stride_);
                r = widen(r, {h, h});
            }
        return r;
    }
    int level = 0, shift = kFirstLevel;
    while (level + 1 < int(levels_.size()) && ((x1 >> shift) - (x0 >> shift) > 1 || (z1 >> shift) - (z0 >> shift) > 1)) {
        ++level;
        ++shift;
    }
    const Level& l = levels_[std::size_t(level)];
    for (int z = z0 >> shift; z <= z1 >> shift; ++z)
        for (int x = x0 >> shift; x <= x1 >> shift; ++x)
            r = widen(r, l.range[std::size_t(z) * std::size_t(l.cols) + std::size_t(x)]);
    return r;
}

} // namespace overflight
