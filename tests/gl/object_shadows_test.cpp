// The objects' cast shadows (gl/ObjectShadowMap, gl/ShadowScreenPass) on a
// literal scene: a flat terrain and one box under a western sun at 45
// degrees, whose shadow on the ground is worked out by hand, in a ray-cast
// method (`voxel`: the screen-space pass over its image) and a mesh method
// (`mesh`: shade()).
#include "core/SunLight.h"
#include "gl/HeadlessRenderer.h"
#include "methods/MethodTable.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace overflight;

namespace {

// A flat 33x33 grid of cell 2 (X and Z in [0, 64]) at height 0, grey; a box
// of 8 x 8 x 8 with its base centred at (24, 0, 32): X in [20, 28], Z in
// [28, 36]. The sun in the west (azimuth 270) at 45 degrees: its rays drop
// one unit per unit eastwards, so the box's top edge at X = 28, Y = 8 puts
// its shadow on the ground over X in [28, 36], Z in [28, 36]; the flat
// terrain casts none.
DataSet box_scene() {
    DataSet d;
    d.terrain = Terrain(33, 33, 2.0f);
    for (auto& c : d.terrain.colors()) c = {200, 200, 200};
    d.environment.fog_density = 0;
    d.environment.sun_dir = sun_direction(270.0, 45.0);
    SceneObject box;
    box.kind = ObjectKind::Box;
    box.x = 24;
    box.z = 32;
    box.y = 0;
    box.width = box.depth = box.height = 8;
    box.color = {200, 40, 40};
    d.scene.objects = {box};
    return d;
}

ColorImage render(const DataSet& d, gl::HeadlessRenderer& r, const char* method, const Camera& cam, const Environment& env,
                  const gl::CompositeOptions& options = {}) {
    const MethodSettings settings;
    const std::unique_ptr<TerrainMethod> m = find_terrain_method(method)->create({d.terrain, settings, {}});
    MethodStats stats;
    ColorImage color;
    r.render(m->produce({cam, env, std::nullopt}, stats), cam, env, options, color, nullptr);
    return color;
}

// Looking north and down from the south-east at the box (and where the
// vehicle is placed beside it).
Camera south_east_camera(int width, int height) {
    Camera cam;
    cam.eye = {32, 40, 72};
    cam.heading = 180;
    cam.pitch = -45;
    cam.width = width;
    cam.height = height;
    cam.near = 1;
    cam.far = 300;
    return cam;
}

// The pixel where the ground point (x, 0, z) is seen (it must be in view).
Rgb8 ground_pixel(const ColorImage& img, const Camera& cam, double x, double z) {
    const auto p = cam.project({x, 0, z});
    EXPECT_TRUE(p.col >= 0 && p.col < cam.width && p.row >= 0 && p.row < cam.height) << x << "," << z;
    return img.at(std::clamp(int(p.col), 0, cam.width - 1), std::clamp(int(p.row), 0, cam.height - 1));
}

// The ground at (x, z) is lit by the ambient light alone: 200 x ambient.
void expect_ambient_only(const ColorImage& img, const Camera& cam, const DataSet& d, const char* method, double x,
                         double z) {
    const glm::vec3 ambient = d.environment.ambient * 200.0f;
    const Rgb8 c = ground_pixel(img, cam, x, z);
    EXPECT_NEAR(c.r, ambient.r, 3.0) << method << " at " << x << "," << z;
    EXPECT_NEAR(c.g, ambient.g, 3.0) << method << " at " << x << "," << z;
    EXPECT_NEAR(c.b, ambient.b, 3.0) << method << " at " << x << "," << z;
}

void expect_box_shadow(const char* method) {
    const DataSet d = box_scene();
    gl::HeadlessRenderer r(d.terrain, d.scene);
    const Camera cam = south_east_camera(320, 240);
    Environment with = d.environment, without = d.environment;
    with.shadows = true;
    const ColorImage on = render(d, r, method, cam, with), off = render(d, r, method, cam, without);
    const auto at = [&](const ColorImage& img, double x, double z) { return ground_pixel(img, cam, x, z); };
    // Inside the footprint: the ambient light alone.
    for (const auto& [x, z] : {std::pair{32.0, 32.0}, {30.0, 30.0}, {34.5, 34.5}, {29.0, 34.0}})
        expect_ambient_only(on, cam, d, method, x, z);
    // Outside it (east of X = 36, south of Z = 36, north of Z = 28, and the
    // box's sunny west side): exactly as without shadows.
    for (const auto& [x, z] : {std::pair{40.0, 32.0}, {32.0, 40.0}, {32.0, 24.0}, {14.0, 32.0}, {44.0, 44.0}})
        EXPECT_EQ(at(on, x, z), at(off, x, z)) << method << " at " << x << "," << z;
    EXPECT_GT(at(off, 32, 32).r, d.environment.ambient.r * 200.0f + 60); // sunlit without the box's shadow
}

} // namespace

