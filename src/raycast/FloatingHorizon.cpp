// Based on: Szenberg 1997 Algorithm 1, sec. 5.1-5.2, eq. 3-7, Algorithm 2,
// sec. 6; Guedes, Algorithm 1 (seed 002). See FloatingHorizon.h.
#include "raycast/FloatingHorizon.h"

#include "raycast/DepthVector.h"
#include "raycast/RowSearch.h"
#include "raycast/ShearResolve.h"
#include "raycast/SliceRunBound.h"

#include <glm/trigonometric.hpp>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace overflight {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

// Columns per task: a block is cast into a scratch that stays in L2
// (kShearBlock x 1080 x 8 bytes, row-major within the block) and resolved into
// runs of kShearBlock pixels of image rows (ShearResolve).
constexpr int kBlock = kShearBlock;

// Slices per skip test (SliceRunBound): a coarse run, split into fine runs
// when its bound reaches the horizon, and those into single samples.
// Measured on the bench view: 16/4 to 64/16 are within a few percent.
constexpr int kRunCoarse = 32;
constexpr int kRunFine = 8;
// The bound is compared in float with the per-slice tables: every rounding
// step involved (tables, product, sum) is within 2^-24 of the operands'
// magnitude, so 2^-20 of it covers them all.
constexpr float kRunSlack = 1.0f / 1048576.0f;
// Rows that every sample of cast_blocks_column writes from the horizon up,
// painted or not (the scratch has that many rows of padding). A visited sample
// paints 1.3 rows on average on the bench view; measured there: 2 and 8 are
// 5-10 % slower than 4.
constexpr int kPaintRows = 4;
// Fraction bits of the fixed-point row guess (SliceGuess): a raw height of
// 2^16 times a rounding error of 2^-25 rows is under 1/512 row.
constexpr int kGuessBits = 24;
// Levels of the max-height pyramid (level L: 2^L samples square): a coarse run
// of 32 slices spans 32 / cos(theta) samples, so 12 levels serve columns up to
// 89 degrees off the view axis.
constexpr int kRunLevels = 12;

// Vertical planes cast per tilted pixel width (at the row where pixels are
// narrowest): the reprojection picks the nearest plane, so the sideways error
// is at most 1/(2 kTiltPlanes) pixel.
constexpr double kTiltPlanes = 2.0;

// CastKernel::X86_64_v3: the block cast compiled for x86-64-v3 (AVX2, BMI2,
// three-operand encodings) beside the baseline. The same operations either
// way (no FMA contraction, see cmake/Warnings.cmake), so the same pixels;
// measured: frame 6 % faster on the bench view. GCC names the level in
// __builtin_cpu_supports.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define OVERFLIGHT_CAST_V3 1
#else
#define OVERFLIGHT_CAST_V3 0
#endif

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr double kFixedOne = 4294967296.0; // 32.32 fixed point

// No sample of height <= h (raw) in the run of slices [k, k + run) can rise
// above the horizon m: its sigma = h a_k' + b_k' is linear in 1/d_k', so at
// most the larger value at the run's two ends; kRunSlack covers the float
// rounding of the tables and of sigma.
bool run_below(const float* ma, const float* mb, int k, int run, float h, float m) {
    const int e = k + run - 1;
    const float bound = std::max(h * ma[k] + mb[k], h * ma[e] + mb[e]);
    return bound + (h * ma[k] + std::abs(mb[k])) * kRunSlack <= m;
}
std::uint32_t float_bits(float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}
float bits_float(std::uint32_t u) {
    float f;
    std::memcpy(&f, &u, sizeof f);
    return f;
}

// One column of cast_blocks between two of its turns: the state of
// Algorithm 1 (horizon row j, next slice k) and of its run skipping.
struct BlockRay {
    std::int64_t gx = 0, gz = 0, sx = 0, sz = 0; // position of slice k and step, 32.32, offset by half a cell
    SliceRunBound coarse, fine;
    int k = 0, k1 = 0; // next slice (the start of a coarse run), end of the column
    int j = 0;         // horizon row (its slope is row_m_[j])
    // The last fine run painted: the next one most likely paints too (near
    // the eye every slice does), so it is cast without testing (measured: 5 %
    // faster).
    bool hot = false;
};

} // namespace

FloatingHorizon::FloatingHorizon(const Terrain& terrain, const Environment& env)
    : terrain_(terrain), env_(env), max_pyramid_(terrain, kRunLevels, false), marcher_(terrain, env) {
    colors_.resize(terrain.colors().size());
    for (std::size_t i = 0; i < colors_.size(); ++i) colors_[i] = pack_rgb(terrain.colors()[i]);
    max_height_ = terrain.max_height();
    level_heights_[0] = terrain.heights().data();
    level_colors_[0] = colors_.data();
    level_cols_[0] = terrain.cols();
}

FloatingHorizon::~FloatingHorizon() = default;

