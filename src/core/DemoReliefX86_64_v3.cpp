// The demo island's relief compiled for x86-64-v3 (AVX2: eight lanes of
// floats and of 32-bit multiplications per instruction): src/CMakeLists.txt
// builds this file alone with -march=x86-64-v3 and defines
// OVERFLIGHT_DEMO_X86_64_V3 where it does (GCC, x86-64); demo_relief runs it
// only on a CPU that has the level. No FMA contraction (-ffp-contract=off),
// so the same bits as the baseline.
#if OVERFLIGHT_DEMO_X86_64_V3
#include "core/DemoRelief.inl"

namespace overflight {

void demo_relief_x86_64_v3(const float* s, const float* t, int octaves, std::uint32_t seed, float* out) {
    relief<kDemoReliefLanes>(s, t, octaves, seed, out);
}

} // namespace overflight
#endif
