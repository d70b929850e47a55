// The imagery draped over a shear block row by row (ShearDrape.h) gives the
// same bits as drape_column (ImageryTexels.h) column by column: the AVX2 and
// AVX-512 kernels against the portable one on random blocks (slices read or,
// evenly spaced, computed), and a hand-worked pixel.
#include "core/ImageryPyramid.h"
#include "raycast/ImageryTexels.h"
#include "raycast/ShearDrape.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

using namespace overflight;

namespace {

// Imagery of w x h random texels over [-0.5, 40.5] x [-0.5, 30.5].
ImageryPyramid random_pyramid(int w, int h, std::mt19937& rng) {
    Image2D<Rgba8> img(w, h);
    std::uniform_int_distribution<int> byte(0, 255);
    for (Rgba8& t : img.pixels)
        t = Rgba8{std::uint8_t(byte(rng)), std::uint8_t(byte(rng)), std::uint8_t(byte(rng)), 255};
    return ImageryPyramid(std::move(img), -0.5, -0.5, 41.0, 31.0);
}

// The SIMD kernels this CPU runs.
std::vector<ResolveKernel> simd_kernels() {
    std::vector<ResolveKernel> out;
    for (const ResolveKernel k :
         {ResolveKernel::Avx2, ResolveKernel::Avx2Loads, ResolveKernel::Avx2Window, ResolveKernel::Avx512})
        if (resolve_kernel_available(k)) out.push_back(k);
    return out;
}

} // namespace

TEST(ShearDrape, SimdKernelsGiveTheSameBitsAsTheColumns) {
    if (simd_kernels().empty()) GTEST_SKIP() << "no AVX2 on this CPU";
    std::mt19937 rng(7);
    const ImageryPyramid pyramid = random_pyramid(123, 91, rng);
    ImageryTexels texels;
    texels.bind(&pyramid);
    const int H = 97, slices = 300;
    std::vector<float> slice_d(slices), row_m(H);
    for (int k = 0; k < slices; ++k) slice_d[std::size_t(k)] = 0.5f + 0.37f * float(k);
    for (int j = 0; j < H; ++j) row_m[std::size_t(j)] = -0.8f + 1.2f * float(j) / float(H - 1); // down, level, up
    texels.prepare_slices(slice_d.data(), slices, 20.0);
    texels.prepare_rows(row_m.data(), H);
    DrapeFrame frame{&texels, slice_d.data(), 0.3f, row_m.data(), 12.5f, 7.25f};
    std::uniform_int_distribution<std::uint32_t> light(0, 0xFFFFFFu);
    std::uniform_real_distribution<float> dir(-1.0f, 1.0f);
    for (int trial = 0; trial < 40; ++trial) {
        // Every other trial tells the kernels that the slices are evenly spaced, as they are.
        frame.d_first = trial % 2 ? 0.5f : 0.0f;
        frame.d_step = trial % 2 ? 0.37f : 0.0f;
        const int n = trial % 5 == 0 ? 1 + trial % kShearBlock : kShearBlock;
        std::vector<std::uint32_t> color(std::size_t(kShearBlock) * H), slice(color.size());
        int jend[kShearBlock];
        float dx[kShearBlock], dz[kShearBlock];
        for (int i = 0; i < kShearBlock; ++i) {
            jend[i] = i < n ? int(rng() % (H + 1)) : 0;
            dx[i] = dir(rng);
            dz[i] = dir(rng);
            // Slices grow up a column, in runs of any length, from slice 0 on.
            int k = int(rng() % 3);
            for (int j = 0; j < H; ++j) {
                if (rng() % 3 == 0) k = std::min(slices - 1, k + 1 + int(rng() % 5));
                slice[std::size_t(j) * kShearBlock + std::size_t(i)] = j < jend[i] ? std::uint32_t(k) : rng();
                color[std::size_t(j) * kShearBlock + std::size_t(i)] = light(rng);
            }
        }
        std::vector<std::uint32_t> portable = color;
        drape_shear_block(frame, dx, dz, n, jend, portable.data(), slice.data(), ResolveKernel::Portable);
        for (const ResolveKernel kernel : simd_kernels()) {
            std::vector<std::uint32_t> simd = color;
            drape_shear_block(frame, dx, dz, n, jend, simd.data(), slice.data(), kernel);
            for (int i = 0; i < kShearBlock; ++i)
                for (int j = 0; j < H; ++j) { // painted pixels the same, the others untouched
                    const std::size_t at = std::size_t(j) * kShearBlock + std::size_t(i);
                    ASSERT_EQ(simd[at], portable[at])
                        << "kernel " << int(kernel) << " trial " << trial << " column " << i << " row " << j;
                }
        }
    }
}

