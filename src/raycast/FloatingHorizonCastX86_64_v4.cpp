// The block cast compiled for x86-64-v4 (AVX-512 F/BW/DQ/VL): everything as
// FloatingHorizonCast.inl casts it, except the papers' case without a light
// mask (evenly spaced one-cell slices of level 0, `blocks` surface), which
// advances 16 columns in lockstep, one slice at a time, in vector registers.
// src/CMakeLists.txt builds this file alone with -march=x86-64-v4 and defines
// OVERFLIGHT_CAST_X86_64_V4 where it does (GCC, x86-64); cast_columns runs
// it only on a CPU that has the level.
//
// Based on: Szenberg, Gattass, Carvalho, "An Algorithm for the Visualization
// of a Terrain with Objects", SIBGRAPI 1997, sec. 5.2: slice k lies at one
// view depth for every column, so the columns of a block can take slice k
// together. Each lane keeps its own column's state of Algorithm 1 (position,
// horizon row) and of the run skipping (the same tests at the same slices as
// cast_blocks), so it paints exactly what its column paints alone.
#if OVERFLIGHT_CAST_X86_64_V4
#include "raycast/FloatingHorizonCast.inl"

#include <immintrin.h>

#include <bit>
#include <climits>

// GCC 12's AVX-512 intrinsics fill their unused operands from a
// self-initialised variable (_mm512_undefined_epi32), which
// -Wmaybe-uninitialized reports where they are inlined.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

