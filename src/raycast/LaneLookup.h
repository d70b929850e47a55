#pragma once
// table[idx] for the 8 lanes of an AVX2 kernel (ShearResolve, ShearDrape),
// three ways that read the same entries, so the kernels templated on the way
// give the same bits with any:
//   GatherLookup - one hardware gather (VPGATHERDD, VGATHERDPS);
//   LoadLookup   - the indices stored to the stack, 8 scalar loads and
//                  inserts;
//   WindowLookup - the 8 entries around lane 0's loaded and permuted in
//                  registers when every lane falls among them, else the
//                  Fallback's lookup.
// The gathers are microcoded on AMD family 17h (Zen, Zen+, Zen 2): Agner Fog,
// "Instruction tables", the AMD Zen and Zen 2 lists, give a ymm gather tens
// of macro-ops and a reciprocal throughput of many clock cycles (measured on
// a Zen 1 EPYC: about 16 cycles per 8 lanes, the loads about 8); on Intel
// since Skylake and on Zen 3 and later the gather is the cheaper
// (cpu_gathers_slow picks).
//
// Every entry is 4 bytes; indices must be in the table (masked lanes
// excepted: LoadLookup reads entry 0 there and clears it). `entries` is the
// table's size (0: unknown), which only WindowLookup uses.
#if defined(__x86_64__) && defined(__GNUC__)
// GCC 12's AVX-512 headers start some intrinsics from an undefined register
// and warn about it where they are inlined (GCC bug 105593, fixed in 13).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace overflight {

struct GatherLookup {
    template <class T>
    __attribute__((target("avx2"))) static __m256i words(const T* table, int /*entries*/, __m256i idx) {
        static_assert(sizeof(T) == 4);
        return _mm256_i32gather_epi32(reinterpret_cast<const int*>(table), idx, 4);
    }
    __attribute__((target("avx2"))) static __m256 floats(const float* table, int /*entries*/, __m256i idx) {
        return _mm256_i32gather_ps(table, idx, 4);
    }
    // words of the lanes where mask is all ones, 0 elsewhere (whose idx is not read).
    template <class T>
    __attribute__((target("avx2"))) static __m256i words(const T* table, int /*entries*/, __m256i idx, __m256i mask) {
        static_assert(sizeof(T) == 4);
        return _mm256_mask_i32gather_epi32(_mm256_setzero_si256(), reinterpret_cast<const int*>(table), idx, mask, 4);
    }
};

struct LoadLookup {
    template <class T>
    __attribute__((target("avx2"))) static __m256i words(const T* table, int /*entries*/, __m256i idx) {
        std::int32_t e[8];
        load(table, idx, e);
        return _mm256_setr_epi32(e[0], e[1], e[2], e[3], e[4], e[5], e[6], e[7]);
    }
    __attribute__((target("avx2"))) static __m256 floats(const float* table, int /*entries*/, __m256i idx) {
        float e[8];
        load(table, idx, e);
        return _mm256_setr_ps(e[0], e[1], e[2], e[3], e[4], e[5], e[6], e[7]);
    }
    template <class T>
    __attribute__((target("avx2"))) static __m256i words(const T* table, int entries, __m256i idx, __m256i mask) {
        return _mm256_and_si256(words(table, entries, _mm256_and_si256(idx, mask)), mask);
    }

private:
    // e[q] = the bytes of table[idx[q]]. The indices go through the stack:
    // one store and 8 loads that the store forwards. The empty asm keeps GCC
    // from turning that round trip into 8 moves from the vector register to
    // general registers (VPEXTRD, VMOVQ and VPEXTRQ), which on Zen 1 made a
    // lookup 3 times slower than the stack's (measured).
    template <class T, class E>
    __attribute__((target("avx2"))) static void load(const T* table, __m256i idx, E* e) {
        static_assert(sizeof(T) == 4 && sizeof(E) == 4);
        alignas(32) std::uint32_t i[8];
        _mm256_store_si256(reinterpret_cast<__m256i*>(i), idx);
        asm("" : "+m"(i));
        // T may be a struct of 4 bytes (Rgba8): its bytes are copied.
        const char* base = reinterpret_cast<const char*>(table);
        for (int q = 0; q < 8; ++q) std::memcpy(&e[q], base + std::size_t(i[q]) * 4, 4);
    }
};

// The lanes of a resolve's block row mostly read neighbouring entries (the
// columns see nearly the same angles, and below the horizon nearly the same
// ground), so the 8 entries from kBefore before lane 0's are loaded as one
// vector and each lane picks its entry with one permute (VPERMD): a handful
// of operations against a gather's tens of macro-ops on AMD family 17h or 8
// loads. A lane outside the window, or a table of fewer than 8 entries,
// takes the Fallback's lookup for all 8. (A 16-entry window, two permutes
// and a blend, fell back less often but cost more than it saved: measured on
// a Zen 1 EPYC, the resolve no faster than LoadLookup's.)
template <class Fallback>
struct WindowLookup {
    static constexpr int kSpan = 8, kBefore = 3;

    template <class T>
    __attribute__((target("avx2"))) static __m256i words(const T* table, int entries, __m256i idx) {
        __m256i out;
        return in_window(table, entries, idx, out) ? out : Fallback::words(table, entries, idx);
    }
    __attribute__((target("avx2"))) static __m256 floats(const float* table, int entries, __m256i idx) {
        return _mm256_castsi256_ps(words(table, entries, idx));
    }
    // Masked-out lanes (their idx unread) take lane 0's place in the window,
    // or the Fallback's masked lookup, and come back 0.
    template <class T>
    __attribute__((target("avx2"))) static __m256i words(const T* table, int entries, __m256i idx, __m256i mask) {
        const __m256i lane0 = _mm256_set1_epi32(_mm_cvtsi128_si32(_mm256_castsi256_si128(idx)));
        __m256i out;
        if (in_window(table, entries, _mm256_blendv_epi8(lane0, idx, mask), out)) return _mm256_and_si256(out, mask);
        return Fallback::words(table, entries, idx, mask);
    }

private:
    // The window's entries for every lane, or false (nothing read) when a lane is outside it.
    template <class T>
    __attribute__((target("avx2"))) static bool in_window(const T* table, int entries, __m256i idx, __m256i& out) {
        static_assert(sizeof(T) == 4);
        if (entries < kSpan) return false;
        const int first = std::clamp(_mm_cvtsi128_si32(_mm256_castsi256_si128(idx)) - kBefore, 0, entries - kSpan);
        // Each lane's place in the window: outside it when a bit above the low 3 is set (negative included).
        const __m256i rel = _mm256_sub_epi32(idx, _mm256_set1_epi32(first));
        if (!_mm256_testz_si256(rel, _mm256_set1_epi32(~(kSpan - 1)))) [[unlikely]]
            return false;
        const char* p = reinterpret_cast<const char*>(table) + std::size_t(first) * 4;
        out = _mm256_permutevar8x32_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)), rel);
        return true;
    }
};

} // namespace overflight
#endif
