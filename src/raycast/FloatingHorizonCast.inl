// The body of the Floating Horizon's block cast (FloatingHorizonCast.h),
// included by one source file per instruction set, each compiling it for its
// own. Everything here has internal linkage (an unnamed namespace) and is
// inlined into the including file's one entry point, so that no copy
// compiled for one instruction set can stand in for the other's.
//
// Based on: Szenberg, Gattass, Carvalho, "An Algorithm for the Visualization
// of a Terrain with Objects", SIBGRAPI 1997, Algorithm 1 (each pixel column
// is painted bottom-up; a sample that rises above the current horizon paints
// pixels until the horizon passes it) with the slices of sec. 5.2.
#include "raycast/FloatingHorizonCast.h"

#include "raycast/FrontFace.h"
#include "raycast/RowSearch.h"
#include "raycast/ShearResolve.h"
#include "raycast/SliceRunBound.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace overflight {

namespace {

// Columns per cast: a block is cast into a scratch that stays in L2
// (kShearBlock x 1080 x 8 bytes, row-major within the block).
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

constexpr double kFixedOne = 4294967296.0; // 32.32 fixed point

// No sample of height <= h (raw) in the run of slices [k, k + run) can rise
// above the horizon m: its sigma = h a_k' + b_k' is linear in 1/d_k', so at
// most the larger value at the run's two ends; kRunSlack covers the float
// rounding of the tables and of sigma.
[[gnu::always_inline]] inline bool run_below(const float* ma, const float* mb, int k, int run, float h, float m) {
    const int e = k + run - 1;
    const float bound = std::max(h * ma[k] + mb[k], h * ma[e] + mb[e]);
    return bound + (h * ma[k] + std::abs(mb[k])) * kRunSlack <= m;
}

// The highest sample in the box [x0, x1] x [z0, z1] (level-0 samples, x0,
// z0 >= 0) widened to the cells of LOD level L that it touches: a bound on
// the samples that nearest lookups on levels <= L in the box read.
[[gnu::always_inline]] inline float level_box_top(const CastTerrain& t, int x0, int x1, int z0, int z1, int L) {
    const int cell = (1 << L) - 1;
    x0 &= ~cell;
    z0 &= ~cell;
    x1 = std::min(x1 | cell, t.terrain.cols() - 1);
    z1 = std::min(z1 | cell, t.terrain.rows() - 1);
    return float(box_max_height(t.max_pyramid, x0, x1, z0, z1));
}

// The highest sample that the nearest lookups of slices [k, e] of a column
// (grid units per unit of view depth ux, uz) on levels <= L can read: their
// positions lie on the column's line in the order of their view depth, so
// the samples they round to lie in the box of the first and last position's.
[[gnu::always_inline]] inline float nearest_run_top(const CastTerrain& t, const CastFrame& f, double ux, double uz,
                                                    int k, int e, int L) {
    const double* slice_d = f.slices.d.data();
    const double xa = f.view.eye_gx + slice_d[k] * ux, za = f.view.eye_gz + slice_d[k] * uz;
    const double xb = f.view.eye_gx + slice_d[e] * ux, zb = f.view.eye_gz + slice_d[e] * uz;
    return level_box_top(t, std::max(int(std::min(xa, xb) + 0.5), 0), int(std::max(xa, xb) + 0.5),
                         std::max(int(std::min(za, zb) + 0.5), 0), int(std::max(za, zb) + 0.5), L);
}

// One column of cast_blocks between two of its turns: the state of
// Algorithm 1 (horizon row j, next slice k) and of its run skipping.
struct BlockRay {
    std::int64_t gx = 0, gz = 0, sx = 0, sz = 0; // position of slice k and step, 32.32, offset by half a cell
    double ux = 0, uz = 0; // a coarser LOD level's cast: grid units per unit of view depth (Columns)
    SliceRunBound coarse, fine;
    int k = 0, k1 = 0; // next slice (the start of a coarse run), end of the column
    int k_first = 0;   // the column's first slice
    int j = 0;         // horizon row (its slope is rows.m[j])
    // The previous slice's sample (FrontFace.h): its color word and raw
    // height, known unless a run was skipped since (cast_slices reads it then).
    std::uint32_t prev_word = 0;
    std::uint16_t prev_raw = 0;
    bool prev_known = false;
    // The last fine run painted: the next one most likely paints too (near
    // the eye every slice does), so it is cast without testing (measured: 5 %
    // faster).
    bool hot = false;
};

// Algorithm 1 for one column, bottom-up. m_j (rows.m) is the slope of row j's
// ray per unit of view depth; the current horizon at slice k is
// eye_y + d_k m_j, and a sample of height h rises above it when
// (h - eye_y)/d_k > m_j, i.e. raw a_k + b_k > m_j (SliceSlopes). Painting a
// pixel moves the horizon up one row (eq. 2); rows only climb, so the column
// is done when the top row is painted or no later slice can reach the horizon
// (SliceSlopes::smax). Color and slice index are stored; depth and fog come
// from the slice when the column is resolved. Where the light mask changes
// between the previous slice's sample and this one, the rows below the point
// where the mesh's light changes take this sample's color under the previous
// one's light (FrontFace.h). This is the general case of level 0 (bilinear
// surface, near refinement); cast_blocks is the papers' case, and
// cast_level_blocks casts the LOD's coarser levels. The column starts at slice
// k_from (at least its first) with the horizon at row j_from: where
// cast_blocks left it after the LOD's evenly spaced slices; it stops before
// slice k_to, where the LOD's coarser levels start (cast_level_blocks).
template <bool kBilinear, bool kVarying>
int cast_column(const CastTerrain& t, const CastFrame& f, int c, std::uint32_t* color, std::uint32_t* slice,
                std::ptrdiff_t stride, long long& visited, int k_from = 0, int j_from = 0,
                int k_to = std::numeric_limits<int>::max()) {
    const std::vector<double>& slice_d = f.slices.d;
    const int k0 = std::max(f.columns.k0[std::size_t(c)], k_from);
    const int k1 = std::min(f.columns.k1[std::size_t(c)], k_to);
    const double ux = f.columns.ux[std::size_t(c)], uz = f.columns.uz[std::size_t(c)];
    const int cols = t.terrain.cols();
    const std::uint16_t* heights = t.terrain.heights().data();
    const std::uint32_t* colors = t.colors.data();
    const float* ma = f.slopes.a.data();
    const float* mb = f.slopes.b.data();
    const float* smax = f.slopes.smax.data();
    const float* rows = f.rows.m.data();
    const int nrows = f.rows.count;
    const double eye_gx = f.view.eye_gx, eye_gz = f.view.eye_gz;
    const Rgb8* other = t.other_colors;
    // The previous slice's sample (FrontFace.h): its position, the index of
    // its color, its height; none at the column's first slice.
    double prev_x = 0, prev_z = 0;
    std::size_t prev_ci = 0;
    float prev_h = 0;
    bool have_prev = false;
    int j = j_from;
    float mj = rows[j];
    int k = k0;
    // Incremental stepping (line 6 of Algorithm 1) in double: 2^-52 per step
    // cannot drift a sample into the next cell over any far plane.
    double gx = eye_gx + (k0 < k1 ? slice_d[std::size_t(k0)] : 0.0) * ux;
    double gz = eye_gz + (k0 < k1 ? slice_d[std::size_t(k0)] : 0.0) * uz;
    const double step = slice_d.size() > 1 ? slice_d[1] - slice_d[0] : 0.0;
    const double sx = step * ux, sz = step * uz;
    // One-cell bilinear slices skip runs as cast_blocks does (fine runs
    // only, positions converted to fixed point for the bound); a skipped run
    // still steps its positions one slice at a time, so the samples after it
    // are the same as without the skip.
    constexpr bool kSkip = kBilinear && !kVarying;
    const SliceRunBound run(t.max_pyramid, kSkip && f.skip_runs ? kRunFine : 0, std::llround(sx * kFixedOne),
                            std::llround(sz * kFixedOne), Footprint::Bilinear);
    int next_test = k0, j_at_test = j_from;
    long long skipped = 0;
    // Uneven slices (near refinement, the LOD's level 0) skip runs too, coarse then fine
    // as cast_blocks does, each bounded from the box of the samples it reads
    // (run_top). coarse_from: the first slice where a coarse run may
    // start (a coarse run that failed its test is cast as fine runs).
    const bool skip_uneven = kVarying && f.skip_runs;
    int coarse_from = k0;
    // The sample at slice k's position (gx, gz): its height and the index of
    // its color.
    const auto sample = [&](double x, double z, float& h) -> std::size_t {
        const int ix = int(x + 0.5), iz = int(z + 0.5);
        if constexpr (kBilinear) {
            const int c0 = std::min(std::max(int(x), 0), cols - 2);
            const int r0 = std::min(std::max(int(z), 0), t.terrain.rows() - 2);
            const float tx = float(x - c0), tz = float(z - r0);
            const std::uint16_t* p = heights + std::size_t(r0) * std::size_t(cols) + std::size_t(c0);
            const float top = float(p[0]) + (float(p[1]) - float(p[0])) * tx;
            const float bottom = float(p[cols]) + (float(p[cols + 1]) - float(p[cols])) * tx;
            h = top + (bottom - top) * tz;
            return std::size_t(iz) * std::size_t(cols) + std::size_t(ix);
        }
        const std::size_t i = std::size_t(iz) * std::size_t(cols) + std::size_t(ix);
        h = float(heights[i]);
        return i;
    };
    if (kVarying && k0 > f.columns.k0[std::size_t(c)] && k0 < k1) { // the previous slice's sample
        prev_x = eye_gx + slice_d[std::size_t(k0) - 1] * ux;
        prev_z = eye_gz + slice_d[std::size_t(k0) - 1] * uz;
        have_prev = true;
        prev_ci = sample(prev_x, prev_z, prev_h);
    }
    // The highest sample that slices [k, e] of this column can read: their
    // positions lie on the column's line in the order of their view depth,
    // so the samples they round to (nearest, or the four around a bilinear
    // position) lie in the box of the first and last position's. 65535 (no
    // bound) where a bilinear position may extrapolate (off the grid's inner
    // area).
    const auto run_top = [&](int e) -> float {
        if constexpr (!kBilinear) return nearest_run_top(t, f, ux, uz, k, e, 0);
        const double xa = eye_gx + slice_d[std::size_t(k)] * ux, za = eye_gz + slice_d[std::size_t(k)] * uz;
        const double xb = eye_gx + slice_d[std::size_t(e)] * ux, zb = eye_gz + slice_d[std::size_t(e)] * uz;
        const double xl = std::min(xa, xb), xh = std::max(xa, xb), zl = std::min(za, zb), zh = std::max(za, zb);
        if (xl < 0 || zl < 0 || xh > cols - 1 || zh > t.terrain.rows() - 1) return 65535.0f;
        return level_box_top(t, int(xl), std::min(int(xh) + 1, cols - 1), int(zl),
                             std::min(int(zh) + 1, t.terrain.rows() - 1), 0);
    };
    // Skips the n slices from k when none of them can rise above the
    // horizon: k becomes the run's last slice, which stands as the previous
    // sample of the next one (FrontFace.h).
    const auto skip_uneven_run = [&](int n) -> bool {
        const int e = k + n - 1;
        if (e >= k1 || !run_below(ma, mb, k, n, run_top(e), mj)) return false;
        prev_x = eye_gx + slice_d[std::size_t(e)] * ux;
        prev_z = eye_gz + slice_d[std::size_t(e)] * uz;
        have_prev = true;
        if (other) prev_ci = sample(prev_x, prev_z, prev_h);
        skipped += n;
        k = e;
        return true;
    };
    for (; k < k1; ++k) {
        if (smax[k] <= mj) break;
        if (skip_uneven && k == next_test) {
            const bool hot = j != j_at_test; // the last run painted: cast the next one without testing
            j_at_test = j;
            next_test = k + kRunFine;
            if (!hot && k >= coarse_from) {
                if (skip_uneven_run(kRunCoarse)) {
                    next_test = k + 1;
                    coarse_from = k + 1;
                    continue;
                }
                coarse_from = k + kRunCoarse;
            }
            if (!hot && skip_uneven_run(kRunFine)) {
                next_test = k + 1;
                continue;
            }
        }
        if (kSkip && k == next_test) {
            const bool hot = j != j_at_test; // the last run painted: cast the next one without testing
            j_at_test = j;
            next_test = k + kRunFine;
            if (!hot && run.usable() && k + kRunFine <= k1 &&
                run_below(ma, mb, k, kRunFine,
                          float(run.max_height(std::llround(gx * kFixedOne), std::llround(gz * kFixedOne))), mj)) {
                double last_x = gx, last_z = gz; // the run's last sample: the next one's previous
                for (int q = 0; q < kRunFine; ++q) {
                    last_x = gx;
                    last_z = gz;
                    gx += sx;
                    gz += sz;
                }
                if (other) prev_ci = sample(last_x, last_z, prev_h);
                prev_x = last_x;
                prev_z = last_z;
                have_prev = true;
                k += kRunFine - 1;
                skipped += kRunFine;
                continue;
            }
        }
        if constexpr (kVarying) {
            gx = eye_gx + slice_d[std::size_t(k)] * ux;
            gz = eye_gz + slice_d[std::size_t(k)] * uz;
        }
        float h;
        const std::size_t ci = sample(gx, gz, h);
        const float sigma = h * ma[k] + mb[k];
        if (sigma > mj) {
            const std::uint32_t word = colors[ci];
            const std::uint32_t col = word & kRgbBits;
            // The rows below where the light changes take the previous sample's light.
            float below = -std::numeric_limits<float>::infinity();
            std::uint32_t near_col = col;
            if (other && have_prev && light_changes(colors[prev_ci], word)) [[unlikely]] {
                const double cross = cell_crossing(prev_x + 0.5, prev_z + 0.5, gx + 0.5, gz + 0.5,
                                               (word & kShadowedBit) == 0, [&](int cell_col, int cell_row) {
                                                   return (colors[std::size_t(cell_row) * std::size_t(cols) + std::size_t(cell_col)] &
                                                           kShadowedBit) != 0;
                                               });
                below = change_slope(f.slopes, slice_d[std::size_t(k) - 1], slice_d[std::size_t(k)], cross, prev_h, h,
                                     kBilinear);
                near_col = pack_rgb(other[ci]);
            }
            do { // paint, move the horizon up one pixel (lines 10-14)
                color[std::ptrdiff_t(j) * stride] = mj < below ? near_col : col;
                slice[std::ptrdiff_t(j) * stride] = std::uint32_t(k);
                mj = rows[++j];
            } while (sigma > mj);
            if (j >= nrows) {
                ++k;
                break;
            }
        }
        prev_x = gx;
        prev_z = gz;
        prev_ci = ci;
        prev_h = h;
        have_prev = true;
        if constexpr (!kVarying) {
            gx += sx;
            gz += sz;
        }
    }
    visited += k - k0 - skipped;
    return j;
}

// The state of cast_blocks' columns: set up for a block, then each column
// takes turns casting one coarse run (cast_run). kMask: the terrain has a
// light mask (FrontFace.h). kLevel: the slices of one coarser level of the
// distance LOD (cast_level_blocks), each column continuing from the row
// where it stopped.
template <std::ptrdiff_t kStride, bool kEvenRows, bool kMask, bool kLevel = false>
struct BlockCast {
    static_assert(!(kLevel && kMask), "a coarser level's samples change no front face's light (FrontFace.h)");

