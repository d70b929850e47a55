// The water surface (core/WaterSurface.h) at values worked out by hand, and
// the ray casters' water pass (raycast/WaterPass.h) reflecting a single
// column of a literal height field.
#include "core/WaterSurface.h"
#include "raycast/RayMarcher.h"
#include "raycast/WaterPass.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>

using namespace overflight;

TEST(WaterSurface, FresnelAtNormalAndGrazingIncidence) {
    EXPECT_FLOAT_EQ(water_fresnel(1.0f), 0.02f);                 // straight down: F0
    EXPECT_FLOAT_EQ(water_fresnel(0.0f), 1.0f);                  // grazing: a mirror
    EXPECT_FLOAT_EQ(water_fresnel(0.5f), 0.02f + 0.98f / 32.0f); // 60 degrees: (1 - 0.5)^5 = 1/32
    EXPECT_FLOAT_EQ(water_fresnel(-0.3f), 1.0f);                 // clamped
}

TEST(WaterSurface, WavesAreSmallAndDeterministic) {
    const glm::vec3 n = water_normal(12.5f, -3.0f, 7.25, 10.0f);
    EXPECT_EQ(n, water_normal(12.5f, -3.0f, 7.25, 10.0f));
    EXPECT_NEAR(glm::length(n), 1.0f, 1e-6f);
    EXPECT_GT(n.y, 0.998f); // slopes sum to at most 0.06: cos(atan 0.06) = 0.9982
    EXPECT_NE(n, water_normal(12.5f, -3.0f, 8.25, 10.0f)); // the waves move
}

TEST(WaterSurface, ReflectionStaysAboveTheWater) {
    const glm::vec3 r = water_reflect(glm::normalize(glm::vec3(0, -1, 1)), glm::vec3(0, 1, 0));
    EXPECT_NEAR(r.x, 0.0f, 1e-6f);
    EXPECT_NEAR(r.y, std::sqrt(0.5f), 1e-6f);
    EXPECT_NEAR(r.z, std::sqrt(0.5f), 1e-6f);
    EXPECT_GT(water_reflect(glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)).y, 0.0f); // grazing: lifted
}

TEST(WaterSurface, ShallowsShowTheBottomDeepWaterItsOwnColor) {
    Environment env;
    env.ambient = {1, 1, 1};
    env.sun_color = {0, 0, 0};
    WaterSample s;
    s.view = {0, -1, 0}; // straight down: F = 0.02
    s.reflected = {0, 0, 0};
    EXPECT_FLOAT_EQ(water_path(2.0f, glm::normalize(glm::vec3(1, -1, 0))), 2.0f * std::sqrt(2.0f));
    s.path = 0.0f;
    WaterLight w = water_light(env, s);
    EXPECT_NEAR(w.behind.r, 0.98f, 1e-6f); // the bottom, less what is reflected
    EXPECT_NEAR(w.surface.r, 0.0f, 1e-6f);
    s.path = 10.0f; // red: exp(-3) of the bottom left, the deep color for the rest
    w = water_light(env, s);
    const float t = std::exp(-3.0f);
    EXPECT_NEAR(w.behind.r, 0.98f * t, 1e-6f);
    EXPECT_NEAR(w.surface.r * (1 - w.behind.r), 0.98f * kWaterDeep[0] * (1 - t), 1e-6f);
    s.path = 1e6f; // deep
    w = water_light(env, s);
    EXPECT_NEAR(w.behind.b, 0.0f, 1e-6f);
    EXPECT_NEAR(w.surface.b, 0.98f * kWaterDeep[2], 1e-6f);
}

TEST(WaterSurface, LevelOutsideTheTerrainIsAOneLineProblem) {
    Terrain t(3, 3, 1.0f, 1.0f, -2.0f); // heights -2 .. 8
    t.raw(1, 1) = 10;
    EXPECT_EQ(water_level_problem(t, 3.0), "");
    EXPECT_EQ(water_level_problem(t, 9.0), "9 is outside the terrain's heights -2..8");
    EXPECT_EQ(water_level_problem(t, -2.5), "-2.5 is outside the terrain's heights -2..8");
    EXPECT_EQ(water_level_problem(t, std::nan("")), "the level must be a finite number");
    Environment env;
    EXPECT_EQ(default_water_level(t, env), 0.0); // 0 within -2..8
    env.sea_level = 4.0f;
    EXPECT_EQ(default_water_level(t, env), 4.0); // the map's key
    Terrain high(3, 3, 1.0f, 0.5f, 100.0f);      // 100 .. 100: no 0, the lowest + one step
    EXPECT_EQ(default_water_level(high, Environment{}), 100.5);
}

