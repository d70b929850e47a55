// See ShearDrape.h and ImageryTexels.h.
#include "raycast/ShearDrape.h"

#include <algorithm>

#if defined(__x86_64__) && defined(__GNUC__)
#define OVERFLIGHT_DRAPE_AVX2 1
// GCC 12's AVX-512 headers start some intrinsics from an undefined register
// and warn about it where they are inlined (GCC bug 105593, fixed in 13).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop

#include "core/CpuFeatures.h"
#include "raycast/LaneLookup.h"
#endif

namespace overflight {

namespace {

#if OVERFLIGHT_DRAPE_AVX2
// Entry lvl of a 16-entry table (ImageryTexels::LevelLanes) per lane: the
// lower or upper 8 permuted, chosen by upper (lvl > 7); the lower alone
// while no lane is upper (any_upper false), as on most rows.
__attribute__((target("avx2"))) inline __m256i pick(const int* table, __m256i lvl, __m256i upper, bool any_upper) {
    const __m256i lo = _mm256_permutevar8x32_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(table)), lvl);
    if (!any_upper) return lo;
    const __m256i hi = _mm256_permutevar8x32_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(table + 8)), lvl);
    return _mm256_blendv_epi8(lo, hi, upper);
}
__attribute__((target("avx2"))) inline __m256 pick(const float* table, __m256i lvl, __m256i upper, bool any_upper) {
    const __m256 lo = _mm256_permutevar8x32_ps(_mm256_load_ps(table), lvl);
    if (!any_upper) return lo;
    const __m256 hi = _mm256_permutevar8x32_ps(_mm256_load_ps(table + 8), lvl);
    return _mm256_blendv_ps(lo, hi, _mm256_castsi256_ps(upper));
}

