// Based on: Szenberg 1997 sec. 5.2, eq. 7, Algorithm 2, sec. 6; Atmosphere.h.
// See ShearResolve.h.
#include "raycast/ShearResolve.h"

#include "core/CpuFeatures.h"
#include "raycast/LaneLookup.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#if defined(__x86_64__) && defined(__GNUC__)
#define OVERFLIGHT_RESOLVE_AVX2 1
#endif
#if defined(__SSE2__) || OVERFLIGHT_RESOLVE_AVX2
// GCC 12's AVX-512 headers start some intrinsics from an undefined register
// and warn about it where they are inlined (GCC bug 105593, fixed in 13).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop
#endif
#if defined(__wasm_simd128__)
#define OVERFLIGHT_RESOLVE_SIMD128 1
#include <wasm_simd128.h>
#endif

namespace overflight {

namespace {

// Image rows ahead of the one being written whose lines are prefetched for
// writing: the block writes a short run into each of H rows, each row a new
// page of each image, so without it every run waits for its lines (measured
// at 3840x2160 on a Zen 1 EPYC: resolve 25-31 ms against 28-36 ms without).
constexpr int kWritePrefetchRows = 8;

// Prefetches for writing the run of n pixels of image row `row` (color, and
// depth unless `streamed`).
// Always inlined: GCC's interprocedural analysis finds a function that only
// prefetches free of side effects (__builtin_prefetch is a const built-in)
// and deletes the calls to it, prefetches and all.
[[gnu::always_inline]] inline void prefetch_run(const Rgb8* out_c, const float* out_d, std::size_t row, int n,
                                                bool streamed) {
    const char* pc = reinterpret_cast<const char*>(out_c + row);
    const char* pd = reinterpret_cast<const char*>(out_d + row);
    for (int b = 0; b < n * 3; b += 64) __builtin_prefetch(pc + b, 1);
    __builtin_prefetch(pc + n * 3 - 1, 1);
    if (streamed) return;
    for (int b = 0; b < n * 4; b += 64) __builtin_prefetch(pd + b, 1);
    __builtin_prefetch(pd + n * 4 - 1, 1);
}

// The image row of block row j (bottom-up), prefetching the one kWritePrefetchRows above.
// A full block's run has a constant length, so that its prefetches unroll;
// kFull: the caller knows the block is full (else GCC may merge the two
// calls into one loop). streamed: the depth rows are written with streaming
// stores (resolve_rows_avx512), which need no prefetch.
template <bool kFull = false>
[[gnu::always_inline]] inline std::size_t image_row(const ShearBlock& blk, int H, int j, std::size_t W,
                                                    const Rgb8* out_c, const float* out_d, bool streamed = false) {
    if (j + kWritePrefetchRows < H) {
        const std::size_t ahead = std::size_t(H - 1 - j - kWritePrefetchRows) * W;
        if (kFull || blk.n == kShearBlock) prefetch_run(out_c, out_d, ahead, kShearBlock, streamed);
        else prefetch_run(out_c, out_d, ahead, blk.n, false);
    }
    return std::size_t(H - 1 - j) * W;
}

// out[i] = sqrt(len2[i] + m2), the ray length per unit of view depth, for
// every lane. std::sqrt would keep the loop that uses it from vectorising (it
// may set errno); these sums are >= 1.
void ray_lengths(const float* len2, float m2, float* out) {
#if defined(__SSE2__)
    const __m128 add = _mm_set1_ps(m2);
    for (int i = 0; i < kShearBlock; i += 4) _mm_storeu_ps(out + i, _mm_sqrt_ps(_mm_add_ps(_mm_loadu_ps(len2 + i), add)));
#else
    for (int i = 0; i < kShearBlock; ++i) out[i] = std::sqrt(len2[i] + m2);
#endif
}

// Writes 4 packed 0x00BBGGRR colors as 12 bytes of Rgb8.
void store_rgb4(const std::uint32_t* p, Rgb8* out) {
    if constexpr (std::endian::native == std::endian::little) {
        // Three words, each stored directly: one 12-byte copy through a stack
        // array would defeat store forwarding.
        const std::uint32_t w0 = p[0] | (p[1] << 24), w1 = (p[1] >> 8) | (p[2] << 16), w2 = (p[2] >> 16) | (p[3] << 8);
        unsigned char* o = reinterpret_cast<unsigned char*>(out);
        std::memcpy(o, &w0, 4);
        std::memcpy(o + 4, &w1, 4);
        std::memcpy(o + 8, &w2, 4);
    } else {
        for (int i = 0; i < 4; ++i) out[i] = unpack_rgb(p[i]);
    }
}

// Writes the first n of a row's kShearBlock resolved pixels.
void write_run(const std::uint32_t* px, const float* z, int n, Rgb8* oc, float* od) {
    if (n == kShearBlock) {
        for (int i = 0; i < kShearBlock; i += 4) store_rgb4(px + i, oc + i);
    } else {
        for (int i = 0; i < n; ++i) oc[i] = unpack_rgb(px[i]);
    }
    std::memcpy(od, z, sizeof(float) * std::size_t(n));
}

// Rows [j0, j1). kTerrain / kSky: whether the rows have terrain / sky lanes;
// with both, lane i is terrain below jend[i]. The lanes are independent; GCC
// 12 vectorises the sky loop but not the fog loop for generic x86-64 (it
// would need gathers), hence resolve_rows_avx2.
// kAir: the aerial perspective (t.air) instead of fog and sky gradient.
template <bool kTerrain, bool kSky, bool kAir>
void resolve_rows_portable(const ShearResolveTables& t, const ShearBlock& blk, int H, int j0, int j1,
                           const std::uint32_t* color, const std::uint32_t* slice, Rgb8* out_c, float* out_d,
                           std::size_t W) {
    const std::uint32_t* fog = t.fog->entries();
    const float fog_step = t.fog->inv_step();
    for (int j = j0; j < j1; ++j) {
        const float m = t.row_m[j];
        const std::uint32_t* sc = color + std::size_t(j) * kShearBlock;
        const std::uint32_t* ss = slice + std::size_t(j) * kShearBlock;
        alignas(64) float lens[kShearBlock];
        alignas(64) std::uint32_t skies[kShearBlock] = {};
        alignas(64) std::uint32_t px[kShearBlock];
        alignas(64) float zs[kShearBlock];
        ray_lengths(blk.len2, m * m, lens);
        if constexpr (kSky && kAir)
            for (int i = 0; i < kShearBlock; ++i)
                skies[i] = t.air->sky(m / lens[i], (blk.sun_dot[i] + m * t.sun_y) / lens[i]);
        else if constexpr (kSky)
            for (int i = 0; i < kShearBlock; ++i) skies[i] = SkyTable::lookup(t.sky, m / lens[i]);
        for (int i = 0; i < kShearBlock; ++i) {
            const float len = lens[i];
            const bool terrain = kTerrain && (!kSky || j < blk.jend[i]);
            std::uint32_t fogged = 0;
            float z = 1.0f;
            if constexpr (kTerrain) {
                // Sky lanes read slice 0 (their entries are stale): a select
                // rather than a masked load.
                const int k = int(ss[i]) & -int(terrain);
                z = t.slice_depth[k];
                const float d = t.slice_d[k];
                if constexpr (kAir) {
                    fogged = t.air->terrain(sc[i], d * len, d * m, (blk.sun_dot[i] + m * t.sun_y) / len);
                } else {
                    // FogTable::weight (the distance is within the table by construction).
                    const int w = std::min(int(d * len * fog_step + 0.5f), FogTable::kEntries);
                    fogged = fog_blend(sc[i], t.fog_color, fog[w]);
                }
            }
            px[i] = terrain ? fogged : skies[i];
            zs[i] = terrain ? z : 1.0f;
        }
        const std::size_t row = image_row(blk, H, j, W, out_c, out_d);
        write_run(px, zs, blk.n, out_c + row, out_d + row);
    }
}

// The per-frame tables' pointers that the vector kernels read per row and
// per pixel, copied into the kernel (as FogParams): the stores to the images
// could alias anything reached through a reference, so the compiler would
// load them again for every few pixels.
struct SliceTables {
    const float* row_m;
    const float* slice_depth;
    const float* slice_d;
    int slices;

