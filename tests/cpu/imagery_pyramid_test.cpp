// ImageryPyramid: levels worked out by hand, mip level of a known footprint,
// the fallback blend at the coverage's edge.
#include "core/ImageryFallback.h"
#include "core/ImageryPyramid.h"

#include <gtest/gtest.h>

using namespace overflight;

namespace {

Image2D<Rgba8> grey4x4(const int (&v)[16]) {
    Image2D<Rgba8> img(4, 4);
    for (int i = 0; i < 16; ++i) img.pixels[std::size_t(i)] = Rgba8{std::uint8_t(v[i]), std::uint8_t(v[i]), std::uint8_t(v[i]), 255};
    return img;
}

} // namespace

TEST(ImageryPyramid, FourByFourLevelsByHand) {
    // Rows top (north) to bottom.
    const int v[16] = {0, 4, 8, 12,     //
                       4, 8, 12, 16,    //
                       100, 100, 0, 2,  //
                       100, 101, 2, 4};
    const ImageryPyramid p(grey4x4(v), 0, 0, 8, 8);
    ASSERT_EQ(p.levels(), 3);
    ASSERT_EQ(p.level(1).width, 2);
    ASSERT_EQ(p.level(1).height, 2);
    // (0+4+4+8)/4 = 4; (8+12+12+16)/4 = 12; (100+100+100+101)/4 = 100.25 -> 100; (0+2+2+4)/4 = 2.
    EXPECT_EQ(p.level(1).at(0, 0).r, 4);
    EXPECT_EQ(p.level(1).at(1, 0).r, 12);
    EXPECT_EQ(p.level(1).at(0, 1).r, 100);
    EXPECT_EQ(p.level(1).at(1, 1).r, 2);
    // Level 2 from level 1: (4 + 12 + 100 + 2) / 4 = 29.5 -> 30 (rounded half up).
    ASSERT_EQ(p.level(2).width, 1);
    EXPECT_EQ(p.level(2).at(0, 0).r, 30);
    EXPECT_EQ(p.level(2).at(0, 0).a, 255);
    // Texels: 2 world units at level 0, 4 at level 1, 8 at level 2.
    EXPECT_DOUBLE_EQ(p.texel_size(0), 2.0);
    EXPECT_DOUBLE_EQ(p.texel_size(1), 4.0);
    EXPECT_DOUBLE_EQ(p.texel_size(2), 8.0);
    // World (5, 1) is texel (col 2, row 0) of level 0 and (col 1, row 0) of level 1.
    EXPECT_EQ(p.nearest(5, 1, 0).r, 8);
    EXPECT_EQ(p.nearest(5, 1, 1).r, 12);
    // Clamped outside.
    EXPECT_EQ(p.nearest(-3, 100, 0).r, 100);
    // Bilinear halfway between the centres of texels (0,0)=0 and (1,0)=4: 2.
    EXPECT_EQ(p.bilinear(2, 1, 0).r, 2);
}

TEST(ImageryPyramid, OddSideFoldsItsLastTexel) {
    Image2D<Rgba8> img(3, 1);
    img.pixels = {Rgba8{10, 0, 0, 255}, Rgba8{20, 0, 0, 255}, Rgba8{60, 0, 0, 0}};
    const ImageryPyramid p(img, 0, 0, 3, 1);
    ASSERT_EQ(p.levels(), 2);
    ASSERT_EQ(p.level(1).width, 1);
    EXPECT_EQ(p.level(1).at(0, 0).r, 30);  // (10 + 20 + 60) / 3
    EXPECT_EQ(p.level(1).at(0, 0).a, 170); // (255 + 255 + 0) / 3
    EXPECT_NEAR(p.coverage(), 2.0 / 3.0, 1e-12);
}

TEST(ImageryPyramid, MipLevelForAKnownFootprint) {
    // 28.5 m texels, 10 levels.
    EXPECT_EQ(mip_level_for_footprint(10.0, 28.5, 10), 0);   // finer than a texel
    EXPECT_EQ(mip_level_for_footprint(28.5, 28.5, 10), 0);   // log2 1 = 0
    EXPECT_EQ(mip_level_for_footprint(57.0, 28.5, 10), 1);   // log2 2 = 1
    EXPECT_EQ(mip_level_for_footprint(90.0, 28.5, 10), 2);   // log2 3.16 = 1.66 -> 2
    EXPECT_EQ(mip_level_for_footprint(228.0, 28.5, 10), 3);  // log2 8 = 3
    EXPECT_EQ(mip_level_for_footprint(1e9, 28.5, 10), 9);    // clamped to the last level
    EXPECT_EQ(mip_level_for_footprint(100.0, 28.5, 1), 0);   // a single level
    // A pixel at 1000 m with a focal length of 500 px covers 2 m: level 0 of 2 m texels, 1 of 1 m texels.
    EXPECT_EQ(mip_level_for_footprint(1000.0 / 500.0, 2.0, 5), 0);
    EXPECT_EQ(mip_level_for_footprint(1000.0 / 500.0, 1.0, 5), 1);
}

TEST(ImageryFallback, UncoveredTexelsTakeTheTerrainColorAndTheEdgeFades) {
    // A 3x3 terrain 2 units apart, all colored (0, 200, 0); imagery 6 texels
    // over [0, 6] x [0, 1]: the left three covered (red), the right three not.
    Terrain t(3, 3, 2.0f);
    for (Rgb8& c : t.colors()) c = Rgb8{0, 200, 0};
    Image2D<Rgba8> img(6, 1);
    for (int c = 0; c < 6; ++c) img.at(c, 0) = c < 3 ? Rgba8{250, 0, 0, 255} : Rgba8{0, 0, 0, 0};
    ImageryPyramid p(img, 0, 0, 6, 1);
    blend_over_terrain_colors(p, t, 1);
    // Texel 0: box of texels 0..1, mean alpha 255: imagery as is.
    EXPECT_EQ(p.level(0).at(0, 0), (Rgba8{250, 0, 0, 255}));
    // Texel 1: box 0..2 all covered: as is.
    EXPECT_EQ(p.level(0).at(1, 0), (Rgba8{250, 0, 0, 255}));
    // Texel 2: box 1..3, mean alpha 170, w = 2/3: 250 x 2/3 = 166.7 -> 167, 200 / 3 = 66.7 -> 67.
    EXPECT_EQ(p.level(0).at(2, 0), (Rgba8{167, 67, 0, 255}));
    // Texels 3..5: the terrain's color, alpha kept at 0.
    for (int c = 3; c < 6; ++c) EXPECT_EQ(p.level(0).at(c, 0), (Rgba8{0, 200, 0, 0}));
}

TEST(ImageryFallback, TerrainColorsFromTheImageryLevelOfACell) {
    // 2x2 terrain 4 units apart over a 4x4 texel image of 2 units: level 1 (4-unit texels) is sampled.
    Terrain t(2, 2, 4.0f);
    const int v[16] = {0, 0, 80, 80, 0, 0, 80, 80, 40, 40, 120, 120, 40, 40, 120, 120};
    const ImageryPyramid p(grey4x4(v), -2, -2, 8, 8);
    colors_from_imagery(p, t);
    EXPECT_EQ(t.color(0, 0).r, 0);
    EXPECT_EQ(t.color(0, 1).r, 80);
    EXPECT_EQ(t.color(1, 0).r, 40);
    EXPECT_EQ(t.color(1, 1).r, 120);
}
