// The classic Voxel Space loop kept as the benchmarks' yardstick
// (raycast/ClassicVoxelSpace.h): on the hand-worked 5x5 terrain of the
// Floating Horizon's tests it paints the same pixels (Szenberg, Gattass,
// Carvalho, SIBGRAPI 1997, Algorithm 1 on the same slices), and on the demo
// island its skyline matches the exact caster's when it steps one sample.
#include "core/Camera.h"
#include "core/DataSet.h"
#include "core/DemoIsland.h"
#include "core/Error.h"
#include "core/Terrain.h"
#include "raycast/ClassicVoxelSpace.h"
#include "raycast/FloatingHorizon.h"

#include "TestCameras.h"

#include <gtest/gtest.h>

using namespace overflight;

namespace {

Terrain hand_terrain() {
    const int H[5][5] = {
        {0, 0, 0, 0, 0}, {0, 0, 1, 0, 0}, {0, 0, 0, 2, 0}, {0, 0, 0, 2, 0}, {0, 1, 0, 6, 0},
    };
    Terrain t(5, 5, 1.0f);
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j) {
            t.raw(i, j) = std::uint16_t(H[i][j]);
            t.color(i, j) = Rgb8{std::uint8_t(10 * i), std::uint8_t(10 * j), 100};
        }
    return t;
}

constexpr Rgb8 kSky{255, 0, 255};

} // namespace

// Eye (2.1, 2.2, 0) facing south, 2x4 pixels, fp = 2, lines at Z = 1..5.
// Column 0 takes samples (1,2) (2,3) (3,3) (4,3): (2,3) at height 2 has its
// top at row 2 - (2 - 2.2) * 2 / 2 = 2.2 and paints rows 2, 3; (4,3) at 6 has
// its top at 2 - 3.8 * 2 / 4 = 0.1 and paints rows 0, 1. Column 1 takes
// (3,1) at 0 (top 3.47: row 3) and nothing else rises above it.
TEST(ClassicVoxelSpace, HandWorkedFiveByFive) {
    ColorImage color;
    ClassicVoxelSpaceOptions options;
    options.sky = kSky;
    const ClassicVoxelSpaceStats stats =
        render_classic_voxel_space(hand_terrain(), test::two_by_four({2.1, 2.2, 0.0}), options, color);
    const Rgb8 c43{40, 30, 100}, c23{20, 30, 100}, c31{30, 10, 100};
    EXPECT_EQ(color.at(0, 0), c43);
    EXPECT_EQ(color.at(0, 1), c43);
    EXPECT_EQ(color.at(0, 2), c23);
    EXPECT_EQ(color.at(0, 3), c23);
    for (int r = 0; r < 3; ++r) EXPECT_EQ(color.at(1, r), kSky) << "row " << r;
    EXPECT_EQ(color.at(1, 3), c31);
    EXPECT_EQ(stats.lines, 5); // the Floating Horizon's slices d = 1..5
    EXPECT_EQ(stats.samples, 10u);
}

TEST(ClassicVoxelSpace, GrowingStepTakesFewerLines) {
    const Camera cam = test::camera_at({100, 50, 0}, 0, 0, 2000, 64, 32);
    Terrain t(9, 9, 1.0f);
    ColorImage color;
    ClassicVoxelSpaceOptions options;
    EXPECT_EQ(render_classic_voxel_space(t, cam, options, color).lines, 2000);
    options.step_growth = 1.01;
    const ClassicVoxelSpaceStats grown = render_classic_voxel_space(t, cam, options, color);
    // line k is at 1 + (1.01^k - 1) / 0.01 <= 2000 for k <= ln(20.99) / ln(1.01) = 305.9
    EXPECT_EQ(grown.lines, 306);
    EXPECT_EQ(grown.samples, 306u * 64u);
}

TEST(ClassicVoxelSpace, RejectsTiltCamerasAndSteps) {
    Terrain t(5, 5, 1.0f);
    ColorImage color;
    EXPECT_THROW(render_classic_voxel_space(t, test::two_by_four({2, 2, 0}, 10.0, Projection::Tilt), {}, color), Error);
    ClassicVoxelSpaceOptions shrinking;
    shrinking.step_growth = 0.9;
    EXPECT_THROW(render_classic_voxel_space(t, test::two_by_four({2, 2, 0}), shrinking, color), Error);
    ClassicVoxelSpaceOptions zero;
    zero.first_step = 0.0;
    EXPECT_THROW(render_classic_voxel_space(t, test::two_by_four({2, 2, 0}), zero, color), Error);
}

// Same slices, same nearest sample, same projection of a sample's top: the
// classic loop's sky/terrain split is the exact caster's, column by column,
// but for pixels whose centre lies within rounding of a sample's top.
TEST(ClassicVoxelSpace, SkylineMatchesTheFloatingHorizonAtOneSampleSteps) {
    DemoOptions demo;
    demo.size = 257;
    const DataSet data = make_demo_island(demo);
    const Terrain& t = data.terrain;
    Camera cam = test::across_terrain(t, 30.0, -5.0, Projection::Shear);
    cam.near = t.h_scale();
    ColorImage classic, exact;
    DepthImage depth;
    ClassicVoxelSpaceOptions options;
    options.sky = kSky;
    render_classic_voxel_space(t, cam, options, classic);
    FloatingHorizon fh(t);
    fh.render(cam, data.environment, {}, exact, depth);
    int agree = 0, terrain_pixels = 0;
    for (int r = 0; r < cam.height; ++r)
        for (int c = 0; c < cam.width; ++c) {
            const bool sky_classic = classic.at(c, r) == kSky, sky_exact = depth.at(c, r) == 1.0f;
            agree += sky_classic == sky_exact;
            terrain_pixels += !sky_exact;
        }
    EXPECT_GT(terrain_pixels, cam.width * cam.height / 4);
    EXPECT_GE(double(agree) / double(cam.width * cam.height), 0.995);
}
