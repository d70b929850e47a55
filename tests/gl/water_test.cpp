// Water (core/WaterSurface.h) in a ray caster and a GL method on the same
// camera: `voxel` floods its image per pixel (raycast/WaterPass.h), `mesh`
// draws the plane in GL (gl/WaterPlane.h). The water pixels, found by depth
// (the pixel's view depth is the plane's along its ray), overlap with
// IoU >= 0.95; their colors agree within a mean of 10 levels per channel
// (the GL march of the mirrored ray is coarser than the ray caster's exact
// one); and both images match their golden images (at most 1 % of the
// pixels more than 6 levels off). Under the water both show the surface from
// below at the plane's depth and dim the terrain by the water's extinction,
// as core/WaterSurface.h works them out per pixel; a terrain wider than the
// GL's largest texture still gets its water (decimated heights).
#include "GoldenImage.h"
#include "core/DemoIsland.h"
#include "core/WaterSurface.h"
#include "gl/HeadlessRenderer.h"
#include "methods/MethodTable.h"
#include "raycast/Atmosphere.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

using namespace overflight;

namespace {

struct Frame {
    ColorImage color;
    DepthImage depth;
};

glm::vec3 unit(Rgb8 c) { return glm::vec3(c.r, c.g, c.b) / 255.0f; }
int off_by(Rgb8 a, Rgb8 b) { return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)}); }

Frame render(const DataSet& d, gl::HeadlessRenderer& r, const char* method, const Camera& cam, const Environment& env) {
    const MethodSettings settings;
    const std::unique_ptr<TerrainMethod> m = find_terrain_method(method)->create({d.terrain, settings, {}});
    MethodStats stats;
    Frame f;
    r.render(m->produce({cam, env, std::nullopt}, stats), cam, env, {}, f.color, &f.depth);
    return f;
}

// 1 where the pixel shows the water at `level`: its ray (shear camera: view
// depth t at height eye.y + t ray.y) meets the plane over the terrain at the
// view depth the pixel holds, within 0.2 %.
std::vector<char> water_mask(const Terrain& t, const Camera& cam, float level, const DepthImage& depth) {
    std::vector<char> m(depth.pixels.size(), 0);
    for (int row = 0; row < cam.height; ++row)
        for (int col = 0; col < cam.width; ++col) {
            const glm::dvec3 ray = cam.ray(cam.u_of(col), cam.v_of(row));
            if (!(ray.y < 0.0)) continue;
            const double d = (level - cam.eye.y) / ray.y;
            const glm::dvec3 p = cam.eye + d * ray;
            const float wd = depth.at(col, row);
            if (!t.contains(float(p.x), float(p.z)) || wd >= 1.0f) continue;
            m[std::size_t(row) * std::size_t(cam.width) + std::size_t(col)] =
                std::abs(cam.view_depth_of_window(wd) - d) < 0.002 * d;
        }
    return m;
}

} // namespace

TEST(Water, VoxelAndMeshAgreeOnTheWater) {
    DemoOptions o;
    o.size = 257;
    const DataSet d = make_demo_island(o);
    Camera cam;
    cam.eye = {1280.0, 2200.0, -900.0}; // north of the island, looking south over it
    cam.heading = 0.0;
    cam.pitch = -40.0;
    cam.width = 256;
    cam.height = 144;
    cam.far = 6000.0;
    Environment env = d.environment;
    env.water = true;
    env.fog_density = 0.0f;
    env.water_level = 600.0f; // the sea raised into the valleys
    env.water_time = 1.5;
    gl::HeadlessRenderer r(d.terrain, Scene{});
    const Frame voxel = render(d, r, "voxel", cam, env);
    const Frame mesh = render(d, r, "mesh", cam, env);
    const std::vector<char> a = water_mask(d.terrain, cam, env.water_level, voxel.depth);
    const std::vector<char> b = water_mask(d.terrain, cam, env.water_level, mesh.depth);
    long long both = 0, either = 0;
    double diff = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        both += a[i] && b[i];
        either += a[i] || b[i];
        if (a[i] && b[i]) {
            const Rgb8 p = voxel.color.pixels[i], q = mesh.color.pixels[i];
            diff += (std::abs(p.r - q.r) + std::abs(p.g - q.g) + std::abs(p.b - q.b)) / 3.0;
        }
    }
    const double iou = double(both) / double(std::max(either, 1LL));
    std::printf("water: %lld pixels of %zu in both, IoU %.4f, mean color difference %.2f levels\n", both, a.size(),
                iou, diff / double(std::max(both, 1LL)));
    EXPECT_GT(double(both) / double(a.size()), 0.1); // the view shows water
    EXPECT_GE(iou, 0.95);
    EXPECT_LE(diff / double(std::max(both, 1LL)), 10.0);
    expect_golden("demo257_water_voxel", voxel.color, 6, 0.01);
    expect_golden("demo257_water_mesh", mesh.color, 6, 0.01);
}

