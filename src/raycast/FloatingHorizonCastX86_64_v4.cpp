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

#include "core/HugePages.h"

#include <immintrin.h>

#include <bit>
#include <climits>
#include <cmath>

// GCC 12's AVX-512 intrinsics fill their unused operands from a
// self-initialised variable (_mm512_undefined_epi32), which
// -Wmaybe-uninitialized reports where they are inlined.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

namespace overflight {

namespace {

constexpr int kLanes = 16;
// Slices ahead of the cast that the lanes' samples are prefetched: the
// samples' loads wait on the terrain's lines (far past L2), and the window of
// out-of-order execution holds only a couple of slices.
constexpr int kAhead = 8;
// Rows a lane paints from its horizon up in one store (the rows it does not
// reach are painted again or lie above its column's top).
constexpr int kLanePaintRows = 8;
// A lane paints the low 8 bits of the slice index into the packed color's
// free top byte (0x00BBGGRR: no light mask here) instead of a second stripe
// of slice indices. A column's rows are painted from slices that never
// decrease upwards (Algorithm 1 paints a row once, front to back), so a row's
// slice is the row below's plus the difference of their low bits modulo 256,
// wherever the step between the two is below 256 slices; where it is not (a
// lane's first rise, or a rise after a gap of 256 slices or more) the rise is
// a jump, kept aside with its row and slice. Consecutive jumps of a lane are
// at least 256 slices apart, so a lane has at most k_end / 256 + 1 of them.
constexpr int kSliceLowBits = 8;
constexpr int kSliceLowMask = (1 << kSliceLowBits) - 1;

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

// The 32.32 positions of 16 lanes as integer parts and fractions, stepped
// together: the fraction's carry is added to the integer part, so the sums
// are those of 64-bit steps.
struct Cursor {
    __m512i ix, fx, iz, fz;
    // Positions (gx, gz) plus n steps (sx, sz).
    [[gnu::always_inline]] void set(const std::int64_t* gx, const std::int64_t* gz, const std::int64_t* sx,
                                    const std::int64_t* sz, int n) {
        alignas(64) std::int64_t x[kLanes], z[kLanes];
        for (int l = 0; l < kLanes; ++l) {
            x[l] = gx[l] + std::int64_t(n) * sx[l];
            z[l] = gz[l] + std::int64_t(n) * sz[l];
        }
        split64(x, ix, fx);
        split64(z, iz, fz);
    }
    [[gnu::always_inline]] void get(std::int64_t* gx, std::int64_t* gz) const {
        join64(ix, fx, gx);
        join64(iz, fz, gz);
    }
    [[gnu::always_inline]] void step(const Cursor& s) {
        const __m512i one = _mm512_set1_epi32(1);
        fx = _mm512_add_epi32(fx, s.fx);
        ix = _mm512_mask_add_epi32(_mm512_add_epi32(ix, s.ix), _mm512_cmplt_epu32_mask(fx, s.fx),
                                   _mm512_add_epi32(ix, s.ix), one);
        fz = _mm512_add_epi32(fz, s.fz);
        iz = _mm512_mask_add_epi32(_mm512_add_epi32(iz, s.iz), _mm512_cmplt_epu32_mask(fz, s.fz),
                                   _mm512_add_epi32(iz, s.iz), one);
    }
    // The index of each lane's nearest sample on a grid of `cols` columns.
    [[gnu::always_inline]] __m512i sample(__m512i cols) const {
        return _mm512_add_epi32(_mm512_mullo_epi32(iz, cols), ix);
    }
};

// A thread's stripes (cast_lanes), grown as needed. Not a std::vector: this
// file must define no symbol that a baseline build also defines (a template's
// instance), so that none compiled for x86-64-v4 stands in for it.
class Stripes {
public:
    Stripes() = default;
    Stripes(const Stripes&) = delete;
    Stripes& operator=(const Stripes&) = delete;
    ~Stripes() { free_huge_pages(data_); }
    // On huge pages (HugePages.h): a step paints 32 stripes.
    std::uint32_t* get(std::size_t n) {
        if (n > size_) {
            free_huge_pages(data_);
            data_ = nullptr;
            data_ = static_cast<std::uint32_t*>(allocate_huge_pages(n * sizeof(std::uint32_t)));
            size_ = n;
        }
        return data_;
    }

private:
    std::uint32_t* data_ = nullptr;
    std::size_t size_ = 0;
};

// 16 records as 8 quadword pairs (a, b) split into their low halves (packed
// colors) and high halves (raw heights).
[[gnu::always_inline]] inline void split_records(__m512i a, __m512i b, __m512i& word, __m512i& raw) {
    const __m512i even = _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30);
    word = _mm512_permutex2var_epi32(a, even, b);
    raw = _mm512_permutex2var_epi32(a, _mm512_add_epi32(even, _mm512_set1_epi32(1)), b);
}

// The records (CastTerrain::records) of the lanes in m at samples idx, as
// two gathers of 8; 0 in the other lanes.
[[gnu::always_inline]] inline void gather_records(__mmask16 m, __m512i idx, const std::uint64_t* rec, __m512i& word,
                                                  __m512i& raw) {
    const __m512i a = _mm512_mask_i32gather_epi64(_mm512_setzero_si512(), __mmask8(m),
                                                  _mm512_castsi512_si256(idx), rec, 8);
    const __m512i b = _mm512_mask_i32gather_epi64(_mm512_setzero_si512(), __mmask8(m >> 8),
                                                  _mm512_extracti64x4_epi64(idx, 1), rec, 8);
    split_records(a, b, word, raw);
}

// The records of all 16 lanes at samples idx (each a sample of the grid), as
// 16 loads: on Zen 4 that is faster than gather_records' two gathers (from
// L1, 3.8 against 5.8 ns per 16 records; the 4K frame about 2 % faster). The
// indices are read back from memory (volatile), as for the prefetches.
[[gnu::always_inline]] inline void load_records(__m512i idx, const std::uint64_t* rec, __m512i& word, __m512i& raw) {
    alignas(64) int stored[kLanes];
    _mm512_store_si512(stored, idx);
    const volatile int* index = stored;
    __m256i pairs[4]; // records 4q .. 4q + 3
    for (int q = 0; q < 4; ++q) {
        const auto pair = [&](int l) {
            const int i0 = index[l], i1 = index[l + 1];
            return _mm_insert_epi64(_mm_cvtsi64_si128(static_cast<long long>(rec[i0])),
                                    static_cast<long long>(rec[i1]), 1);
        };
        pairs[q] = _mm256_inserti128_si256(_mm256_castsi128_si256(pair(4 * q)), pair(4 * q + 2), 1);
    }
    split_records(_mm512_inserti64x4(_mm512_castsi256_si512(pairs[0]), pairs[1], 1),
                  _mm512_inserti64x4(_mm512_castsi256_si512(pairs[2]), pairs[3], 1), word, raw);
}

// A 16 x 16 tile of 32-bit values transposed: v[i] element e becomes v[e] element i.
[[gnu::always_inline]] inline void transpose16(__m512i* v) {
    __m512i t[16], u[16];
    for (int i = 0; i < 16; i += 2) {
        t[i] = _mm512_unpacklo_epi32(v[i], v[i + 1]);
        t[i + 1] = _mm512_unpackhi_epi32(v[i], v[i + 1]);
    }
    // u[4a + b], 128-bit lane q: element 4q + b of v[4a .. 4a + 3].
    for (int a = 0; a < 16; a += 4) {
        u[a] = _mm512_unpacklo_epi64(t[a], t[a + 2]);
        u[a + 1] = _mm512_unpackhi_epi64(t[a], t[a + 2]);
        u[a + 2] = _mm512_unpacklo_epi64(t[a + 1], t[a + 3]);
        u[a + 3] = _mm512_unpackhi_epi64(t[a + 1], t[a + 3]);
    }
    for (int b = 0; b < 4; ++b) { // the 128-bit lanes of u[b], u[4 + b], u[8 + b], u[12 + b] transposed
        const __m512i v0 = _mm512_shuffle_i32x4(u[b], u[4 + b], 0x44), v1 = _mm512_shuffle_i32x4(u[b], u[4 + b], 0xEE);
        const __m512i v2 = _mm512_shuffle_i32x4(u[8 + b], u[12 + b], 0x44);
        const __m512i v3 = _mm512_shuffle_i32x4(u[8 + b], u[12 + b], 0xEE);
        v[b] = _mm512_shuffle_i32x4(v0, v2, 0x88);
        v[4 + b] = _mm512_shuffle_i32x4(v0, v2, 0xDD);
        v[8 + b] = _mm512_shuffle_i32x4(v1, v3, 0x88);
        v[12 + b] = _mm512_shuffle_i32x4(v1, v3, 0xDD);
    }
}

// The SliceRunBound of each lane for one run length, asked for all lanes at
// once: when every usable lane reads the same pyramid level (all but the
// groups of columns where the level changes with the heading), the four
// corners of the lanes' boxes are gathered; otherwise each lane asks its own.
class LaneRuns {
public:
    LaneRuns(const HeightPyramid& pyramid, const SliceRunBound* runs, int lanes) : runs_(runs) {
        alignas(64) std::int64_t dx[kLanes] = {}, dz[kLanes] = {};
        int level = -1;
        for (int l = 0; l < lanes; ++l) {
            if (!runs[l].usable()) continue;
            usable_ |= 1u << l;
            dx[l] = runs[l].dx();
            dz[l] = runs[l].dz();
            if (level < 0) level = runs[l].level();
            uniform_ = uniform_ && runs[l].level() == level;
        }
        split64(dx, dxi_, dxf_);
        split64(dz, dzi_, dzf_);
        if (level < 0 || !uniform_) return;
        const HeightPyramid::Level& lv = pyramid.level(level);
        // As the terrain's heights: each read as the 32 bits ending with it.
        base_ = reinterpret_cast<const char*>(lv.heights.data()) - 2;
        level_ = _mm512_set1_epi32(level);
        cols_ = _mm512_set1_epi32(lv.cols);
        last_col_ = _mm512_set1_epi32(lv.cols - 1);
        last_row_ = _mm512_set1_epi32(lv.rows - 1);
    }
    __mmask16 usable() const { return __mmask16(usable_); }