// Lanes [i, i + 8) of a block: drape_pixel lane by lane (DrapeRun's slope of
// the run's top row found on the way down), modulate_light with 16-bit
// multiplies (each channel's l a + 64 fits: 255 x 255 + 64 < 2^16). The
// slice tables and texels are read through Lookup (LaneLookup.h).
template <class Lookup>
__attribute__((target("avx2"))) void drape_lanes_avx2(const DrapeFrame& f, const float* dir_x, const float* dir_z,
                                                      const int* jend, int i, std::uint32_t* color,
                                                      const std::uint32_t* slice) {
    int jtop = 0;
    for (int q = 0; q < 8; ++q) jtop = std::max(jtop, jend[i + q]);
    if (jtop == 0) return;
    const ImageryTexels& im = *f.imagery;
    const ImageryTexels::LevelLanes& lv = im.level_lanes();
    const float* slog = im.slice_log2();
    const float* rlog = im.row_log2();
    const Rgba8* texels = im.texels();
    const __m256i jendv = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(jend + i));
    const __m256 dx = _mm256_loadu_ps(dir_x + i), dz = _mm256_loadu_ps(dir_z + i);
    const __m256 eye_x = _mm256_set1_ps(f.eye_x), eye_z = _mm256_set1_ps(f.eye_z);
    const __m256 x0 = _mm256_set1_ps(im.x0()), z0 = _mm256_set1_ps(im.z0());
    const __m256 half = _mm256_set1_ps(0.5f), zero_f = _mm256_setzero_ps();
    const __m256 d_before = _mm256_set1_ps(f.d_before_first);
    const __m256i zero = _mm256_setzero_si256(), one = _mm256_set1_epi32(1);
    const __m256i last = _mm256_set1_epi32(im.last_level());
    const __m256i seven = _mm256_set1_epi32(7);
    const __m256i c28 = _mm256_set1_epi32(28), c3 = _mm256_set1_epi32(3);
    const __m256i rb_mask = _mm256_set1_epi32(0x00FF00FF), byte = _mm256_set1_epi32(0xFF);
    const __m256i round = _mm256_set1_epi32(0x00400040), max_rb = _mm256_set1_epi32(0x00FF00FF);
    __m256 m_top = zero_f;
    __m256i prev = _mm256_set1_epi32(-1); // no slice: the first row gathers
    // What the lanes' slices give, gathered again only on a row where some
    // lane's slice changed: along most rows every lane stays in its run.
    // (An unpainted lane's stale top and values are never used: its top
    // painted row is a top row, whatever its slice.)
    __m256 dk = zero_f, d_prev = zero_f, sl = zero_f;
    for (int j = jtop - 1; j >= 0; --j) {
        const float mj = f.row_m[j];
        const __m256 m = _mm256_set1_ps(mj);
        const __m256i painted = _mm256_cmpgt_epi32(jendv, _mm256_set1_epi32(j));
        // Unpainted lanes read slice 0 (their entries are stale).
        const __m256i k = _mm256_and_si256(
            _mm256_loadu_si256(reinterpret_cast<const __m256i*>(slice + std::size_t(j) * kShearBlock + i)), painted);
        // A run's top row: the column's top painted row, or the row below a new slice.
        const __m256i same = _mm256_cmpeq_epi32(k, prev);
        const __m256i top = _mm256_or_si256(_mm256_cmpeq_epi32(jendv, _mm256_set1_epi32(j + 1)),
                                            _mm256_xor_si256(same, _mm256_set1_epi32(-1)));
        m_top = _mm256_blendv_ps(m_top, m, _mm256_castsi256_ps(top));
        prev = k;
        if (_mm256_movemask_epi8(same) != -1) {
            dk = Lookup::floats(f.slice_d, 0, k);
            d_prev = _mm256_blendv_ps(Lookup::floats(f.slice_d, 0, _mm256_max_epi32(_mm256_sub_epi32(k, one), zero)),
                                      d_before, _mm256_castsi256_ps(_mm256_cmpeq_epi32(k, zero)));
            sl = Lookup::floats(slog, 0, k);
        }
        __m256 d = dk;
        if (mj < 0.0f) {
            // Rays looking down meet the sample's height in front of slice k,
            // clamped to the cell [d_{k-1}, d_k]; others hit its face at d_k.
            const __m256 v = _mm256_mul_ps(dk, _mm256_div_ps(m_top, m));
            const __m256 clamped = _mm256_min_ps(_mm256_max_ps(v, d_prev), dk);
            d = _mm256_blendv_ps(dk, clamped, _mm256_cmp_ps(m_top, zero_f, _CMP_LT_OQ));
        }
        const __m256 x = _mm256_add_ps(eye_x, _mm256_mul_ps(d, dx));
        const __m256 z = _mm256_add_ps(eye_z, _mm256_mul_ps(d, dz));
        // ImageryTexels::level: l < 1 truncates to at most 0.
        const __m256 l = _mm256_add_ps(_mm256_add_ps(sl, _mm256_set1_ps(rlog[j])), half);
        const __m256i lvl = _mm256_min_epi32(_mm256_max_epi32(_mm256_cvttps_epi32(l), zero), last);
        // ImageryTexels::at.
        const __m256i upper = _mm256_cmpgt_epi32(lvl, seven);
        const bool any_upper = !_mm256_testz_si256(upper, upper);
        const __m256i w = pick(lv.w, lvl, upper, any_upper);
        const __m256i h = pick(lv.h, lvl, upper, any_upper);
        const __m256i col = _mm256_min_epi32(
            _mm256_max_epi32(_mm256_cvttps_epi32(_mm256_mul_ps(_mm256_sub_ps(x, x0), pick(lv.inv_x, lvl, upper, any_upper))), zero),
            _mm256_sub_epi32(w, one));
        const __m256i row = _mm256_min_epi32(
            _mm256_max_epi32(_mm256_cvttps_epi32(_mm256_mul_ps(_mm256_sub_ps(z, z0), pick(lv.inv_z, lvl, upper, any_upper))), zero),
            _mm256_sub_epi32(h, one));
        // ImageryTexels::tiled_index, plus the level's first texel.
        const __m256i page = _mm256_add_epi32(
            _mm256_mullo_epi32(_mm256_srli_epi32(row, 5), pick(lv.tiles_x, lvl, upper, any_upper)),
            _mm256_srli_epi32(col, 5));
        const __m256i in_page = _mm256_or_si256(
            _mm256_or_si256(_mm256_slli_epi32(_mm256_and_si256(row, c28), 5), _mm256_slli_epi32(_mm256_and_si256(col, c28), 2)),
            _mm256_or_si256(_mm256_slli_epi32(_mm256_and_si256(row, c3), 2), _mm256_and_si256(col, c3)));
        const __m256i idx = _mm256_add_epi32(pick(lv.first, lvl, upper, any_upper),
                                             _mm256_or_si256(_mm256_slli_epi32(page, 10), in_page));
        // Unpainted lanes' texels are not used (their pixels stay as they are).
        const __m256i albedo = Lookup::words(texels, 0, idx, painted);
        // modulate_light.
        std::uint32_t* out = color + std::size_t(j) * kShearBlock + i;
        const __m256i light = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(out));
        __m256i rb = _mm256_mullo_epi16(_mm256_and_si256(light, rb_mask), _mm256_and_si256(albedo, rb_mask));
        rb = _mm256_min_epu16(_mm256_srli_epi16(_mm256_add_epi16(rb, round), 7), max_rb);
        __m256i g = _mm256_mullo_epi16(_mm256_and_si256(_mm256_srli_epi32(light, 8), byte),
                                       _mm256_and_si256(_mm256_srli_epi32(albedo, 8), byte));
        g = _mm256_min_epu16(_mm256_srli_epi16(_mm256_add_epi16(g, round), 7), max_rb);
        const __m256i lit = _mm256_or_si256(rb, _mm256_slli_epi32(_mm256_and_si256(g, byte), 8));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), _mm256_blendv_epi8(light, lit, painted));
    }
}

