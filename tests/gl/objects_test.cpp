// Objects composited with every terrain renderer (Szenberg et al. 1997 sec. 5,
// DESIGN sec. 2 and 5): the same box covers the same pixels over the ray-cast
// terrain and over the GL mesh, lands where the analytic projection of its
// corners says, is hidden behind a ridge in both, and cables sag as specified.
// Golden images of the demo guard the look of the GL methods.
#include "TestSupport.h"
#include "core/DemoIsland.h"
#include "gl/HeadlessRenderer.h"
#include "gl/ObjectGeometry.h"
#include "methods/MethodTable.h"
#include "io/ImageWriters.h"
#include "raycast/FloatingHorizon.h"

#include "GoldenImage.h"

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

using namespace overflight;

namespace {

const DataSet& demo() {
    static const DataSet d = make_demo_island({.size = 257});
    return d;
}

// Above and behind the demo's village, looking down at it.
Camera demo_camera(int w = 160, int h = 100) {
    const DataSet& d = demo();
    Camera c;
    const double hr = glm::radians(d.start.heading);
    const glm::dvec3 fwd(std::sin(hr), 0, std::cos(hr));
    c.eye = glm::dvec3(d.start.x, 0, d.start.z) - 50.0 * d.terrain.h_scale() * fwd;
    c.eye.y = d.terrain.height_bilinear(float(d.start.x), float(d.start.z)) + 350.0;
    c.heading = d.start.heading;
    c.pitch = -30;
    c.fov = 60;
    c.width = w;
    c.height = h;
    c.near = 1;
    c.far = 4000;
    return c;
}

struct Frame {
    ColorImage color;
    DepthImage depth;
};

Frame voxel(const DataSet& d, const Camera& cam) {
    FloatingHorizon fh(d.terrain);
    Frame f;
    fh.render(cam, d.environment, RaycastOptions{}, f.color, f.depth);
    return f;
}

// Over the ray caster without `read_depth` the composite loads depth only in
// the objects' screen rectangle (Compositor::depth_rect), as bench does.
Frame with_objects(gl::HeadlessRenderer& r, const char* method, const Camera& cam, const Frame* raycast,
                   bool read_depth = false) {
    Frame f;
    const Environment& env = demo().environment;
    if (raycast) {
        r.render(MethodOutput::images(raycast->color, raycast->depth), cam, env, {}, f.color,
                 read_depth ? &f.depth : nullptr);
    } else {
        const MethodSettings settings;
        const std::unique_ptr<TerrainMethod> m = find_terrain_method(method)->create({demo().terrain, settings, {}});
        MethodStats stats;
        r.render(m->produce({cam, env, std::nullopt}, stats), cam, env, {}, f.color, &f.depth);
    }
    return f;
}

// Pixels whose color differs between two frames: where an object is visible.
std::vector<bool> changed(const Frame& a, const Frame& b) {
    std::vector<bool> m(a.color.pixels.size());
    for (std::size_t i = 0; i < m.size(); ++i) m[i] = !(a.color.pixels[i] == b.color.pixels[i]);
    return m;
}

double iou(const std::vector<bool>& a, const std::vector<bool>& b) {
    long long inter = 0, uni = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        inter += a[i] && b[i];
        uni += a[i] || b[i];
    }
    return uni ? double(inter) / double(uni) : 1.0;
}

long long count(const std::vector<bool>& m) { return std::count(m.begin(), m.end(), true); }

struct Box2 { double c0 = 1e9, r0 = 1e9, c1 = -1e9, r1 = -1e9; };

Box2 mask_bounds(const std::vector<bool>& m, int w) {
    Box2 b;
    for (std::size_t i = 0; i < m.size(); ++i)
        if (m[i]) {
            const double c = double(i % std::size_t(w)), r = double(i / std::size_t(w));
            b.c0 = std::min(b.c0, c); b.c1 = std::max(b.c1, c + 1);
            b.r0 = std::min(b.r0, r); b.r1 = std::max(b.r1, r + 1);
        }
    return b;
}

SceneObject magenta_box(double x, double z, double size) {
    SceneObject o;
    o.kind = ObjectKind::Box;
    o.x = x;
    o.z = z;
    o.width = o.depth = o.height = size;
    o.heading = 30;
    o.color = {255, 0, 255};
    return o;
}

} // namespace