    BlockRay rays[kBlock];
    int live[kBlock]; // the columns still casting, in order
    int n_live = 0;
    long long visited = 0;

    std::uint32_t* color;
    std::uint32_t* slice;
    int* jend;
    std::ptrdiff_t col_stride;
    const std::size_t cols;
    const std::uint16_t* heights;
    const std::uint32_t* colors;
    const float* ma;
    const float* mb;
    const float* smax;
    const float* rows;
    const int nrows;
    const RowSearch search;
    const SliceGuess* guesses;
    const Rgb8* other; // CastTerrain::other_colors
    const SliceSlopes& slopes;
    const double* slice_d;
    // kLevel: the level cast, what its runs are bounded with, the eye.
    const int level;
    const CastTerrain& terrain;
    const CastFrame& frame;
    const double eye_gx, eye_gz;

    // Columns [c0, c1) over slices [k_begin, k_end) of `level` (level 0: from
    // each column's first slice, k_begin 0).
    [[gnu::always_inline]] BlockCast(const CastTerrain& t, const CastFrame& f, int c0, int c1,
                                     std::uint32_t* out_color, std::uint32_t* out_slice, int* out_jend,
                                     std::ptrdiff_t out_col_stride, int cast_level, int k_begin, int k_end)
        : color(out_color), slice(out_slice), jend(out_jend), col_stride(out_col_stride),
          cols(std::size_t(t.level_cols[cast_level])), heights(t.level_heights[cast_level]),
          colors(t.level_colors[cast_level]), ma(f.slopes.a.data()), mb(f.slopes.b.data()),
          smax(f.slopes.smax.data()), rows(f.rows.m.data()), nrows(f.rows.count),
          search(rows, kEvenRows ? nrows : 0), guesses(f.guesses.data()), other(t.other_colors), slopes(f.slopes),
          slice_d(f.slices.d.data()), level(cast_level), terrain(t), frame(f), eye_gx(f.view.eye_gx),
          eye_gz(f.view.eye_gz) {
        const Columns& cc = f.columns;
        const double step = f.slices.d.size() > 1 ? slice_d[1] - slice_d[0] : 0.0;
        for (int c = c0; c < c1; ++c) {
            const std::size_t ic = std::size_t(c);
            const int k0 = std::max(cc.k0[ic], k_begin), k1 = std::min(cc.k1[ic], k_end);
            if constexpr (kLevel) {
                const int j = jend[c - c0];
                if (k0 >= k1 || j >= nrows) continue;
                BlockRay& r = rays[c - c0];
                r.ux = cc.ux[ic];
                r.uz = cc.uz[ic];
                r.k = k0;
                r.k1 = k1;
                r.j = j;
                r.hot = false;
                live[n_live++] = c - c0;
                continue;
            }
            jend[c - c0] = 0;
            if (k0 >= k1 || nrows == 0) continue;
            BlockRay& r = rays[c - c0];
            const double d0 = slice_d[std::size_t(k0)];
            r.gx = std::llround((frame.view.eye_gx + d0 * cc.ux[ic] + 0.5) * kFixedOne);
            r.gz = std::llround((frame.view.eye_gz + d0 * cc.uz[ic] + 0.5) * kFixedOne);
            r.sx = std::llround(step * cc.ux[ic] * kFixedOne);
            r.sz = std::llround(step * cc.uz[ic] * kFixedOne);
            r.coarse = SliceRunBound(t.max_pyramid, frame.skip_runs ? kRunCoarse : 0, r.sx, r.sz);
            r.fine = SliceRunBound(t.max_pyramid, frame.skip_runs ? kRunFine : 0, r.sx, r.sz);
            r.k = k0;
            r.k_first = k0;
            r.k1 = k1;
            r.j = 0;
            r.hot = false;
            r.prev_known = false;
            live[n_live++] = c - c0;
        }
    }