    explicit SliceTables(const ShearResolveTables& t)
        : row_m(t.row_m), slice_depth(t.slice_depth), slice_d(t.slice_d), slices(t.slices) {}
};

// Rows [j0, j1) of a block that are all terrain (kTerrain, !kSky), partly
// terrain (both) or all sky (!kTerrain); kEven: the first slices are evenly
// spaced (ShearResolveTables::d_step), for the kernels that compute their
// view depth rather than look it up (and look it up beyond them).
template <bool kTerrain_, bool kSky_, bool kEven_>
struct Band {
    static constexpr bool kTerrain = kTerrain_, kSky = kSky_, kEven = kEven_;
    int j0, j1;
};

// A block's rows band by band, each through its own instantiation of a
// kernel (`rows(Band)`): all terrain below every column's horizon (jmin),
// both up to the highest (jmax), all sky above.
template <class Rows>
void resolve_bands(const ShearResolveTables& t, int H, int jmin, int jmax, Rows rows) {
    if (t.d_step > 0.0f) {
        rows(Band<true, false, true>{0, jmin});
        rows(Band<true, true, true>{jmin, jmax});
    } else {
        rows(Band<true, false, false>{0, jmin});
        rows(Band<true, true, false>{jmin, jmax});
    }
    rows(Band<false, true, false>{jmax, H});
}

#if OVERFLIGHT_RESOLVE_AVX2
// Lanes i..i+7 of an image row's run: with `direct` (a full block) straight
// to the images (row_c, row_d: the run's first pixel), else to px/zs for
// write_run.
__attribute__((target("avx2"))) inline void store_lanes(__m256i pixel, __m256 depth, int i, bool direct,
                                                         std::uint32_t* px, float* zs, Rgb8* row_c, float* row_d) {
    if (!direct) {
        _mm256_store_si256(reinterpret_cast<__m256i*>(px + i), pixel);
        _mm256_store_ps(zs + i, depth);
        return;
    }
    // 8 packed colors to 24 bytes of Rgb8: 12 bytes per 128-bit lane, then the lanes joined.
    const __m256i rgb_bytes = _mm256_setr_epi8(0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1, //
                                               0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1);
    const __m256i rgb = _mm256_permutevar8x32_epi32(_mm256_shuffle_epi8(pixel, rgb_bytes),
                                                    _mm256_setr_epi32(0, 1, 2, 4, 5, 6, 7, 7));
    char* oc = reinterpret_cast<char*>(row_c + i);
    // 32 bytes hold these 24 and the next 8 pixels' first 8, which the next
    // store overwrites; the last 8 pixels store exactly 24 (the next block's
    // pixels may be another thread's).
    if (i + 8 < kShearBlock) {
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(oc), rgb);
    } else {
        _mm_storeu_si128(reinterpret_cast<__m128i*>(oc), _mm256_castsi256_si128(rgb));
        _mm_storel_epi64(reinterpret_cast<__m128i*>(oc + 16), _mm256_extracti128_si256(rgb, 1));
    }
    _mm256_storeu_ps(row_d + i, depth);
}

// What the vector kernels read of the tables for GL_EXP fog and the sky
// gradient (FogParams) and for the aerial perspective (AirParams), held by
// value: a kernel works on its own copy, which no store to the images can
// change, so the compiler keeps it in registers (through a reference into the
// tables it loaded and broadcast them again for every 8 or 16 pixels).
struct FogParams {
    const std::uint32_t* fog;
    float fog_step;
    std::uint32_t fog_color;
    const std::uint32_t* sky_table;

    explicit FogParams(const ShearResolveTables& t)
        : fog(t.fog->entries()), fog_step(t.fog->inv_step()), fog_color(t.fog_color), sky_table(t.sky) {}
};
struct AirParams {
    const std::uint32_t *haze, *transmit, *opacity;
    const float* column_table;
    float dy_lo, inv_dy_step, sun_y;

    explicit AirParams(const ShearResolveTables& t)
        : haze(t.air->haze()), transmit(t.air->transmit()), opacity(t.air->opacity()), column_table(t.air->column()),
          dy_lo(t.air->dy_lo()), inv_dy_step(t.air->inv_dy_step()), sun_y(t.sun_y) {}
};

// The pixels of 8 lanes, GL_EXP fog and sky gradient: resolve_rows_portable's
// operations lane by lane, the tables read through L (LaneLookup.h). m: the
// row's slope; len, d: each lane's ray length per unit of view depth and view
// depth; c: the surface colors.
template <class L>
struct FogLanes : FogParams {
    using Lookup = L;
    using FogParams::FogParams;