    // SliceRunBound::max_height of the runs starting at each lane of `at`
    // in `lanes` (usable ones), as floats; 0 elsewhere. gx, gz: scratch.
    [[gnu::always_inline]] __m512 max_height(__mmask16 lanes, const Cursor& at, std::int64_t* gx,
                                             std::int64_t* gz) const;

private:
    // The cells of the box's two corners along one axis: the first and last
    // positions' samples (the 64-bit sum as in Cursor::step), ordered, on
    // the level's grid, clamped to it.
    [[gnu::always_inline]] void cells(__m512i i, __m512i f, __m512i di, __m512i df, __m512i last, __m512i& lo,
                                      __m512i& hi) const {
        const __m512i fe = _mm512_add_epi32(f, df);
        const __m512i ie = _mm512_mask_add_epi32(_mm512_add_epi32(i, di), _mm512_cmplt_epu32_mask(fe, df),
                                                 _mm512_add_epi32(i, di), _mm512_set1_epi32(1));
        const __m512i zero = _mm512_setzero_si512();
        lo = _mm512_min_epi32(_mm512_max_epi32(_mm512_srav_epi32(_mm512_min_epi32(i, ie), level_), zero), last);
        hi = _mm512_min_epi32(_mm512_max_epi32(_mm512_srav_epi32(_mm512_max_epi32(i, ie), level_), zero), last);
    }