    // No sample of the run of slices from k at (x, z) can rise above the horizon m.
    [[gnu::always_inline]] bool below(const SliceRunBound& run, int k, std::int64_t x, std::int64_t z, float m) const {
        return run_below(ma, mb, k, run.run(), float(run.max_height(x, z)), m);
    }

    // The previous slice's sample of column i before slice k at (gx, gz)
    // after a skipped run (FrontFace.h): read back when there is a light
    // mask; the column's first slice has none (itself stands in).
    [[gnu::always_inline]] void find_prev(const BlockRay& r, int k, std::int64_t gx, std::int64_t gz,
                                          std::uint32_t& prev_word, std::uint16_t& prev_raw) const {
        prev_word = 0;
        if (!other) return;
        if (k > r.k_first) {
            gx -= r.sx;
            gz -= r.sz;
        }
        const std::size_t ci = std::size_t(gz >> 32) * cols + std::size_t(gx >> 32);
        prev_word = colors[ci];
        prev_raw = heights[ci];
    }

    // Sample k (at (x, z), one step (sx, sz) after the previous sample; color
    // index ci, raw height raw) paints rows [j, top) of column out_c after the
    // sample of raw height prev_raw: where their light differs, repaints the
    // rows below the point where the light changes with this sample's color
    // under the other light (FrontFace.h). Rare (shadow edges), so out of the
    // loop's way.
    [[gnu::noinline]] void paint_near_part(std::uint32_t* out_c, int k, std::size_t ci, std::int64_t x,
                                           std::int64_t z, std::int64_t sx, std::int64_t sz, std::uint16_t prev_raw,
                                           std::uint16_t raw, int j, int top) const {
        constexpr double kCell = 1.0 / kFixedOne;
        const double cross = cell_crossing(double(x - sx) * kCell, double(z - sz) * kCell, double(x) * kCell,
                                       double(z) * kCell, (colors[ci] & kShadowedBit) == 0, [&](int cell_col, int cell_row) {
                                           return (colors[std::size_t(cell_row) * cols + std::size_t(cell_col)] & kShadowedBit) != 0;
                                       });
        const float m = change_slope(slopes, slice_d[k - 1], slice_d[k], cross, prev_raw, raw, false);
        const int end = std::min(top, search.first_not_below(m));
        const std::uint32_t near_col = pack_rgb(other[ci]);
        for (int q = j; q < end; ++q) out_c[std::ptrdiff_t(q) * kStride] = near_col;
    }