// Slices at view depth d_k along F from d_first to d_last (sec. 5.2: one step of
// h_scale along F is the column's unit step scaled by 1/cos(theta_k)). With
// --lod the step doubles each time a pixel (1/fp_h of the distance) spans twice
// as many cells. Tabulates, per slice, what all columns share: 1/d_k folded
// into the height-to-slope map, the depth vector and the early-exit bound.
void FloatingHorizon::setup_slices(const Camera& camera, const RaycastOptions& options, double d_first, double d_last,
                                   double fp_h) {
    const double hs = terrain_.h_scale();
    slice_d_.clear();
    slice_level_.clear();
    int max_level = 0;
    if (options.lod) {
        if (!pyramid_) pyramid_ = std::make_unique<HeightPyramid>(terrain_, 12);
        max_level = std::min(pyramid_->levels(), 31);
        for (int L = 1; L <= max_level; ++L) {
            level_heights_[L] = pyramid_->level(L).heights.data();
            level_colors_[L] = pyramid_->level(L).colors.data();
            level_cols_[L] = pyramid_->level(L).cols;
        }
    }
    uniform_slices_ = !options.lod && !(options.near_step_pixels > 0.0);
    // The bound reads the raw maximum as the highest world point: v_scale > 0.
    skip_runs_ = options.skip_runs && terrain_.v_scale() > 0.0f;
    if (uniform_slices_) {
        const long long count = (long long)std::floor((d_last - d_first) / hs + 1e-9) + 1;
        slice_d_.resize(std::size_t(std::max(count, 1LL)));
        for (std::size_t k = 0; k < slice_d_.size(); ++k) slice_d_[k] = d_first + hs * double(k);
        slice_level_.assign(slice_d_.size(), 0);
    } else {
        const double lod_cells = fp_h * hs * std::max(options.lod_pixels, 1e-3);
        const double near_px = options.near_step_pixels;
        for (double d = d_first; d <= d_last + 1e-9;) {
            int L = 0;
            while (options.lod && L < max_level && d >= lod_cells * double(2 << L)) ++L;
            slice_d_.push_back(d);
            slice_level_.push_back(std::uint8_t(L));
            double step = hs * double(1 << L);
            if (near_px > 0.0) step = std::min(step, std::max(hs / 8.0, near_px * d / fp_h));
            d += step;
        }
    }
    const std::size_t n = slice_d_.size();
    slice_df_.resize(n);
    // Evenly spaced: in float as d_first + step k, which the shear resolve may
    // compute rather than read (ShearResolveTables::d_step).
    for (std::size_t k = 0; k < n; ++k)
        slice_df_[k] = uniform_slices_ ? float(d_first) + float(hs) * float(k) : float(slice_d_[k]);
    slice_a_.resize(n);
    slice_b_.resize(n);
    slice_smax_.resize(n);
    const double vs = terrain_.v_scale(), y0 = terrain_.y_offset();
    float running = -kInf;
    for (std::size_t k = n; k-- > 0;) {
        const double inv = 1.0 / slice_d_[k];
        slice_a_[k] = float(vs * inv);
        slice_b_[k] = float((y0 - eye_y_) * inv);
        // Rounded up so that float rounding can never stop a column early.
        running = std::max(running, std::nextafter(float((max_height_ - eye_y_) * inv), kInf));
        slice_smax_[k] = running;
    }
    // Shear: the view axis is F, so slice k's window depth is one number for
    // the whole slice (Algorithm 2). Tilt resolves depth per pixel instead.
    if (camera.projection == Projection::Shear) {
        if (uniform_slices_) {
            depth_vector(camera, d_first, hs, int(n), slice_depth_);
        } else {
            slice_depth_.resize(n);
            for (std::size_t k = 0; k < n; ++k) slice_depth_[k] = float(camera.window_depth(slice_d_[k]));
        }
    }
}

// Column planes: horizontal direction F + a R. The slices inside the terrain
// form one interval per column (a straight line leaves a rectangle once), so
// the inner loop needs no bounds test.
void FloatingHorizon::setup_columns() {
    const double hs = terrain_.h_scale();
    const std::vector<double>& a = col_a_;
    const std::size_t n = a.size();
    col_ux_.resize(n);
    col_uz_.resize(n);
    col_k0_.resize(n);
    col_k1_.resize(n);
    const double gx_max = terrain_.cols() - 1, gz_max = terrain_.rows() - 1;
    auto range = [](double e, double u, double hi, double& lo_d, double& hi_d) {
        if (u == 0.0) {
            if (e < 0.0 || e > hi) hi_d = -1.0;
            return;
        }
        double t0 = (0.0 - e) / u, t1 = (hi - e) / u;
        if (t0 > t1) std::swap(t0, t1);
        lo_d = std::max(lo_d, t0);
        hi_d = std::min(hi_d, t1);
    };
    for (std::size_t c = 0; c < n; ++c) {
        const double ux = (fx_ + a[c] * rx_) / hs, uz = (fz_ + a[c] * rz_) / hs;
        col_ux_[c] = ux;
        col_uz_[c] = uz;
        double lo = 0.0, hi = std::numeric_limits<double>::infinity();
        range(eye_gx_, ux, gx_max, lo, hi);
        range(eye_gz_, uz, gz_max, lo, hi);
        if (hi < lo) {
            col_k0_[c] = col_k1_[c] = 0;
            continue;
        }
        // Grow by a hair so that a slice exactly on the edge stays in; a sample
        // that far out still rounds to an edge sample (blocks) or is clamped (bilinear).
        lo -= 1e-9 * (1.0 + lo);
        hi += 1e-9 * (1.0 + hi);
        col_k0_[c] = int(std::lower_bound(slice_d_.begin(), slice_d_.end(), lo) - slice_d_.begin());
        col_k1_[c] = int(std::upper_bound(slice_d_.begin(), slice_d_.end(), hi) - slice_d_.begin());
        if (col_k1_[c] < col_k0_[c]) col_k1_[c] = col_k0_[c];
    }
}