// drape_lanes_avx2 for lanes [i, i + 16) with AVX-512, with the same bits.
// Its permutes pick from all 16 entries of a level table at once, and masks
// replace the blends (a masked gather, a masked store of the painted lanes).
// It gathers nothing but texels on most rows: kEven (DrapeFrame::d_step)
// computes the view depths of slices k and k - 1 as the slices were placed,
// and the mip level is found among the row's level starts
// (ImageryTexels::level_starts) rather than from the slice's gathered term,
// so the slice tables' three gathers and the branch around them (taken on
// most rows far from the eye, where nearly every pixel is a run of its own)
// are gone.
#define OVERFLIGHT_AVX512 __attribute__((target("avx512f,avx512bw,avx512dq,avx512vl")))
template <bool kEven>
OVERFLIGHT_AVX512 void drape_lanes_avx512(const DrapeFrame& f, const float* dir_x, const float* dir_z,
                                          const int* jend, int i, std::uint32_t* color, const std::uint32_t* slice) {
    const __m512i jendv = _mm512_loadu_si512(jend + i);
    const int jtop = _mm512_reduce_max_epi32(jendv);
    if (jtop == 0) return;
    const ImageryTexels& im = *f.imagery;
    const ImageryTexels::LevelLanes& lv = im.level_lanes();
    const int* texels = reinterpret_cast<const int*>(im.texels());
    const __m512 inv_x = _mm512_loadu_ps(lv.inv_x), inv_z = _mm512_loadu_ps(lv.inv_z);
    const __m512i w_tab = _mm512_loadu_si512(lv.w), h_tab = _mm512_loadu_si512(lv.h);
    const __m512i tiles_tab = _mm512_loadu_si512(lv.tiles_x), first_tab = _mm512_loadu_si512(lv.first);
    const __m512 dx = _mm512_loadu_ps(dir_x + i), dz = _mm512_loadu_ps(dir_z + i);
    const __m512 eye_x = _mm512_set1_ps(f.eye_x), eye_z = _mm512_set1_ps(f.eye_z);
    const __m512 x0 = _mm512_set1_ps(im.x0()), z0 = _mm512_set1_ps(im.z0());
    const __m512 zero_f = _mm512_setzero_ps();
    const __m512 d_before = _mm512_set1_ps(f.d_before_first);
    const __m512 d_first = _mm512_set1_ps(f.d_first), d_step = _mm512_set1_ps(f.d_step);
    const __m512i zero = _mm512_setzero_si512(), one = _mm512_set1_epi32(1);
    const __m512i c28 = _mm512_set1_epi32(28), c3 = _mm512_set1_epi32(3);
    const __m512i rb_mask = _mm512_set1_epi32(0x00FF00FF), byte = _mm512_set1_epi32(0xFF);
    const __m512i round = _mm512_set1_epi32(0x00400040), max_rb = _mm512_set1_epi32(0x00FF00FF);
    __m512 m_top = zero_f;
    __m512i prev = _mm512_set1_epi32(-1);
    __m512 dk = zero_f, d_prev = zero_f;
    for (int j = jtop - 1; j >= 0; --j) {
        const float mj = f.row_m[j];
        const __m512 m = _mm512_set1_ps(mj);
        const __mmask16 painted = _mm512_cmpgt_epi32_mask(jendv, _mm512_set1_epi32(j));
        const __m512i k = _mm512_maskz_loadu_epi32(painted, slice + std::size_t(j) * kShearBlock + i);
        const __mmask16 same = _mm512_cmpeq_epi32_mask(k, prev);
        const __mmask16 top = __mmask16(_mm512_cmpeq_epi32_mask(jendv, _mm512_set1_epi32(j + 1)) | __mmask16(~same));
        m_top = _mm512_mask_mov_ps(m_top, top, m);
        prev = k;
        if constexpr (kEven) {
            dk = _mm512_add_ps(d_first, _mm512_mul_ps(d_step, _mm512_cvtepi32_ps(k)));
            d_prev = _mm512_mask_add_ps(d_before, _mm512_cmpneq_epi32_mask(k, zero), d_first,
                                        _mm512_mul_ps(d_step, _mm512_cvtepi32_ps(_mm512_sub_epi32(k, one))));
        } else if (same != 0xFFFF) {
            dk = _mm512_i32gather_ps(k, f.slice_d, 4);
            d_prev = _mm512_mask_i32gather_ps(d_before, _mm512_cmpneq_epi32_mask(k, zero), _mm512_sub_epi32(k, one),
                                              f.slice_d, 4);
        }
        __m512 d = dk;
        if (mj < 0.0f) {
            const __m512 v = _mm512_mul_ps(dk, _mm512_div_ps(m_top, m));
            const __m512 clamped = _mm512_min_ps(_mm512_max_ps(v, d_prev), dk);
            d = _mm512_mask_mov_ps(dk, _mm512_cmp_ps_mask(m_top, zero_f, _CMP_LT_OQ), clamped);
        }
        const __m512 x = _mm512_add_ps(eye_x, _mm512_mul_ps(d, dx));
        const __m512 z = _mm512_add_ps(eye_z, _mm512_mul_ps(d, dz));
        // ImageryTexels::level: how many of the row's level starts are at or below k.
        const __m512i starts = _mm512_load_si512(im.level_starts(j).k);
        __m512i lvl = zero;
        for (int step = 8; step > 0; step /= 2) {
            const __m512i up = _mm512_add_epi32(lvl, _mm512_set1_epi32(step));
            lvl = _mm512_mask_mov_epi32(lvl, _mm512_cmple_epi32_mask(_mm512_permutexvar_epi32(up, starts), k), up);
        }
        const __m512i col = _mm512_min_epi32(
            _mm512_max_epi32(_mm512_cvttps_epi32(_mm512_mul_ps(_mm512_sub_ps(x, x0), _mm512_permutexvar_ps(lvl, inv_x))), zero),
            _mm512_sub_epi32(_mm512_permutexvar_epi32(lvl, w_tab), one));
        const __m512i row = _mm512_min_epi32(
            _mm512_max_epi32(_mm512_cvttps_epi32(_mm512_mul_ps(_mm512_sub_ps(z, z0), _mm512_permutexvar_ps(lvl, inv_z))), zero),
            _mm512_sub_epi32(_mm512_permutexvar_epi32(lvl, h_tab), one));
        const __m512i page = _mm512_add_epi32(
            _mm512_mullo_epi32(_mm512_srli_epi32(row, 5), _mm512_permutexvar_epi32(lvl, tiles_tab)), _mm512_srli_epi32(col, 5));
        // (a | b | c) as one ternary-logic op.
        const __m512i in_page = _mm512_ternarylogic_epi32(
            _mm512_slli_epi32(_mm512_and_si512(row, c28), 5), _mm512_slli_epi32(_mm512_and_si512(col, c28), 2),
            _mm512_or_si512(_mm512_slli_epi32(_mm512_and_si512(row, c3), 2), _mm512_and_si512(col, c3)), 0xFE);
        const __m512i idx = _mm512_add_epi32(_mm512_permutexvar_epi32(lvl, first_tab),
                                             _mm512_or_si512(_mm512_slli_epi32(page, 10), in_page));
        const __m512i albedo = _mm512_mask_i32gather_epi32(zero, painted, idx, texels, 4);
        std::uint32_t* out = color + std::size_t(j) * kShearBlock + i;
        const __m512i light = _mm512_loadu_si512(out);
        __m512i rb = _mm512_mullo_epi16(_mm512_and_si512(light, rb_mask), _mm512_and_si512(albedo, rb_mask));
        rb = _mm512_min_epu16(_mm512_srli_epi16(_mm512_add_epi16(rb, round), 7), max_rb);
        __m512i g = _mm512_mullo_epi16(_mm512_and_si512(_mm512_srli_epi32(light, 8), byte),
                                       _mm512_and_si512(_mm512_srli_epi32(albedo, 8), byte));
        g = _mm512_min_epu16(_mm512_srli_epi16(_mm512_add_epi16(g, round), 7), max_rb);
        const __m512i lit = _mm512_or_si512(rb, _mm512_slli_epi32(_mm512_and_si512(g, byte), 8));
        _mm512_mask_storeu_epi32(out, painted, lit);
    }
}
#undef OVERFLIGHT_AVX512
#endif

} // namespace

