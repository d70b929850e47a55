#pragma once
// The relief of the demo island (DemoIsland.h) in metres, evaluated for a
// batch of kDemoReliefLanes positions at once so that the noise's float and
// integer arithmetic runs in SIMD lanes. Every kernel gives the bits of the
// one-position evaluation (DemoReliefKernel::Scalar): the same operations in
// the same order, none fused or reassociated (DemoRelief.inl).
#include <cstdint>

namespace overflight {

// Positions per batch: one x86-64-v3 register of floats.
constexpr int kDemoReliefLanes = 8;

// Scalar: one position after another (the reference). Portable: the batch's
// lanes in loops that the compiler vectorises for the baseline instruction
// set. X86_64_v3: the same loops compiled for x86-64-v3 (AVX2), GCC on
// x86-64 only. Auto: the fastest that this CPU runs. X86_64_v3 where it is
// not available (demo_relief_kernel_available) runs Portable.
enum class DemoReliefKernel { Auto, Scalar, Portable, X86_64_v3 };

// The integer hash of the noise's lattice points (x, y) (also what places
// the island's village).
std::uint32_t demo_lattice_hash(std::uint32_t x, std::uint32_t y, std::uint32_t seed);

bool demo_relief_kernel_available(DemoReliefKernel kernel);

// relief[i] = the relief at normalised position (s[i], t[i]) for i <
// kDemoReliefLanes (the island is [0,1]^2; any finite position is defined).
void demo_relief(const float* s, const float* t, int octaves, std::uint32_t seed, float* relief,
                 DemoReliefKernel kernel = DemoReliefKernel::Auto);

} // namespace overflight
