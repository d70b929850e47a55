// The demo island's relief (core/DemoRelief.h): every batch kernel gives the
// bits of the one-position evaluation, lane by lane, at positions that put
// the noise's lattice points, negative coordinates and cell boundaries in
// every lane; and the island is the one it was before the batches (its
// heights and colors hashed).
#include "core/DemoIsland.h"
#include "core/DemoRelief.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

using namespace overflight;

namespace {

constexpr int kLanes = kDemoReliefLanes;

// Positions (s, t): on the lattices of the warp (s * 3, s * 4 integers, s * 6
// for the ridges) and one float either side of them, negative and far from
// the island, and a deterministic scatter over [-4, 4]^2.
std::vector<float> positions() {
    std::vector<float> p;
    for (int k = -24; k <= 24; ++k) {
        const float s = float(k) / 12.0f;
        p.insert(p.end(), {s, std::nextafter(s, -1e9f), std::nextafter(s, 1e9f)});
    }
    for (float s : {-1000.0f, -3.5f, -0.0f, 0.0f, 1.0f, 250.25f, 1000.0f}) p.push_back(s);
    std::uint32_t r = 12345;
    for (int k = 0; k < 600; ++k) {
        r = r * 1664525u + 1013904223u;
        p.push_back(float(r >> 8) / float(1 << 24) * 8.0f - 4.0f);
    }
    return p;
}

} // namespace

TEST(DemoRelief, KernelsGiveTheBitsOfTheScalarEvaluation) {
    const std::vector<float> p = positions();
    int compared = 0;
    for (DemoReliefKernel kernel : {DemoReliefKernel::Portable, DemoReliefKernel::X86_64_v3}) {
        if (!demo_relief_kernel_available(kernel)) continue;
        for (int octaves : {4, 9, 13})
            for (std::uint32_t seed : {1997u, 0xFFFFFFF0u}) {
                // Each batch pairs kLanes consecutive positions with one t, the
                // next batch shifted by 3 so every position meets every lane.
                for (std::size_t b = 0; b + kLanes <= p.size(); b += 3) {
                    const float t = p[(b * 7) % p.size()];
                    float s[kLanes], u[kLanes], scalar[kLanes], batch[kLanes];
                    for (int i = 0; i < kLanes; ++i) {
                        s[i] = p[b + std::size_t(i)];
                        u[i] = i % 2 ? t : p[(b + std::size_t(i) * 11) % p.size()];
                    }
                    demo_relief(s, u, octaves, seed, scalar, DemoReliefKernel::Scalar);
                    demo_relief(s, u, octaves, seed, batch, kernel);
                    for (int i = 0; i < kLanes; ++i)
                        ASSERT_EQ(std::bit_cast<std::uint32_t>(batch[i]), std::bit_cast<std::uint32_t>(scalar[i]))
                            << "kernel " << int(kernel) << " at (" << s[i] << ", " << u[i] << "), octaves " << octaves
                            << ", seed " << seed << ": " << batch[i] << " vs " << scalar[i];
                    ++compared;
                }
            }
    }
    EXPECT_GT(compared, 0);
}

// FNV-1a of the heights and colors of the 33 and 257 islands as they were
// made one sample at a time, before the batches.
TEST(DemoRelief, IslandAsBeforeTheBatches) {
    for (auto [n, expected] : {std::pair{33, 0xada9f1c036d3362cull}, std::pair{257, 0x4bf6e64e06e03c3dull}}) {
        const DataSet d = make_demo_island({.size = n});
        std::uint64_t h = 14695981039346656037ull;
        auto mix = [&](std::uint8_t b) { h = (h ^ b) * 1099511628211ull; };
        for (std::uint16_t v : d.terrain.heights()) {
            mix(std::uint8_t(v));
            mix(std::uint8_t(v >> 8));
        }
        for (const Rgb8& c : d.terrain.colors()) {
            mix(c.r);
            mix(c.g);
            mix(c.b);
        }
        EXPECT_EQ(h, expected) << "size " << n;
    }
}