    const SliceRunBound* runs_;
    unsigned usable_ = 0;
    bool uniform_ = true;
    __m512i dxi_, dxf_, dzi_, dzf_;
    const void* base_ = nullptr;
    __m512i level_, cols_, last_col_, last_row_;
};

[[gnu::always_inline]] inline __m512 LaneRuns::max_height(__mmask16 lanes, const Cursor& at, std::int64_t* gx,
                                                          std::int64_t* gz) const {
    if (!uniform_) {
        alignas(64) float h[kLanes] = {};
        at.get(gx, gz);
        for (unsigned m = lanes; m; m &= m - 1) {
            const int l = std::countr_zero(m);
            h[l] = float(runs_[l].max_height(gx[l], gz[l]));
        }
        return _mm512_load_ps(h);
    }
    __m512i x0, x1, z0, z1;
    cells(at.ix, at.fx, dxi_, dxf_, last_col_, x0, x1);
    cells(at.iz, at.fz, dzi_, dzf_, last_row_, z0, z1);
    // x1 is x0 or x0 + 1 (the box covers at most 2 x 2 cells), so one read
    // of the 32 bits ending with (x1, row) holds both cells of the row.
    const __mmask16 two = _mm512_cmpgt_epi32_mask(x1, x0);
    const __m512i low = _mm512_set1_epi32(0xFFFF);
    auto read = [&](__m512i z) {
        const __m512i cell = _mm512_add_epi32(_mm512_mullo_epi32(z, cols_), x1);
        const __m512i v = _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), lanes, cell, base_, 2);
        return _mm512_mask_max_epi32(_mm512_srli_epi32(v, 16), two, _mm512_srli_epi32(v, 16),
                                     _mm512_and_si512(v, low));
    };
    return _mm512_cvtepi32_ps(_mm512_max_epi32(read(z0), read(z1)));
}

