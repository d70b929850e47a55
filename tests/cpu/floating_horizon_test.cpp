// Floating Horizon on a 5x5 height field whose image is worked out by hand
// (Szenberg, Gattass, Carvalho, "An Algorithm for the Visualization of a
// Terrain with Objects", SIBGRAPI 1997: Algorithm 1 with the sec. 5.2
// slices), for the fast caster
// and the literal transcription; plus the per-frame properties of the fast one.
#include "core/Camera.h"
#include "core/DataSet.h"
#include "core/Error.h"
#include "core/Terrain.h"
#include "raycast/Atmosphere.h"
#include "raycast/FloatingHorizon.h"
#include "raycast/FloatingHorizonLiteral.h"

#include "TestCameras.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace overflight;

namespace {

// Rows i (Z, south) top to bottom, columns j (X, east); h_scale 1, v_scale 1.
Terrain hand_terrain() {
    const int H[5][5] = {
        {0, 0, 0, 0, 0},
        {0, 0, 1, 0, 0},
        {0, 0, 0, 2, 0},
        {0, 0, 0, 2, 0},
        {0, 1, 0, 6, 0},
    };
    Terrain t(5, 5, 1.0f);
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j) {
            t.raw(i, j) = std::uint16_t(H[i][j]);
            t.color(i, j) = Rgb8{std::uint8_t(10 * i), std::uint8_t(10 * j), 100};
        }
    return t;
}

// Eye (2.1, 2.2, 0) facing south (F = +Z, R = -X), 2x4 pixels, fp = 2
// (fov = 2 atan(1/2)), near 1, far 5: slices at Z = 1, 2, 3, 4 (5 is off the map).
// Column 0 (u = -0.5): a = -0.25, X = 2.1 + 0.25 d -> samples (1,2) (2,3) (3,3) (4,3).
// Column 1 (u = +0.5): a = +0.25, X = 2.1 - 0.25 d -> samples (1,2) (2,2) (3,1) (4,1).
// Row slopes bottom-up m = -0.75, -0.25, 0.25, 0.75; sigma = (h - 2.2) / d.
//   col 0: (2,3) sigma -0.1 paints j = 0,1; (3,3) -0.067 < 0.25; (4,3) 0.95 paints j = 2,3.
//   col 1: (3,1) sigma -0.733 > -0.75 paints j = 0; (4,1) -0.3 < -0.25; the rest is sky.
// Window depth (f - f n / d) / (f - n): d = 2 -> 0.625, 3 -> 0.8333, 4 -> 0.9375.
Camera hand_camera() { return test::two_by_four({2.1, 2.2, 0.0}); }

void expect_hand_image(const ColorImage& color, const DepthImage& depth) {
    const Rgb8 c43{40, 30, 100}, c23{20, 30, 100}, c31{30, 10, 100};
    // column 0, rows top to bottom
    EXPECT_EQ(color.at(0, 0), c43);
    EXPECT_EQ(color.at(0, 1), c43);
    EXPECT_EQ(color.at(0, 2), c23);
    EXPECT_EQ(color.at(0, 3), c23);
    EXPECT_FLOAT_EQ(depth.at(0, 0), 0.9375f);
    EXPECT_FLOAT_EQ(depth.at(0, 1), 0.9375f);
    EXPECT_FLOAT_EQ(depth.at(0, 2), 0.625f);
    EXPECT_FLOAT_EQ(depth.at(0, 3), 0.625f);
    // column 1
    EXPECT_EQ(color.at(1, 3), c31);
    EXPECT_NEAR(depth.at(1, 3), 5.0 / 6.0, 1e-6);
    for (int r = 0; r < 3; ++r) EXPECT_EQ(depth.at(1, r), 1.0f) << "row " << r << " is sky";
}

} // namespace

TEST(FloatingHorizon, HandWorkedFiveByFive) {
    const Terrain t = hand_terrain();
    const Environment env;
    FloatingHorizon fh(t);
    ColorImage color;
    DepthImage depth;
    RaycastStats stats;
    fh.render(hand_camera(), env, {}, color, depth, &stats);
    expect_hand_image(color, depth);
    EXPECT_EQ(stats.columns, 2);
    EXPECT_EQ(stats.slices, 5);
    EXPECT_EQ(stats.samples, 10);
    EXPECT_EQ(stats.pixels_painted, 5);
}

TEST(FloatingHorizonLiteral, HandWorkedFiveByFive) {
    const Terrain t = hand_terrain();
    const Environment env;
    ColorImage color;
    DepthImage depth;
    render_floating_horizon_literal(t, env, hand_camera(), SurfaceModel::Blocks, color, depth);
    expect_hand_image(color, depth);
}

