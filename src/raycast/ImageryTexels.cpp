// See ImageryTexels.h.
#include "raycast/ImageryTexels.h"

#include "core/Parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace overflight {

void ImageryTexels::bind(const ImageryPyramid* pyramid) {
    pyramid_ = pyramid;
    levels_.clear();
    texels_.clear();
    lanes_ = LevelLanes{};
    lane_tables_ = false;
    level_starts_.clear();
    starts_of_slices_.clear();
    starts_of_rows_.clear();
    if (!pyramid) return;
    x0_ = float(pyramid->x0());
    z0_ = float(pyramid->z0());
    std::int64_t total = 0;
    for (int l = 0; l < pyramid->levels(); ++l) {
        const Image2D<Rgba8>& img = pyramid->level(l);
        Level lv{img.width, img.height, float(1.0 / pyramid->texel_x(l)), float(1.0 / pyramid->texel_z(l)),
                 (img.width + kPageSide - 1) / kPageSide, total};
        total += std::int64_t(lv.tiles_x) * ((img.height + kPageSide - 1) / kPageSide) * kPageSide * kPageSide;
        levels_.push_back(lv);
    }
    last_level_ = pyramid->levels() - 1;
    // Padding texels past a level's edge are never read (at() clamps first).
    texels_.assign(std::size_t(total), Rgba8{});
    Rgba8* out = texels_.data();
    for (int l = 0; l < pyramid->levels(); ++l) {
        const Image2D<Rgba8>& img = pyramid->level(l);
        const Level& lv = levels_[std::size_t(l)];
        parallel::for_each_index(0, img.height, [&](int row) {
            for (int col = 0; col < img.width; ++col)
                out[std::size_t(lv.first) + tiled_index(col, row, lv.tiles_x)] = img.at(col, row);
        });
    }
    lane_tables_ = total <= std::numeric_limits<std::int32_t>::max() && pyramid->levels() <= LevelLanes::kLevels;
    if (!lane_tables_) return;
    for (int l = 0; l < LevelLanes::kLevels; ++l) {
        const Level& lv = levels_[std::size_t(std::min(l, last_level_))];
        lanes_.inv_x[l] = lv.inv_x;
        lanes_.inv_z[l] = lv.inv_z;
        lanes_.w[l] = lv.w;
        lanes_.h[l] = lv.h;
        lanes_.tiles_x[l] = lv.tiles_x;
        lanes_.first[l] = int(lv.first);
    }
}

DrapeRun drape_run(const DrapeFrame& f, const std::uint32_t* slice, int j, int jend, std::ptrdiff_t row_stride) {
    DrapeRun run;
    run.k = slice[j * row_stride];
    int top = j + 1;
    while (top < jend && slice[top * row_stride] == run.k) ++top;
    run.dk = f.slice_d[run.k];
    run.d_prev = run.k > 0 ? f.slice_d[run.k - 1] : f.d_before_first;
    run.m_top = f.row_m[top - 1];
    return run;
}

void drape_column(const DrapeFrame& f, float dir_x, float dir_z, std::uint32_t* color, const std::uint32_t* slice,
                  int jend, std::ptrdiff_t row_stride) {
    DrapeRun run;
    for (int j = 0; j < jend; ++j) {
        // Slices only grow up a column: a new index is a new run.
        if (slice[j * row_stride] != run.k) run = drape_run(f, slice, j, jend, row_stride);
        std::uint32_t& c = color[j * row_stride];
        c = drape_pixel(f, run, dir_x, dir_z, j, c);
    }
}

void ImageryTexels::prepare_slices(const float* slice_d, int slices, double focal_px) {
    slice_log2_.resize(std::size_t(std::max(slices, 0)));
    if (!pyramid_) return;
    const double scale = 1.0 / (focal_px * pyramid_->texel_size(0));
    for (int k = 0; k < slices; ++k)
        slice_log2_[std::size_t(k)] = float(std::log2(std::max(double(slice_d[k]) * scale, 1e-30)));
}

namespace {

// The first k in [0, n) with pred(k), n if none, for a pred false up to
// some k and true from there on: a galloping search (Bentley and Yao, "An
// almost optimal algorithm for unbounded searching", IPL 1976) outward from
// `hint`, so a boundary that moves little from one search to the next costs
// a few probes.
template <class Pred>
int first_true_near(int hint, int n, Pred pred) {
    hint = std::clamp(hint, 0, n);
    int lo = 0, hi = n; // the boundary is in [lo, hi] (n: pred holds nowhere)
    if (hint == n || pred(hint)) {
        hi = hint;
        for (int step = 1; hint - step >= 0; step *= 2) {
            if (!pred(hint - step)) {
                lo = hint - step + 1;
                break;
            }
            hi = hint - step;
        }
    } else {
        lo = hint + 1;
        for (int step = 1; hint + step < n; step *= 2) {
            if (pred(hint + step)) {
                hi = hint + step;
                break;
            }
            lo = hint + step + 1;
        }
    }
    while (lo < hi) {
        const int mid = lo + (hi - lo) / 2;
        if (pred(mid)) hi = mid;
        else lo = mid + 1;
    }
    return lo;
}

} // namespace

void ImageryTexels::prepare_rows(const float* row_m, int rows) {
    row_log2_.resize(std::size_t(std::max(rows, 0)));
    // Slopes flatter than this are taken as this: the footprint along a ray
    // grazing the ground grows without bound, the pyramid's levels do not.
    constexpr float kFlattest = 1.0f / 1024.0f;
    for (int j = 0; j < rows; ++j)
        row_log2_[std::size_t(j)] = row_m[j] < 0.0f ? -std::log2(std::max(-row_m[j], kFlattest)) : 0.0f;
    if (!pyramid_ || !lane_tables_) return;
    // A camera that keeps its pitch, field of view and depth range (a
    // flight) keeps its level starts.
    if (level_starts_.size() == row_log2_.size() && starts_of_slices_ == slice_log2_ && starts_of_rows_ == row_log2_)
        return;
    starts_of_slices_ = slice_log2_;
    starts_of_rows_ = row_log2_;
    // level(k, j) >= L >= 1 exactly where the unclamped l of level() is >= L
    // (int(l) truncates l >= 1 down) and L <= last_level_. Neighbouring rows
    // have nearly the same term (rows level or rising, the same), so each
    // row's search starts at the row before's boundaries.
    level_starts_.resize(row_log2_.size());
    const int slices = int(slice_log2_.size());
    int hint[LevelLanes::kLevels] = {};
    for (int j = 0; j < rows; ++j) {
        const float r = row_log2_[std::size_t(j)];
        std::int32_t* starts = level_starts_[std::size_t(j)].k;
        if (j > 0 && r == row_log2_[std::size_t(j - 1)]) {
            level_starts_[std::size_t(j)] = level_starts_[std::size_t(j - 1)];
            continue;
        }
        starts[0] = 0;
        for (int L = 1; L < LevelLanes::kLevels; ++L) {
            if (L > last_level_) {
                starts[L] = std::numeric_limits<std::int32_t>::max();
                continue;
            }
            const float level = float(L);
            const int k = first_true_near(std::max(hint[L], hint[L - 1]), slices, [&](int s) {
                return slice_log2_[std::size_t(s)] + r + 0.5f >= level;
            });
            hint[L] = k;
            starts[L] = k < slices ? k : std::numeric_limits<std::int32_t>::max();
        }
    }
}

} // namespace overflight