// Algorithm 1 for one column, bottom-up. m_j (row_m_) is the slope of row j's
// ray per unit of view depth; the current horizon at slice k is
// eye_y + d_k m_j, and a sample of height h rises above it when
// (h - eye_y)/d_k > m_j, i.e. raw*slice_a_[k] + slice_b_[k] > m_j. Painting
// a pixel moves the horizon up one row (eq. 2); rows only climb, so the column
// is done when the top row is painted or no later slice can reach the horizon
// (slice_smax_). Color and slice index are stored; depth and fog come from the
// slice when the block is resolved. This is the general case (bilinear
// surface, LOD and near refinement); cast_blocks_column is the papers' case.
template <bool kBilinear, bool kVarying>
int FloatingHorizon::cast_column(int c, std::uint32_t* color, std::uint32_t* slice, std::ptrdiff_t stride,
                                 long long& visited) const {
    const int k0 = col_k0_[std::size_t(c)], k1 = col_k1_[std::size_t(c)];
    const double ux = col_ux_[std::size_t(c)], uz = col_uz_[std::size_t(c)];
    const int cols = terrain_.cols();
    const std::uint16_t* heights = terrain_.heights().data();
    const std::uint32_t* colors = colors_.data();
    const float* ma = slice_a_.data();
    const float* mb = slice_b_.data();
    const float* smax = slice_smax_.data();
    const float* rows = row_m_.data();
    const int nrows = rows_cast_;
    int j = 0;
    float mj = rows[0];
    int k = k0;
    // Incremental stepping (line 6 of Algorithm 1) in double: 2^-52 per step
    // cannot drift a sample into the next cell over any far plane.
    double gx = eye_gx_ + (k0 < k1 ? slice_d_[std::size_t(k0)] : 0.0) * ux;
    double gz = eye_gz_ + (k0 < k1 ? slice_d_[std::size_t(k0)] : 0.0) * uz;
    const double step = slice_d_.size() > 1 ? slice_d_[1] - slice_d_[0] : 0.0;
    const double sx = step * ux, sz = step * uz;
    // One-cell bilinear slices skip runs as cast_blocks_column does (fine runs
    // only, positions converted to fixed point for the bound); a skipped run
    // still steps its positions one slice at a time, so the samples after it
    // are the same as without the skip.
    constexpr bool kSkip = kBilinear && !kVarying;
    const SliceRunBound run(max_pyramid_, kSkip && skip_runs_ ? kRunFine : 0, std::llround(sx * kFixedOne),
                            std::llround(sz * kFixedOne), Footprint::Bilinear);
    int next_test = k0, j_at_test = 0;
    long long skipped = 0;
    for (; k < k1; ++k) {
        if (smax[k] <= mj) break;
        if (kSkip && k == next_test) {
            const bool hot = j != j_at_test; // the last run painted: cast the next one without testing
            j_at_test = j;
            next_test = k + kRunFine;
            if (!hot && run.usable() && k + kRunFine <= k1 &&
                run_below(ma, mb, k, kRunFine,
                          float(run.max_height(std::llround(gx * kFixedOne), std::llround(gz * kFixedOne))), mj)) {
                for (int q = 0; q < kRunFine; ++q) {
                    gx += sx;
                    gz += sz;
                }
                k += kRunFine - 1;
                skipped += kRunFine;
                continue;
            }
        }
        if constexpr (kVarying) {
            gx = eye_gx_ + slice_d_[std::size_t(k)] * ux;
            gz = eye_gz_ + slice_d_[std::size_t(k)] * uz;
        }
        const int ix = int(gx + 0.5), iz = int(gz + 0.5);
        float h;
        std::size_t ci;
        int level = 0;
        if constexpr (kVarying) level = slice_level_[std::size_t(k)];
        if (kVarying && level > 0) {
            ci = std::size_t(iz >> level) * std::size_t(level_cols_[level]) + std::size_t(ix >> level);
            h = float(level_heights_[level][ci]);
        } else if constexpr (kBilinear) {
            const int c0 = std::min(std::max(int(gx), 0), cols - 2), r0 = std::min(std::max(int(gz), 0), terrain_.rows() - 2);
            const float tx = float(gx - c0), tz = float(gz - r0);
            const std::uint16_t* p = heights + std::size_t(r0) * std::size_t(cols) + std::size_t(c0);
            const float top = float(p[0]) + (float(p[1]) - float(p[0])) * tx;
            const float bottom = float(p[cols]) + (float(p[cols + 1]) - float(p[cols])) * tx;
            h = top + (bottom - top) * tz;
            ci = std::size_t(iz) * std::size_t(cols) + std::size_t(ix);
        } else {
            ci = std::size_t(iz) * std::size_t(cols) + std::size_t(ix);
            h = float(heights[ci]);
        }
        const float sigma = h * ma[k] + mb[k];
        if (sigma > mj) {
            const std::uint32_t col = (kVarying && level > 0) ? level_colors_[level][ci] : colors[ci];
            do { // paint, move the horizon up one pixel (lines 10-14)
                color[std::ptrdiff_t(j) * stride] = col;
                slice[std::ptrdiff_t(j) * stride] = std::uint32_t(k);
                mj = rows[++j];
            } while (sigma > mj);
            if (j >= nrows) {
                ++k;
                break;
            }
        }
        if constexpr (!kVarying) {
            gx += sx;
            gz += sz;
        }
    }
    visited += k - k0 - skipped;
    return j;
}

