// Sun lighting and the terrain's cast shadows in every kind of terrain
// method: the ray caster (`voxel`, lit colors per sample from core/SunLight)
// and the full mesh (`mesh`, shade() with the shadow ceiling texture) under a
// low sun on the same camera. Their shadow masks (the pixels that --shadows
// takes most of the sun's light from) overlap with IoU >= 0.9 on a real DEM,
// and their lit colors agree on terrain pixels within a mean of 6 levels per
// channel (per-sample against per-fragment normals). Objects receive the
// terrain's shadow.
#include "TestSupport.h"
#include "core/DemoIsland.h"
#include "core/SunLight.h"
#include "gl/HeadlessRenderer.h"
#include "io/LoadTerrain.h"
#include "methods/MethodTable.h"

#include <gtest/gtest.h>

#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace overflight;

namespace {

struct Frame {
    ColorImage color;
    DepthImage depth;
};

// `method` for `env`, through the method table and the compositor, as `render` draws it.
Frame render(const DataSet& d, gl::HeadlessRenderer& r, const char* method, const Camera& cam, const Environment& env,
             const MethodSettings& settings = {}) {
    const std::unique_ptr<TerrainMethod> m = find_terrain_method(method)->create({d.terrain, settings, {}});
    MethodStats stats;
    Frame f;
    r.render(m->produce({cam, env, std::nullopt}, stats), cam, env, {}, f.color, &f.depth);
    return f;
}

int sum(Rgb8 c) { return c.r + c.g + c.b; }

// Per pixel: 1 where the shadows take more than half of the sun's light, 0
// where less, -1 where there is no terrain or the sun adds less than 15
// levels (summed over channels) to the ambient light, so that the slopes
// turned from the sun, whose Lambert term per sample (voxel) and per
// fragment (mesh) differ, do not count: `lit` without shadows, `dark`
// without the sun.
std::vector<int> shadow_mask(const Frame& lit, const Frame& shadowed, const Frame& dark) {
    std::vector<int> m(lit.color.pixels.size());
    for (std::size_t i = 0; i < m.size(); ++i) {
        const int sun = sum(lit.color.pixels[i]) - sum(dark.color.pixels[i]);
        const int lost = sum(lit.color.pixels[i]) - sum(shadowed.color.pixels[i]);
        m[i] = lit.depth.pixels[i] < 1.0f && sun >= 15 ? int(2 * lost > sun) : -1;
    }
    return m;
}

struct Comparison {
    double iou = 0, shadowed_share = 0, mean_diff = 0;
};

Comparison compare_methods(const DataSet& d, const Camera& cam, const glm::vec3& sun, const MethodSettings& voxel_settings = {}) {
    gl::HeadlessRenderer r(d.terrain, Scene{});
    Environment env = d.environment;
    env.fog_density = 0;
    env.sun_dir = sun;
    Environment with = env, dark = env;
    with.shadows = true;
    dark.sun_color = glm::vec3(0.0f);
    const Frame voxel = render(d, r, "voxel", cam, env, voxel_settings),
                voxel_s = render(d, r, "voxel", cam, with, voxel_settings);
    const Frame mesh = render(d, r, "mesh", cam, env), mesh_s = render(d, r, "mesh", cam, with);
    const std::vector<int> a = shadow_mask(voxel, voxel_s, render(d, r, "voxel", cam, dark, voxel_settings));
    const std::vector<int> b = shadow_mask(mesh, mesh_s, render(d, r, "mesh", cam, dark));
    long long both = 0, either = 0, terrain = 0, shadowed = 0, terrain_pixels = 0;
    double diff = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (a[i] >= 0 && b[i] >= 0) { // the IoU where both images tell
            both += a[i] && b[i];
            either += a[i] || b[i];
            ++terrain;
            shadowed += b[i];
        }
        if (voxel.depth.pixels[i] < 1.0f && mesh.depth.pixels[i] < 1.0f) {
            ++terrain_pixels;
            const Rgb8 p = voxel_s.color.pixels[i], q = mesh_s.color.pixels[i];
            diff += (std::abs(p.r - q.r) + std::abs(p.g - q.g) + std::abs(p.b - q.b)) / 3.0;
        }
    }
    Comparison c;
    c.iou = either ? double(both) / double(either) : 1.0;
    c.shadowed_share = terrain ? double(shadowed) / double(terrain) : 0.0;
    c.mean_diff = terrain_pixels ? diff / double(terrain_pixels) : 0.0;
    std::printf("  IoU %.4f, %.1f %% of sunlit terrain pixels shadowed, mean color difference %.2f\n", c.iou,
                100.0 * c.shadowed_share, c.mean_diff);
    return c;
}

// Looking down across the terrain from near its south-west corner towards its centre.
Camera across(const Terrain& t, double agl, double pitch) {
    Camera c;
    const double x = 0.2 * t.width(), z = 0.8 * t.depth();
    c.eye = {x, t.height_bilinear(float(x), float(z)) + agl, z};
    c.heading = glm::degrees(std::atan2(0.5 * t.width() - x, 0.5 * t.depth() - z));
    c.pitch = pitch;
    c.width = 480;
    c.height = 270;
    c.near = 1;
    c.far = std::hypot(t.width(), t.depth());
    return c;
}

} // namespace

