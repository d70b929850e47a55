#pragma once
// The x86-64 instruction sets that kernels with run-time dispatch test for,
// tested one way everywhere. Call only where the caller is compiled for
// x86-64 (GCC or clang: __builtin_cpu_supports).

namespace overflight {

#if defined(__x86_64__)
// AVX-512 as the 16-lane kernels use it: the foundation plus the byte/word,
// doubleword/quadword and 128/256-bit-vector extensions.
inline bool cpu_has_avx512() {
    return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
           __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl");
}
#endif

} // namespace overflight