// run_below (FloatingHorizonCast.inl) for the lanes in `lanes`, all at slice
// k: the same operations in the same order, so the same outcome.
[[gnu::always_inline]] inline __mmask16 runs_below(__mmask16 lanes, const float* ma, const float* mb, int k, int run,
                                                   __m512 h, __m512 m) {
    const int e = k + run - 1;
    const __m512 hk = _mm512_mul_ps(h, _mm512_set1_ps(ma[k]));
    const __m512 bound = _mm512_max_ps(_mm512_add_ps(hk, _mm512_set1_ps(mb[k])),
                                       _mm512_add_ps(_mm512_mul_ps(h, _mm512_set1_ps(ma[e])), _mm512_set1_ps(mb[e])));
    const __m512 slack = _mm512_mul_ps(_mm512_add_ps(hk, _mm512_set1_ps(std::abs(mb[k]))), _mm512_set1_ps(kRunSlack));
    return _mm512_mask_cmp_ps_mask(lanes, _mm512_add_ps(bound, slack), m, _CMP_LE_OQ);
}

// How far RowSearch's guess (sigma - m0) * inv_step, in float, can lie from
// the row whose slope sigma is: the guess is non-decreasing in sigma, so a
// sample whose guess t has a fraction clear of this margin lies above row
// floor(t) and not above row floor(t) + 1 (m_floor(t) < sigma <= m_floor(t)+1),
// as the table would say. Twice the largest distance of a row's own guess
// from its index, and a little more for the rounding of 1 - margin.
inline float row_guess_margin(const float* rows, int nrows, float m0, float inv_step) {
    __m512 worst = _mm512_setzero_ps();
    for (int r = 0; r < nrows; r += kLanes) {
        const __mmask16 in = __mmask16(nrows - r >= kLanes ? 0xFFFFu : (1u << (nrows - r)) - 1);
        const __m512 guess = _mm512_mul_ps(_mm512_sub_ps(_mm512_maskz_loadu_ps(in, rows + r), _mm512_set1_ps(m0)),
                                           _mm512_set1_ps(inv_step));
        const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
        const __m512 index = _mm512_cvtepi32_ps(_mm512_add_epi32(_mm512_set1_epi32(r), lane));
        worst = _mm512_mask_max_ps(worst, in, worst, _mm512_abs_ps(_mm512_sub_ps(guess, index)));
    }
    return 2.0f * _mm512_reduce_max_ps(worst) + 0x1p-12f;
}