// The demo island's cliffs are steep for its cells, which span many pixels
// here. Algorithm 1 of Szenberg, Gattass, Carvalho (SIBGRAPI 1997) paints
// each block's front face, the span between the near sample's top and its
// own, with one sample; the mesh's slope there shows the near sample's light
// in its near part. The ray caster paints that part with the near sample's
// light (raycast/FrontFace.h: below where the ray crosses into the far
// sample's cell), so a shadow ends where the mesh's does; what is left is
// the blocks' surface (flat tops, vertical faces) against the mesh's slopes
// (measured: IoU 0.927, mean difference 3.8; 0.800 and 4.1 with each span
// in its far sample's light alone; the next test takes the blocks out).
TEST(SunShadows, VoxelAndMeshAgreeOnTheDemo) {
    const DataSet d = make_demo_island();
    const Comparison c = compare_methods(d, across(d.terrain, 1500.0, -35.0), sun_direction(250.0, 12.0));
    EXPECT_GT(c.shadowed_share, 0.05); // the test sees shadows
    EXPECT_GE(c.iou, 0.9);
    EXPECT_LE(c.mean_diff, 6.0);
}

// The same view with the ray caster's surface made the mesh's: bilinear
// cells (DESIGN sec. 3: the mesh and bilinear surfaces agree on the grid
// lines) and slices closer than a cell near the eye (--near-step 1), so that
// a pixel shows the same ground point in both. The shadows then agree
// (measured: IoU 0.948, mean difference 2.7; 0.907 and 2.8 with each span in
// its far sample's light alone): what the blocks lose above is their
// surface, not their shadow test, which is the mesh's (nearest sample, the
// boundary halfway between a shadowed and a lit sample).
TEST(SunShadows, VoxelOnTheMeshsSurfaceAndMeshAgreeOnTheDemo) {
    const DataSet d = make_demo_island();
    MethodSettings bilinear;
    bilinear.raycast.surface = SurfaceModel::Bilinear;
    bilinear.raycast.near_step_pixels = 1.0;
    const Comparison c = compare_methods(d, across(d.terrain, 1500.0, -35.0), sun_direction(250.0, 12.0), bilinear);
    EXPECT_GT(c.shadowed_share, 0.05);
    EXPECT_GE(c.iou, 0.9);
    EXPECT_LE(c.mean_diff, 6.0);
}

// A real DEM seen from above (measured: IoU 0.98, mean difference 1.0; 0.94
// and 1.1 with each span in its far sample's light alone).
TEST(SunShadows, VoxelAndMeshAgreeOnMountRainier) {
    OVERFLIGHT_SHARED_FILE(path, "srtm/mt_rainier_90m.tif");
    const DataSet d = load_terrain(path);
    const Comparison c = compare_methods(d, across(d.terrain, 1500.0, -30.0), sun_direction(120.0, 10.0));
    EXPECT_GT(c.shadowed_share, 0.05);
    EXPECT_GE(c.iou, 0.9);
    EXPECT_LE(c.mean_diff, 6.0);
}

// An object standing in the terrain's shadow is darker with --shadows; one
// in the sun is not: objects receive the terrain's shadows (shade()).
TEST(SunShadows, ObjectsReceiveTheTerrainsShadow) {
    // A wall of 20 along X at row 2 of a flat 33x33 grid; the sun in the
    // north at 30 degrees: its shadow falls south of the wall, 20 / tan 30 =
    // 34.6 world units deep (hs 2: 17 rows).
    DataSet d;
    d.terrain = Terrain(33, 33, 2.0f);
    for (int c = 0; c < 33; ++c) d.terrain.raw(2, c) = 20;
    for (auto& c : d.terrain.colors()) c = {200, 200, 200};
    d.environment.fog_density = 0;
    d.environment.sun_dir = sun_direction(0.0, 30.0);
    SceneObject shaded, sunny;
    shaded.kind = ObjectKind::Box;
    shaded.x = 32;
    shaded.z = 20; // 16 south of the wall: in its shadow up to 20 - 16 tan 30 = 10.8 high
    shaded.y = 0;
    shaded.width = shaded.depth = 4;
    shaded.height = 4;
    shaded.color = {200, 40, 40};
    sunny = shaded;
    sunny.z = 48; // 44 south: beyond the shadow (20 - 44 tan 30 < 0)
    d.scene.objects = {shaded, sunny};
    gl::HeadlessRenderer r(d.terrain, d.scene);
    Camera cam;
    cam.eye = {32, 40, 100};
    cam.heading = 180; // looking north at both boxes
    cam.pitch = -30;
    cam.width = 200;
    cam.height = 150;
    cam.near = 1;
    cam.far = 500;
    Environment with = d.environment;
    with.shadows = true;
    const Frame lit = render(d, r, "mesh", cam, d.environment), shadowed = render(d, r, "mesh", cam, with);
    const auto at = [&](const Frame& f, double z) {
        const auto p = cam.project({32, 4, z}); // the boxes' tops' centres (their sides face away from the sun)
        EXPECT_TRUE(p.col >= 0 && p.col < cam.width && p.row >= 0 && p.row < cam.height);
        return f.color.at(std::clamp(int(p.col), 0, cam.width - 1), std::clamp(int(p.row), 0, cam.height - 1));
    };
    EXPECT_LT(sum(at(shadowed, 20)) + 30, sum(at(lit, 20)));
    EXPECT_EQ(sum(at(shadowed, 48)), sum(at(lit, 48)));
}