// Imagery of 17 levels (65537 x 2 texels) has no lane tables: the AVX2
// kernel asked for drapes column by column, with the same bits.
TEST(ShearDrape, ImageryWithoutLaneTablesGivesTheSameBits) {
    std::mt19937 rng(3);
    Image2D<Rgba8> img(65537, 2);
    std::uniform_int_distribution<int> byte(0, 255);
    for (Rgba8& t : img.pixels)
        t = Rgba8{std::uint8_t(byte(rng)), std::uint8_t(byte(rng)), std::uint8_t(byte(rng)), 255};
    const ImageryPyramid pyramid(std::move(img), -0.5, -0.5, 41.0, 31.0);
    ASSERT_EQ(pyramid.levels(), 17);
    ImageryTexels texels;
    texels.bind(&pyramid);
    EXPECT_FALSE(texels.lane_tables());
    const int H = 40, slices = 50;
    std::vector<float> slice_d(slices), row_m(H);
    for (int k = 0; k < slices; ++k) slice_d[std::size_t(k)] = 0.5f + 0.37f * float(k);
    for (int j = 0; j < H; ++j) row_m[std::size_t(j)] = -0.8f + 0.02f * float(j);
    texels.prepare_slices(slice_d.data(), slices, 20.0);
    texels.prepare_rows(row_m.data(), H);
    const DrapeFrame frame{&texels, slice_d.data(), 0.3f, row_m.data(), 12.5f, 7.25f};
    std::vector<std::uint32_t> color(std::size_t(kShearBlock) * H), slice(color.size());
    int jend[kShearBlock];
    float dx[kShearBlock], dz[kShearBlock];
    for (int i = 0; i < kShearBlock; ++i) {
        jend[i] = H - i;
        dx[i] = 0.1f * float(i) - 1.0f;
        dz[i] = 1.0f;
        for (int j = 0; j < H; ++j) {
            slice[std::size_t(j) * kShearBlock + std::size_t(i)] = std::uint32_t(j + i / 4);
            color[std::size_t(j) * kShearBlock + std::size_t(i)] = std::uint32_t(rng()) & 0xFFFFFFu;
        }
    }
    std::vector<std::uint32_t> portable = color;
    drape_shear_block(frame, dx, dz, kShearBlock, jend, portable.data(), slice.data(), ResolveKernel::Portable);
    EXPECT_NE(portable, color);
    for (const ResolveKernel kernel : simd_kernels()) {
        std::vector<std::uint32_t> simd = color;
        drape_shear_block(frame, dx, dz, kShearBlock, jend, simd.data(), slice.data(), kernel);
        EXPECT_EQ(simd, portable);
    }
}

// One column of one painted row, worked by hand: slice 1 (view depth 2,
// the cell from depth 1), a row looking down with slope -0.5 at the run's top,
// so the ray meets the sample's height at depth 2 straight ahead: world
// (2, 3) on a 4 x 4 imagery over [0, 4]^2, texel (2, 3) at level 0; light
// (128, 64, 255) times albedo (100, 200, 2) = (100, 100, 4).
TEST(ShearDrape, HandWorkedPixel) {
    Image2D<Rgba8> img(4, 4);
    img.at(2, 3) = Rgba8{100, 200, 2, 255};
    const ImageryPyramid pyramid(std::move(img), 0.0, 0.0, 4.0, 4.0);
    ImageryTexels texels;
    texels.bind(&pyramid);
    const std::vector<float> slice_d = {1.0f, 2.0f}, row_m = {-0.5f};
    texels.prepare_slices(slice_d.data(), 2, 100.0);
    texels.prepare_rows(row_m.data(), 1);
    EXPECT_EQ(texels.level(1, 0), 0);
    const DrapeFrame frame{&texels, slice_d.data(), 1.0f, row_m.data(), 2.0f, 1.0f};
    for (const ResolveKernel kernel :
         {ResolveKernel::Portable, ResolveKernel::Avx2, ResolveKernel::Avx2Loads, ResolveKernel::Avx2Window,
          ResolveKernel::Avx512}) {
        if (!resolve_kernel_available(kernel)) continue;
        std::vector<std::uint32_t> color(kShearBlock, 0), slice(kShearBlock, 0);
        color[0] = 128u | (64u << 8) | (255u << 16);
        slice[0] = 1;
        const int jend[1] = {1};
        const float dx[1] = {0.0f}, dz[1] = {1.0f};
        drape_shear_block(frame, dx, dz, 1, jend, color.data(), slice.data(), kernel);
        EXPECT_EQ(color[0], 100u | (100u << 8) | (4u << 16));
    }
}