// cast_column<false, false>, the papers' case (one-cell slices, `blocks`
// surface), for a block of at most kBlock columns, painting exactly the same
// pixels faster:
// - positions in 32.32 fixed point, offset by half a cell so that the nearest
//   sample is the integer part: exact integer steps, no float-to-int
//   conversion per sample (2^-32 cell of rounding per step: nothing over 2^16
//   steps);
// - runs of slices skipped when no sample in them can rise above the current
//   horizon: a sample of height h <= H (SliceRunBound) at slice k' of the run
//   [k, e] has (v_scale h + y0 - eye_y)/d_k' <= the larger of that bound at k
//   and at e (linear in 1/d), which the float tables give to within
//   kRunSlack. A run that paints nothing leaves the horizon unchanged, so the
//   rest of the column is cast exactly as without the skip;
// - for the shear camera's evenly spaced rows (kEvenRows), lines 9-15 of
//   Algorithm 1 (paint while the sample is above the horizon) without a
//   branch on the sample: the row slopes never decrease, so the
//   horizon moves to the larger of its row and the first row not below the
//   sample (RowSearch). Every sample writes its color and slice into
//   kPaintRows rows from the horizon up, painted or not: a row it does not
//   reach is written again by the sample that paints it, or stays above the
//   column's top, where the scratch may hold anything. On the bench view a
//   visited sample paints more often than not, at random, so the branch was
//   mispredicted at a high rate, each time once the sample's height load
//   (often a cache miss) had come in. The color is read for every sample,
//   not only for painting ones, so that its load starts with the height's
//   rather than after it (measured: 12 % faster on the whole frame);
// - RowSearch starts from a guess computed from the raw height in integer
//   (SliceGuess) beside sigma rather than in float from sigma: the cast waits
//   on the chain behind each height load (perf: the samples sit on the
//   compares that consume it), and that moves five float operations off it
//   (measured: cast 10-15 % faster on the bench view). The per-slice values
//   it reads are one record, so that the loop keeps fewer pointers;
// - the columns of the block take turns, a coarse run each (see the end).
// Inlined, with its turns, into cast_columns_body so that each kernel
// (CastKernel) compiles it for its own instruction set.
template <std::ptrdiff_t kStride, bool kEvenRows>
[[gnu::always_inline]] inline long long FloatingHorizon::cast_blocks(int c0, int c1, std::uint32_t* color,
                                                                     std::uint32_t* slice, int* jend,
                                                                     std::ptrdiff_t col_stride) const {
    const int nrows = rows_cast_;
    const double step = slice_d_.size() > 1 ? slice_d_[1] - slice_d_[0] : 0.0;
    const std::size_t cols = std::size_t(terrain_.cols());
    const std::uint16_t* heights = terrain_.heights().data();
    const std::uint32_t* colors = colors_.data();
    const float* ma = slice_a_.data();
    const float* mb = slice_b_.data();
    const float* smax = slice_smax_.data();
    const float* rows = row_m_.data();
    const RowSearch search(rows, kEvenRows ? nrows : 0);
    const SliceGuess* guesses = slice_guess_.data();
    long long visited = 0;

    BlockRay rays[kBlock];
    int live[kBlock]; // the columns still casting, in order
    int n_live = 0;
    for (int c = c0; c < c1; ++c) {
        const std::size_t cc = std::size_t(c);
        const int k0 = col_k0_[cc], k1 = col_k1_[cc];
        jend[c - c0] = 0;
        if (k0 >= k1 || nrows == 0) continue;
        BlockRay& r = rays[c - c0];
        const double d0 = slice_d_[std::size_t(k0)];
        r.gx = std::llround((eye_gx_ + d0 * col_ux_[cc] + 0.5) * kFixedOne);
        r.gz = std::llround((eye_gz_ + d0 * col_uz_[cc] + 0.5) * kFixedOne);
        r.sx = std::llround(step * col_ux_[cc] * kFixedOne);
        r.sz = std::llround(step * col_uz_[cc] * kFixedOne);
        r.coarse = SliceRunBound(max_pyramid_, skip_runs_ ? kRunCoarse : 0, r.sx, r.sz);
        r.fine = SliceRunBound(max_pyramid_, skip_runs_ ? kRunFine : 0, r.sx, r.sz);
        r.k = k0;
        r.k1 = k1;
        r.j = 0;
        r.hot = false;
        live[n_live++] = c - c0;
    }

    // No sample of the run of slices from k_ at (x, z) can rise above the horizon m.
    auto below = [=](const SliceRunBound& run, int k_, std::int64_t x, std::int64_t z, float m) {
        return run_below(ma, mb, k_, run.run(), float(run.max_height(x, z)), m);
    };
    // One coarse run of column i (one turn of the loop of Algorithm 1 over
    // the column's runs): skipped whole, or split into fine runs that are
    // skipped or cast. False when the column is done.
    auto cast_run = [&](int i) __attribute__((always_inline)) {
        BlockRay& r = rays[i];
        int k = r.k, j = r.j;
        float mj = rows[j];
        if (k >= r.k1 || smax[k] <= mj) {
            jend[i] = j;
            return false;
        }
        const std::int64_t sx = r.sx, sz = r.sz;
        std::int64_t gx = r.gx, gz = r.gz;
        bool hot = r.hot;
        if (!hot && r.coarse.usable() && k + kRunCoarse <= r.k1 && below(r.coarse, k, gx, gz, mj)) {
            r.k = k + kRunCoarse;
            r.gx = gx + kRunCoarse * sx;
            r.gz = gz + kRunCoarse * sz;
            return true;
        }
        std::uint32_t* const out_c = color + std::ptrdiff_t(i) * col_stride;
        std::uint32_t* const out_s = slice + std::ptrdiff_t(i) * col_stride;
        const int kc = std::min(k + kRunCoarse, r.k1);
        while (k < kc) {
            if (!hot && r.fine.usable() && k + kRunFine <= kc && below(r.fine, k, gx, gz, mj)) {
                k += kRunFine;
                gx += kRunFine * sx;
                gz += kRunFine * sz;
                continue;
            }
            // Lines 5-16 of Algorithm 1 for the slices of the fine run.
            const int ke = std::min(k + kRunFine, kc);
            visited += ke - k;
            const int j_before = j;
            for (; k < ke; ++k) {
                const std::size_t ci = std::size_t(gz >> 32) * cols + std::size_t(gx >> 32);
                gx += sx;
                gz += sz;
                const std::uint16_t raw = heights[ci];
                if constexpr (kEvenRows) {
                    const SliceGuess& g = guesses[k];
                    const float sigma = float(raw) * g.a + g.b;
                    const std::int64_t guess = (std::int64_t(raw) * g.ga + g.gb) >> kGuessBits;
                    const int top = search.first_not_below(sigma, int(std::clamp<std::int64_t>(guess, 0, nrows)));
                    const std::uint32_t col = colors[ci];
                    std::uint32_t* oc = out_c + std::ptrdiff_t(j) * kStride;
                    std::uint32_t* os = out_s + std::ptrdiff_t(j) * kStride;
                    for (int q = 0; q < kPaintRows; ++q) {
                        oc[q * kStride] = col;
                        os[q * kStride] = std::uint32_t(k);
                    }
                    for (int q = j + kPaintRows; q < top; ++q) { // a tall sample (near the eye)
                        out_c[std::ptrdiff_t(q) * kStride] = col;
                        out_s[std::ptrdiff_t(q) * kStride] = std::uint32_t(k);
                    }
                    j = std::max(j, top);
                } else if (const float sigma = float(raw) * ma[k] + mb[k]; sigma > mj) {
                    const std::uint32_t col = colors[ci];
                    do { // paint, move the horizon up one pixel (lines 10-14)
                        out_c[std::ptrdiff_t(j) * kStride] = col;
                        out_s[std::ptrdiff_t(j) * kStride] = std::uint32_t(k);
                        mj = rows[++j];
                    } while (sigma > mj);
                }
                if (j == nrows) { // the column is full
                    visited -= ke - k - 1;
                    jend[i] = nrows;
                    return false;
                }
            }
            mj = rows[j];
            hot = j != j_before;
        }
        r.gx = gx;
        r.gz = gz;
        r.k = k;
        r.j = j;
        r.hot = hot;
        return true;
    };
    // The columns take turns, a coarse run each (sec. 5.2: slice k is at one
    // view depth for all columns, and the columns start together): the block
    // moves away from the eye together, so a column finds most of its
    // terrain lines in L1, where its neighbours just loaded them, rather than
    // in L2 or further (measured: cast about 5 % faster on the bench view
    // than column after column). Each column keeps its own state, runs and
    // tests, so it paints what it would paint alone.
    while (n_live > 0) {
        int kept = 0;
        for (int n = 0; n < n_live; ++n)
            if (cast_run(live[n])) live[kept++] = live[n];
        n_live = kept;
    }
    return visited;
}

