// The reference ray marcher on a 9x9 height field whose depth image is worked
// out by hand: a block's front face, flat ground, and sky.
#include "core/Camera.h"
#include "core/DataSet.h"
#include "core/Terrain.h"
#include "raycast/RayMarcher.h"

#include <gtest/gtest.h>

using namespace overflight;

namespace {

// Flat ground at 0 with one wall of blocks, height 5, at row 3, cols 3..5
// (cells X in [2.5, 5.5], Z in [2.5, 3.5]).
Terrain wall_terrain() {
    Terrain t(9, 9, 1.0f);
    for (int j = 3; j <= 5; ++j) {
        t.raw(3, j) = 5;
        t.color(3, j) = Rgb8{200, 0, std::uint8_t(j)};
    }
    return t;
}

// Eye (4, 1, 0) facing south (F = +Z, R = -X), 4x4 pixels, fov 90 (fp = 2), near 0.5, far 10.
// Columns: a = u/fp = -0.75, -0.25, 0.25, 0.75 -> X = 4 - a d. Rows: slope v/fp = 0.75, 0.25, -0.25, -0.75.
// Columns 1, 2 reach Z = 2.5 at X = 4.625, 3.375 (inside the wall): rows 0-2 (heights 2.875, 1.625, 0.375)
// hit its front face at d = 2.5; row 3 meets the ground (y = 1 - 0.75 d = 0) at d = 4/3.
// Columns 0, 3 pass beside the wall (X = 5.875..6.625, 1.375..2.125): rows 0, 1 rise to the sky, row 2
// meets the ground at d = 4, row 3 at d = 4/3.
// Window depth (f - f n / d)/(f - n): d = 2.5 -> 8/9.5, 4/3 -> 6.25/9.5, 4 -> 8.75/9.5.
Camera wall_camera() {
    Camera c;
    c.eye = {4, 1, 0};
    c.heading = 0;
    c.pitch = 0;
    c.fov = 90;
    c.width = 4;
    c.height = 4;
    c.near = 0.5;
    c.far = 10;
    return c;
}

} // namespace

TEST(RayMarcher, HandWorkedWallBlocks) {
    const Terrain t = wall_terrain();
    const Environment env;
    RayMarcher rm(t, env);
    ColorImage color;
    DepthImage depth;
    rm.render(wall_camera(), SurfaceModel::Blocks, color, depth);
    const float wall = 8.0f / 9.5f, near_ground = 6.25f / 9.5f, far_ground = 8.75f / 9.5f;
    for (int c : {1, 2}) {
        for (int r = 0; r < 3; ++r) EXPECT_NEAR(depth.at(c, r), wall, 1e-6) << c << "," << r;
        EXPECT_NEAR(depth.at(c, 3), near_ground, 1e-6) << c;
    }
    EXPECT_EQ(color.at(1, 1), (Rgb8{200, 0, 5})); // X = 4.625 -> sample column 5
    EXPECT_EQ(color.at(2, 1), (Rgb8{200, 0, 3})); // X = 3.375 -> sample column 3
    for (int c : {0, 3}) {
        EXPECT_EQ(depth.at(c, 0), 1.0f) << c;
        EXPECT_EQ(depth.at(c, 1), 1.0f) << c;
        EXPECT_NEAR(depth.at(c, 2), far_ground, 1e-6) << c;
        EXPECT_NEAR(depth.at(c, 3), near_ground, 1e-6) << c;
    }
}

TEST(RayMarcher, TiltedCameraSeesTheSameWallPoint) {
    // A point on the wall seen by a tilted camera projects to where the marcher finds it.
    const Terrain t = wall_terrain();
    const Environment env;
    RayMarcher rm(t, env);
    Camera cam = wall_camera();
    cam.projection = Projection::Tilt;
    cam.pitch = 10;
    cam.width = 64;
    cam.height = 64;
    const RayMarcher::Frame f = rm.frame(cam);
    const Camera::Projected p = cam.project({4.0, 2.0, 2.5}); // on the wall's front face
    Rgb8 color;
    float depth;
    rm.shade_pixel(cam, f, SurfaceModel::Blocks, int(p.col), int(p.row), color, depth);
    EXPECT_NEAR(cam.view_depth_of_window(depth), cam.view_depth_of_window(p.depth), 0.1);
}

TEST(RayMarcher, BilinearFlatGround) {
    Terrain t(9, 9, 1.0f);
    for (auto& h : t.heights()) h = 2;
    const Environment env;
    RayMarcher rm(t, env);
    Camera cam = wall_camera();
    cam.eye.y = 3; // one unit above the ground: row 3 meets it at d = 4/3, row 2 at d = 4
    ColorImage color;
    DepthImage depth;
    rm.render(cam, SurfaceModel::Bilinear, color, depth);
    EXPECT_NEAR(depth.at(1, 3), 6.25f / 9.5f, 1e-5);
    EXPECT_NEAR(depth.at(1, 2), 8.75f / 9.5f, 1e-5);
    EXPECT_EQ(depth.at(1, 0), 1.0f);
}