    template <bool kTerrain, bool kSky>
    __attribute__((target("avx2"))) __m256i shade(const ShearBlock&, int, __m256 m, __m256 len, __m256 d, __m256i terrain,
                                                  __m256i c) const {
        const __m256 half = _mm256_set1_ps(0.5f);
        __m256i fogged = _mm256_setzero_si256(), sky = _mm256_setzero_si256();
        if constexpr (kTerrain) {
            const __m256 x = _mm256_add_ps(_mm256_mul_ps(_mm256_mul_ps(d, len), _mm256_set1_ps(fog_step)), half);
            const __m256i a = L::words(fog, FogTable::kEntries + 1,
                                       _mm256_min_epi32(_mm256_cvttps_epi32(x), _mm256_set1_epi32(FogTable::kEntries)));
            const __m256i b = _mm256_sub_epi32(_mm256_set1_epi32(256), a);
            const __m256i mask_rb = _mm256_set1_epi32(0xFF00FF), mask_g = _mm256_set1_epi32(0x00FF00);
            // fog_blend, lane by lane.
            const __m256i rb = _mm256_add_epi32(
                _mm256_mullo_epi32(_mm256_and_si256(c, mask_rb), a),
                _mm256_add_epi32(_mm256_mullo_epi32(_mm256_set1_epi32(int(fog_color & 0xFF00FFu)), b),
                                 _mm256_set1_epi32(0x800080)));
            const __m256i g = _mm256_add_epi32(
                _mm256_mullo_epi32(_mm256_and_si256(c, mask_g), a),
                _mm256_add_epi32(_mm256_mullo_epi32(_mm256_set1_epi32(int(fog_color & 0x00FF00u)), b),
                                 _mm256_set1_epi32(0x008000)));
            fogged = _mm256_or_si256(_mm256_and_si256(_mm256_srli_epi32(rb, 8), mask_rb),
                                     _mm256_and_si256(_mm256_srli_epi32(g, 8), mask_g));
        }
        if constexpr (kSky) {
            const __m256 x = _mm256_add_ps(
                _mm256_mul_ps(_mm256_div_ps(m, len), _mm256_set1_ps(float(SkyTable::kEntries - 1))), half);
            const __m256i e = _mm256_max_epi32(
                _mm256_min_epi32(_mm256_cvttps_epi32(x), _mm256_set1_epi32(SkyTable::kEntries - 1)), _mm256_setzero_si256());
            sky = L::words(sky_table, SkyTable::kEntries, e);
        }
        return _mm256_blendv_epi8(sky, fogged, terrain);
    }
};

// AerialTables::clamp_index, lane by lane.
__attribute__((target("avx2"))) inline __m256i clamp_lanes(__m256 x, float last) {
    return _mm256_cvttps_epi32(_mm256_min_ps(_mm256_max_ps(x, _mm256_setzero_ps()), _mm256_set1_ps(last)));
}

// AerialTables::blend (and, without the surface's share, shade_sky) of 8
// lanes: each channel's (s w + h (256 - w) + 128) >> 8 is at most 65408, so
// red and blue share 16-bit multiplies (the weights are 10-bit fields of t).
__attribute__((target("avx2"))) inline __m256i air_blend(__m256i surface, __m256i t, __m256i haze,
                                                          bool with_surface = true) {
    const __m256i rb = _mm256_set1_epi32(0x00FF00FF), byte = _mm256_set1_epi32(0xFF);
    const __m256i full = _mm256_set1_epi32(0x01000100), round = _mm256_set1_epi32(0x00800080);
    const __m256i w_rb = _mm256_or_si256(_mm256_and_si256(t, _mm256_set1_epi32(0x3FF)),
                                         _mm256_and_si256(_mm256_srli_epi32(t, 4), _mm256_set1_epi32(0x3FF0000)));
    const __m256i w_g = _mm256_and_si256(_mm256_srli_epi32(t, 10), _mm256_set1_epi32(0x3FF));
    const __m256i h_rb = _mm256_and_si256(haze, rb), h_g = _mm256_and_si256(_mm256_srli_epi32(haze, 8), byte);
    __m256i out_rb, out_g;
    if (with_surface) {
        out_rb = _mm256_add_epi16(_mm256_mullo_epi16(_mm256_and_si256(surface, rb), w_rb),
                                  _mm256_mullo_epi16(h_rb, _mm256_sub_epi16(full, w_rb)));
        out_g = _mm256_add_epi16(_mm256_mullo_epi16(_mm256_and_si256(_mm256_srli_epi32(surface, 8), byte), w_g),
                                 _mm256_mullo_epi16(h_g, _mm256_sub_epi16(full, w_g)));
    } else {
        out_rb = _mm256_mullo_epi16(h_rb, w_rb);
        out_g = _mm256_mullo_epi16(h_g, w_g);
    }
    out_rb = _mm256_srli_epi16(_mm256_add_epi16(out_rb, round), 8);
    out_g = _mm256_srli_epi16(_mm256_add_epi16(out_g, round), 8);
    return _mm256_or_si256(out_rb, _mm256_slli_epi32(out_g, 8));
}

// The pixels of 8 lanes through the air (t.air): AerialTables' lookups and
// blends lane by lane, as FogLanes.
template <class L>
struct AirLanes : AirParams {
    using Lookup = L;
    using AirParams::AirParams;