[[gnu::always_inline]] inline long long
FloatingHorizon::cast_columns_body(const RaycastOptions& options, int c0, int c1, std::uint32_t* color,
                                   std::uint32_t* slice, int* jend, std::ptrdiff_t col_stride,
                                   std::ptrdiff_t row_stride) const {
    const bool bil = options.surface == SurfaceModel::Bilinear;
    if (uniform_slices_ && !bil) {
        if (row_stride == kBlock && rows_even_) return cast_blocks<kBlock, true>(c0, c1, color, slice, jend, col_stride);
        if (row_stride == kBlock) return cast_blocks<kBlock, false>(c0, c1, color, slice, jend, col_stride);
        if (row_stride == 1) return cast_blocks<1, false>(c0, c1, color, slice, jend, col_stride);
        throw std::logic_error("FloatingHorizon: unsupported scratch layout");
    }
    long long visited = 0;
    for (int c = c0; c < c1; ++c) {
        std::uint32_t* cc = color + std::ptrdiff_t(c - c0) * col_stride;
        std::uint32_t* cs = slice + std::ptrdiff_t(c - c0) * col_stride;
        int j;
        if (!uniform_slices_)
            j = bil ? cast_column<true, true>(c, cc, cs, row_stride, visited)
                    : cast_column<false, true>(c, cc, cs, row_stride, visited);
        else j = cast_column<true, false>(c, cc, cs, row_stride, visited);
        jend[c - c0] = j;
    }
    return visited;
}

#if OVERFLIGHT_CAST_V3
__attribute__((target("arch=x86-64-v3"))) long long
FloatingHorizon::cast_columns_v3(const RaycastOptions& options, int c0, int c1, std::uint32_t* color,
                                 std::uint32_t* slice, int* jend, std::ptrdiff_t col_stride,
                                 std::ptrdiff_t row_stride) const {
    return cast_columns_body(options, c0, c1, color, slice, jend, col_stride, row_stride);
}
#endif

bool cast_kernel_available(CastKernel kernel) {
    switch (kernel) {
    case CastKernel::Auto:
    case CastKernel::Portable: return true;
    case CastKernel::X86_64_v3:
#if OVERFLIGHT_CAST_V3
        return __builtin_cpu_supports("x86-64-v3");
#else
        return false;
#endif
    }
    return false;
}

long long FloatingHorizon::cast_columns(const RaycastOptions& options, int c0, int c1, std::uint32_t* color,
                                        std::uint32_t* slice, int* jend, std::ptrdiff_t col_stride,
                                        std::ptrdiff_t row_stride) const {
    if (c1 - c0 > kBlock) throw std::logic_error("FloatingHorizon: more columns than one block");
#if OVERFLIGHT_CAST_V3
    static const bool v3 = cast_kernel_available(CastKernel::X86_64_v3);
    if (v3 && options.kernel != CastKernel::Portable)
        return cast_columns_v3(options, c0, c1, color, slice, jend, col_stride, row_stride);
#endif
    return cast_columns_body(options, c0, c1, color, slice, jend, col_stride, row_stride);
}

void FloatingHorizon::render(const Camera& camera, const RaycastOptions& options, ColorImage& color, DepthImage& depth,
                             RaycastStats* stats) {
    const auto t0 = Clock::now();
    camera.validate();
    if (color.width != camera.width || color.height != camera.height) color.resize(camera.width, camera.height);
    if (depth.width != camera.width || depth.height != camera.height) depth.resize(camera.width, camera.height);
    const double hs = terrain_.h_scale();
    eye_gx_ = camera.eye.x / hs;
    eye_gz_ = camera.eye.z / hs;
    eye_y_ = camera.eye.y;
    const glm::dvec3 F = camera.forward(), R = camera.right();
    fx_ = F.x;
    fz_ = F.z;
    rx_ = R.x;
    rz_ = R.z;
    sky_.build(env_);
    fog_color_ = pack_rgb(to_rgb8(env_.fog_color));
    RaycastStats local;
    if (camera.projection == Projection::Shear) cast_shear(camera, options, color, depth, local);
    else if (options.tilt == TiltMethod::Exact) cast_tilt_exact(camera, options, color, depth, local);
    else cast_tilt_guedes(camera, options, color, depth, local);
    local.slices = int(slice_d_.size());
    local.samples = (long long)local.columns * (long long)local.slices;
    local.ms_total = ms_since(t0);
    if (stats) *stats = local;
}

