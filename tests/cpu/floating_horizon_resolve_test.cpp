// The shear resolve (ShearResolve): what the cast painted becomes image pixels
// with the slice's window depth (Szenberg eq. 7), fog and sky; the AVX2 and
// AVX-512 kernels give the same bits as the portable one.
#include "core/DataSet.h"
#include "core/Image.h"
#include "raycast/Atmosphere.h"
#include "raycast/ShearResolve.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

using namespace overflight;

namespace {

// A block's scratch: kShearBlock entries per row, rows bottom-up.
struct Scratch {
    std::vector<std::uint32_t> color, slice;
    explicit Scratch(int H) : color(std::size_t(kShearBlock) * std::size_t(H)), slice(color.size()) {}
    void set(int j, int i, std::uint32_t c, std::uint32_t k) {
        color[std::size_t(j) * kShearBlock + std::size_t(i)] = c;
        slice[std::size_t(j) * kShearBlock + std::size_t(i)] = k;
    }
};

ShearBlock block(int n, const std::vector<int>& jend, const std::vector<float>& len2) {
    ShearBlock b;
    b.n = n;
    for (int i = 0; i < kShearBlock; ++i) {
        b.jend[i] = i < n ? jend[std::size_t(i)] : 0;
        b.len2[i] = i < n ? len2[std::size_t(i)] : 1.0f;
        b.sun_dot[i] = 0.0f;
    }
    return b;
}

// The kernels other than the portable one that this CPU runs.
std::vector<ResolveKernel> fast_kernels() {
    std::vector<ResolveKernel> out;
    for (ResolveKernel k :
         {ResolveKernel::Avx2, ResolveKernel::Avx2Loads, ResolveKernel::Avx2Window, ResolveKernel::Avx512})
        if (resolve_kernel_available(k)) out.push_back(k);
    return out;
}

} // namespace

// Three columns of a 5-pixel-wide, 3-row image, the block starting at image
// column 1; no fog, sky from black (horizon) to white (zenith).
//   row slopes bottom-up m = -0.75, 0, 0.75; column planes straight ahead (len2 = 1)
//   column 0: painted 3 rows from slices 0, 1, 1; column 1: 1 row from slice 0; column 2: sky
//   sky at m = 0: sine 0 -> black; at m = 0.75: sine 0.75 / 1.25 = 0.6 -> entry 614 of 1023 -> 153
TEST(ShearResolve, HandWorkedBlock) {
    Environment env;
    env.fog_density = 0.0f;
    env.sky_horizon = {0, 0, 0};
    env.sky_zenith = {1, 1, 1};
    FogTable fog;
    fog.build(env.fog_density, 100.0f);
    SkyTable sky;
    sky.build(env);
    const std::vector<float> rows = {-0.75f, 0.0f, 0.75f}, depth = {0.25f, 0.5f}, d = {10.0f, 20.0f};
    const ShearResolveTables t{rows.data(), depth.data(), d.data(), &fog, 0xFFFFFFu, sky.entries()};
    const int H = 3, W = 5;
    const Rgb8 a{10, 20, 30}, b{40, 50, 60}, c{70, 80, 90}, e{1, 2, 3};
    for (ResolveKernel kernel :
         {ResolveKernel::Portable, ResolveKernel::Avx2, ResolveKernel::Avx2Loads, ResolveKernel::Avx2Window,
          ResolveKernel::Avx512}) {
        if (!resolve_kernel_available(kernel)) continue;
        Scratch s(H);
        s.set(0, 0, pack_rgb(a), 0);
        s.set(1, 0, pack_rgb(b), 1);
        s.set(2, 0, pack_rgb(c), 1);
        s.set(0, 1, pack_rgb(e), 0);
        s.set(1, 1, 0xABCDEFu, 12345); // above the painted rows: stale, must not be read
        ColorImage color;
        DepthImage z;
        color.resize(W, H);
        z.resize(W, H);
        const Rgb8 untouched{9, 9, 9};
        std::fill(color.pixels.begin(), color.pixels.end(), untouched);
        std::fill(z.pixels.begin(), z.pixels.end(), -1.0f);
        resolve_shear_block(t, block(3, {3, 1, 0}, {1, 1, 1}), H, s.color.data(), s.slice.data(),
                            color.pixels.data() + 1, z.pixels.data() + 1, std::size_t(W), kernel);
        const Rgb8 black{0, 0, 0}, grey{153, 153, 153};
        // image rows top-down: r = H - 1 - j
        EXPECT_EQ(color.at(1, 2), a);
        EXPECT_EQ(color.at(1, 1), b);
        EXPECT_EQ(color.at(1, 0), c);
        EXPECT_EQ(z.at(1, 2), 0.25f);
        EXPECT_EQ(z.at(1, 1), 0.5f);
        EXPECT_EQ(z.at(1, 0), 0.5f);
        EXPECT_EQ(color.at(2, 2), e);
        EXPECT_EQ(z.at(2, 2), 0.25f);
        EXPECT_EQ(color.at(2, 1), black);
        EXPECT_EQ(color.at(2, 0), grey);
        EXPECT_EQ(color.at(3, 1), black);
        for (int r = 0; r < H; ++r) {
            EXPECT_EQ(z.at(3, r), 1.0f);
            EXPECT_EQ(color.at(0, r), untouched) << "outside the block";
            EXPECT_EQ(color.at(4, r), untouched) << "outside the block";
            EXPECT_EQ(z.at(4, r), -1.0f);
        }
        EXPECT_EQ(z.at(2, 1), 1.0f);
    }
}