    template <bool kTerrain, bool kSky>
    __attribute__((target("avx2"))) __m256i shade(const ShearBlock& blk, int i, __m256 m, __m256 len, __m256 d,
                                                  __m256i terrain, __m256i c) const {
        const __m256 half = _mm256_set1_ps(0.5f);
        const __m256 cos_sun = _mm256_div_ps(
            _mm256_add_ps(_mm256_loadu_ps(blk.sun_dot + i), _mm256_mul_ps(m, _mm256_set1_ps(sun_y))), len);
        const __m256i p = clamp_lanes(_mm256_add_ps(_mm256_mul_ps(_mm256_add_ps(cos_sun, _mm256_set1_ps(1.0f)),
                                                            _mm256_set1_ps(AerialTables::kPhaseScale)),
                                              half),
                                float(AerialTables::kPhases - 1));
        const __m256i h = L::words(haze, AerialTables::kPhases, p);
        __m256i lit = _mm256_setzero_si256(), sky = _mm256_setzero_si256();
        if constexpr (kTerrain) {
            const __m256 dy = _mm256_mul_ps(d, m);
            const __m256i hj = clamp_lanes(_mm256_add_ps(_mm256_mul_ps(_mm256_sub_ps(dy, _mm256_set1_ps(dy_lo)),
                                                                 _mm256_set1_ps(inv_dy_step)),
                                                   half),
                                     float(AerialTables::kHeights - 1));
            const __m256 per_unit = L::floats(column_table, AerialTables::kHeights, hj);
            const __m256 x = _mm256_add_ps(_mm256_mul_ps(_mm256_mul_ps(d, len), per_unit), half);
            const __m256i w = L::words(transmit, AerialTables::kColumns + 1, _mm256_cvttps_epi32(_mm256_min_ps(
                                                           x, _mm256_set1_ps(float(AerialTables::kColumns)))));
            lit = air_blend(c, w, h);
        }
        if constexpr (kSky) {
            const __m256i q = clamp_lanes(_mm256_add_ps(_mm256_mul_ps(_mm256_div_ps(m, len),
                                                                _mm256_set1_ps(float(AerialTables::kSkies - 1))),
                                                  half),
                                    float(AerialTables::kSkies - 1));
            sky = air_blend(_mm256_setzero_si256(), L::words(opacity, AerialTables::kSkies, q), h, false);
        }
        return _mm256_blendv_epi8(sky, lit, terrain);
    }
};

// resolve_rows_portable with AVX2 gathers or their scalar loads (GCC does
// not emit gathers for generic x86-64 tuning; Lanes::Lookup, LaneLookup.h):
// the same operations in the same order, so the same bits; the pixels of
// each 8 lanes come from `lanes` (FogLanes or AirLanes).
// kEven: the first slices are evenly spaced (ShearResolveTables::d_step), so
// their view depth is computed rather than gathered. A full block's pixels go
// to the images straight from the registers.
// The tables and the lanes are read into locals first (SliceTables, FogParams).
template <bool kTerrain, bool kSky, bool kEven, class Lanes>
__attribute__((target("avx2"))) void resolve_rows_avx2(const ShearResolveTables& t, const Lanes& lanes_in,
                                                       const ShearBlock& blk, int H, int j0, int j1,
                                                       const std::uint32_t* color, const std::uint32_t* slice,
                                                       Rgb8* out_c, float* out_d, std::size_t W) {
    const Lanes lanes = lanes_in;
    const SliceTables st(t);
    const __m256 one = _mm256_set1_ps(1.0f);
    const __m256 d_first = _mm256_set1_ps(t.d_first), d_step = _mm256_set1_ps(t.d_step);
    const __m256i last_even = _mm256_set1_epi32(t.even - 1);
    const bool direct = blk.n == kShearBlock;
    for (int j = j0; j < j1; ++j) {
        const float mj = st.row_m[j];
        const __m256 m = _mm256_set1_ps(mj), m2 = _mm256_set1_ps(mj * mj);
        const __m256i jv = _mm256_set1_epi32(j);
        const std::uint32_t* sc = color + std::size_t(j) * kShearBlock;
        const std::uint32_t* ss = slice + std::size_t(j) * kShearBlock;
        const std::size_t row = image_row(blk, H, j, W, out_c, out_d);
        alignas(32) std::uint32_t px[kShearBlock];
        alignas(32) float zs[kShearBlock];
        for (int i = 0; i < kShearBlock; i += 8) {
            const __m256 len = _mm256_sqrt_ps(_mm256_add_ps(_mm256_loadu_ps(blk.len2 + i), m2));
            const __m256i terrain =
                kTerrain && kSky
                    ? _mm256_cmpgt_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(blk.jend + i)), jv)
                    : _mm256_set1_epi32(kTerrain ? -1 : 0);
            __m256 z = one, d = one;
            __m256i c = _mm256_setzero_si256();
            if constexpr (kTerrain) {
                // Sky lanes read slice 0 (their entries are stale).
                const __m256i k = _mm256_and_si256(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(ss + i)), terrain);
                z = Lanes::Lookup::floats(st.slice_depth, st.slices, k);
                if constexpr (kEven) {
                    d = _mm256_add_ps(d_first, _mm256_mul_ps(d_step, _mm256_cvtepi32_ps(k)));
                    const __m256i beyond = _mm256_cmpgt_epi32(k, last_even);
                    if (!_mm256_testz_si256(beyond, beyond)) [[unlikely]]
                        d = _mm256_blendv_ps(d, Lanes::Lookup::floats(st.slice_d, st.slices, k),
                                             _mm256_castsi256_ps(beyond));
                } else {
                    d = Lanes::Lookup::floats(st.slice_d, st.slices, k);
                }
                c = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(sc + i));
            }
            store_lanes(lanes.template shade<kTerrain, kSky>(blk, i, m, len, d, terrain, c),
                        _mm256_blendv_ps(one, z, _mm256_castsi256_ps(terrain)), i, direct, px, zs, out_c + row,
                        out_d + row);
        }
        if (!direct) write_run(px, zs, blk.n, out_c + row, out_d + row);
    }
}

#define OVERFLIGHT_RESOLVE_AVX512 __attribute__((target("avx512f,avx512bw,avx512dq,avx512vl")))

// table[idx] of 16 lanes (indices in [0, entries)). Neighbouring lanes of an
// image's block read neighbouring entries of each table (the columns see
// nearly the same angles, and below the horizon nearly the same ground: on
// the benchmark view the indices of 16 lanes span less than 8 entries in
// more than 99 % of the cases), so a 32-entry window of the table from 8
// before lane 0's entry is permuted in registers; only when a lane falls
// outside it, or the table is smaller, is it gathered (a gather costs as
// much as the rest of the pixel's work).
template <class T>
OVERFLIGHT_RESOLVE_AVX512 inline __m512i lookup_near(const T* table, int entries, __m512i idx) {
    static_assert(sizeof(T) == 4);
    if (entries >= 32) {
        // Lane 0's entry at least 8 from the start and 24 from the end: no clamp.
        int first = _mm_cvtsi128_si32(_mm512_castsi512_si128(idx)) - 8;
        if (unsigned(first) > unsigned(entries - 32)) [[unlikely]]
            first = std::clamp(first, 0, entries - 32);
        const __m512i rel = _mm512_sub_epi32(idx, _mm512_set1_epi32(first));
        if (!_mm512_cmpge_epu32_mask(rel, _mm512_set1_epi32(32))) [[likely]]
            return _mm512_permutex2var_epi32(_mm512_loadu_si512(table + first), rel,
                                             _mm512_loadu_si512(table + first + 16));
    }
    return _mm512_i32gather_epi32(idx, table, 4);
}

// AerialTables::clamp_index, lane by lane.
OVERFLIGHT_RESOLVE_AVX512 inline __m512i clamp_lanes16(__m512 x, float last) {
    return _mm512_cvttps_epi32(_mm512_min_ps(_mm512_max_ps(x, _mm512_setzero_ps()), _mm512_set1_ps(last)));
}

