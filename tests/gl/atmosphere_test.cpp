// The atmosphere (core/AerialPerspective.h) as the GL programs draw it: the
// shaders' sky and aerial perspective against the C++ model on a flat
// terrain, and the ray caster (tables) against the mesh (shaders) on the
// same cameras over the demo island.
#include "TestCameras.h"
#include "core/AerialPerspective.h"
#include "core/DemoIsland.h"
#include "gl/HeadlessRenderer.h"
#include "methods/TerrainMethod.h"
#include "raycast/Atmosphere.h"
#include "raycast/FloatingHorizon.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

using namespace overflight;

namespace {

// Lighting that leaves the albedo as it is (no sun, ambient 1), so that the
// colors compared are the atmosphere's alone.
void unlit(Environment& env) {
    env.sun_color = {0, 0, 0};
    env.ambient = {1, 1, 1};
}

int channel_difference(Rgb8 a, Rgb8 b) {
    return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
}

double mean_channel_difference(Rgb8 a, Rgb8 b) {
    return (std::abs(a.r - b.r) + std::abs(a.g - b.g) + std::abs(a.b - b.b)) / 3.0;
}

} // namespace

// A flat grey 5x5 terrain 100 units below a level eye: a sky pixel is
// aerial_sky() of its pixel-centre ray and a terrain pixel
// aerial_perspective() of its hit point, within 1.5 color levels (float
// shaders against double C++).
TEST(Atmosphere, ShadersFollowTheModel) {
    DataSet data;
    data.terrain = Terrain(5, 5, 2000.0f);
    for (auto& h : data.terrain.heights()) h = 100;
    for (auto& c : data.terrain.colors()) c = {100, 100, 100};
    Environment& env = data.environment;
    unlit(env);
    env.atmosphere = true;
    env.sun_dir = {0.2f, 0.3f, 1.0f};
    gl::HeadlessRenderer renderer(data.terrain, Scene{});
    const Camera cam = test::camera_at({4000.0, 200.0, -10.0}, 0.0, 0.0, 20000.0, 64, 48);
    ColorImage color;
    DepthImage depth;
    renderer.render(MethodOutput::resident(ResidentSurface::Mesh), cam, env, {}, color, &depth);
    const AerialFrame f = aerial_frame(env, cam.eye.y);
    int sky = 0, terrain = 0;
    for (int row = 0; row < cam.height; row += 5)
        for (int col = 0; col < cam.width; col += 7) {
            const glm::dvec3 dir = cam.ray(cam.u_of(col), cam.v_of(row));
            Rgb8 expected;
            if (depth.at(col, row) == 1.0f) {
                expected = aerial_sky_rgb(f, dir);
                ++sky;
            } else {
                ASSERT_LT(dir.y, 0.0);
                const double t = (100.0 - cam.eye.y) / dir.y; // the plane y = 100
                expected = aerial_rgb(f, {100, 100, 100}, t * dir);
                ++terrain;
            }
            EXPECT_LE(channel_difference(color.at(col, row), expected), 1) << col << "," << row;
        }
    EXPECT_GT(sky, 10);
    EXPECT_GT(terrain, 10);
}

// Voxel (AerialTables, nearest sample) and mesh (shaders, interpolated
// colors) on the same cameras over a 20 km island, sun low in the south-east.
// Where both see terrain, the mean color difference (of 255, per channel) is
// at most 5 levels with the atmosphere and exceeds the one without it by at
// most half a level (what the two surfaces differ by is the mesh's
// interpolation, not the atmosphere: measured 2.5-3.5 without, +0.04-0.15
// with); where both see sky, they differ by at most 2 levels (tables against
// float shaders).
TEST(Atmosphere, VoxelAndMeshAgree) {
    DataSet data = make_demo_island({.size = 257, .h_scale = 80.0f});
    unlit(data.environment);
    data.environment.sun_dir = {0.6f, 0.25f, 0.7f};
    gl::HeadlessRenderer renderer(data.terrain, Scene{});
    FloatingHorizon caster(data.terrain);
    for (double heading : {0.0, 135.0, 250.0}) {
        const Camera cam = test::across_terrain(data.terrain, heading, -4.0, Projection::Shear);
        double mean[2] = {0, 0};
        int worst_sky = 0;
        for (int air = 0; air < 2; ++air) {
            Environment env = data.environment;
            env.atmosphere = air == 1;
            ColorImage voxel, mesh;
            DepthImage voxel_depth, mesh_depth;
            caster.render(cam, env, RaycastOptions{}, voxel, voxel_depth);
            renderer.render(MethodOutput::resident(ResidentSurface::Mesh), cam, env, {}, mesh, &mesh_depth);
            long long n = 0;
            double sum = 0;
            for (int row = 0; row < cam.height; ++row)
                for (int col = 0; col < cam.width; ++col) {
                    const bool vs = voxel_depth.at(col, row) == 1.0f, ms = mesh_depth.at(col, row) == 1.0f;
                    if (!vs && !ms) {
                        sum += mean_channel_difference(voxel.at(col, row), mesh.at(col, row));
                        ++n;
                    } else if (vs && ms && air) {
                        worst_sky = std::max(worst_sky, channel_difference(voxel.at(col, row), mesh.at(col, row)));
                    }
                }
            ASSERT_GT(n, cam.width * cam.height / 10) << heading;
            mean[air] = sum / double(n);
        }
        std::printf("heading %g: mean terrain difference %.2f without, %.2f with the atmosphere; sky %d\n", heading,
                    mean[0], mean[1], worst_sky);
        EXPECT_LE(mean[1], 5.0) << heading;
        EXPECT_LE(mean[1], mean[0] + 0.5) << heading;
        EXPECT_LE(worst_sky, 2) << heading;
    }
}