// GL_EXP fog at the eye distance d_k |ray|: a pixel 100 units away along a ray
// of slope 0.75 in a plane straight ahead (|ray| = 1.25 per unit of depth) is
// fogged at distance 125, as FogTable and fog_blend say.
TEST(ShearResolve, FogAtTheEyeDistanceOfThePixel) {
    Environment env;
    env.fog_density = 0.01f;
    FogTable fog;
    fog.build(env.fog_density, 400.0f);
    SkyTable sky;
    sky.build(env);
    const std::vector<float> rows = {0.75f}, depth = {0.9f}, d = {100.0f};
    const std::uint32_t fog_color = 0x808080u, surface = pack_rgb(Rgb8{200, 10, 30});
    const ShearResolveTables t{rows.data(), depth.data(), d.data(), &fog, fog_color, sky.entries()};
    const std::uint32_t expected = fog_blend(surface, fog_color, fog.weight(125.0f));
    EXPECT_NE(expected, surface);
    for (ResolveKernel kernel :
         {ResolveKernel::Portable, ResolveKernel::Avx2, ResolveKernel::Avx2Loads, ResolveKernel::Avx2Window,
          ResolveKernel::Avx512}) {
        if (!resolve_kernel_available(kernel)) continue;
        Scratch s(1);
        s.set(0, 0, surface, 0);
        ColorImage color;
        DepthImage z;
        color.resize(1, 1);
        z.resize(1, 1);
        resolve_shear_block(t, block(1, {1}, {1.0f}), 1, s.color.data(), s.slice.data(), color.pixels.data(),
                            z.pixels.data(), 1, kernel);
        EXPECT_EQ(color.at(0, 0), unpack_rgb(expected));
        EXPECT_EQ(z.at(0, 0), 0.9f);
    }
}

