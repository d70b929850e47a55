#pragma once
// An upper bound on the heights that a run of consecutive one-cell slices of
// one Floating Horizon column samples, read from the max-height pyramid.
//
// Based on: Szenberg 1997, Algorithm 1 (a slice paints only when its sample
// rises above the current horizon, so a run of slices whose every sample stays
// below it paints nothing and leaves the horizon where it was: skipping the
// run is exact) and the usual max-mipmap of height-field ray casting.
//
// The nearest samples of a run lie in the bounding box of its first and last
// sample (a straight line, and rounding is monotone); a bilinear sample reads
// the four samples around it and, away from the grid's edge (no
// extrapolation), is never above the highest of them. The pyramid level L is
// chosen once per column so that the box is at most 2^L samples wide: it
// covers at most 2 x 2 aligned level-L cells, four lookups per run.
#include "raycast/HeightPyramid.h"

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>

namespace overflight {

// Which samples a position reads (DESIGN sec. 3).
enum class Footprint {
    Nearest,  // `blocks`: the nearest sample
    Bilinear, // `bilinear`: the four around it
};

// The max height over the samples [x0, x1] x [z0, z1] (x0 <= x1, z0 <= z1,
// on the grid), read from the coarsest level needed to cover the box with at
// most 2 x 2 aligned cells; 65535 (no bound) when the pyramid has no level
// that coarse. For runs whose positions are not evenly stepped (the distance
// LOD's slices), where the caller knows the box of the samples read.
inline std::uint16_t box_max_height(const HeightPyramid& pyramid, int x0, int x1, int z0, int z1) {
    const int L = std::max(1, int(std::bit_width(unsigned(std::max(x1 - x0, z1 - z0)))));
    if (L > pyramid.levels()) return 65535;
    const HeightPyramid::Level& lv = pyramid.level(L);
    const std::uint16_t* r0 = lv.heights.data() + std::size_t(z0 >> L) * std::size_t(lv.cols);
    const std::uint16_t* r1 = lv.heights.data() + std::size_t(z1 >> L) * std::size_t(lv.cols);
    return std::max(std::max(r0[x0 >> L], r0[x1 >> L]), std::max(r1[x0 >> L], r1[x1 >> L]));
}

class SliceRunBound {
public:
    // A run of `run` slices with a step of (sx, sz) samples per slice in 32.32
    // fixed point. Not usable() when the pyramid has no level that coarse, or
    // for runs shorter than 2 slices.
    SliceRunBound() = default; // not usable()
    SliceRunBound(const HeightPyramid& pyramid, int run, std::int64_t sx, std::int64_t sz,
                  Footprint footprint = Footprint::Nearest)
        : run_(run), dx_(std::int64_t(run - 1) * sx), dz_(std::int64_t(run - 1) * sz) {
        // Bilinear: the samples around the run's positions, one more each side
        // for positions stepped in floating point rather than exactly.
        if (footprint == Footprint::Bilinear) {
            below_ = 1;
            above_ = 2;
        }
        // Rounded end points differ by at most floor(|d|) + 1 samples.
        const std::int64_t extent = std::max(magnitude(dx_) >> 32, magnitude(dz_) >> 32) + 2 + below_ + above_;
        while ((std::int64_t(1) << level_) < extent) ++level_;
        if (run >= 2 && level_ <= pyramid.levels()) {
            const HeightPyramid::Level& lv = pyramid.level(level_);
            heights_ = lv.heights.data();
            cols_ = lv.cols;
            rows_ = lv.rows;
        }
        if (footprint == Footprint::Bilinear) {
            last_x_ = pyramid.cols() - 1;
            last_z_ = pyramid.rows() - 1;
        }
    }

    bool usable() const { return heights_ != nullptr; }
    int run() const { return run_; }
    // The pyramid level read, and the 32.32 offset from a run's first
    // position to its last (for casts that bound several runs at once).
    int level() const { return level_; }
    std::int64_t dx() const { return dx_; }
    std::int64_t dz() const { return dz_; }

    // Max height over the run starting at (gx, gz): 32.32 fixed-point sample
    // coordinates, offset by half a sample for Nearest (so that >> 32 is the
    // nearest sample), not for Bilinear (>> 32 is the sample below). The run
    // must lie on the grid. Bilinear runs near the grid's edge get 65535 (no
    // bound: the cast clamps and may extrapolate there). Requires usable().
    std::uint16_t max_height(std::int64_t gx, std::int64_t gz) const {
        const std::int64_t x0 = gx >> 32, x1 = (gx + dx_) >> 32, z0 = gz >> 32, z1 = (gz + dz_) >> 32;
        const std::int64_t xl = std::min(x0, x1) - below_, xh = std::max(x0, x1) + above_;
        const std::int64_t zl = std::min(z0, z1) - below_, zh = std::max(z0, z1) + above_;
        if (below_ > 0 && (xl < 0 || zl < 0 || xh > last_x_ || zh > last_z_)) return 65535;
        const std::size_t X0 = cell(xl, cols_), X1 = cell(xh, cols_);
        const std::size_t Z0 = cell(zl, rows_), Z1 = cell(zh, rows_);
        const std::uint16_t* r0 = heights_ + Z0 * std::size_t(cols_);
        const std::uint16_t* r1 = heights_ + Z1 * std::size_t(cols_);
        return std::max(std::max(r0[X0], r0[X1]), std::max(r1[X0], r1[X1]));
    }

private:
    static std::int64_t magnitude(std::int64_t v) { return v < 0 ? -v : v; }
    // The level-L cell of sample coordinate v, clamped to the level's n cells.
    std::size_t cell(std::int64_t v, int n) const {
        return std::size_t(std::clamp<std::int64_t>(v >> level_, 0, std::int64_t(n) - 1));
    }

    int run_ = 0;
    std::int64_t dx_ = 0, dz_ = 0; // from the run's first sample to its last
    int below_ = 0, above_ = 0; // samples read beyond the positions' box
    std::int64_t last_x_ = 0, last_z_ = 0; // the grid's last sample (Bilinear)
    int level_ = 1;
    const std::uint16_t* heights_ = nullptr;
    int cols_ = 0, rows_ = 0;
};

} // namespace overflight
