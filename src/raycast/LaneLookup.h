#pragma once
// table[idx] for the 8 lanes of an AVX2 kernel (ShearResolve, ShearDrape),
// two ways that read the same entries, so the kernels templated on the way
// give the same bits with either:
//   GatherLookup - one hardware gather (VPGATHERDD, VGATHERDPS);
//   LoadLookup   - the indices stored to the stack, 8 scalar loads and
//                  inserts.
// The gathers are microcoded on AMD family 17h (Zen, Zen+, Zen 2): Agner Fog,
// "Instruction tables", the AMD Zen and Zen 2 lists, give a ymm gather tens
// of macro-ops and a reciprocal throughput of many clock cycles (measured on
// a Zen 1 EPYC: about 16 cycles per 8 lanes, the loads about 8); on Intel
// since Skylake and on Zen 3 and later the gather is the cheaper
// (cpu_gathers_slow picks).
//
// Every entry is 4 bytes; indices must be in the table (masked lanes
// excepted: LoadLookup reads entry 0 there and clears it).
#if defined(__x86_64__) && defined(__GNUC__)
// GCC 12's AVX-512 headers start some intrinsics from an undefined register
// and warn about it where they are inlined (GCC bug 105593, fixed in 13).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace overflight {

struct GatherLookup {
    template <class T>
    __attribute__((target("avx2"))) static __m256i words(const T* table, __m256i idx) {
        static_assert(sizeof(T) == 4);
        return _mm256_i32gather_epi32(reinterpret_cast<const int*>(table), idx, 4);
    }
    __attribute__((target("avx2"))) static __m256 floats(const float* table, __m256i idx) {
        return _mm256_i32gather_ps(table, idx, 4);
    }
    // words of the lanes where mask is all ones, 0 elsewhere (whose idx is not read).
    template <class T>
    __attribute__((target("avx2"))) static __m256i words(const T* table, __m256i idx, __m256i mask) {
        static_assert(sizeof(T) == 4);
        return _mm256_mask_i32gather_epi32(_mm256_setzero_si256(), reinterpret_cast<const int*>(table), idx, mask, 4);
    }
};

struct LoadLookup {
    template <class T>
    __attribute__((target("avx2"))) static __m256i words(const T* table, __m256i idx) {
        std::int32_t e[8];
        load(table, idx, e);
        return _mm256_setr_epi32(e[0], e[1], e[2], e[3], e[4], e[5], e[6], e[7]);
    }
    __attribute__((target("avx2"))) static __m256 floats(const float* table, __m256i idx) {
        float e[8];
        load(table, idx, e);
        return _mm256_setr_ps(e[0], e[1], e[2], e[3], e[4], e[5], e[6], e[7]);
    }
    template <class T>
    __attribute__((target("avx2"))) static __m256i words(const T* table, __m256i idx, __m256i mask) {
        return _mm256_and_si256(words(table, _mm256_and_si256(idx, mask)), mask);
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

} // namespace overflight
#endif