// Per channel of 16 lanes, h + ((s - h) w + 128) >> 8, which is
// AerialTables::blend's (s w + h (256 - w) + 128) >> 8 exactly (h 256 is a
// multiple of 256): with a = (s - h) 128 and b = w, mulhrs's
// (a b + 2^14) >> 15 is that shift. Red and blue share the 16-bit halves of
// each lane, green has the low half of another; t holds the 10-bit weights.
OVERFLIGHT_RESOLVE_AVX512 inline __m512i air_blend16(__m512i surface, __m512i t, __m512i haze) {
    const __m512i rb = _mm512_set1_epi32(0x00FF00FF), byte = _mm512_set1_epi32(0xFF);
    // Red's weight (bits 0-9 of t) and blue's (bits 20-29) into the halves.
    const __m512i w_rb = _mm512_and_si512(_mm512_mask_blend_epi16(__mmask32(0xAAAAAAAAu), t, _mm512_srli_epi32(t, 4)),
                                          _mm512_set1_epi32(0x03FF03FF));
    const __m512i w_g = _mm512_and_si512(_mm512_srli_epi32(t, 10), _mm512_set1_epi32(0x3FF));
    const __m512i h_rb = _mm512_and_si512(haze, rb), h_g = _mm512_and_si512(_mm512_srli_epi32(haze, 8), byte);
    const __m512i s_rb = _mm512_and_si512(surface, rb), s_g = _mm512_and_si512(_mm512_srli_epi32(surface, 8), byte);
    const __m512i out_rb = _mm512_add_epi16(
        h_rb, _mm512_mulhrs_epi16(_mm512_slli_epi16(_mm512_sub_epi16(s_rb, h_rb), 7), w_rb));
    const __m512i out_g = _mm512_add_epi16(
        h_g, _mm512_mulhrs_epi16(_mm512_slli_epi16(_mm512_sub_epi16(s_g, h_g), 7), w_g));
    return _mm512_or_si512(out_rb, _mm512_slli_epi32(out_g, 8));
}

// AerialTables::shade_sky of 16 lanes: (v h + 128) >> 8 per channel, as mulhrs(h 128, v).
OVERFLIGHT_RESOLVE_AVX512 inline __m512i air_sky16(__m512i v, __m512i haze) {
    const __m512i v_rb = _mm512_and_si512(_mm512_mask_blend_epi16(__mmask32(0xAAAAAAAAu), v, _mm512_srli_epi32(v, 4)),
                                          _mm512_set1_epi32(0x03FF03FF));
    const __m512i v_g = _mm512_and_si512(_mm512_srli_epi32(v, 10), _mm512_set1_epi32(0x3FF));
    const __m512i h_rb = _mm512_and_si512(haze, _mm512_set1_epi32(0x00FF00FF));
    const __m512i h_g = _mm512_and_si512(_mm512_srli_epi32(haze, 8), _mm512_set1_epi32(0xFF));
    const __m512i out_rb = _mm512_mulhrs_epi16(_mm512_slli_epi16(h_rb, 7), v_rb);
    const __m512i out_g = _mm512_mulhrs_epi16(_mm512_slli_epi16(h_g, 7), v_g);
    return _mm512_or_si512(out_rb, _mm512_slli_epi32(out_g, 8));
}

// FogLanes on 16 lanes, the tables read through lookup_near: the same
// operations in the same order, so the same bits.
struct FogLanes16 : FogParams {
    using FogParams::FogParams;

    template <bool kTerrain, bool kSky>
    OVERFLIGHT_RESOLVE_AVX512 __m512i shade(const ShearBlock&, int, __m512 m, __m512 len, __m512 d,
                                            __mmask16 terrain, __m512i c) const {
        const __m512 half = _mm512_set1_ps(0.5f);
        __m512i fogged = _mm512_setzero_si512(), sky = _mm512_setzero_si512();
        if constexpr (kTerrain) {
            const __m512 x = _mm512_add_ps(_mm512_mul_ps(_mm512_mul_ps(d, len), _mm512_set1_ps(fog_step)), half);
            const __m512i entry = _mm512_min_epi32(_mm512_cvttps_epi32(x), _mm512_set1_epi32(FogTable::kEntries));
            const __m512i a = lookup_near(fog, FogTable::kEntries + 1, entry);
            // fog_blend's (c a + f (256 - a) + 128) >> 8 per channel is
            // f + ((c - f) a + 128) >> 8 (256 f is a multiple of 256), and
            // mulhrs((c - f) 128, a) is that shift (as air_blend16).
            const __m512i w = _mm512_or_si512(a, _mm512_slli_epi32(a, 16));
            const __m512i rb = _mm512_set1_epi32(0x00FF00FF);
            const __m512i f_rb = _mm512_set1_epi32(int(fog_color & 0xFF00FFu));
            const __m512i f_g = _mm512_set1_epi32(int(fog_color >> 8 & 0xFFu));
            const __m512i s_rb = _mm512_and_si512(c, rb);
            const __m512i s_g = _mm512_and_si512(_mm512_srli_epi32(c, 8), _mm512_set1_epi32(0xFF));
            const __m512i out_rb =
                _mm512_add_epi16(f_rb, _mm512_mulhrs_epi16(_mm512_slli_epi16(_mm512_sub_epi16(s_rb, f_rb), 7), w));
            const __m512i out_g =
                _mm512_add_epi16(f_g, _mm512_mulhrs_epi16(_mm512_slli_epi16(_mm512_sub_epi16(s_g, f_g), 7), w));
            fogged = _mm512_or_si512(out_rb, _mm512_slli_epi32(out_g, 8));
        }
        if constexpr (kSky) {
            const __m512 x = _mm512_add_ps(
                _mm512_mul_ps(_mm512_div_ps(m, len), _mm512_set1_ps(float(SkyTable::kEntries - 1))), half);
            const __m512i e =
                _mm512_max_epi32(_mm512_min_epi32(_mm512_cvttps_epi32(x), _mm512_set1_epi32(SkyTable::kEntries - 1)),
                                 _mm512_setzero_si512());
            sky = lookup_near(sky_table, SkyTable::kEntries, e);
        }
        return _mm512_mask_blend_epi32(terrain, sky, fogged);
    }
};

// AirLanes on 16 lanes, the tables read through lookup_near.
struct AirLanes16 : AirParams {
    using AirParams::AirParams;

    template <bool kTerrain, bool kSky>
    OVERFLIGHT_RESOLVE_AVX512 __m512i shade(const ShearBlock& blk, int i, __m512 m, __m512 len, __m512 d,
                                            __mmask16 terrain, __m512i c) const {
        const __m512 one = _mm512_set1_ps(1.0f), half = _mm512_set1_ps(0.5f);
        const __m512 cos_sun =
            _mm512_div_ps(_mm512_add_ps(_mm512_loadu_ps(blk.sun_dot + i), _mm512_mul_ps(m, _mm512_set1_ps(sun_y))),
                          len);
        const __m512 phase =
            _mm512_add_ps(_mm512_mul_ps(_mm512_add_ps(cos_sun, one), _mm512_set1_ps(AerialTables::kPhaseScale)), half);
        const __m512i p = clamp_lanes16(phase, float(AerialTables::kPhases - 1));
        const __m512i h = lookup_near(haze, AerialTables::kPhases, p);
        __m512i pixel = _mm512_setzero_si512();
        if constexpr (kSky) {
            const __m512i q = clamp_lanes16(
                _mm512_add_ps(_mm512_mul_ps(_mm512_div_ps(m, len), _mm512_set1_ps(float(AerialTables::kSkies - 1))),
                              half),
                float(AerialTables::kSkies - 1));
            pixel = air_sky16(lookup_near(opacity, AerialTables::kSkies, q), h);
        }
        if constexpr (kTerrain) {
            const __m512i hj = clamp_lanes16(
                _mm512_add_ps(_mm512_mul_ps(_mm512_sub_ps(_mm512_mul_ps(d, m), _mm512_set1_ps(dy_lo)),
                                            _mm512_set1_ps(inv_dy_step)),
                              half),
                float(AerialTables::kHeights - 1));
            const __m512 column = _mm512_castsi512_ps(lookup_near(column_table, AerialTables::kHeights, hj));
            const __m512 x = _mm512_add_ps(_mm512_mul_ps(_mm512_mul_ps(d, len), column), half);
            const __m512i w =
                lookup_near(transmit, AerialTables::kColumns + 1,
                            _mm512_cvttps_epi32(_mm512_min_ps(x, _mm512_set1_ps(float(AerialTables::kColumns)))));
            const __m512i lit = air_blend16(c, w, h);
            pixel = kSky ? _mm512_mask_blend_epi32(terrain, pixel, lit) : lit;
        }
        return pixel;
    }
};

