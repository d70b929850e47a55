// Water (core/WaterSurface.h) in a ray caster and a GL method on the same
// camera: `voxel` floods its image per pixel (raycast/WaterPass.h), `mesh`
// draws the plane in GL (gl/WaterPlane.h). The water pixels, found by depth
// (the pixel's view depth is the plane's along its ray), overlap with
// IoU >= 0.95; their colors agree within a mean of 10 levels per channel
// (the GL march of the mirrored ray is coarser than the ray caster's exact
// one); and both images match their golden images (at most 1 % of the
// pixels more than 6 levels off).
#include "GoldenImage.h"
#include "core/DemoIsland.h"
#include "gl/HeadlessRenderer.h"
#include "methods/MethodTable.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

using namespace overflight;

namespace {

struct Frame {
    ColorImage color;
    DepthImage depth;
};

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
