// TerrainMethod::swap_images for `voxel`: the caller gets the last frame's
// buffers as they were produced, and a frame rendered into buffers handed in
// holding garbage equals one rendered by a fresh method (the caster writes
// every pixel, sky included), for the shear and both tilt casts, with water.
#include "core/DemoIsland.h"
#include "methods/MethodTable.h"

#include "TestCameras.h"

#include <gtest/gtest.h>

#include <memory>

using namespace overflight;

namespace {

struct Frame {
    ColorImage color;
    DepthImage depth;
};

Frame fresh_frame(const DataSet& d, const MethodSettings& settings, const Camera& cam, const Environment& env) {
    const std::unique_ptr<TerrainMethod> m = find_terrain_method("voxel")->create({d.terrain, settings, {}});
    MethodStats stats;
    const MethodOutput out = m->produce({cam, env, std::nullopt}, stats);
    return {*out.color, *out.depth};
}

void expect_swaps_render_over_garbage(const DataSet& d, const MethodSettings& settings, const Camera& cam,
                                      const Environment& env) {
    const Frame expected = fresh_frame(d, settings, cam, env);
    const std::unique_ptr<TerrainMethod> m = find_terrain_method("voxel")->create({d.terrain, settings, {}});
    MethodStats stats;
    // A first frame of another view, then buffers full of garbage handed in.
    Camera other = cam;
    other.heading += 90;
    other.pitch = 20;
    const MethodOutput first = m->produce({other, env, std::nullopt}, stats);
    const Frame first_copy{*first.color, *first.depth};
    Frame lent{ColorImage(cam.width, cam.height, Rgb8{171, 205, 239}), DepthImage(cam.width, cam.height, 0.123f)};
    ASSERT_TRUE(m->swap_images(lent.color, &lent.depth));
    EXPECT_EQ(lent.color.pixels, first_copy.color.pixels);
    EXPECT_EQ(lent.depth.pixels, first_copy.depth.pixels);
    const MethodOutput out = m->produce({cam, env, std::nullopt}, stats);
    EXPECT_EQ(out.color->pixels, expected.color.pixels);
    EXPECT_EQ(out.depth->pixels, expected.depth.pixels);
    // Color alone, with an empty buffer handed in (resized by the caster).
    ColorImage empty;
    ASSERT_TRUE(m->swap_images(empty, nullptr));
    EXPECT_EQ(empty.pixels, expected.color.pixels);
    const MethodOutput again = m->produce({cam, env, std::nullopt}, stats);
    EXPECT_EQ(again.color->pixels, expected.color.pixels);
    EXPECT_EQ(again.depth->pixels, expected.depth.pixels);
}

TEST(VoxelSwapImages, FramesRenderedIntoLentBuffersEqualFreshOnes) {
    const DataSet d = make_demo_island({129});
    Environment water = d.environment;
    water.water = true;
    water.water_level = 0.5f * (d.terrain.min_height() + d.terrain.max_height());
    for (const TiltMethod tilt : {TiltMethod::Exact, TiltMethod::Guedes}) {
        MethodSettings settings;
        settings.raycast.tilt = tilt;
        for (const Projection proj : {Projection::Shear, Projection::Tilt})
            for (const double pitch : {0.0, -25.0, 30.0}) {
                SCOPED_TRACE(testing::Message() << "tilt " << to_string(tilt) << " projection "
                                                << int(proj) << " pitch " << pitch);
                const Camera cam = test::across_terrain(d.terrain, 30, pitch, proj);
                expect_swaps_render_over_garbage(d, settings, cam, d.environment);
                expect_swaps_render_over_garbage(d, settings, cam, water);
            }
    }
}

TEST(VoxelSwapImages, OtherMethodsDecline) {
    const DataSet d = make_demo_island({129});
    const MethodSettings settings;
    const std::unique_ptr<TerrainMethod> m = find_terrain_method("mesh")->create({d.terrain, settings, {}});
    ColorImage color;
    EXPECT_FALSE(m->swap_images(color, nullptr));
}

} // namespace
