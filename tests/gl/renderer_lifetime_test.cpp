// Several headless renderers alive at once (tests, the Python module's
// terrains, `bench` beside `render`): each has its own EGL context, and GL
// deletes its objects in whichever context is current, so a renderer
// destroyed after another one drew must delete in its own context, not in
// the other's, whose frames must stay the same.
#include "core/DemoIsland.h"
#include "gl/HeadlessRenderer.h"
#include "methods/MethodTable.h"

#include <gtest/gtest.h>

#include <memory>

using namespace overflight;

namespace {

ColorImage render(const DataSet& d, gl::HeadlessRenderer& r, const char* method, const Camera& cam) {
    const MethodSettings settings;
    const std::unique_ptr<TerrainMethod> m = find_terrain_method(method)->create({d.terrain, settings, {}});
    MethodStats stats;
    ColorImage color;
    const gl::CompositeOptions options{true, false, false, std::nullopt};
    r.render(m->produce({cam, d.environment, std::nullopt}, stats), cam, d.environment, options, color, nullptr);
    return color;
}

} // namespace

TEST(HeadlessRenderer, DestroyedInAnyOrderLeavesTheOthersFramesAlone) {
    DemoOptions demo;
    demo.size = 129;
    DataSet d = make_demo_island(demo);
    d.environment.shadows = true;
    Camera cam;
    cam.eye = {640, 400, 1400};
    cam.heading = 180;
    cam.pitch = -15;
    cam.width = 160;
    cam.height = 120;
    cam.far = 3000;
    for (const char* method : {"voxel", "mesh"}) {
        auto first = std::make_unique<gl::HeadlessRenderer>(d.terrain, d.scene);
        auto second = std::make_unique<gl::HeadlessRenderer>(d.terrain, d.scene);
        auto third = std::make_unique<gl::HeadlessRenderer>(d.terrain, d.scene);
        render(d, *first, method, cam);
        const ColorImage before_second = render(d, *second, method, cam);
        const ColorImage before_third = render(d, *third, method, cam);
        first.reset(); // the third's context is current here
        EXPECT_EQ(render(d, *third, method, cam).pixels, before_third.pixels) << method;
        third.reset(); // and now the third's again
        EXPECT_EQ(render(d, *second, method, cam).pixels, before_second.pixels) << method;
    }
}