namespace overflight {

namespace {

constexpr int kLanes = 16;

// 16 signed 64-bit values split into their high and low 32 bits (a 32.32
// position's integer part and fraction), and joined back.
[[gnu::always_inline]] inline void split64(const std::int64_t* v, __m512i& hi, __m512i& lo) {
    const __m512i a = _mm512_load_si512(v), b = _mm512_load_si512(v + 8);
    const __m512i even = _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30);
    lo = _mm512_permutex2var_epi32(a, even, b);
    hi = _mm512_permutex2var_epi32(a, _mm512_add_epi32(even, _mm512_set1_epi32(1)), b);
}
[[gnu::always_inline]] inline void join64(__m512i hi, __m512i lo, std::int64_t* v) {
    const __m512i first = _mm512_setr_epi32(0, 16, 1, 17, 2, 18, 3, 19, 4, 20, 5, 21, 6, 22, 7, 23);
    _mm512_store_si512(v, _mm512_permutex2var_epi32(lo, first, hi));
    _mm512_store_si512(v + 8, _mm512_permutex2var_epi32(lo, _mm512_add_epi32(first, _mm512_set1_epi32(8)), hi));
}

// Columns [c0, c1) (at most kLanes) of a block as cast_blocks casts them
// (kMask false), output as cast_columns describes (kStride: the row stride).
// The lanes step their 32.32 positions together as integer part and
// fraction (the fraction's carry added: the same sums as 64-bit steps);
// lane l samples slice k while it casts (a run that its tests did not skip).
// Lines 9-15 of Algorithm 1 run on all lanes whose sample rises above their
// horizon: paint one row, read the next row's slope, again while any lane
// still rises. The tests of run skipping run per lane at the slices where
// cast_run makes them (its coarse and fine runs start at the column's first
// slice plus a multiple of kRunFine), between slices.
template <std::ptrdiff_t kStride>
long long cast_lanes(const CastTerrain& t, const CastFrame& f, int c0, int c1, std::uint32_t* color,
                     std::uint32_t* slice, int* jend, std::ptrdiff_t col_stride) {
    static_assert(std::has_single_bit(std::size_t(kStride)), "rows are addressed by a shift");
    constexpr unsigned kRowShift = unsigned(std::countr_zero(std::size_t(kStride)));
    const Columns& cc = f.columns;
    const double* slice_d = f.slices.d.data();
    const double step = f.slices.d.size() > 1 ? slice_d[1] - slice_d[0] : 0.0;
    const int nrows = f.rows.count;
    const float* rows = f.rows.m.data();
    const float* ma = f.slopes.a.data();
    const float* mb = f.slopes.b.data();
    const float* smax = f.slopes.smax.data();
    const int k_end = f.slices.even;

    // Per lane, as BlockRay: the position at the group's slice k, its step,
    // the run bounds, the last slice, the next slice where a test is due, the
    // end of the current coarse run, and the horizon row when the current
    // cast run started.
    alignas(64) std::int64_t gx[kLanes] = {}, gz[kLanes] = {}, sx[kLanes] = {}, sz[kLanes] = {};
    alignas(64) int jv[kLanes] = {};
    alignas(64) float mjv[kLanes] = {};
    alignas(64) int lane_off[kLanes] = {};
    SliceRunBound coarse[kLanes], fine[kLanes];
    int k1[kLanes] = {}, next[kLanes] = {}, kc[kLanes] = {}, j_before[kLanes] = {};
    bool hot[kLanes] = {}, casting[kLanes] = {};
    unsigned live = 0;
    int k = INT_MAX;
    for (int l = 0; l < c1 - c0; ++l) {
        const std::size_t ic = std::size_t(c0 + l);
        jend[l] = 0;
        lane_off[l] = int(l * col_stride);
        const int k0 = std::max(cc.k0[ic], 0), kl = std::min(cc.k1[ic], k_end);
        if (k0 >= kl || nrows == 0) continue;
        const double d0 = slice_d[std::size_t(k0)];
        gx[l] = std::llround((f.view.eye_gx + d0 * cc.ux[ic] + 0.5) * kFixedOne);
        gz[l] = std::llround((f.view.eye_gz + d0 * cc.uz[ic] + 0.5) * kFixedOne);
        sx[l] = std::llround(step * cc.ux[ic] * kFixedOne);
        sz[l] = std::llround(step * cc.uz[ic] * kFixedOne);
        coarse[l] = SliceRunBound(t.max_pyramid, f.skip_runs ? kRunCoarse : 0, sx[l], sz[l]);
        fine[l] = SliceRunBound(t.max_pyramid, f.skip_runs ? kRunFine : 0, sx[l], sz[l]);
        k1[l] = kl;
        next[l] = kc[l] = k0;
        mjv[l] = rows[0];
        live |= 1u << l;
        k = std::min(k, k0);
    }
    if (live == 0) return 0;
    for (unsigned m = live; m; m &= m - 1) { // every lane at slice k (exact: integer steps back)
        const int l = std::countr_zero(m);
        gx[l] -= std::int64_t(next[l] - k) * sx[l];
        gz[l] -= std::int64_t(next[l] - k) * sz[l];
    }

    const std::uint16_t* heights = t.terrain.heights().data();
    const std::uint32_t* colors = t.colors.data();
    // A height is read as the 32 bits ending with it (the upper half), so
    // that the read stays within the array's allocation at its last sample.
    const void* height_base = reinterpret_cast<const char*>(heights) - 2;
    const __m512i cols_v = _mm512_set1_epi32(t.terrain.cols());
    const __m512i off_v = _mm512_load_si512(lane_off);
    const __m512i one = _mm512_set1_epi32(1);
    const __m512i nrows_v = _mm512_set1_epi32(nrows);
    __m512i ix, fx, iz, fz, six, sfx, siz, sfz;
    split64(gx, ix, fx);
    split64(gz, iz, fz);
    split64(sx, six, sfx);
    split64(sz, siz, sfz);
    __m512i j = _mm512_setzero_si512();
    __m512 mj = _mm512_load_ps(mjv);

    long long visited = 0;
    unsigned active = 0; // lanes casting slice k
    int due = k;         // the first slice where a lane's test is due
    for (;;) {
        if (k == due) {
            join64(ix, fx, gx);
            join64(iz, fz, gz);
            _mm512_store_si512(jv, j);
            _mm512_store_ps(mjv, mj);
            for (unsigned m = live; m; m &= m - 1) { // cast_run's decisions, lane by lane
                const int l = std::countr_zero(m);
                const unsigned bit = 1u << l;
                if (next[l] != k) continue;
                if (casting[l]) {
                    hot[l] = jv[l] != j_before[l];
                    casting[l] = false;
                    active &= ~bit;
                }
                if (k == kc[l]) {
                    if (k >= k1[l] || smax[k] <= mjv[l]) {
                        jend[l] = jv[l];
                        live &= ~bit;
                        continue;
                    }
                    if (!hot[l] && coarse[l].usable() && k + kRunCoarse <= k1[l] &&
                        run_below(ma, mb, k, kRunCoarse, float(coarse[l].max_height(gx[l], gz[l])), mjv[l])) {
                        next[l] = kc[l] = k + kRunCoarse;
                        continue;
                    }
                    kc[l] = std::min(k + kRunCoarse, k1[l]);
                }
                if (!hot[l] && fine[l].usable() && k + kRunFine <= kc[l] &&
                    run_below(ma, mb, k, kRunFine, float(fine[l].max_height(gx[l], gz[l])), mjv[l])) {
                    next[l] = k + kRunFine;
                    continue;
                }
                next[l] = std::min(k + kRunFine, kc[l]);
                casting[l] = true;
                j_before[l] = jv[l];
                active |= bit;
            }
            if (live == 0) break;
            due = INT_MAX;
            for (unsigned m = live; m; m &= m - 1) due = std::min(due, next[std::countr_zero(m)]);
            if (active == 0) { // every lane skips: on to the first test due
                for (unsigned m = live; m; m &= m - 1) {
                    const int l = std::countr_zero(m);
                    gx[l] += std::int64_t(due - k) * sx[l];
                    gz[l] += std::int64_t(due - k) * sz[l];
                }
                split64(gx, ix, fx);
                split64(gz, iz, fz);
                k = due;
                continue;
            }
        }
        const __mmask16 act = __mmask16(active);
        const __m512i ci = _mm512_add_epi32(_mm512_mullo_epi32(iz, cols_v), ix);
        const __m512i raw = _mm512_srli_epi32(
            _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), act, ci, height_base, 2), 16);
        const __m512i word = _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), act, ci, colors, 4);
        const __m512 sigma = _mm512_add_ps(_mm512_mul_ps(_mm512_cvtepi32_ps(raw), _mm512_set1_ps(ma[k])),
                                           _mm512_set1_ps(mb[k]));
        __mmask16 up = _mm512_mask_cmp_ps_mask(act, sigma, mj, _CMP_GT_OQ);
        if (up) {
            const __m512i kv = _mm512_set1_epi32(k);
            do { // paint, move the horizon up one pixel (lines 10-14), every lane still above it
                const __m512i at = _mm512_add_epi32(off_v, _mm512_slli_epi32(j, kRowShift));
                _mm512_mask_i32scatter_epi32(color, up, at, word, 4);
                _mm512_mask_i32scatter_epi32(slice, up, at, kv, 4);
                j = _mm512_mask_add_epi32(j, up, j, one);
                mj = _mm512_mask_i32gather_ps(mj, up, j, rows, 4);
                up = _mm512_mask_cmp_ps_mask(up, sigma, mj, _CMP_GT_OQ);
            } while (up);
            if (const unsigned full = _mm512_mask_cmpeq_epi32_mask(act, j, nrows_v)) [[unlikely]] {
                // Columns full: done after this slice.
                for (unsigned m = full; m; m &= m - 1) jend[std::countr_zero(m)] = nrows;
                live &= ~full;
                active &= ~full;
                visited += std::popcount(full);
                if (live == 0) break;
                due = INT_MAX;
                for (unsigned m = live; m; m &= m - 1) due = std::min(due, next[std::countr_zero(m)]);
            }
        }
        visited += std::popcount(active);
        fx = _mm512_add_epi32(fx, sfx);
        ix = _mm512_mask_add_epi32(_mm512_add_epi32(ix, six), _mm512_cmplt_epu32_mask(fx, sfx),
                                   _mm512_add_epi32(ix, six), one);
        fz = _mm512_add_epi32(fz, sfz);
        iz = _mm512_mask_add_epi32(_mm512_add_epi32(iz, siz), _mm512_cmplt_epu32_mask(fz, sfz),
                                   _mm512_add_epi32(iz, siz), one);
        ++k;
        if (active == 0 && k < due) { // the lanes that cast are done: on to the first test due
            join64(ix, fx, gx);
            join64(iz, fz, gz);
            for (unsigned m = live; m; m &= m - 1) {
                const int l = std::countr_zero(m);
                gx[l] += std::int64_t(due - k) * sx[l];
                gz[l] += std::int64_t(due - k) * sz[l];
            }
            split64(gx, ix, fx);
            split64(gz, iz, fz);
            k = due;
        }
    }
    return visited;
}