void drape_shear_block(const DrapeFrame& f, const float* dir_x, const float* dir_z, int n, const int* jend,
                       std::uint32_t* color, const std::uint32_t* slice, ResolveKernel kernel) {
#if OVERFLIGHT_DRAPE_AVX2
    static const ResolveKernel fastest = resolve_kernel_available(ResolveKernel::Avx512) ? ResolveKernel::Avx512
                                         : !resolve_kernel_available(ResolveKernel::Avx2) ? ResolveKernel::Portable
                                         : cpu_gathers_slow()                              ? ResolveKernel::Avx2Loads
                                                                                           : ResolveKernel::Avx2;
    if (kernel == ResolveKernel::Auto) kernel = fastest;
    // Imagery of 2^31 texels and more or of more than 16 levels goes the portable way.
    if (kernel != ResolveKernel::Portable && f.imagery->lane_tables()) {
        // Lanes at or past n are painted nowhere.
        alignas(32) int ends[kShearBlock];
        alignas(32) float dxs[kShearBlock], dzs[kShearBlock];
        for (int i = 0; i < kShearBlock; ++i) {
            ends[i] = i < n ? jend[i] : 0;
            dxs[i] = i < n ? dir_x[i] : 0.0f;
            dzs[i] = i < n ? dir_z[i] : 0.0f;
        }
        if (kernel == ResolveKernel::Avx512)
            for (int i = 0; i < kShearBlock; i += 16)
                if (f.d_step > 0.0f) drape_lanes_avx512<true>(f, dxs, dzs, ends, i, color, slice);
                else drape_lanes_avx512<false>(f, dxs, dzs, ends, i, color, slice);
        else if (kernel == ResolveKernel::Avx2Loads || kernel == ResolveKernel::Avx2Window)
            for (int i = 0; i < kShearBlock; i += 8) drape_lanes_avx2<LoadLookup>(f, dxs, dzs, ends, i, color, slice);
        else
            for (int i = 0; i < kShearBlock; i += 8) drape_lanes_avx2<GatherLookup>(f, dxs, dzs, ends, i, color, slice);
        return;
    }
#endif
    for (int i = 0; i < n; ++i) drape_column(f, dir_x[i], dir_z[i], color + i, slice + i, jend[i], kShearBlock);
}

} // namespace overflight