TEST(ObjectShadows, BoxOnFlatGroundInTheRayCaster) { expect_box_shadow("voxel"); }

TEST(ObjectShadows, BoxOnFlatGroundInTheMesh) { expect_box_shadow("mesh"); }

// The ray caster's composite loads depth only where the objects, the vehicle
// and the objects' shadows can be drawn (Compositor::depth_rect): the same
// pixels as with the whole depth loaded (a read-back asks for it), with the
// vehicle in view beside the box's shadow.
TEST(ObjectShadows, PartialDepthLoadDrawsTheSamePixelsAsTheWholeDepth) {
    const DataSet d = box_scene();
    gl::HeadlessRenderer r(d.terrain, d.scene);
    const Camera cam = south_east_camera(320, 240);
    Environment env = d.environment;
    env.shadows = true;
    const MethodSettings settings;
    const std::unique_ptr<TerrainMethod> m = find_terrain_method("voxel")->create({d.terrain, settings, {}});
    const gl::CompositeOptions options{true, false, false, gl::VehiclePose{44, 44, 30}};
    MethodStats stats;
    const MethodOutput out = m->produce({cam, env, glm::dvec2(44, 44)}, stats);
    const PixelRect rect = r.compositor().depth_rect(cam, env, options);
    EXPECT_FALSE(rect.empty());
    EXPECT_LT(rect.area(), (long long)cam.width * cam.height) << "the test must load less than the whole depth";
    ColorImage partial, whole;
    DepthImage depth;
    r.render(out, cam, env, options, partial, nullptr);
    r.render(out, cam, env, options, whole, &depth);
    EXPECT_EQ(partial.pixels, whole.pixels);
    // The vehicle is drawn (its color differs from the grey ground and the red box).
    const auto p = cam.project({44, 1, 44});
    ASSERT_TRUE(p.in_front);
    EXPECT_NE(partial.at(int(p.col), int(p.row)), out.color->at(int(p.col), int(p.row)));
}

namespace {

// The vehicle (gl/FlightVehicle: skirt 3 wide from 0.3 to 1.0 above the
// ground, body to 1.7, cabin to 2.3) at (24, 32) heading north, on the same
// flat ground with no objects, under the same western sun at 45 degrees: the
// skirt's shadow covers X in [22.8, 26.5], Z in [29.5, 34.5], the body's
// reaches X = 26.975 over Z in [29.75, 34.25].
void expect_vehicle_shadow(const char* method) {
    DataSet d = box_scene();
    d.scene.objects.clear();
    gl::HeadlessRenderer r(d.terrain, d.scene);
    const Camera cam = south_east_camera(640, 480);
    Environment with = d.environment, without = d.environment;
    with.shadows = true;
    gl::CompositeOptions options;
    options.vehicle = gl::VehiclePose{24, 32, 0};
    const ColorImage on = render(d, r, method, cam, with, options), off = render(d, r, method, cam, without, options);
    const auto at = [&](const ColorImage& img, double x, double z) { return ground_pixel(img, cam, x, z); };
    for (const auto& [x, z] : {std::pair{26.2, 32.0}, {26.0, 30.5}, {26.0, 33.5}, {26.6, 31.5}}) {
        expect_ambient_only(on, cam, d, method, x, z);
        EXPECT_GT(at(off, x, z).r, d.environment.ambient.r * 200.0f + 60) << method << " at " << x << "," << z;
    }
    for (const auto& [x, z] : {std::pair{28.0, 32.0}, {24.0, 37.0}, {24.0, 27.0}, {30.0, 36.0}})
        EXPECT_EQ(at(on, x, z), at(off, x, z)) << method << " at " << x << "," << z;
}

} // namespace

TEST(ObjectShadows, VehicleOnFlatGroundInTheRayCaster) { expect_vehicle_shadow("voxel"); }

TEST(ObjectShadows, VehicleOnFlatGroundInTheMesh) { expect_vehicle_shadow("mesh"); }