// cast_columns_body's kernel for the evenly spaced slices of level 0: the
// lanes where they apply, cast_blocks elsewhere (a light mask; a scratch
// whose offsets overflow 32 bits; a grid of 2^31 samples or more).
struct LaneColumns {
    template <std::ptrdiff_t kStride, bool kEvenRows>
    static long long cast(const CastTerrain& t, const CastFrame& f, int c0, int c1, std::uint32_t* color,
                          std::uint32_t* slice, int* jend, std::ptrdiff_t col_stride) {
        const double span = double(kLanes) * double(col_stride) + double(f.rows.count + 1) * double(kStride);
        const double samples = double(t.terrain.cols()) * double(t.terrain.rows());
        if (t.other_colors || span >= 0x1p31 || samples >= 0x1p31)
            return cast_blocks<kStride, kEvenRows>(t, f, c0, c1, color, slice, jend, col_stride);
        long long visited = 0;
        for (int g = c0; g < c1; g += kLanes) {
            const std::ptrdiff_t o = std::ptrdiff_t(g - c0) * col_stride;
            visited += cast_lanes<kStride>(t, f, g, std::min(g + kLanes, c1), color + o, slice + o, jend + (g - c0),
                                           col_stride);
        }
        return visited;
    }
};

} // namespace

long long cast_columns_x86_64_v4(const CastTerrain& terrain, const CastFrame& frame, SurfaceModel surface, int c0,
                                 int c1, std::uint32_t* color, std::uint32_t* slice, int* jend,
                                 std::ptrdiff_t col_stride, std::ptrdiff_t row_stride) {
    return cast_columns_body<LaneColumns>(terrain, frame, surface, c0, c1, color, slice, jend, col_stride,
                                          row_stride);
}

} // namespace overflight
#endif
