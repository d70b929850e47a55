// The demo island's relief for the baseline instruction set, its gradient
// table, and the run-time pick of the kernel (DemoReliefKernel).
#include "core/DemoRelief.inl"

#include <vector>

namespace overflight {

// The same float expressions as when each noise call computed its gradient
// (cosf, sinf of the angle), so the same bits.
const DemoGradient* demo_gradients() {
    static const std::vector<DemoGradient> table = [] {
        std::vector<DemoGradient> g(65536);
        for (std::uint32_t k = 0; k < 65536; ++k) {
            const float a = float(k) * (6.28318530718f / 65536.0f);
            g[k] = {std::cos(a), std::sin(a)};
        }
        return g;
    }();
    return table.data();
}

std::uint32_t demo_lattice_hash(std::uint32_t x, std::uint32_t y, std::uint32_t seed) {
    return lattice_hash(x, y, seed);
}

bool demo_relief_kernel_available(DemoReliefKernel kernel) {
    switch (kernel) {
    case DemoReliefKernel::Auto:
    case DemoReliefKernel::Scalar:
    case DemoReliefKernel::Portable: return true;
    case DemoReliefKernel::X86_64_v3:
#if OVERFLIGHT_DEMO_X86_64_V3
        return __builtin_cpu_supports("x86-64-v3");
#else
        return false;
#endif
    }
    return false;
}

void demo_relief(const float* s, const float* t, int octaves, std::uint32_t seed, float* out,
                 DemoReliefKernel kernel) {
#if OVERFLIGHT_DEMO_X86_64_V3
    static const bool v3 = demo_relief_kernel_available(DemoReliefKernel::X86_64_v3);
    if (v3 && (kernel == DemoReliefKernel::Auto || kernel == DemoReliefKernel::X86_64_v3))
        return demo_relief_x86_64_v3(s, t, octaves, seed, out);
#endif
    if (kernel == DemoReliefKernel::Scalar) {
        for (int i = 0; i < kDemoReliefLanes; ++i) relief<1>(s + i, t + i, octaves, seed, out + i);
        return;
    }
    relief<kDemoReliefLanes>(s, t, octaves, seed, out);
}

} // namespace overflight