TEST(GlObjects, SameBoxCoversTheSamePixelsOverVoxelAndMesh) {
    const DataSet& d = demo();
    const Camera cam = demo_camera(320, 200);
    // A box in the village clearing the camera looks at.
    const glm::dvec3 F = cam.forward();
    const double bx = d.start.x + 3 * d.terrain.h_scale() * F.x, bz = d.start.z + 3 * d.terrain.h_scale() * F.z;
    Scene scene;
    scene.objects.push_back(magenta_box(bx, bz, 40));

    gl::HeadlessRenderer empty(d.terrain, Scene{});
    gl::HeadlessRenderer boxed(d.terrain, scene);
    const Frame rc = voxel(d, cam);
    const auto voxel_mask = changed(with_objects(empty, "voxel", cam, &rc), with_objects(boxed, "voxel", cam, &rc));
    const auto mesh_mask = changed(with_objects(empty, "mesh", cam, nullptr), with_objects(boxed, "mesh", cam, nullptr));
    ASSERT_GT(count(voxel_mask), 200);
    ASSERT_GT(count(mesh_mask), 200);
    EXPECT_GE(iou(voxel_mask, mesh_mask), 0.9);

    // Bounding box within 2 px of the analytic projection of its 8 corners
    // (the box stands in the open, so its silhouette is not cut by terrain).
    Box2 analytic;
    for (const glm::dvec3& p : gl::box_corners(scene.objects[0], d.terrain)) {
        const auto pr = cam.project(p);
        analytic.c0 = std::min(analytic.c0, pr.col); analytic.c1 = std::max(analytic.c1, pr.col);
        analytic.r0 = std::min(analytic.r0, pr.row); analytic.r1 = std::max(analytic.r1, pr.row);
    }
    for (const auto* mask : {&voxel_mask, &mesh_mask}) {
        const Box2 b = mask_bounds(*mask, cam.width);
        EXPECT_NEAR(b.c0, analytic.c0, 2.0);
        EXPECT_NEAR(b.c1, analytic.c1, 2.0);
        EXPECT_NEAR(b.r0, analytic.r0, 2.0);
        // The base sits on the ground, partly below the surface on a slope: only the top is exact.
    }
}

// The depth upload transfers only the rows below the horizon and clears the
// sky rows: what the objects are tested against must still be the ray
// caster's depth, bit for bit, on a view with sky above and terrain below.
TEST(GlObjects, CompositedDepthIsTheRayCastersWithSkyRows) {
    const DataSet& d = demo();
    Camera cam = demo_camera(320, 200);
    cam.pitch = 20;
    gl::HeadlessRenderer empty(d.terrain, Scene{});
    const Frame rc = voxel(d, cam);
    for (int c = 0; c < cam.width; ++c) ASSERT_EQ(rc.depth.at(c, 0), 1.0f) << "the view must show sky at the top";
    ASSERT_LT(rc.depth.at(160, 199), 1.0f) << "and terrain at the bottom";
    const Frame f = with_objects(empty, "voxel", cam, &rc, true);
    EXPECT_EQ(f.depth.pixels, rc.depth.pixels);
    EXPECT_EQ(f.color.pixels, rc.color.pixels);
}