// resolve_rows_avx2 on 16 lanes (FogLanes16 or AirLanes16): the same
// operations in the same order, so the same bits. kEven: as
// resolve_rows_avx2; kDirect: a full block (blk.n == kShearBlock), whose
// pixels go to the images straight from the registers, the depth with
// streaming stores where `stream_depth` (each row's run whole cache lines).
// The tables and the lanes are read into locals first (SliceTables, FogParams).
template <bool kTerrain, bool kSky, bool kEven, bool kDirect, class Lanes>
OVERFLIGHT_RESOLVE_AVX512 void resolve_rows_avx512(const ShearResolveTables& t, const Lanes& lanes_in,
                                                   const ShearBlock& blk, int H, int j0, int j1,
                                                   const std::uint32_t* color, const std::uint32_t* slice,
                                                   Rgb8* out_c, float* out_d, std::size_t W, bool stream_depth) {
    const Lanes lanes = lanes_in;
    const SliceTables st(t);
    const __m512 one = _mm512_set1_ps(1.0f);
    const __m512 d_first = _mm512_set1_ps(t.d_first), d_step = _mm512_set1_ps(t.d_step);
    const __m512i even = _mm512_set1_epi32(t.even);
    // Packed colors to Rgb8: 12 bytes per 128-bit lane (rgb_bytes), then a
    // full block's 32 pixels' 96 bytes joined from the lanes of both halves
    // into one 64-byte and one 32-byte store (first_words, last_words). Both
    // stores stay within the block's own pixels; a masked store of each
    // half's 48 bytes instead made the resolve of a 4K frame about 10 %
    // slower on a Zen 4 (masked stores to memory are slow there).
    static_assert(kShearBlock == 32);
    const __m512i rgb_bytes =
        _mm512_broadcast_i32x4(_mm_setr_epi8(0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1));
    const __m512i first_words = _mm512_setr_epi32(0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, 16, 17, 18, 20);
    const __m256i last_words = _mm256_setr_epi32(5, 6, 8, 9, 10, 12, 13, 14);
    for (int j = j0; j < j1; ++j) {
        const float mj = st.row_m[j];
        const __m512 m = _mm512_set1_ps(mj), m2 = _mm512_set1_ps(mj * mj);
        const std::uint32_t* sc = color + std::size_t(j) * kShearBlock;
        const std::uint32_t* ss = slice + std::size_t(j) * kShearBlock;
        const std::size_t row = image_row<kDirect>(blk, H, j, W, out_c, out_d, kDirect && stream_depth);
        alignas(64) std::uint32_t px[kShearBlock];
        alignas(64) float zs[kShearBlock];
        __m512i lanes_rgb[2]; // kDirect: each half's pixels, 12 bytes per 128-bit lane
        for (int i = 0; i < kShearBlock; i += 16) {
            const __m512 len = _mm512_sqrt_ps(_mm512_add_ps(_mm512_loadu_ps(blk.len2 + i), m2));
            const __mmask16 terrain =
                kTerrain && kSky ? _mm512_cmpgt_epi32_mask(_mm512_loadu_si512(blk.jend + i), _mm512_set1_epi32(j))
                                 : __mmask16(kTerrain ? 0xFFFF : 0);
            __m512 depth = one, d = one;
            __m512i c = _mm512_setzero_si512();
            if constexpr (kTerrain) {
                // Sky lanes read slice 0 (their entries are stale).
                const __m512i k = _mm512_maskz_loadu_epi32(terrain, ss + i);
                const __m512 z = _mm512_castsi512_ps(lookup_near(st.slice_depth, st.slices, k));
                if constexpr (kEven) {
                    d = _mm512_add_ps(d_first, _mm512_mul_ps(d_step, _mm512_cvtepi32_ps(k)));
                    if (const __mmask16 beyond = _mm512_cmpge_epi32_mask(k, even)) [[unlikely]]
                        d = _mm512_mask_mov_ps(d, beyond, _mm512_castsi512_ps(lookup_near(st.slice_d, st.slices, k)));
                } else {
                    d = _mm512_castsi512_ps(lookup_near(st.slice_d, st.slices, k));
                }
                c = _mm512_loadu_si512(sc + i);
                depth = kSky ? _mm512_mask_blend_ps(terrain, one, z) : z;
            }
            const __m512i pixel = lanes.template shade<kTerrain, kSky>(blk, i, m, len, d, terrain, c);
            if constexpr (kDirect) {
                lanes_rgb[i / 16] = _mm512_shuffle_epi8(pixel, rgb_bytes);
                if (stream_depth) _mm512_stream_ps(out_d + row + i, depth);
                else _mm512_storeu_ps(out_d + row + i, depth);
            } else {
                _mm512_store_si512(px + i, pixel);
                _mm512_store_ps(zs + i, depth);
            }
        }
        if constexpr (kDirect) {
            char* oc = reinterpret_cast<char*>(out_c + row);
            _mm512_storeu_si512(oc, _mm512_permutex2var_epi32(lanes_rgb[0], first_words, lanes_rgb[1]));
            _mm256_storeu_si256(reinterpret_cast<__m256i*>(oc + 64),
                                _mm512_castsi512_si256(_mm512_permutexvar_epi32(
                                    _mm512_castsi256_si512(last_words), lanes_rgb[1])));
        } else {
            write_run(px, zs, blk.n, out_c + row, out_d + row);
        }
    }
}
#endif