namespace {

// 5 columns x 41 rows one unit apart, flat at 0 (green); with `column`, the
// sample at row 40, column 2 is 10 high and red.
Terrain strip(bool column) {
    Terrain t(41, 5, 1.0f);
    for (Rgb8& c : t.colors()) c = {0, 200, 0};
    if (column) {
        t.raw(40, 2) = 10;
        t.color(40, 2) = {255, 0, 0};
    }
    return t;
}

// The eye 3 up at z = 0.5 looking south along column 2, water at 1: the
// ray of image row v (v = H/2 - row - 0.5, fp pixels of focal length, pitch
// 0) meets the water at view depth 2 fp / -v; mirrored, it climbs at slope
// -v / fp from there and meets the column's front (z = 39.5) below its top
// (10) for -v < 11 fp / 39 (the mirror image of the top, seen from the eye).
struct StripView {
    Camera camera;
    Environment env;
    StripView() {
        camera.eye = {2.0, 3.0, 0.5};
        camera.heading = 0.0;
        camera.fov = 10.0;
        camera.width = 9;
        camera.height = 200;
        camera.near = 0.1;
        camera.far = 200.0;
        env.water = true;
        env.water_level = 1.0f;
    }
    void render(const Terrain& t, ColorImage& color, DepthImage& depth) const {
        RayMarcher(t, env).render(camera, SurfaceModel::Blocks, color, depth);
        WaterPass(t).apply(camera, env, SurfaceModel::Blocks, color, depth);
    }
};

} // namespace

TEST(WaterPass, ReflectsASingleColumn) {
    const StripView scene;
    const Terrain with = strip(true), without = strip(false);
    ColorImage c1, c0;
    DepthImage d1, d0;
    scene.render(with, c1, d1);
    scene.render(without, c0, d0);
    const double fp = scene.camera.focal_px(); // 4.5 / tan 5 deg = 51.4
    const double top = 11.0 * fp / 39.0;       // -v of the reflected top: 14.5
    // The waves turn the normal by a slope of at most 0.06, the mirrored ray
    // by twice that: rows within 0.13 fp of the top may go either way.
    const double margin = 0.13 * fp;
    int reflected = 0;
    for (int row = 101; row < 200; ++row) {
        const double v = scene.camera.v_of(row);
        const double d = 2.0 * fp / -v; // view depth of the water
        if (d > 38.0) continue;          // near the column's foot
        // Depth: the plane's, exactly, with or without the column.
        EXPECT_NEAR(d0.at(4, row), scene.camera.window_depth(d), 1e-6) << row;
        EXPECT_EQ(d1.at(4, row), d0.at(4, row)) << row;
        const Rgb8 a = c1.at(4, row), b = c0.at(4, row);
        if (-v < top - margin) { // the mirrored ray meets the column: red for the sky's blue, F >= 0.3 here
            EXPECT_GT(int(a.r), int(b.r)) << row;
            EXPECT_GT(int(b.b) - int(a.b), 40) << row;
            ++reflected;
        } else if (-v > top + margin) { // over the column: the sky, as without it
            EXPECT_EQ(a.r, b.r) << row;
            EXPECT_EQ(a.g, b.g) << row;
            EXPECT_EQ(a.b, b.b) << row;
        }
    }
    EXPECT_GE(reflected, 3);
}

// Without water the image stays as it was; with the eye below the level
// everything is seen through the water (gl_water_test checks it per pixel).
TEST(WaterPass, DryWithoutWaterDimmedWithTheEyeBelowIt) {
    StripView scene;
    const Terrain t = strip(true);
    ColorImage c;
    DepthImage d;
    RayMarcher(t, scene.env).render(scene.camera, SurfaceModel::Blocks, c, d);
    const ColorImage c0 = c;
    scene.env.water = false;
    EXPECT_EQ(WaterPass(t).apply(scene.camera, scene.env, SurfaceModel::Blocks, c, d), 0);
    EXPECT_TRUE(c.pixels == c0.pixels);
    scene.env.water = true;
    scene.env.water_level = 5.0f; // above the eye
    WaterPass(t).apply(scene.camera, scene.env, SurfaceModel::Blocks, c, d);
    EXPECT_FALSE(c.pixels == c0.pixels);
}