    // Lines 5-16 of Algorithm 1 for the slices [k, ke) of column i, from
    // horizon row j at position (gx, gz), after the sample of prev_word,
    // prev_raw. False when the column is full (jend written).
    // kLevel: the positions are not stepped but computed from the slice's
    // view depth (cast_level_blocks; the column's direction ux, uz; gx, gz,
    // sx, sz unused), and read on the level's grid.
    [[gnu::always_inline]] bool cast_slices(int i, int& k, int ke, int& j, float& mj, std::int64_t& gx,
                                            std::int64_t& gz, std::int64_t sx, std::int64_t sz,
                                            std::uint32_t& prev_word, std::uint16_t& prev_raw, double ux = 0,
                                            double uz = 0) {
        std::uint32_t* const out_c = color + std::ptrdiff_t(i) * col_stride;
        std::uint32_t* const out_s = slice + std::ptrdiff_t(i) * col_stride;
        visited += ke - k;
        for (; k < ke; ++k) {
            std::size_t ci;
            if constexpr (kLevel) {
                const double x = eye_gx + slice_d[k] * ux, z = eye_gz + slice_d[k] * uz;
                ci = std::size_t(int(z + 0.5) >> level) * cols + std::size_t(int(x + 0.5) >> level);
            } else {
                ci = std::size_t(gz >> 32) * cols + std::size_t(gx >> 32);
                gx += sx;
                gz += sz;
            }
            const std::uint16_t raw = heights[ci];
            const std::uint32_t word = colors[ci];
            const std::uint32_t col = kMask ? word & kRgbBits : word;
            if constexpr (kEvenRows) {
                const SliceGuess& g = guesses[k];
                const float sigma = float(raw) * g.a + g.b;
                const std::int64_t guess = (std::int64_t(raw) * g.ga + g.gb) >> kGuessBits;
                const int top = search.first_not_below(sigma, int(std::clamp<std::int64_t>(guess, 0, nrows)));
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
                if (kMask && light_changes(prev_word, word) && top > j) [[unlikely]]
                    paint_near_part(out_c, k, ci, gx - sx, gz - sz, sx, sz, prev_raw, raw, j, top);
                j = std::max(j, top);
            } else if (const float sigma = float(raw) * ma[k] + mb[k]; sigma > mj) {
                const int j_from = j;
                do { // paint, move the horizon up one pixel (lines 10-14)
                    out_c[std::ptrdiff_t(j) * kStride] = col;
                    out_s[std::ptrdiff_t(j) * kStride] = std::uint32_t(k);
                    mj = rows[++j];
                } while (sigma > mj);
                if (kMask && light_changes(prev_word, word)) [[unlikely]]
                    paint_near_part(out_c, k, ci, gx - sx, gz - sz, sx, sz, prev_raw, raw, j_from, j);
            }
            if constexpr (kMask) {
                prev_word = word;
                prev_raw = raw;
            }
            if (j == nrows) { // the column is full
                visited -= ke - k - 1;
                jend[i] = nrows;
                return false;
            }
        }
        return true;
    }