#if OVERFLIGHT_RESOLVE_SIMD128
// 4 entries of `table` at the lanes of `i`, one by one: WebAssembly SIMD has
// no gather.
inline v128_t lookup4(const std::uint32_t* table, v128_t i) {
    return wasm_u32x4_make(table[wasm_i32x4_extract_lane(i, 0)], table[wasm_i32x4_extract_lane(i, 1)],
                           table[wasm_i32x4_extract_lane(i, 2)], table[wasm_i32x4_extract_lane(i, 3)]);
}
inline v128_t lookup4(const float* table, v128_t i) {
    return wasm_f32x4_make(table[wasm_i32x4_extract_lane(i, 0)], table[wasm_i32x4_extract_lane(i, 1)],
                           table[wasm_i32x4_extract_lane(i, 2)], table[wasm_i32x4_extract_lane(i, 3)]);
}

// Lanes i..i+3 of a full block's image row (row_c, row_d: the run's first
// pixel): 4 packed colors to 12 bytes of Rgb8, stored as 16 whose last 4 the
// next store overwrites; the last 4 pixels store exactly 12 (the next block's
// pixels are not this block's to write).
inline void store_lanes_simd128(v128_t pixel, v128_t depth, int i, Rgb8* row_c, float* row_d) {
    const v128_t rgb = wasm_i8x16_shuffle(pixel, pixel, 0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, 15, 15, 15, 15);
    unsigned char* oc = reinterpret_cast<unsigned char*>(row_c + i);
    if (i + 4 < kShearBlock) {
        wasm_v128_store(oc, rgb);
    } else {
        const std::uint64_t lo = std::uint64_t(wasm_i64x2_extract_lane(rgb, 0));
        const std::uint32_t hi = std::uint32_t(wasm_i32x4_extract_lane(rgb, 2));
        std::memcpy(oc, &lo, 8);
        std::memcpy(oc + 8, &hi, 4);
    }
    wasm_v128_store(row_d + i, depth);
}

// resolve_rows_portable for GL_EXP fog and the sky gradient in 4 lanes (the
// table lookups lane by lane): the same operations in the same order, so the
// same bits. kEven: the view depth computed from the slice index, as
// resolve_rows_avx2. A full block's pixels go to the images straight from
// the registers.
template <bool kTerrain, bool kSky, bool kEven>
void resolve_rows_simd128(const ShearResolveTables& t, const ShearBlock& blk, int H, int j0, int j1,
                          const std::uint32_t* color, const std::uint32_t* slice, Rgb8* out_c, float* out_d,
                          std::size_t W) {
    // The tables' pointers in locals, as resolve_rows_avx2's.
    const SliceTables st(t);
    const std::uint32_t* const fog = t.fog->entries();
    const std::uint32_t* const sky_table = t.sky;
    const v128_t one = wasm_f32x4_splat(1.0f), half = wasm_f32x4_splat(0.5f);
    const v128_t d_first = wasm_f32x4_splat(t.d_first), d_step = wasm_f32x4_splat(t.d_step);
    const v128_t even = wasm_i32x4_splat(t.even);
    const v128_t fog_step = wasm_f32x4_splat(t.fog->inv_step());
    const v128_t fog_last = wasm_i32x4_splat(FogTable::kEntries);
    const v128_t sky_scale = wasm_f32x4_splat(float(SkyTable::kEntries - 1));
    const v128_t sky_last = wasm_i32x4_splat(SkyTable::kEntries - 1);
    const v128_t mask_rb = wasm_i32x4_splat(0xFF00FF), mask_g = wasm_i32x4_splat(0x00FF00);
    const v128_t fog_rb = wasm_i32x4_splat(int(t.fog_color & 0xFF00FFu));
    const v128_t fog_g = wasm_i32x4_splat(int(t.fog_color & 0x00FF00u));
    const v128_t w_full = wasm_i32x4_splat(256);
    const bool direct = blk.n == kShearBlock;
    for (int j = j0; j < j1; ++j) {
        const float mj = st.row_m[j];
        const v128_t m = wasm_f32x4_splat(mj), m2 = wasm_f32x4_splat(mj * mj);
        const v128_t jv = wasm_i32x4_splat(j);
        const std::uint32_t* sc = color + std::size_t(j) * kShearBlock;
        const std::uint32_t* ss = slice + std::size_t(j) * kShearBlock;
        const std::size_t row = image_row(blk, H, j, W, out_c, out_d);
        alignas(16) std::uint32_t px[kShearBlock];
        alignas(16) float zs[kShearBlock];
        for (int i = 0; i < kShearBlock; i += 4) {
            const v128_t len = wasm_f32x4_sqrt(wasm_f32x4_add(wasm_v128_load(blk.len2 + i), m2));
            const v128_t terrain = kTerrain && kSky ? wasm_i32x4_gt(wasm_v128_load(blk.jend + i), jv)
                                                    : wasm_i32x4_splat(kTerrain ? -1 : 0);
            v128_t fogged = wasm_i32x4_splat(0), sky = wasm_i32x4_splat(0), z = one;
            if constexpr (kTerrain) {
                // Sky lanes read slice 0 (their entries are stale).
                const v128_t k = wasm_v128_and(wasm_v128_load(ss + i), terrain);
                z = lookup4(st.slice_depth, k);
                v128_t d;
                if constexpr (kEven) {
                    d = wasm_f32x4_add(d_first, wasm_f32x4_mul(d_step, wasm_f32x4_convert_i32x4(k)));
                    const v128_t beyond = wasm_i32x4_ge(k, even);
                    if (wasm_v128_any_true(beyond)) d = wasm_v128_bitselect(lookup4(st.slice_d, k), d, beyond);
                } else {
                    d = lookup4(st.slice_d, k);
                }
                const v128_t x = wasm_f32x4_add(wasm_f32x4_mul(wasm_f32x4_mul(d, len), fog_step), half);
                const v128_t a = lookup4(fog, wasm_i32x4_min(wasm_i32x4_trunc_sat_f32x4(x), fog_last));
                const v128_t b = wasm_i32x4_sub(w_full, a);
                const v128_t c = wasm_v128_load(sc + i);
                // fog_blend, lane by lane.
                const v128_t rb = wasm_i32x4_add(wasm_i32x4_mul(wasm_v128_and(c, mask_rb), a),
                                                 wasm_i32x4_add(wasm_i32x4_mul(fog_rb, b), wasm_i32x4_splat(0x800080)));
                const v128_t g = wasm_i32x4_add(wasm_i32x4_mul(wasm_v128_and(c, mask_g), a),
                                                wasm_i32x4_add(wasm_i32x4_mul(fog_g, b), wasm_i32x4_splat(0x008000)));
                fogged = wasm_v128_or(wasm_v128_and(wasm_u32x4_shr(rb, 8), mask_rb),
                                      wasm_v128_and(wasm_u32x4_shr(g, 8), mask_g));
            }
            if constexpr (kSky) {
                // SkyTable::lookup.
                const v128_t x = wasm_f32x4_add(wasm_f32x4_mul(wasm_f32x4_div(m, len), sky_scale), half);
                const v128_t e = wasm_i32x4_max(wasm_i32x4_min(wasm_i32x4_trunc_sat_f32x4(x), sky_last),
                                                wasm_i32x4_splat(0));
                sky = lookup4(sky_table, e);
            }
            const v128_t pixel = wasm_v128_bitselect(fogged, sky, terrain);
            const v128_t depth = wasm_v128_bitselect(z, one, terrain);
            if (direct) {
                store_lanes_simd128(pixel, depth, i, out_c + row, out_d + row);
            } else {
                wasm_v128_store(px + i, pixel);
                wasm_v128_store(zs + i, depth);
            }
        }
        if (!direct) write_run(px, zs, blk.n, out_c + row, out_d + row);
    }
}
#endif

} // namespace

