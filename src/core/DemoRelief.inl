// The relief of the demo island (DemoRelief.h) for N positions at once,
// included by one source file per instruction set, each compiling it for its
// own. Every step is a loop over the N lanes doing what the one-position
// evaluation (N = 1) does, in the same order, so that the compiler can run
// the lanes in SIMD registers and every lane keeps the bits of N = 1: IEEE
// single-precision operations are exact per lane, floor and the truncating
// int conversion have exact vector forms, and the including file's build has
// no FMA contraction (-ffp-contract=off, src/CMakeLists.txt). Everything here
// has internal linkage (an unnamed namespace) and is inlined into the
// including file's entry points, so that no copy compiled for one instruction
// set can stand in for another's.
//
// Based on: Musgrave's ridged multifractal (Texturing & Modeling, ch. 16) over
// gradient noise (Perlin 2002), with domain warping (Quilez) for the drainage-
// like ridges, and an island falloff. Deterministic: the noise is built on an
// integer hash, not on std:: distributions whose output differs by library.
#include "core/DemoRelief.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace overflight {

// The unit gradients of the noise, one per 16-bit angle: a lattice point's
// gradient is picked by 16 bits of its hash, so 65536 cosines and sines
// computed once (DemoRelief.cpp) stand for the 140 per position that the
// island's octaves would otherwise compute.
struct DemoGradient {
    float cos, sin;
};
const DemoGradient* demo_gradients();

#if OVERFLIGHT_DEMO_X86_64_V3
// DemoReliefX86_64_v3.cpp's entry point (demo_relief picks it).
void demo_relief_x86_64_v3(const float* s, const float* t, int octaves, std::uint32_t seed, float* relief);
#endif