    // One coarse run of column i (one turn of the loop of Algorithm 1 over
    // the column's runs): skipped whole, or split into fine runs that are
    // skipped or cast. False when the column is done.
    // No sample of slices [k, e] of column r on the cast level can rise above the horizon m.
    [[gnu::always_inline]] bool level_below(const BlockRay& r, int k, int e, float m) const {
        return frame.skip_runs &&
               run_below(ma, mb, k, e - k + 1, nearest_run_top(terrain, frame, r.ux, r.uz, k, e, level), m);
    }

    // cast_run on a coarser level: runs bounded from the box of the samples
    // they read (nearest_run_top), cut short where the level's slices end.
    [[gnu::always_inline]] bool cast_level_run(int i) {
        BlockRay& r = rays[i];
        int k = r.k, j = r.j;
        float mj = rows[j];
        if (k >= r.k1 || smax[k] <= mj) {
            jend[i] = j;
            return false;
        }
        bool hot = r.hot;
        const int kc = std::min(k + kRunCoarse, r.k1);
        if (!hot && level_below(r, k, kc - 1, mj)) {
            r.k = kc;
            return true;
        }
        std::int64_t unused_x = 0, unused_z = 0;
        std::uint32_t unused_word = 0;
        std::uint16_t unused_raw = 0;
        while (k < kc) {
            const int kf = std::min(k + kRunFine, kc);
            if (!hot && level_below(r, k, kf - 1, mj)) {
                k = kf;
                continue;
            }
            const int j_before = j;
            if (!cast_slices(i, k, kf, j, mj, unused_x, unused_z, 0, 0, unused_word, unused_raw, r.ux, r.uz))
                return false;
            mj = rows[j];
            hot = j != j_before;
        }
        r.k = k;
        r.j = j;
        r.hot = hot;
        return true;
    }