// The papers' case: vertical view plane, horizon shifted by fp tan(pitch).
// Column c is the plane F + (u_c/fp) R; row j (bottom-up) has slope
// (v_j + fp tan p)/fp; slices run from near to far along F, which is the view
// axis, so slice k's window depth is the depth vector entry (eq. 7).
void FloatingHorizon::cast_shear(const Camera& camera, const RaycastOptions& options, ColorImage& color,
                                 DepthImage& depth, RaycastStats& stats) {
    auto t0 = Clock::now();
    const int W = camera.width, H = camera.height;
    const double fp = camera.focal_px();
    const double shift = fp * std::tan(glm::radians(camera.pitch));
    setup_slices(camera, options, camera.near, camera.far, fp);
    col_a_.resize(std::size_t(W));
    for (int c = 0; c < W; ++c) col_a_[std::size_t(c)] = camera.u_of(c) / fp;
    setup_columns();
    rows_cast_ = H;
    rows_even_ = true; // m_j = (v_j + shift) / fp
    row_m_.resize(std::size_t(H) + 1);
    for (int j = 0; j < H; ++j) row_m_[std::size_t(j)] = float((camera.v_of(H - 1 - j) + shift) / fp);
    row_m_[std::size_t(H)] = kInf;
    // RowSearch's guess straight from the raw height (cast_blocks_column):
    // its map from sigma folded into each slice's sigma = raw a_k + b_k, in
    // fixed point. RowSearch corrects any guess to the exact row; this one is
    // within a row. Saturated so that the sum cannot overflow (the guess is
    // then merely far off, for absurd cameras).
    const RowSearch search(row_m_.data(), H);
    slice_guess_.resize(slice_d_.size());
    const double one = double(std::int64_t(1) << kGuessBits);
    for (std::size_t k = 0; k < slice_d_.size(); ++k) {
        const double a = double(slice_a_[k]) * search.inv_step();
        const double b = (double(slice_b_[k]) - search.m0()) * search.inv_step() + 1.0;
        SliceGuess& g = slice_guess_[k];
        g.ga = std::llround(std::clamp(a, -0x1p20, 0x1p20) * one);
        g.gb = std::llround(std::clamp(b, -0x1p36, 0x1p36) * one);
        g.a = slice_a_[k];
        g.b = slice_b_[k];
    }
    const double a_edge = (W * 0.5) / fp;
    const double m_edge = std::max(std::abs(row_m_[0]), std::abs(row_m_[std::size_t(H) - 1]));
    fog_.build(env_.fog_density, float(camera.far * std::sqrt(1.0 + a_edge * a_edge + m_edge * m_edge) * 1.001));
    stats.ms_setup = ms_since(t0);
    stats.columns = W;

    t0 = Clock::now();
    ShearResolveTables tables{row_m_.data(), slice_depth_.data(), slice_df_.data(), &fog_, fog_color_, sky_.entries()};
    if (uniform_slices_) {
        tables.d_first = slice_df_[0];
        tables.d_step = float(terrain_.h_scale());
    }
    const int blocks = (W + kBlock - 1) / kBlock;
    std::atomic<long long> visited{0}, painted{0};
    // Thread time of each step, summed over the blocks (nanoseconds).
    std::atomic<long long> cast_ns{0}, resolve_ns{0};
    tbb::parallel_for(0, blocks, [&](int b) {
        const auto tc = Clock::now();
        BlockScratch& s = block_scratch_.local();
        const std::size_t need = std::size_t(kBlock) * std::size_t(H + kPaintRows);
        if (s.color.size() < need) {
            s.color.resize(need);
            s.slice.resize(need);
        }
        if (s.jend.size() < std::size_t(kBlock)) s.jend.resize(kBlock);
        const int c0 = b * kBlock, c1 = std::min(W, c0 + kBlock);
        visited += cast_columns(options, c0, c1, s.color.data(), s.slice.data(), s.jend.data(), 1, kBlock);
        long long px = 0;
        for (int c = c0; c < c1; ++c) px += s.jend[std::size_t(c - c0)];
        painted += px;
        ShearBlock blk;
        blk.n = c1 - c0;
        for (int i = 0; i < kBlock; ++i) {
            const double a = i < blk.n ? col_a_[std::size_t(c0 + i)] : 0.0;
            blk.len2[i] = float(1.0 + a * a);
            blk.jend[i] = i < blk.n ? s.jend[std::size_t(i)] : 0;
        }
        const auto tr = Clock::now();
        resolve_shear_block(tables, blk, H, s.color.data(), s.slice.data(), color.pixels.data() + c0,
                            depth.pixels.data() + c0, std::size_t(W));
        const auto te = Clock::now();
        cast_ns += std::chrono::duration_cast<std::chrono::nanoseconds>(tr - tc).count();
        resolve_ns += std::chrono::duration_cast<std::chrono::nanoseconds>(te - tr).count();
    });
    // Cast and resolve are fused per block (the block's scratch stays in L2),
    // so the step's wall time is split between them in proportion to the
    // thread time each took.
    const double ms_fused = ms_since(t0);
    const double thread_ns = double(cast_ns + resolve_ns);
    const double resolve_share = thread_ns > 0 ? double(resolve_ns) / thread_ns : 0.0;
    stats.ms_resolve = ms_fused * resolve_share;
    stats.ms_cast = ms_fused - stats.ms_resolve;
    stats.samples_visited = visited;
    stats.pixels_painted = painted;
}

// Geometry of the tilted camera's rows (DESIGN sec. 2, tilt): the ray through
// (u, v) is F' + (u/fp) R + (v/fp) U' = w F + (u/fp) R + (sin p + (v/fp) cos p) Y
// with w = cos p - (v/fp) sin p, i.e. per unit of depth along F it goes
// sideways u/(fp w) and up m = (sin p + (v/fp) cos p)/w. Its view depth along
// F' is (depth along F)/w.
const FloatingHorizon::TiltRows& FloatingHorizon::tilt_rows(const Camera& camera) {
    TiltRows& t = tilt_rows_;
    const int H = camera.height;
    const double fp = camera.focal_px();
    const double p = glm::radians(camera.pitch), sp = std::sin(p), cp = std::cos(p);
    t.w.resize(std::size_t(H));
    t.m.resize(std::size_t(H));
    double w_top = -1;
    for (int r = 0; r < H; ++r) {
        const double v = camera.v_of(r);
        t.w[std::size_t(r)] = cp - (v / fp) * sp;
        t.m[std::size_t(r)] = (sp + (v / fp) * cp) / t.w[std::size_t(r)];
        w_top = std::max(w_top, t.w[std::size_t(r)]);
    }
    // Rows whose rays point (nearly) straight up or down would need planes
    // fanning out without bound; they go to the ray marcher. Keeping w >=
    // w_max/4 bounds the planes cast to 4 kTiltPlanes times the image width.
    const double w_cut = std::max(w_top * 0.25, 1e-3);
    t.j_lo = H;
    t.j_hi = 0;
    t.w_min = w_top;
    t.w_max = 0;
    for (int j = 0; j < H; ++j) {
        const double w = t.w[std::size_t(H - 1 - j)];
        if (w >= w_cut) {
            t.j_lo = std::min(t.j_lo, j);
            t.j_hi = std::max(t.j_hi, j + 1);
            t.w_min = std::min(t.w_min, w);
            t.w_max = std::max(t.w_max, w);
        }
    }
    if (t.j_hi <= t.j_lo) t.j_lo = t.j_hi = 0;
    return t;
}