namespace {

// A flat sandy floor at height 0 (65 x 65 samples, cell 10), water at 20 and
// the eye at 10 in the middle, looking north and up at 10 degrees: rays that
// rise meet the surface from below at distance (20 - 10) / ray.y, and there
// the pixel must hold the plane's depth and the color of water_underside
// dimmed over that path; the other pixels show the floor, each the dry
// image's color dimmed over the path to it (all of it under the water).
void expect_under_water(const char* method) {
    DataSet d;
    d.terrain = Terrain(65, 65, 10.0f);
    for (auto& c : d.terrain.colors()) c = {200, 180, 120};
    Environment env = d.environment;
    env.fog_density = 0.0f;
    env.water = true;
    env.water_level = 20.0f;
    env.water_time = 0.5;
    Environment dry = env;
    dry.water = false;
    Camera cam;
    cam.eye = {320.0, 10.0, 320.0};
    cam.heading = 0.0;
    cam.pitch = 10.0;
    cam.width = 320;
    cam.height = 240;
    cam.near = 1.0;
    cam.far = 2000.0;
    gl::HeadlessRenderer r(d.terrain, Scene{});
    const Frame wet = render(d, r, method, cam, env), before = render(d, r, method, cam, dry);
    long long surface = 0, floor = 0, bad_surface = 0, bad_depth = 0, bad_floor = 0;
    for (int row = 0; row < cam.height; ++row)
        for (int col = 0; col < cam.width; ++col) {
            const std::size_t i = std::size_t(row) * std::size_t(cam.width) + std::size_t(col);
            const glm::dvec3 ray = cam.ray(cam.u_of(col), cam.v_of(row));
            const double t = ray.y > 0.0 ? (env.water_level - cam.eye.y) / ray.y : -1.0;
            const glm::dvec3 p = cam.eye + t * ray;
            if (t > 0.0 && d.terrain.contains(float(p.x), float(p.z)) && t < cam.far) {
                ++surface;
                bad_depth += std::abs(cam.view_depth_of_window(wet.depth.pixels[i]) - t) > 0.002 * t;
                const glm::vec3 view(glm::normalize(ray));
                const glm::vec3 n = water_normal(float(p.x), float(p.z), env.water_time, d.terrain.h_scale());
                const glm::vec3 up = water_refract_up(view, n);
                const glm::vec3 c = water_underside(env, view, n, unit(sky_color(env, glm::dvec3(up))));
                const Rgb8 expected = to_rgb8(glm::clamp(underwater_color(env, c, float(glm::length(p - cam.eye))), 0.0f, 1.0f));
                bad_surface += off_by(wet.color.pixels[i], expected) > 6;
            } else if (before.depth.pixels[i] < 1.0f && ray.y < 0.0) {
                ++floor;
                const double s = cam.eye.y / -ray.y; // the floor at 0 along the ray
                const Rgb8 expected = to_rgb8(glm::clamp(
                    underwater_color(env, unit(before.color.pixels[i]), float(s * glm::length(ray))), 0.0f, 1.0f));
                bad_floor += off_by(wet.color.pixels[i], expected) > 3;
            }
        }
    std::printf("%s under water: %lld surface pixels (%lld off in color, %lld in depth), %lld floor pixels (%lld off)\n",
                method, surface, bad_surface, bad_depth, floor, bad_floor);
    EXPECT_GT(surface, cam.width * cam.height / 4);
    EXPECT_GT(floor, cam.width * cam.height / 20);
    EXPECT_LE(bad_depth, surface / 100);
    EXPECT_LE(bad_surface, surface / 100);
    EXPECT_LE(bad_floor, floor / 100);
}

} // namespace

TEST(Water, SeenFromUnderTheSurfaceInTheRayCaster) { expect_under_water("voxel"); }

TEST(Water, SeenFromUnderTheSurfaceInTheMesh) { expect_under_water("mesh"); }

TEST(Water, DecimationFitsTheLargestTexture) {
    EXPECT_EQ(gl::water_decimation(257, 257, 16384), 1);
    EXPECT_EQ(gl::water_decimation(257, 129, 64), 5); // 255 / 5 + 2 = 53 texels; 4 would need 65
    EXPECT_EQ(gl::water_decimation(65, 65, 65), 1);
    EXPECT_EQ(gl::water_decimation(66, 10, 65), 2);
}

// The view of VoxelAndMeshAgreeOnTheWater in the mesh, with the GL's largest
// texture taken as 64: the heights go up decimated 5 times, and the water is
// still drawn on the same pixels, its colors near the full heights' ones.
TEST(Water, ATerrainWiderThanATextureStillGetsItsWater) {
    DemoOptions o;
    o.size = 257;
    const DataSet d = make_demo_island(o);
    Camera cam;
    cam.eye = {1280.0, 2200.0, -900.0};
    cam.heading = 0.0;
    cam.pitch = -40.0;
    cam.width = 256;
    cam.height = 144;
    cam.far = 6000.0;
    Environment env = d.environment;
    env.water = true;
    env.fog_density = 0.0f;
    env.water_level = 600.0f;
    env.water_time = 1.5;
    gl::HeadlessRenderer full(d.terrain, Scene{});
    const Frame a = render(d, full, "mesh", cam, env);
    gl::HeadlessRenderer small(d.terrain, Scene{});
    small.compositor().water().set_max_texture_size(64);
    const Frame b = render(d, small, "mesh", cam, env);
    EXPECT_EQ(small.compositor().water().decimation(), 5);
    const std::vector<char> ma = water_mask(d.terrain, cam, env.water_level, a.depth);
    const std::vector<char> mb = water_mask(d.terrain, cam, env.water_level, b.depth);
    long long n = 0, same = 0;
    double diff = 0;
    for (std::size_t i = 0; i < ma.size(); ++i) {
        n += ma[i];
        same += ma[i] && mb[i];
        if (ma[i] && mb[i]) {
            const Rgb8 p = a.color.pixels[i], q = b.color.pixels[i];
            diff += (std::abs(p.r - q.r) + std::abs(p.g - q.g) + std::abs(p.b - q.b)) / 3.0;
        }
    }
    std::printf("decimated water: %lld of %lld water pixels kept, mean color difference %.2f levels\n", same, n,
                diff / double(std::max(same, 1LL)));
    EXPECT_GT(n, (long long)(ma.size() / 10));
    EXPECT_GE(same, n * 99 / 100);
    EXPECT_LE(diff / double(std::max(same, 1LL)), 10.0);
}