TEST(FloatingHorizon, SkyPixelsGetTheSkyGradient) {
    const Terrain t = hand_terrain();
    Environment env;
    env.sky_horizon = {1, 0, 0};
    env.sky_zenith = {0, 0, 1};
    FloatingHorizon fh(t);
    ColorImage color;
    DepthImage depth;
    Camera cam = hand_camera();
    fh.render(cam, env, {}, color, depth);
    // Column 1, top row: ray (0.25, 0.75, 1) in (R, Y, F); sin(elevation) = 0.75 / sqrt(1.625) = 0.588.
    const Rgb8 expect = sky_color(env, glm::dvec3(0.25, 0.75, 1.0));
    EXPECT_NEAR(color.at(1, 0).r, expect.r, 1);
    EXPECT_NEAR(color.at(1, 0).b, expect.b, 1);
    EXPECT_GT(color.at(1, 0).b, color.at(1, 1).b); // bluer higher up
}

TEST(FloatingHorizon, FogUsesTheEyeDistance) {
    Terrain t(5, 5, 1.0f);
    for (auto& c : t.colors()) c = Rgb8{200, 200, 200};
    Environment env;
    env.fog_density = 0.2f;
    env.fog_color = {0, 0, 0};
    FloatingHorizon fh(t);
    Camera cam = hand_camera();
    cam.eye.y = 0.5; // bottom row: slope -0.75 -> hits the flat ground at the first slice below the eye
    ColorImage color;
    DepthImage depth;
    fh.render(cam, env, {}, color, depth);
    // Bottom row, column 0: painted at slice d = 1 (0 > 0.5 - 0.75): ray (-0.25, -0.75, 1) per unit depth,
    // eye distance sqrt(1 + 0.0625 + 0.5625) = 1.2748, factor exp(-0.255) = 0.775, 200 * 0.775 = 155.
    EXPECT_NEAR(color.at(0, 3).r, 155, 1);
    EXPECT_FLOAT_EQ(depth.at(0, 3), 0.0f);
}

TEST(FloatingHorizon, BadCameraThrows) {
    const Terrain t = hand_terrain();
    const Environment env;
    FloatingHorizon fh(t);
    ColorImage color;
    DepthImage depth;
    Camera cam = hand_camera();
    cam.far = 0.5;
    EXPECT_THROW(fh.render(cam, env, {}, color, depth), Error);
    cam = hand_camera();
    cam.projection = Projection::Tilt;
    EXPECT_THROW(render_floating_horizon_literal(t, env, cam, SurfaceModel::Blocks, color, depth), Error);
}

TEST(FloatingHorizon, EyeOutsideTheMapLookingAtItSeesIt) {
    Terrain t(9, 9, 10.0f);
    for (auto& h : t.heights()) h = 50;
    const Environment env;
    FloatingHorizon fh(t);
    Camera cam;
    cam.eye = {40, 100, -200}; // north of the map, facing south
    cam.width = 40;
    cam.height = 30;
    cam.pitch = -20;
    cam.near = 1;
    cam.far = 1000;
    ColorImage color;
    DepthImage depth;
    RaycastStats stats;
    fh.render(cam, env, {}, color, depth, &stats);
    EXPECT_GT(stats.pixels_painted, 0);
    EXPECT_LT(stats.samples_visited, stats.samples); // slices off the map are clipped, not visited
    // The bottom row looks at the (empty) ground north of the map and passes under
    // the map's edge: blocks are solid down to the floor, so it sees the edge wall,
    // in the first slice on the map: slices are h_scale = 10 apart from near = 1,
    // the map starts at Z = 0 (d = 200), so d = 201.
    EXPECT_FLOAT_EQ(depth.at(20, 29), float(cam.window_depth(201.0)));
    // The top row looks above the plateau (slope > (50 - 100) / d for every d): sky.
    EXPECT_EQ(depth.at(20, 0), 1.0f);
}

TEST(FloatingHorizon, ReusesBuffersAcrossFrames) {
    const Terrain t = hand_terrain();
    const Environment env;
    FloatingHorizon fh(t);
    ColorImage color;
    DepthImage depth;
    fh.render(hand_camera(), env, {}, color, depth);
    const Rgb8* c0 = color.pixels.data();
    const float* d0 = depth.pixels.data();
    fh.render(hand_camera(), env, {}, color, depth);
    EXPECT_EQ(c0, color.pixels.data());
    EXPECT_EQ(d0, depth.pixels.data());
    expect_hand_image(color, depth);
}