// Tilt, exact: every tilted row r is one ray slope m_r in every vertical plane
// (see TiltRows), so a floating horizon over vertical planes with the rows'
// slopes as its rows gives each tilted pixel's first hit exactly, in the plane
// nearest to its own (planes spaced at most 1/kTiltPlanes tilted pixel apart,
// so the sideways error is at most a quarter pixel). Slices cover [near w_min, far w_max]
// along F; a hit past the far plane along F' is sky, as GL would clip it.
void FloatingHorizon::cast_tilt_exact(const Camera& camera, const RaycastOptions& options, ColorImage& color,
                                      DepthImage& depth, RaycastStats& stats) {
    auto t0 = Clock::now();
    const int W = camera.width, H = camera.height;
    const double fp = camera.focal_px();
    const double p = glm::radians(camera.pitch), sp = std::sin(p), cp = std::cos(p);
    const TiltRows& tr = tilt_rows(camera);
    const int rc = tr.j_hi - tr.j_lo;
    const double fp_h = fp * tr.w_max * kTiltPlanes;
    const double a_max = rc > 0 ? (W * 0.5) / (fp * tr.w_min) : 0.0;
    const int ws = rc > 0 ? std::max(1, int(std::ceil(2.0 * a_max * fp_h))) : 0;
    setup_slices(camera, options, camera.near * tr.w_min, camera.far * tr.w_max, fp_h);
    col_a_.resize(std::size_t(ws));
    for (int i = 0; i < ws; ++i) col_a_[std::size_t(i)] = (i + 0.5 - ws * 0.5) / fp_h;
    setup_columns();
    rows_cast_ = rc;
    rows_even_ = false; // tilted rows are not evenly spaced in slope (RowSearch would walk)
    row_m_.resize(std::size_t(rc) + 1);
    for (int i = 0; i < rc; ++i) row_m_[std::size_t(i)] = float(tr.m[std::size_t(H - 1 - (tr.j_lo + i))]);
    row_m_[std::size_t(rc)] = kInf;
    const double lmax = std::sqrt(1.0 + std::pow(W * 0.5 / fp, 2) + std::pow(H * 0.5 / fp, 2));
    fog_.build(env_.fog_density, float(camera.far * lmax * 1.001));
    const std::size_t cstride = std::size_t(rc); // column stride of the scratch
    tilt_color_.resize(std::size_t(ws) * cstride);
    tilt_slice_.resize(tilt_color_.size());
    tilt_jend_.resize(std::size_t(ws));
    stats.ms_setup = ms_since(t0);
    stats.columns = ws;

    t0 = Clock::now();
    std::atomic<long long> visited{0};
    const int blocks = (ws + kBlock - 1) / kBlock;
    tbb::parallel_for(0, blocks, [&](int b) {
        const int c0 = b * kBlock, c1 = std::min(ws, c0 + kBlock);
        const std::size_t off = std::size_t(c0) * cstride;
        visited += cast_columns(options, c0, c1, tilt_color_.data() + off, tilt_slice_.data() + off, tilt_jend_.data() + c0,
                                std::ptrdiff_t(cstride), 1);
    });
    stats.samples_visited = visited;
    stats.ms_cast = ms_since(t0);

    t0 = Clock::now();
    const RayMarcher::Frame mf = RayMarcher::frame(camera);
    std::atomic<long long> painted{0};
    std::atomic<int> fallback{0};
    tbb::parallel_for(0, H, [&](int r) {
        const int j = H - 1 - r;
        const double v = camera.v_of(r), w = tr.w[std::size_t(r)];
        long long px = 0;
        if (j < tr.j_lo || j >= tr.j_hi) {
            for (int c = 0; c < W; ++c) {
                marcher_.shade_pixel(camera, mf, options.surface, c, r, color.at(c, r), depth.at(c, r));
                px += depth.at(c, r) < 1.0f;
            }
            fallback += W;
            painted += px;
            return;
        }
        const int i = j - tr.j_lo;
        const float m_i = row_m_[std::size_t(i)];
        const double scale = fp_h / (fp * w);
        const double up = sp + (v / fp) * cp;
        for (int c = 0; c < W; ++c) {
            const double u = camera.u_of(c);
            const int cs = std::clamp(int(std::floor(u * scale + ws * 0.5)), 0, ws - 1);
            const double len = std::sqrt(1.0 + (u / fp) * (u / fp) + (v / fp) * (v / fp)); // |ray| per unit F' depth
            bool hit = false;
            if (i < tilt_jend_[std::size_t(cs)]) {
                const std::size_t e = std::size_t(cs) * cstride + std::size_t(i);
                const double dv = slice_d_[tilt_slice_[e]] / w; // view depth along F'
                if (dv <= camera.far) {
                    // Fog at the eye distance of the cast ray (plane cs, row i) at the slice.
                    const double a = col_a_[std::size_t(cs)];
                    const float cast_len = std::sqrt(float(1.0 + a * a) + m_i * m_i);
                    const std::uint32_t fw = fog_.weight(slice_df_[tilt_slice_[e]] * cast_len);
                    color.at(c, r) = unpack_rgb(fog_blend(tilt_color_[e], fog_color_, fw));
                    depth.at(c, r) = float(camera.window_depth(std::max(dv, camera.near)));
                    hit = true;
                    ++px;
                }
            }
            if (!hit) {
                color.at(c, r) = unpack_rgb(sky_.color(float(up / len)));
                depth.at(c, r) = 1.0f;
            }
        }
        painted += px;
    });
    stats.pixels_painted = painted;
    stats.fallback_pixels = fallback;
    stats.ms_resolve = ms_since(t0);
}