bool resolve_kernel_available(ResolveKernel kernel) {
    switch (kernel) {
    case ResolveKernel::Auto:
    case ResolveKernel::Portable: return true;
    case ResolveKernel::Avx2:
    case ResolveKernel::Avx2Loads:
    case ResolveKernel::Avx2Window:
#if OVERFLIGHT_RESOLVE_AVX2
        return __builtin_cpu_supports("avx2");
#else
        return false;
#endif
    case ResolveKernel::Avx512:
#if OVERFLIGHT_RESOLVE_AVX2
        return cpu_has_avx512();
#else
        return false;
#endif
    case ResolveKernel::Simd128:
#if OVERFLIGHT_RESOLVE_SIMD128
        return true;
#else
        return false;
#endif
    }
    return false;
}

void resolve_shear_block(const ShearResolveTables& t, const ShearBlock& blk, int H, const std::uint32_t* color,
                         const std::uint32_t* slice, Rgb8* out_c, float* out_d, std::size_t W, ResolveKernel kernel) {
    // Rows below every column's horizon are all terrain, rows above all sky.
    int jmin = H, jmax = 0;
    for (int i = 0; i < kShearBlock; ++i) {
        jmin = std::min(jmin, blk.jend[i]);
        jmax = std::max(jmax, blk.jend[i]);
    }
    // Avx2Window where gathers are slow (cpu_gathers_slow). On a Zen 1 EPYC,
    // bench_raycast_bench's 1080p view, 4097^2 demo, the three ways
    // interleaved in one process (medians of 6-10): the resolve step took
    // 8.6 / 7.8 / 7.8 ms (gathers / loads / windows) on one thread, 5.0 /
    // 4.5 / 4.4 ms on two (two series); with every look (the aerial
    // perspective's four tables) 14.9 / 14.1 / 12.5 ms on one thread, 7.7 /
    // 7.0 / 6.3 ms on two.
    static const ResolveKernel fastest = [] {
        if (resolve_kernel_available(ResolveKernel::Avx512)) return ResolveKernel::Avx512;
#if OVERFLIGHT_RESOLVE_AVX2
        if (resolve_kernel_available(ResolveKernel::Avx2))
            return cpu_gathers_slow() ? ResolveKernel::Avx2Window : ResolveKernel::Avx2;
#endif
        if (resolve_kernel_available(ResolveKernel::Simd128)) return ResolveKernel::Simd128;
        return ResolveKernel::Portable;
    }();
    if (kernel == ResolveKernel::Auto) kernel = fastest;
#if OVERFLIGHT_RESOLVE_AVX2
    if (kernel == ResolveKernel::Avx512) {
        // A full block's depth rows are whole cache lines where they start
        // one (W a multiple of 16): streaming stores write them without
        // reading them from memory first, the 4K frame about 5 % faster on
        // a Zen 4 (the color's 96 bytes per row share lines with the next
        // block's, so they are written as before). Streaming stores are
        // weakly ordered: the block ends with a fence, so that the images
        // are whole for whoever waits for the blocks.
        const bool stream_depth =
            blk.n == kShearBlock && W % 16 == 0 && reinterpret_cast<std::uintptr_t>(out_d) % 64 == 0;
        const auto avx512 = [&](const auto& lanes) {
            resolve_bands(t, H, jmin, jmax, [&](auto b) {
                using B = decltype(b);
                if (blk.n == kShearBlock) // a full block: the pixels straight to the images
                    resolve_rows_avx512<B::kTerrain, B::kSky, B::kEven, true>(t, lanes, blk, H, b.j0, b.j1, color,
                                                                             slice, out_c, out_d, W, stream_depth);
                else
                    resolve_rows_avx512<B::kTerrain, B::kSky, B::kEven, false>(t, lanes, blk, H, b.j0, b.j1, color,
                                                                              slice, out_c, out_d, W, false);
            });
        };
        if (t.air) avx512(AirLanes16(t));
        else avx512(FogLanes16(t));
        if (stream_depth) _mm_sfence();
        return;
    }
    const auto avx2 = [&](const auto& lanes) {
        resolve_bands(t, H, jmin, jmax, [&](auto b) {
            using B = decltype(b);
            resolve_rows_avx2<B::kTerrain, B::kSky, B::kEven>(t, lanes, blk, H, b.j0, b.j1, color, slice, out_c,
                                                             out_d, W);
        });
    };
    if (kernel == ResolveKernel::Avx2Loads) {
        if (t.air) avx2(AirLanes<LoadLookup>(t));
        else avx2(FogLanes<LoadLookup>(t));
        return;
    }
    if (kernel == ResolveKernel::Avx2Window) {
        if (t.air) avx2(AirLanes<WindowLookup<LoadLookup>>(t));
        else avx2(FogLanes<WindowLookup<LoadLookup>>(t));
        return;
    }
    if (kernel == ResolveKernel::Avx2) {
        if (t.air) avx2(AirLanes<GatherLookup>(t));
        else avx2(FogLanes<GatherLookup>(t));
        return;
    }
#endif
#if OVERFLIGHT_RESOLVE_SIMD128
    if (kernel == ResolveKernel::Simd128 && !t.air) {
        resolve_bands(t, H, jmin, jmax, [&](auto b) {
            using B = decltype(b);
            resolve_rows_simd128<B::kTerrain, B::kSky, B::kEven>(t, blk, H, b.j0, b.j1, color, slice, out_c, out_d,
                                                                W);
        });
        return;
    }
#endif
    // The portable kernel looks the view depth up for every band.
    resolve_bands(t, H, jmin, jmax, [&](auto b) {
        using B = decltype(b);
        if (t.air) resolve_rows_portable<B::kTerrain, B::kSky, true>(t, blk, H, b.j0, b.j1, color, slice, out_c, out_d, W);
        else resolve_rows_portable<B::kTerrain, B::kSky, false>(t, blk, H, b.j0, b.j1, color, slice, out_c, out_d, W);
    });
}

} // namespace overflight