    [[gnu::always_inline]] bool cast_run(int i) {
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
            r.prev_known = false;
            return true;
        }
        const int kc = std::min(k + kRunCoarse, r.k1);
        // Locals, so that the cast keeps them in registers.
        bool prev_known = r.prev_known;
        std::uint32_t prev_word = r.prev_word;
        std::uint16_t prev_raw = r.prev_raw;
        while (k < kc) {
            if (!hot && r.fine.usable() && k + kRunFine <= kc && below(r.fine, k, gx, gz, mj)) {
                k += kRunFine;
                gx += kRunFine * sx;
                gz += kRunFine * sz;
                prev_known = false;
                continue;
            }
            if (kMask && !prev_known) {
                find_prev(r, k, gx, gz, prev_word, prev_raw);
                prev_known = true;
            }
            const int j_before = j;
            if (!cast_slices(i, k, std::min(k + kRunFine, kc), j, mj, gx, gz, sx, sz, prev_word, prev_raw))
                return false;
            mj = rows[j];
            hot = j != j_before;
        }
        r.gx = gx;
        r.gz = gz;
        r.k = k;
        r.j = j;
        r.hot = hot;
        r.prev_known = prev_known;
        r.prev_word = prev_word;
        r.prev_raw = prev_raw;
        return true;
    }