// Tilt, Guedes (seed 002, Algorithm 1): each column is the vertical plane of
// its pixel on the centre row (a = u / (fp cos p)); every row j of it is a ray
// of slope dz[j] in that plane. Per voxel step the ray height grows by
// step*dz[row] and the depth along F' by step*(cos VA - dz sin VA) (VA = -pitch:
// Guedes' view angle is positive looking down); climbing a pixel raises the
// ray by ph = v*(dz[row+1] - dz[row]) and the depth by -ph sin VA. The printed
// algorithm stores d after the climb (the next row's depth); here each pixel
// gets the depth of its own ray. Its error is that pixels off the centre row
// are not in that plane (measured against the ray marcher, see README).
void FloatingHorizon::cast_tilt_guedes(const Camera& camera, const RaycastOptions& options, ColorImage& color,
                                       DepthImage& depth, RaycastStats& stats) {
    auto t0 = Clock::now();
    const int W = camera.width, H = camera.height;
    const double fp = camera.focal_px();
    const double p = glm::radians(camera.pitch), sp = std::sin(p), cp = std::cos(p);
    const TiltRows& tr = tilt_rows(camera);
    const int rc = tr.j_hi - tr.j_lo;
    RaycastOptions opt = options;
    opt.lod = false; // Guedes' incremental depth steps one cell per voxel
    opt.near_step_pixels = 0.0;
    setup_slices(camera, opt, camera.near * tr.w_min, camera.far * tr.w_max, fp);
    col_a_.resize(std::size_t(W));
    for (int c = 0; c < W; ++c) col_a_[std::size_t(c)] = camera.u_of(c) / (fp * cp);
    setup_columns();
    const std::vector<double>& a = col_a_;
    rows_cast_ = rc;
    row_m_.resize(std::size_t(rc) + 1);
    for (int i = 0; i < rc; ++i) row_m_[std::size_t(i)] = float(tr.m[std::size_t(H - 1 - (tr.j_lo + i))]);
    row_m_[std::size_t(rc)] = kInf;
    const double lmax = std::sqrt(1.0 + std::pow(W * 0.5 / fp, 2) + std::pow(H * 0.5 / fp, 2));
    fog_.build(env_.fog_density, float(camera.far * lmax * 1.001));
    tilt_color_.resize(std::size_t(W) * std::size_t(rc));
    tilt_slice_.resize(tilt_color_.size());
    tilt_jend_.resize(std::size_t(W));
    stats.ms_setup = ms_since(t0);
    stats.columns = W;

    t0 = Clock::now();
    const std::uint32_t fog_color = fog_color_;
    const double hs = terrain_.h_scale();
    const double ey = eye_y_;
    const int cols = terrain_.cols();
    std::atomic<long long> visited{0};
    tbb::parallel_for(0, W, [&](int c) {
        std::uint32_t* out_c = tilt_color_.data() + std::size_t(c) * std::size_t(rc);
        std::uint32_t* out_d = tilt_slice_.data() + std::size_t(c) * std::size_t(rc);
        const int k0 = col_k0_[std::size_t(c)], k1 = col_k1_[std::size_t(c)];
        const double ux = col_ux_[std::size_t(c)], uz = col_uz_[std::size_t(c)];
        const double lat = std::sqrt(1.0 + a[std::size_t(c)] * a[std::size_t(c)]); // horizontal length per unit F
        int row = 0;
        if (rc == 0 || k0 >= k1) {
            tilt_jend_[std::size_t(c)] = 0;
            return;
        }
        // The state as if stepped from the eye to the first slice inside the terrain.
        double v = slice_d_[std::size_t(k0)];
        double x = eye_gx_ + v * ux, y = eye_gz_ + v * uz;
        double z = ey + v * row_m_[0];
        double d = v * (cp + row_m_[0] * sp);
        const double dx = hs * ux, dy = hs * uz;
        int k = k0;
        for (; k < k1; ++k) {
            const std::size_t ci = std::size_t(int(y + 0.5)) * std::size_t(cols) + std::size_t(int(x + 0.5));
            const double h = terrain_.v_scale() * double(terrain_.heights()[ci]) + terrain_.y_offset();
            if (h > z) {
                const std::uint32_t col = colors_[ci];
                do {
                    const double dist = std::sqrt(v * v * lat * lat + (z - ey) * (z - ey));
                    out_c[row] = fog_.enabled() ? fog_blend(col, fog_color, fog_.weight(float(dist))) : col;
                    out_d[row] = float_bits(float(d));
                    if (row + 1 >= rc) {
                        ++row;
                        break;
                    }
                    const double ph = v * (double(row_m_[std::size_t(row) + 1]) - row_m_[std::size_t(row)]);
                    ++row;
                    z += ph;          // update ray height
                    d += ph * sp;     // d -= ph sin(VA)
                } while (h > z);
                if (row >= rc) break;
            }
            x += dx;
            y += dy;
            v += hs;
            z += hs * row_m_[std::size_t(row)];
            d += hs * (cp + row_m_[std::size_t(row)] * sp); // cos VA - dz sin VA
        }
        visited += k - k0;
        tilt_jend_[std::size_t(c)] = row;
    });
    stats.samples_visited = visited;
    stats.ms_cast = ms_since(t0);

    t0 = Clock::now();
    const RayMarcher::Frame mf = RayMarcher::frame(camera);
    std::atomic<long long> painted{0};
    std::atomic<int> fallback{0};
    tbb::parallel_for(0, H, [&](int r) {
        const int j = H - 1 - r;
        long long px = 0;
        if (j < tr.j_lo || j >= tr.j_hi) {
            for (int c = 0; c < W; ++c) {
                marcher_.shade_pixel(camera, mf, options.surface, c, r, color.at(c, r), depth.at(c, r));
                px += depth.at(c, r) < 1.0f;
            }
            fallback += W;
            painted += px;
            return;
        }
        const int i = j - tr.j_lo;
        const double v = camera.v_of(r);
        const double up = sp + (v / fp) * cp;
        for (int c = 0; c < W; ++c) {
            const double u = camera.u_of(c);
            const std::size_t e = std::size_t(c) * std::size_t(rc) + std::size_t(i);
            const double dv = i < tilt_jend_[std::size_t(c)] ? double(bits_float(tilt_slice_[e])) : 2.0 * camera.far;
            if (dv <= camera.far) {
                color.at(c, r) = unpack_rgb(tilt_color_[e]);
                depth.at(c, r) = float(camera.window_depth(std::max(dv, camera.near)));
                ++px;
            } else {
                const double len = std::sqrt(1.0 + (u / fp) * (u / fp) + (v / fp) * (v / fp));
                color.at(c, r) = unpack_rgb(sky_.color(float(up / len)));
                depth.at(c, r) = 1.0f;
            }
        }
        painted += px;
    });
    stats.pixels_painted = painted;
    stats.fallback_pixels = fallback;
    stats.ms_resolve = ms_since(t0);
}

} // namespace overflight