// The aerial perspective at the pixel's eye distance and height: a pixel 100
// units of view depth away along a ray of slope 0.75 in a plane straight
// ahead is 125 away and 75 above the eye; with the sun along the plane
// (sun_dot 0.6, sun Y 0.8) the ray's cosine to the sun is (0.6 + 0.75 * 0.8)
// / 1.25 = 0.96. A sky pixel of slope 0 looks at the horizon (sine 0, cosine
// 0.6). Both as AerialTables says.
TEST(ShearResolve, AerialPerspectiveAtThePixel) {
    Environment env;
    env.atmosphere = true;
    env.sun_dir = {0.0f, 0.8f, 0.6f};
    FogTable fog;
    fog.build(0.0f, 400.0f);
    SkyTable sky;
    sky.build(env);
    AerialTables air;
    air.build(aerial_frame(env, 100.0), -100.0f, 200.0f);
    const std::vector<float> rows = {0.0f, 0.75f}, depth = {0.9f}, d = {100.0f};
    const std::uint32_t surface = pack_rgb(Rgb8{200, 10, 30});
    ShearResolveTables t{rows.data(), depth.data(), d.data(), &fog, 0, sky.entries()};
    t.air = &air;
    t.sun_y = 0.8f;
    const std::uint32_t expected = air.terrain(surface, 125.0f, 75.0f, 0.96f);
    EXPECT_NE(expected, surface);
    for (ResolveKernel kernel :
         {ResolveKernel::Portable, ResolveKernel::Avx2, ResolveKernel::Avx2Loads, ResolveKernel::Avx2Window,
          ResolveKernel::Avx512}) {
        if (!resolve_kernel_available(kernel)) continue;
        Scratch s(2);
        s.set(1, 0, surface, 0);
        ShearBlock blk = block(1, {0}, {1.0f});
        blk.jend[0] = 2;
        blk.sun_dot[0] = 0.6f;
        ColorImage color;
        DepthImage z;
        color.resize(1, 2);
        z.resize(1, 2);
        // Row 1 (bottom-up) painted from slice 0; row 0 sky when jend = 1.
        resolve_shear_block(t, blk, 2, s.color.data(), s.slice.data(), color.pixels.data(), z.pixels.data(), 1, kernel);
        EXPECT_EQ(color.at(0, 0), unpack_rgb(expected));
        blk.jend[0] = 0;
        resolve_shear_block(t, blk, 2, s.color.data(), s.slice.data(), color.pixels.data(), z.pixels.data(), 1, kernel);
        EXPECT_EQ(color.at(0, 1), unpack_rgb(air.sky(0.0f, 0.6f)));
        EXPECT_EQ(z.at(0, 1), 1.0f);
    }
}