namespace {

template <std::size_t N>
using Floats = std::array<float, N>;
template <std::size_t N>
using Words = std::array<std::uint32_t, N>;

// The lattice hash's three terms: seed, x and y each times its own odd
// constant (hash_mix combines the terms).
constexpr std::uint32_t kHashSeed = 0x9E3779B9u, kHashX = 0x85EBCA6Bu, kHashY = 0xC2B2AE35u;

[[gnu::always_inline]] inline std::uint32_t hash_mix(std::uint32_t seed_term, std::uint32_t x_term,
                                                     std::uint32_t y_term) {
    std::uint32_t h = seed_term ^ x_term ^ y_term;
    h ^= h >> 16; h *= 0x7FEB352Du;
    h ^= h >> 15; h *= 0x846CA68Bu;
    h ^= h >> 16;
    return h;
}

[[gnu::always_inline]] inline std::uint32_t lattice_hash(std::uint32_t x, std::uint32_t y, std::uint32_t seed) {
    return hash_mix(seed * kHashSeed, x * kHashX, y * kHashY);
}

// 2D gradient noise in about [-1, 1] with quintic fade, at (x[i], y[i]).
// A cell's corners x + 1 and y + 1 enter the hash as x kHashX + kHashX and
// y kHashY + kHashY: the same words modulo 2^32, so the four corners' hashes
// share three multiplications of the lattice coordinates and seed, not twelve.
template <std::size_t N>
[[gnu::always_inline]] inline Floats<N> gradient_noise(const Floats<N>& x, const Floats<N>& y, std::uint32_t seed,
                                                       const DemoGradient* table) {
    Floats<N> tx, ty;
    Words<N> hx, hy;
    for (std::size_t i = 0; i < N; ++i) {
        const float fx = std::floor(x[i]), fy = std::floor(y[i]);
        hx[i] = std::uint32_t(std::int32_t(fx)) * kHashX;
        hy[i] = std::uint32_t(std::int32_t(fy)) * kHashY;
        tx[i] = x[i] - fx;
        ty[i] = y[i] - fy;
    }
    const std::uint32_t hs = seed * kHashSeed;
    Words<N> k00, k10, k01, k11;
    for (std::size_t i = 0; i < N; ++i) {
        k00[i] = hash_mix(hs, hx[i], hy[i]) & 0xFFFFu;
        k10[i] = hash_mix(hs, hx[i] + kHashX, hy[i]) & 0xFFFFu;
        k01[i] = hash_mix(hs, hx[i], hy[i] + kHashY) & 0xFFFFu;
        k11[i] = hash_mix(hs, hx[i] + kHashX, hy[i] + kHashY) & 0xFFFFu;
    }
    // The table lookups in a loop of their own: lane by lane where the
    // compiler uses no gather, without keeping the arithmetic around them from
    // being vectorised.
    Floats<N> c00, s00, c10, s10, c01, s01, c11, s11;
    for (std::size_t i = 0; i < N; ++i) {
        c00[i] = table[k00[i]].cos, s00[i] = table[k00[i]].sin;
        c10[i] = table[k10[i]].cos, s10[i] = table[k10[i]].sin;
        c01[i] = table[k01[i]].cos, s01[i] = table[k01[i]].sin;
        c11[i] = table[k11[i]].cos, s11[i] = table[k11[i]].sin;
    }
    Floats<N> noise;
    for (std::size_t i = 0; i < N; ++i) {
        const float n00 = c00[i] * tx[i] + s00[i] * ty[i];
        const float n10 = c10[i] * (tx[i] - 1) + s10[i] * ty[i];
        const float n01 = c01[i] * tx[i] + s01[i] * (ty[i] - 1);
        const float n11 = c11[i] * (tx[i] - 1) + s11[i] * (ty[i] - 1);
        auto fade = [](float t) { return t * t * t * (t * (t * 6 - 15) + 10); };
        const float u = fade(tx[i]), v = fade(ty[i]);
        const float a = n00 + (n10 - n00) * u, b = n01 + (n11 - n01) * u;
        noise[i] = 1.41421356f * (a + (b - a) * v);
    }
    return noise;
}

template <std::size_t N>
[[gnu::always_inline]] inline Floats<N> scaled(const Floats<N>& x, float scale) {
    Floats<N> r;
    for (std::size_t i = 0; i < N; ++i) r[i] = x[i] * scale;
    return r;
}

// With an offset; the overload above adds none, as adding 0 would turn -0
// into +0.
template <std::size_t N>
[[gnu::always_inline]] inline Floats<N> scaled(const Floats<N>& x, float scale, float offset) {
    Floats<N> r;
    for (std::size_t i = 0; i < N; ++i) r[i] = x[i] * scale + offset;
    return r;
}

template <std::size_t N>
[[gnu::always_inline]] inline Floats<N> fbm(const Floats<N>& x, const Floats<N>& y, int octaves, std::uint32_t seed,
                                            const DemoGradient* table) {
    Floats<N> sum{};
    float amp = 0.5f, freq = 1;
    for (int o = 0; o < octaves; ++o) {
        const Floats<N> n = gradient_noise(scaled(x, freq), scaled(y, freq), seed + std::uint32_t(o), table);
        for (std::size_t i = 0; i < N; ++i) sum[i] += amp * n[i];
        amp *= 0.5f;
        freq *= 2.03f;
    }
    return sum;
}

// Ridged multifractal: sharp crests where the noise crosses zero, each octave
// weighted by the previous one so valleys stay smooth (erosion-like).
template <std::size_t N>
[[gnu::always_inline]] inline Floats<N> ridged(const Floats<N>& x, const Floats<N>& y, int octaves,
                                               std::uint32_t seed, const DemoGradient* table) {
    Floats<N> sum{}, weight;
    weight.fill(1.0f);
    float amp = 0.5f, freq = 1, norm = 0;
    for (int o = 0; o < octaves; ++o) {
        const Floats<N> g = gradient_noise(scaled(x, freq), scaled(y, freq), seed + 101u + std::uint32_t(o), table);
        for (std::size_t i = 0; i < N; ++i) {
            float n = 1.0f - std::abs(g[i]);
            n *= n;
            n *= weight[i];
            weight[i] = std::clamp(n * 2.0f, 0.0f, 1.0f);
            sum[i] += n * amp;
        }
        norm += amp;
        amp *= 0.5f;
        freq *= 2.0f;
    }
    for (std::size_t i = 0; i < N; ++i) sum[i] /= norm;
    return sum;
}

// Relief in metres at normalised positions (s[i], t[i]).
template <std::size_t N>
[[gnu::always_inline]] inline void relief(const float* s_in, const float* t_in, int octaves, std::uint32_t seed,
                                          float* out) {
    constexpr float kPeak = 1400.0f; // highest relief before the falloff
    const DemoGradient* table = demo_gradients();
    Floats<N> s, t;
    std::copy_n(s_in, N, s.begin());
    std::copy_n(t_in, N, t.begin());
    // Domain warp bends the ridges into drainage-like patterns.
    const Floats<N> wx = fbm(scaled(s, 3.0f), scaled(t, 3.0f), 4, seed + 7u, table);
    const Floats<N> wy = fbm(scaled(s, 3.0f, 5.2f), scaled(t, 3.0f, 1.3f), 4, seed + 11u, table);
    Floats<N> x, y;
    for (std::size_t i = 0; i < N; ++i) {
        x[i] = s[i] * 6.0f + 0.8f * wx[i];
        y[i] = t[i] * 6.0f + 0.8f * wy[i];
    }
    const Floats<N> mountains = ridged(x, y, octaves, seed, table);
    const Floats<N> hill_noise = fbm(scaled(x, 1.7f), scaled(y, 1.7f), octaves, seed + 31u, table);
    // Island falloff: distance from the centre, perturbed so the coast is ragged.
    const Floats<N> coast = fbm(scaled(s, 4.0f), scaled(t, 4.0f), 5, seed + 53u, table);
    for (std::size_t i = 0; i < N; ++i) {
        const float dx = s[i] - 0.5f, dy = t[i] - 0.5f;
        const float r = std::sqrt(dx * dx + dy * dy) * 2.0f + 0.25f * coast[i];
        const float island = std::clamp(1.15f - r * 1.2f, -1.0f, 1.0f);
        const float land = island > 0 ? std::pow(island, 0.8f) : island;
        const float hills = 0.5f + 0.5f * hill_noise[i];
        out[i] = land * (0.75f * mountains[i] + 0.25f * hills) * kPeak + (land - 0.12f) * 220.0f;
    }
}

} // namespace
} // namespace overflight