    // The columns take turns, a coarse run each (sec. 5.2: slice k is at one
    // view depth for all columns, and the columns start together): the block
    // moves away from the eye together, so a column finds most of its
    // terrain lines in L1, where its neighbours just loaded them, rather than
    // in L2 or further (measured: cast about 5 % faster on the bench view
    // than column after column). Each column keeps its own state, runs and
    // tests, so it paints what it would paint alone.
    [[gnu::always_inline]] long long run() {
        while (n_live > 0) {
            int kept = 0;
            for (int n = 0; n < n_live; ++n)
                if (kLevel ? cast_level_run(live[n]) : cast_run(live[n])) live[kept++] = live[n];
            n_live = kept;
        }
        return visited;
    }
};

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
// - the columns of the block take turns, a coarse run each (BlockCast::run).
// - with a light mask (CastTerrain::other_colors), each column carries its
//   previous sample for the front faces' light (FrontFace.h); without one the
//   cast is compiled without it, so the unshadowed frame pays nothing.
// kStride: row stride of the output; kEvenRows: the rows are evenly spaced in
// slope (shear) and the output has kPaintRows rows of padding.
// k_end: the cast stops before slice k_end (f.slices.even: the slices one
// cell apart).
template <std::ptrdiff_t kStride, bool kEvenRows>
[[gnu::always_inline]] inline long long cast_blocks(const CastTerrain& t, const CastFrame& f, int c0, int c1,
                                                    std::uint32_t* color, std::uint32_t* slice, int* jend,
                                                    std::ptrdiff_t col_stride) {
    const int k_end = f.slices.even;
    if (t.other_colors) {
        BlockCast<kStride, kEvenRows, true> block(t, f, c0, c1, color, slice, jend, col_stride, 0, 0, k_end);
        return block.run();
    }
    BlockCast<kStride, kEvenRows, false> block(t, f, c0, c1, color, slice, jend, col_stride, 0, 0, k_end);
    return block.run();
}

// The evenly spaced slices of level 0 as cast_blocks casts them: what
// cast_columns_body runs unless its caller brings a kernel of its own for
// them (FloatingHorizonCastX86_64_v4.cpp).
struct BlockColumns {
    template <std::ptrdiff_t kStride, bool kEvenRows>
    [[gnu::always_inline]] static long long cast(const CastTerrain& t, const CastFrame& f, int c0, int c1,
                                                 std::uint32_t* color, std::uint32_t* slice, int* jend,
                                                 std::ptrdiff_t col_stride) {
        return cast_blocks<kStride, kEvenRows>(t, f, c0, c1, color, slice, jend, col_stride);
    }
};