// Random blocks, full and partial: both kernels write the same bytes.
TEST(ShearResolve, KernelsAgreeBitForBit) {
    if (!resolve_kernel_available(ResolveKernel::Avx2)) GTEST_SKIP() << "no AVX2 on this CPU";
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const int H = 301, S = 500, W = 70;
    std::vector<float> rows(H), depth(S), d(S), d_lod(S);
    for (int j = 0; j < H; ++j) rows[std::size_t(j)] = -1.2f + 2.4f * float(j) / float(H);
    for (int k = 0; k < S; ++k) {
        d[std::size_t(k)] = 1.0f + 3.0f * float(k);
        depth[std::size_t(k)] = 1.0f - 1.0f / d[std::size_t(k)];
        // As the distance LOD places them: evenly spaced up to slice 200, twice as far apart beyond.
        d_lod[std::size_t(k)] = k < 200 ? d[std::size_t(k)] : 602.5f + 6.0f * float(k - 200);
    }
    Environment env;
    FogTable fog;
    fog.build(0.002f, d.back() * 2.0f);
    SkyTable sky;
    sky.build(env);
    // The view depths read from the table, computed (d[k] = 1 + 3 k in float),
    // and computed for the first 200 slices only.
    ShearResolveTables read{rows.data(), depth.data(), d.data(), &fog, 0x9AB0C8u, sky.entries()};
    read.slices = S;
    ShearResolveTables even = read;
    even.d_first = 1.0f;
    even.d_step = 3.0f;
    even.even = S;
    ShearResolveTables part = even;
    part.slice_d = d_lod.data();
    part.even = 200;
    // And with the aerial perspective instead of fog and sky gradient.
    env.atmosphere = true;
    env.sun_dir = {0.3f, 0.2f, -0.9f};
    AerialTables air;
    air.build(aerial_frame(env, 50.0), -300.0f, 400.0f);
    ShearResolveTables read_air = read, even_air = even, part_air = part;
    for (ShearResolveTables* t : {&read_air, &even_air, &part_air}) {
        t->air = &air;
        t->sun_y = 0.2f;
    }
    for (const ShearResolveTables& t : {read, even, part, read_air, even_air, part_air}) {
        for (int n : {kShearBlock, 7}) {
            std::vector<int> jend(kShearBlock, 0);
            std::vector<float> len2(kShearBlock, 1.0f);
            for (int i = 0; i < n; ++i) {
                jend[std::size_t(i)] = int(unit(rng) * float(H + 1)) % (H + 1);
                len2[std::size_t(i)] = 1.0f + unit(rng);
            }
            jend[0] = H; // a full column and an empty one
            jend[1] = 0;
            Scratch s(H);
            for (int j = 0; j < H; ++j)
                for (int i = 0; i < kShearBlock; ++i)
                    s.set(j, i, std::uint32_t(rng()) & 0xFFFFFFu, j < jend[std::size_t(i)] ? std::uint32_t(rng() % S) : rng());
            ColorImage c1, c2;
            DepthImage z1, z2;
            for (ColorImage* c : {&c1, &c2}) c->resize(W, H);
            for (DepthImage* z : {&z1, &z2}) z->resize(W, H);
            const Rgb8 untouched{7, 7, 7};
            for (ColorImage* c : {&c1, &c2}) std::fill(c->pixels.begin(), c->pixels.end(), untouched);
            for (DepthImage* z : {&z1, &z2}) std::fill(z->pixels.begin(), z->pixels.end(), -1.0f);
            ShearBlock blk = block(n, jend, len2);
            for (int i = 0; i < n; ++i) blk.sun_dot[i] = 2.0f * unit(rng) - 1.0f;
            resolve_shear_block(t, blk, H, s.color.data(), s.slice.data(), c1.pixels.data() + 3, z1.pixels.data() + 3,
                                std::size_t(W), ResolveKernel::Portable);
            for (ResolveKernel kernel : fast_kernels()) {
                for (Rgb8& p : c2.pixels) p = untouched;
                for (float& z : z2.pixels) z = -1.0f;
                resolve_shear_block(t, blk, H, s.color.data(), s.slice.data(), c2.pixels.data() + 3,
                                    z2.pixels.data() + 3, std::size_t(W), kernel);
                for (int r = 0; r < H; ++r) // nothing written beside the block's n columns
                    for (int c : {2, 3 + n}) {
                        ASSERT_EQ(c2.at(c, r), untouched) << "n " << n << " column " << c << " row " << r;
                        ASSERT_EQ(z2.at(c, r), -1.0f) << "n " << n << " column " << c << " row " << r;
                    }
                EXPECT_EQ(0, std::memcmp(c1.pixels.data(), c2.pixels.data(), c1.pixels.size() * sizeof(Rgb8)))
                    << "n " << n << " kernel " << int(kernel);
                EXPECT_EQ(0, std::memcmp(z1.pixels.data(), z2.pixels.data(), z1.pixels.size() * sizeof(float)))
                    << "n " << n << " kernel " << int(kernel);
            }
            long long terrain = 0;
            for (float v : z1.pixels) terrain += v >= 0.0f && v < 1.0f;
            EXPECT_GT(terrain, 0);
        }
    }
}