TEST(GlObjects, BoxBehindARidgeIsHiddenInBothRenderers) {
    const DataSet& d = demo();
    const Camera cam = demo_camera(320, 200);
    gl::HeadlessRenderer empty(d.terrain, Scene{});
    const Frame rc = voxel(d, cam);
    const Frame mesh = with_objects(empty, "mesh", cam, nullptr);
    // Search the terrain for a spot whose whole box (20 m cube) is behind the
    // terrain by a clear margin in both depth buffers, in the view, far behind a ridge.
    const float hs = d.terrain.h_scale();
    std::optional<SceneObject> hidden;
    for (int row = 4; row < d.terrain.rows() - 4 && !hidden; row += 3)
        for (int col = 4; col < d.terrain.cols() - 4 && !hidden; col += 3) {
            const SceneObject o = magenta_box(col * hs, row * hs, 20);
            bool ok = true;
            for (const glm::dvec3& p : gl::box_corners(o, d.terrain)) {
                const auto pr = cam.project(p);
                if (!pr.in_front || pr.col < 3 || pr.row < 3 || pr.col > cam.width - 3 || pr.row > cam.height - 3) { ok = false; break; }
                const double behind = cam.view_depth(p);
                for (int dr = -2; dr <= 2 && ok; ++dr)
                    for (int dc = -2; dc <= 2 && ok; ++dc) {
                        const int c = int(pr.col) + dc, r = int(pr.row) + dr;
                        for (const DepthImage* z : {&rc.depth, &mesh.depth})
                            if (!(cam.view_depth_of_window(z->at(c, r)) < behind - 80.0)) ok = false;
                    }
            }
            if (ok) hidden = o;
        }
    ASSERT_TRUE(hidden) << "no hidden spot found for this camera";
    Scene scene;
    scene.objects.push_back(*hidden);
    gl::HeadlessRenderer boxed(d.terrain, scene);
    EXPECT_EQ(count(changed(with_objects(empty, "voxel", cam, &rc), with_objects(boxed, "voxel", cam, &rc))), 0);
    EXPECT_EQ(count(changed(mesh, with_objects(boxed, "mesh", cam, nullptr))), 0);
    // The same box moved into the village clearing shows in both.
    scene.objects[0].x = d.start.x;
    scene.objects[0].z = d.start.z;
    gl::HeadlessRenderer moved(d.terrain, scene);
    EXPECT_GT(count(changed(with_objects(empty, "voxel", cam, &rc), with_objects(moved, "voxel", cam, &rc))), 20);
    EXPECT_GT(count(changed(mesh, with_objects(moved, "mesh", cam, nullptr))), 20);
}

TEST(GlObjects, CablesSagAsSpecifiedInTheImage) {
    // Flat white ground at Y = 0, a two-tower line along X seen from the south side.
    DataSet d;
    d.terrain = Terrain(65, 65, 10.0f);
    for (auto& c : d.terrain.colors()) c = {255, 255, 255};
    d.environment.fog_density = 0;
    TransmissionLine line;
    line.points = {{100.0, 320.0}, {540.0, 320.0}};
    line.height = 40;
    line.sag = 15;
    line.color = {0, 0, 0};
    d.scene.lines.push_back(line);
    gl::HeadlessRenderer r(d.terrain, d.scene);
    Camera cam;
    cam.eye = {320, 40, 700}; // at cable height, 380 m south of the line, looking north
    cam.heading = 180;
    cam.pitch = 0;
    cam.fov = 70;
    cam.width = 240;
    cam.height = 160;
    cam.near = 1;
    cam.far = 2000;
    Frame f;
    r.render(MethodOutput::resident(ResidentSurface::Mesh), cam, d.environment, {}, f.color, nullptr);
    const auto dark = [&](int c, int row) { const Rgb8 p = f.color.at(c, row); return p.r < 60 && p.g < 60 && p.b < 60; };
    const double arm = gl::tower_arm(line.height);
    for (double side : {-arm, 0.0, arm}) {
        // Cross-arms point across the line (along Z here): conductors at z = 320 + side.
        const glm::dvec3 mid(320, 40 - 15, 320 + side), chord(320, 40, 320 + side);
        const auto pm = cam.project(mid), pc = cam.project(chord);
        ASSERT_GT(pm.row - pc.row, 5.0); // the sag is visible: more than 5 px
        bool found = false;
        for (int dr = -1; dr <= 1; ++dr) found = found || dark(int(pm.col), int(pm.row) + dr);
        EXPECT_TRUE(found) << "no cable at the sagged mid-span point, side " << side;
    }
    // Nothing dark at the chord's mid-span (rows of the straight line between attachments).
    const auto pc = cam.project({320, 40, 320});
    for (int dr = -1; dr <= 1; ++dr) EXPECT_FALSE(dark(int(pc.col), int(pc.row) + dr));
}

TEST(GlGolden, DemoWithObjects) {
    const DataSet& d = demo();
    const Camera cam = demo_camera();
    gl::HeadlessRenderer r(d.terrain, d.scene);
    for (const char* m : {"mesh", "top-faces", "blocks"}) {
        Frame f = with_objects(r, m, cam, nullptr);
        expect_golden(std::string("demo257_") + m, f.color, 6, 0.01);
    }
    const Frame rc = voxel(d, cam);
    expect_golden("demo257_voxel_objects", with_objects(r, "voxel", cam, &rc).color, 6, 0.01);
}