// Columns [c0, c1) (at most kLanes) of a block as cast_blocks<kBlock, true>
// casts them without a light mask, into the block's scratch (color, slice:
// column c0's entries; row stride kBlock). Lane l samples slice k while its
// column casts (a run that its tests did not skip): the samples of the lanes
// are read as {color, height} records (CastTerrain::records), and the
// first row not below each sample found at once from RowSearch's guess
// (row_guess_margin: the table is read only for a guess close to a row), so
// that a lane rises when that row lies above its horizon and no lane waits on
// another's painting. Lane l paints its own stripe
// (column-major: kLanePaintRows rows from the horizon up in one store, as the
// scalar cast does row by row), the color with the slice's low bits
// (kSliceLowBits); the stripes are transposed into the block at the end, and
// the slice indices restored row by row from the row below and the jumps.
// The tests of run skipping are cast_run's, due at the same slices with the
// same outcome, made for all the lanes due at a slice at once (LaneRuns,
// runs_below); when all lanes skip: on to the first slice where a test is due.
long long cast_lanes(const CastTerrain& t, const CastFrame& f, int c0, int c1, std::uint32_t* color,
                     std::uint32_t* slice, int* jend) {
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
    // the run bounds, the last slice and the first.
    alignas(64) std::int64_t gx[kLanes] = {}, gz[kLanes] = {}, sx[kLanes] = {}, sz[kLanes] = {};
    SliceRunBound coarse[kLanes], fine[kLanes];
    alignas(64) int k1[kLanes] = {}, next[kLanes] = {};
    unsigned live = 0;
    int k = INT_MAX;
    for (int l = 0; l < c1 - c0; ++l) {
        const std::size_t ic = std::size_t(c0 + l);
        jend[l] = 0;
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
        next[l] = k0;
        live |= 1u << l;
        k = std::min(k, k0);
    }
    if (live == 0) return 0;
    for (unsigned m = live; m; m &= m - 1) { // every lane at slice k (exact: integer steps back)
        const int l = std::countr_zero(m);
        gx[l] -= std::int64_t(next[l] - k) * sx[l];
        gz[l] -= std::int64_t(next[l] - k) * sz[l];
    }

    const std::uint64_t* records = t.records.data();
    const __m512i cols_v = _mm512_set1_epi32(t.terrain.cols());
    const __m512i one = _mm512_set1_epi32(1);
    const __m512i nrows_v = _mm512_set1_epi32(nrows);
    Cursor at, ahead, steps;
    split64(sx, steps.ix, steps.fx);
    split64(sz, steps.iz, steps.fz);
    at.set(gx, gz, sx, sz, 0);
    ahead.set(gx, gz, sx, sz, kAhead);
    Cursor coarse_step, fine_step; // kRunCoarse and kRunFine steps
    {
        alignas(64) const std::int64_t none[kLanes] = {};
        coarse_step.set(none, none, sx, sz, kRunCoarse);
        fine_step.set(none, none, sx, sz, kRunFine);
    }
    const std::size_t last_sample = t.terrain.heights().size() - 1;
    const __m512i last_v = _mm512_set1_epi32(int(last_sample));
    const __m512i zero = _mm512_setzero_si512();
    const __m512i paint_rows_v = _mm512_set1_epi32(kLanePaintRows);
    const RowSearch search(rows, nrows);
    const __m512 m0_v = _mm512_set1_ps(search.m0()), inv_step_v = _mm512_set1_ps(search.inv_step());
    const __m512 guess_max = _mm512_set1_ps(float(nrows) + 0.5f);
    const float row_margin_f = row_guess_margin(rows, nrows, search.m0(), search.inv_step());
    const __m512 row_margin = _mm512_set1_ps(row_margin_f);
    const __m512 row_margin_up = _mm512_set1_ps(1.0f - row_margin_f);
    // Each lane paints its own column-major stripe (kLanePaintRows rows of
    // padding, whole 16-row tiles), copied to the output at the end; after
    // the stripes, each lane's jumps (kSliceLowBits): their rows, then their
    // slices, up to `jumps_cap` of each.
    const std::ptrdiff_t stripe = (nrows + kLanePaintRows + 15) / 16 * 16;
    const std::ptrdiff_t jumps_cap = k_end / (kSliceLowMask + 1) + 2;
    thread_local Stripes stripes;
    std::uint32_t* const stripe_c = stripes.get(std::size_t(kLanes * (stripe + 2 * jumps_cap)));
    std::uint32_t* const jump_row = stripe_c + kLanes * stripe;
    std::uint32_t* const jump_k = jump_row + kLanes * jumps_cap;
    alignas(64) int jumps[kLanes] = {};
    // The slice of each lane's last rise (none yet: its first is a jump).
    __m512i k_rose = _mm512_set1_epi32(INT_MIN / 2);
    const __m512i jump_min = _mm512_set1_epi32(kSliceLowMask + 1);
    __m512i j = _mm512_setzero_si512();
    // cast_run's state per lane: the last slice, the next slice where a test
    // is due, the end of the current coarse run, the row when the current
    // cast run started, and whether the last run painted / a run is cast.
    const __m512i k1_v = _mm512_load_si512(k1);
    __m512i next_v = _mm512_load_si512(next), kc_v = next_v, j_before = j;
    __mmask16 hot = 0, casting = 0;
    const LaneRuns coarse_runs(t.max_pyramid, coarse, c1 - c0), fine_runs(t.max_pyramid, fine, c1 - c0);

    long long visited = 0;
    // The samples of slice k, loaded at the end of slice k - 1 for the
    // lanes in `fetched` (the rest gathered when their run starts).
    __m512i next_raw = _mm512_setzero_si512(), next_word = next_raw;
    __mmask16 fetched = 0;
    unsigned active = 0; // lanes casting slice k
    int due = k;         // the first slice where a lane's test is due
    // When every lane skips a run, none casts and the horizons stay put, so
    // the rounds due at the next runs' ends would make the same tests of the
    // same lanes: they are made here in a row, each run's box read from
    // positions stepped on rather than after the previous round's outcome
    // (which cost one round's latency per run). From slice k + run while
    // every lane in `lanes` skips its run of `run` slices ending by `limit`
    // and, with `ends`, no lane's column would end at the run's start (smax,
    // as the round tests it); returns the slice of the first round left to
    // the loop.
    auto skip_in_a_row = [&](__mmask16 lanes, const LaneRuns& runs, const Cursor& run_step, int run, int limit,
                             __m512 mj, bool ends) __attribute__((always_inline)) {
        Cursor on = at;
        on.step(run_step);
        int kk = k + run;
        while (kk + run <= limit &&
               !(ends && _mm512_mask_cmp_ps_mask(lanes, _mm512_set1_ps(smax[kk]), mj, _CMP_LE_OQ)) &&
               runs_below(lanes, ma, mb, kk, run, runs.max_height(lanes, on, gx, gz), mj) == lanes) {
            kk += run;
            on.step(run_step);
        }
        return kk;
    };
    for (;;) {
        if (k == due) {
            // cast_run's decisions for the lanes whose test is due, all at
            // slice k: the same tests as lane by lane, as masks.
            const __m512i kv = _mm512_set1_epi32(k);
            const __m512 mj = _mm512_i32gather_ps(j, rows, 4); // m_j, the horizon's slope
            __mmask16 due_now = _mm512_mask_cmpeq_epi32_mask(__mmask16(live), next_v, kv);
            const __mmask16 ended_run = due_now & casting;
            hot = (hot & ~ended_run) | _mm512_mask_cmpneq_epi32_mask(ended_run, j, j_before);
            casting &= ~ended_run;
            active &= ~unsigned(ended_run);
            __mmask16 at_coarse = _mm512_mask_cmpeq_epi32_mask(due_now, kc_v, kv);
            __mmask16 done = _mm512_mask_cmpge_epi32_mask(at_coarse, kv, k1_v);
            if (const __mmask16 open = at_coarse & ~done)
                done |= _mm512_mask_cmp_ps_mask(open, _mm512_set1_ps(smax[k]), mj, _CMP_LE_OQ);
            _mm512_mask_storeu_epi32(jend, done, j);
            live &= ~unsigned(done);
            at_coarse &= ~done;
            due_now &= ~done;
            const __m512i k_coarse = _mm512_set1_epi32(k + kRunCoarse);
            __mmask16 skip = _mm512_mask_cmple_epi32_mask(at_coarse & ~hot & coarse_runs.usable(), k_coarse, k1_v);
            if (skip)
                skip = runs_below(skip, ma, mb, k, kRunCoarse, coarse_runs.max_height(skip, at, gx, gz), mj);
            next_v = _mm512_mask_mov_epi32(next_v, skip, k_coarse);
            kc_v = _mm512_mask_mov_epi32(kc_v, skip, k_coarse);
            kc_v = _mm512_mask_min_epi32(kc_v, at_coarse & ~skip, k_coarse, k1_v);
            if (skip && skip == __mmask16(live)) {
                const int kk = skip_in_a_row(skip, coarse_runs, coarse_step, kRunCoarse,
                                             _mm512_mask_reduce_min_epi32(skip, k1_v), mj, true);
                next_v = _mm512_mask_mov_epi32(next_v, skip, _mm512_set1_epi32(kk));
                kc_v = _mm512_mask_mov_epi32(kc_v, skip, _mm512_set1_epi32(kk));
            }
            due_now &= ~skip;
            const __m512i k_fine = _mm512_set1_epi32(k + kRunFine);
            skip = _mm512_mask_cmple_epi32_mask(due_now & ~hot & fine_runs.usable(), k_fine, kc_v);
            if (skip) skip = runs_below(skip, ma, mb, k, kRunFine, fine_runs.max_height(skip, at, gx, gz), mj);
            next_v = _mm512_mask_mov_epi32(next_v, skip, k_fine);
            if (skip && skip == __mmask16(live)) { // fine runs within every lane's coarse run
                const int kk = skip_in_a_row(skip, fine_runs, fine_step, kRunFine,
                                             _mm512_mask_reduce_min_epi32(skip, kc_v), mj, false);
                next_v = _mm512_mask_mov_epi32(next_v, skip, _mm512_set1_epi32(kk));
            }
            const __mmask16 cast = due_now & ~skip;
            next_v = _mm512_mask_min_epi32(next_v, cast, k_fine, kc_v);
            casting |= cast;
            j_before = _mm512_mask_mov_epi32(j_before, cast, j);
            active |= cast;
            if (live == 0) break;
            due = _mm512_mask_reduce_min_epi32(__mmask16(live), next_v);
            if (active == 0) { // every lane skips: on to the first test due
                at.get(gx, gz);
                at.set(gx, gz, sx, sz, due - k);
                ahead.set(gx, gz, sx, sz, due - k + kAhead);
                k = due;
                fetched = 0;
                continue;
            }
        }
        const __mmask16 act = __mmask16(active);
        {
            // Prefetch the samples kAhead slices on of the lanes casting now
            // (most cast on: a run that paints is followed by one cast
            // without a test); the others read sample 0.
            // The indices are read back from memory (volatile): 16 loads cost
            // less than the lane extractions GCC emits for them otherwise
            // (4K frame about 1 % faster).
            alignas(64) int pv[kLanes];
            _mm512_store_si512(pv, _mm512_maskz_min_epu32(__mmask16(active), ahead.sample(cols_v), last_v));
            const volatile int* stored = pv;
            for (int l = 0; l < kLanes; ++l)
                _mm_prefetch(reinterpret_cast<const char*>(records + stored[l]), _MM_HINT_T0);
        }
        if (const __mmask16 fresh = act & ~fetched) { // lanes that started a run at this slice
            const __m512i ci = at.sample(cols_v);
            __m512i w, r;
            gather_records(fresh, ci, records, w, r);
            next_raw = _mm512_mask_mov_epi32(next_raw, fresh, r);
            next_word = _mm512_mask_mov_epi32(next_word, fresh, w);
        }
        const __m512i raw = next_raw;
        const __m512i word = next_word;
        const __m512 sigma = _mm512_add_ps(_mm512_mul_ps(_mm512_cvtepi32_ps(raw), _mm512_set1_ps(ma[k])),
                                           _mm512_set1_ps(mb[k]));
        // The first row not below each sample (RowSearch), without reading
        // the row table: the guess's fraction lies clear of the rows'
        // (row_margin); only a lane whose guess lies within it asks the table.
        // A sample rises (sigma > m_j) when that row lies above the horizon j.
        const __m512 guess = _mm512_min_ps(
            _mm512_max_ps(_mm512_mul_ps(_mm512_sub_ps(sigma, m0_v), inv_step_v), _mm512_set1_ps(-1.5f)), guess_max);
        const __m512 guess_floor = _mm512_roundscale_ps(guess, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
        const __m512 fraction = _mm512_sub_ps(guess, guess_floor);
        __m512i top = _mm512_min_epi32(
            _mm512_max_epi32(_mm512_add_epi32(_mm512_cvttps_epi32(guess_floor), one), zero), nrows_v);
        if (const __mmask16 near_row = _mm512_mask_cmp_ps_mask(act, fraction, row_margin, _CMP_LE_OQ) |
                                       _mm512_mask_cmp_ps_mask(act, fraction, row_margin_up, _CMP_GE_OQ))
            [[unlikely]] {
            alignas(64) int tv[kLanes];
            alignas(64) float sv[kLanes];
            _mm512_store_si512(tv, top);
            _mm512_store_ps(sv, sigma);
            for (unsigned m = near_row; m; m &= m - 1) {
                const int l = std::countr_zero(m);
                tv[l] = search.first_not_below(sv[l], tv[l]);
            }
            top = _mm512_load_si512(tv);
        }
        const __mmask16 up = _mm512_mask_cmpgt_epi32_mask(act, top, j);
        if (up) {
            // Paint rows [j, top) (lines 10-14): kLanePaintRows from the
            // horizon up in every lane's stripe, painted or not, the rest for
            // the rare taller spans.
            alignas(64) int jv_now[kLanes];
            alignas(64) std::uint32_t wv[kLanes];
            _mm512_store_si512(jv_now, j);
            _mm512_store_si512(wv, _mm512_or_si512(word, _mm512_set1_epi32(int(unsigned(k) << 24))));
            const __m512i kv = _mm512_set1_epi32(k);
            if (const unsigned jump = _mm512_mask_cmpge_epi32_mask(up, _mm512_sub_epi32(kv, k_rose), jump_min))
                [[unlikely]] {
                for (unsigned m = jump; m; m &= m - 1) {
                    const int l = std::countr_zero(m);
                    jump_row[l * jumps_cap + jumps[l]] = std::uint32_t(jv_now[l]);
                    jump_k[l * jumps_cap + jumps[l]] = std::uint32_t(k);
                    ++jumps[l];
                }
            }
            k_rose = _mm512_mask_mov_epi32(k_rose, up, kv);
            for (int l = 0; l < kLanes; ++l)
                _mm256_storeu_si256(reinterpret_cast<__m256i*>(stripe_c + std::ptrdiff_t(l) * stripe + jv_now[l]),
                                    _mm256_set1_epi32(int(wv[l])));
            if (const unsigned tall = _mm512_mask_cmpgt_epi32_mask(up, _mm512_sub_epi32(top, j), paint_rows_v))
                [[unlikely]] {
                alignas(64) int tv[kLanes];
                _mm512_store_si512(tv, top);
                for (unsigned m = tall; m; m &= m - 1) {
                    const int l = std::countr_zero(m);
                    const __m256i c = _mm256_set1_epi32(int(wv[l]));
                    for (int r = jv_now[l] + kLanePaintRows; r < tv[l]; r += kLanePaintRows)
                        _mm256_storeu_si256(reinterpret_cast<__m256i*>(stripe_c + std::ptrdiff_t(l) * stripe + r), c);
                }
            }
            j = _mm512_mask_mov_epi32(j, up, top);
            if (const unsigned full = _mm512_mask_cmpeq_epi32_mask(act, j, nrows_v)) [[unlikely]] {
                // Columns full: done after this slice.
                _mm512_mask_storeu_epi32(jend, __mmask16(full), nrows_v);
                live &= ~full;
                active &= ~full;
                visited += std::popcount(full);
                if (live == 0) break;
                due = _mm512_mask_reduce_min_epi32(__mmask16(live), next_v);
            }
        }
        visited += std::popcount(active);
        at.step(steps);
        ahead.step(steps);
        ++k;
        if (active == 0 && k < due) { // the lanes that cast are done: on to the first test due
            at.get(gx, gz);
            at.set(gx, gz, sx, sz, due - k);
            ahead.set(gx, gz, sx, sz, due - k + kAhead);
            k = due;
            fetched = 0;
            continue;
        }
        // The next slice's samples of the lanes casting now, asked for before
        // this slice's painting retires (every lane's, clamped: a lane may
        // end here or not cast).
        load_records(_mm512_min_epu32(at.sample(cols_v), last_v), records, next_word, next_raw);
        fetched = __mmask16(active);
    }
    // The stripes to the block's rows [0, jend) of each column, 16 x 16 tiles
    // transposed; each row's slices from the row below's and its low bits,
    // or from the lane's next jump where it starts at the row (row 0 always:
    // a lane's first rise is a jump).
    int top = 0;
    for (int l = 0; l < c1 - c0; ++l) top = std::max(top, jend[l]);
    const __mmask16 lanes = __mmask16((1u << (c1 - c0)) - 1);
    alignas(64) int next_jump[kLanes] = {}, jump_at[kLanes], jump_slice[kLanes];
    // Lane l's jump next_jump[l] (row INT_MAX when none is left).
    const auto load_jump = [&](int l) {
        const int i = next_jump[l];
        jump_at[l] = i < jumps[l] ? int(jump_row[l * jumps_cap + i]) : INT_MAX;
        jump_slice[l] = i < jumps[l] ? int(jump_k[l * jumps_cap + i]) : 0;
    };
    for (int l = 0; l < kLanes; ++l) load_jump(l);
    __m512i jump_at_v = _mm512_load_si512(jump_at), jump_slice_v = _mm512_load_si512(jump_slice);
    const __m512i low_mask = _mm512_set1_epi32(kSliceLowMask), color_mask = _mm512_set1_epi32(0x00FFFFFF);
    __m512i below = _mm512_setzero_si512(); // the slices of the row below
    for (int r0 = 0; r0 < top; r0 += 16) {
        __m512i v[16];
        for (int l = 0; l < 16; ++l) v[l] = _mm512_loadu_si512(stripe_c + r0 + l * stripe);
        transpose16(v);
        const int n = std::min(16, top - r0);
        for (int r = 0; r < n; ++r) {
            const __m512i low = _mm512_srli_epi32(v[r], 32 - kSliceLowBits);
            __m512i ks = _mm512_add_epi32(below, _mm512_and_si512(_mm512_sub_epi32(low, below), low_mask));
            if (const unsigned jump = _mm512_cmpeq_epi32_mask(jump_at_v, _mm512_set1_epi32(r0 + r))) [[unlikely]] {
                ks = _mm512_mask_mov_epi32(ks, __mmask16(jump), jump_slice_v);
                _mm512_store_si512(jump_at, jump_at_v);
                _mm512_store_si512(jump_slice, jump_slice_v);
                for (unsigned m = jump; m; m &= m - 1) {
                    const int l = std::countr_zero(m);
                    ++next_jump[l];
                    load_jump(l);
                }
                jump_at_v = _mm512_load_si512(jump_at);
                jump_slice_v = _mm512_load_si512(jump_slice);
            }
            below = ks;
            const std::ptrdiff_t row_at = std::ptrdiff_t(r0 + r) * kBlock;
            _mm512_mask_storeu_epi32(color + row_at, lanes, _mm512_and_si512(v[r], color_mask));
            _mm512_mask_storeu_epi32(slice + row_at, lanes, ks);
        }
    }
    return visited;
}

// cast_columns_body's kernel for the evenly spaced slices of level 0: the
// lanes for the shear camera's evenly spaced rows (where RowSearch's guess is
// within a row) without a light mask, on a grid of fewer than 2^31 samples
// whose records are built; cast_blocks elsewhere.
struct LaneColumns {
    template <std::ptrdiff_t kStride, bool kEvenRows>
    static long long cast(const CastTerrain& t, const CastFrame& f, int c0, int c1, std::uint32_t* color,
                          std::uint32_t* slice, int* jend, std::ptrdiff_t col_stride) {
        const double samples = double(t.terrain.cols()) * double(t.terrain.rows());
        if (!kEvenRows || t.other_colors || col_stride != 1 || samples >= 0x1p31 || t.records.empty())
            return cast_blocks<kStride, kEvenRows>(t, f, c0, c1, color, slice, jend, col_stride);
        long long visited = 0;
        for (int g = c0; g < c1; g += kLanes)
            visited += cast_lanes(t, f, g, std::min(g + kLanes, c1), color + (g - c0), slice + (g - c0),
                                  jend + (g - c0));
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