// As an image's blocks are (the random lanes above are not): neighbouring
// lanes see nearly the same sun angle, ray length and slice, so their table
// entries are adjacent, with jumps on some rows (Avx2Window reads them
// through its window, and its fallback at the jumps); the bits stay the
// portable kernel's with GL_EXP fog, read and computed view depths, and the
// aerial perspective, up to the tables' last entries (rows up to the zenith,
// columns of air past the last).
TEST(ShearResolve, KernelsAgreeOnSmoothLanes) {
    if (!resolve_kernel_available(ResolveKernel::Avx2)) GTEST_SKIP() << "no AVX2 on this CPU";
    const int H = 400, S = 3000, W = kShearBlock;
    std::vector<float> rows(H), depth(S), d(S), d_lod(S);
    for (int j = 0; j < H; ++j) rows[std::size_t(j)] = -0.6f + 40.0f * float(j * j) / float(H * H);
    for (int k = 0; k < S; ++k) {
        d[std::size_t(k)] = 1.0f + 8.0f * float(k);
        depth[std::size_t(k)] = 1.0f - 1.0f / d[std::size_t(k)];
        d_lod[std::size_t(k)] = k < 1000 ? d[std::size_t(k)] : 8005.0f + 16.0f * float(k - 1000);
    }
    Environment env;
    env.atmosphere = true;
    env.sun_dir = {0.6f, 0.1f, 0.8f};
    FogTable fog;
    fog.build(0.0004f, d.back() * 1.5f);
    SkyTable sky;
    sky.build(env);
    AerialTables air;
    air.build(aerial_frame(env, 50.0), -300.0f, 400.0f);
    ShearResolveTables fogged{rows.data(), depth.data(), d.data(), &fog, 0x9AB0C8u, sky.entries()};
    fogged.slices = S;
    ShearResolveTables even = fogged;
    even.d_first = 1.0f;
    even.d_step = 8.0f;
    even.even = S;
    ShearResolveTables part = even; // evenly spaced up to slice 1000 (the distance LOD)
    part.slice_d = d_lod.data();
    part.even = 1000;
    ShearResolveTables t = fogged;
    t.air = &air;
    t.sun_y = 0.1f;
    std::vector<int> jend(kShearBlock);
    std::vector<float> len2(kShearBlock);
    for (int i = 0; i < kShearBlock; ++i) {
        jend[std::size_t(i)] = 250 + i;
        const float a = -0.3f + 0.002f * float(i);
        len2[std::size_t(i)] = 1.0f + a * a;
    }
    ShearBlock blk = block(kShearBlock, jend, len2);
    for (int i = 0; i < kShearBlock; ++i) blk.sun_dot[i] = 0.8f - 0.6f * (-0.3f + 0.002f * float(i));
    Scratch s(H);
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < kShearBlock; ++i)
            s.set(j, i, std::uint32_t(0x406080 + 0x010203 * i),
                  std::uint32_t(std::clamp((S - 1) - 12 * j + i / 5 + (j % 7 == 0 ? 40 * (i % 3) : 0), 0, S - 1)));
    ColorImage c1, c2;
    DepthImage z1, z2;
    c1.resize(W, H);
    c2.resize(W, H);
    z1.resize(W, H);
    z2.resize(W, H);
    for (const ShearResolveTables* tables : {&fogged, &even, &part, &t}) {
        resolve_shear_block(*tables, blk, H, s.color.data(), s.slice.data(), c1.pixels.data(), z1.pixels.data(),
                            std::size_t(W), ResolveKernel::Portable);
        for (ResolveKernel kernel : fast_kernels()) {
            resolve_shear_block(*tables, blk, H, s.color.data(), s.slice.data(), c2.pixels.data(), z2.pixels.data(),
                                std::size_t(W), kernel);
            EXPECT_EQ(0, std::memcmp(c1.pixels.data(), c2.pixels.data(), c1.pixels.size() * sizeof(Rgb8)))
                << int(kernel) << (tables->air ? " air" : " fog");
            EXPECT_EQ(0, std::memcmp(z1.pixels.data(), z2.pixels.data(), z1.pixels.size() * sizeof(float)))
                << int(kernel) << (tables->air ? " air" : " fog");
        }
    }
}
