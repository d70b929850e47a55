#pragma once
// The x86-64 instruction sets that kernels with run-time dispatch test for,
// tested one way everywhere. Call only where the caller is compiled for
// x86-64 (GCC or clang: __builtin_cpu_supports).
#if defined(__x86_64__)
#include <cpuid.h>
#endif

namespace overflight {

#if defined(__x86_64__)
// AVX-512 as the 16-lane kernels use it: the foundation plus the byte/word,
// doubleword/quadword and 128/256-bit-vector extensions.
inline bool cpu_has_avx512() {
    return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
           __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl");
}

// Whether AVX2's gathers are slower than as many scalar loads: on AMD family
// 17h (Zen, Zen+, Zen 2) they are microcoded (raycast/LaneLookup.h).
inline bool cpu_gathers_slow() {
    unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
    if (!__builtin_cpu_is("amd") || !__get_cpuid(1, &eax, &ebx, &ecx, &edx)) return false;
    // The family: the base field, plus the extended field where the base is 0xF.
    const unsigned base = (eax >> 8) & 0xF;
    return base + (base == 0xF ? (eax >> 20) & 0xFF : 0) == 0x17;
}
#endif

} // namespace overflight