// The distance LOD's coarser levels the same way, level after level, each
// column continuing from the row (jend) where the finer slices left it. A
// level-L slice reads the level's cell of the nearest sample at the position
// computed from its view depth (eye + d_k u, in double: not stepped, so the
// same cell whatever came before); no front face's light changes there. A
// run is bounded from the box of the samples it reads (nearest_run_top).
// The slices of level L are [level_begin[L], level_begin[L + 1]).
template <std::ptrdiff_t kStride, bool kEvenRows>
[[gnu::always_inline]] inline long long cast_level_blocks(const CastTerrain& t, const CastFrame& f, int c0, int c1,
                                                          std::uint32_t* color, std::uint32_t* slice, int* jend,
                                                          std::ptrdiff_t col_stride, const int* level_begin,
                                                          int levels) {
    long long visited = 0;
    for (int L = 1; L <= levels; ++L)
        if (level_begin[L] < level_begin[L + 1]) {
            BlockCast<kStride, kEvenRows, false, true> block(t, f, c0, c1, color, slice, jend, col_stride, L,
                                                             level_begin[L], level_begin[L + 1]);
            visited += block.run();
        }
    return visited;
}

// Blocks: how the evenly spaced slices of level 0 are cast (BlockColumns).
template <class Blocks = BlockColumns>
[[gnu::always_inline]] inline long long cast_columns_body(const CastTerrain& t, const CastFrame& f,
                                                          SurfaceModel surface, int c0, int c1, std::uint32_t* color,
                                                          std::uint32_t* slice, int* jend, std::ptrdiff_t col_stride,
                                                          std::ptrdiff_t row_stride) {
    const bool bil = surface == SurfaceModel::Bilinear;
    const bool uniform = f.slices.uniform;
    if (row_stride != kBlock && row_stride != 1) throw std::logic_error("FloatingHorizon: unsupported scratch layout");
    const bool even_rows = row_stride == kBlock && f.rows.even;
    long long visited = 0;
    // `blocks`: the evenly spaced slices (all of them, or the LOD's
    // level-0 part) as cast_blocks.
    if (!bil && f.slices.even > 0) {
        if (even_rows) visited = Blocks::template cast<kBlock, true>(t, f, c0, c1, color, slice, jend, col_stride);
        else if (row_stride == kBlock)
            visited = Blocks::template cast<kBlock, false>(t, f, c0, c1, color, slice, jend, col_stride);
        else visited = Blocks::template cast<1, false>(t, f, c0, c1, color, slice, jend, col_stride);
        if (uniform) return visited;
    }
    if (uniform) { // bilinear
        for (int c = c0; c < c1; ++c)
            jend[c - c0] = cast_column<true, false>(t, f, c, color + std::ptrdiff_t(c - c0) * col_stride,
                                                    slice + std::ptrdiff_t(c - c0) * col_stride, row_stride, visited);
        return visited;
    }
    // Uneven slices: the rest of level 0 column by column, continuing each
    // column from where it left off, then the LOD's coarser levels as blocks.
    // Levels never decrease along the slices.
    const std::vector<std::uint8_t>& lv = f.slices.level;
    int level_begin[CastTerrain::kMaxLevels + 1];
    int levels = 0;
    level_begin[0] = 0;
    level_begin[1] = int(std::upper_bound(lv.begin(), lv.end(), std::uint8_t(0)) - lv.begin());
    if (level_begin[1] < int(lv.size())) {
        levels = lv.back();
        for (int L = 2; L <= levels + 1; ++L)
            level_begin[L] = int(std::upper_bound(lv.begin(), lv.end(), std::uint8_t(L - 1)) - lv.begin());
    }
    const int k_from = bil ? 0 : f.slices.even;
    for (int c = c0; c < c1; ++c) {
        const int j_from = k_from > 0 ? jend[c - c0] : 0;
        jend[c - c0] = j_from == f.rows.count
                           ? j_from
                           : bil ? cast_column<true, true>(t, f, c, color + std::ptrdiff_t(c - c0) * col_stride,
                                                           slice + std::ptrdiff_t(c - c0) * col_stride, row_stride,
                                                           visited, 0, 0, level_begin[1])
                                 : cast_column<false, true>(t, f, c, color + std::ptrdiff_t(c - c0) * col_stride,
                                                            slice + std::ptrdiff_t(c - c0) * col_stride, row_stride,
                                                            visited, k_from, j_from, level_begin[1]);
    }
    if (levels == 0) return visited;
    if (even_rows)
        visited += cast_level_blocks<kBlock, true>(t, f, c0, c1, color, slice, jend, col_stride, level_begin, levels);
    else if (row_stride == kBlock)
        visited += cast_level_blocks<kBlock, false>(t, f, c0, c1, color, slice, jend, col_stride, level_begin, levels);
    else visited += cast_level_blocks<1, false>(t, f, c0, c1, color, slice, jend, col_stride, level_begin, levels);
    return visited;
}

} // namespace

} // namespace overflight
