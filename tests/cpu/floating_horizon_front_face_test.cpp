// The terrain's shadow on the Floating Horizon's front faces (raycast/FrontFace.h):
// Algorithm 1 of Szenberg, Gattass, Carvalho, "An Algorithm for the
// Visualization of a Terrain with Objects", SIBGRAPI 1997, paints with each
// sample the span between the near sample's top and its own; where the light
// mask changes between the two, the span's part below their midpoint takes
// the near sample's light, so that a shadow ends halfway between a shadowed
// and a lit sample, as on the mesh. Worked out on level ground for every cast
// and the literal transcription; on the demo island, the speed-ups (run
// skipping, the x86-64-v3 kernel) paint the same bits with the mask as
// without it, and the literal transcription the same pixels.
#include "core/Camera.h"
#include "core/DataSet.h"
#include "core/DemoIsland.h"
#include "core/SunLight.h"
#include "core/Terrain.h"
#include "raycast/FloatingHorizon.h"
#include "raycast/FloatingHorizonLiteral.h"

#include "TestCameras.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

using namespace overflight;

namespace {

const Rgb8 kLit{200, 200, 200}, kShadowed{50, 50, 50};

// Level ground 65x65 (h_scale 1), shadowed from row Z = 32 on: the colors
// lit with that mask and each sample's color under the other light.
struct ShadowedGround {
    Terrain terrain{65, 65, 1.0f};
    std::vector<std::uint8_t> mask;
    std::vector<Rgb8> colors, other;
    LightMask light_mask() const { return {&mask, &other}; }

    ShadowedGround() {
        const std::size_t n = terrain.colors().size();
        mask.resize(n);
        colors.resize(n);
        other.resize(n);
        for (int row = 0; row < 65; ++row)
            for (int col = 0; col < 65; ++col) {
                const std::size_t i = terrain.index(row, col);
                mask[i] = row >= 32;
                colors[i] = mask[i] ? kShadowed : kLit;
                other[i] = mask[i] ? kLit : kShadowed;
            }
    }
};

// Eye at Z = 0 facing south (+Z): the shear camera's slices are at Z = 1, 2,
// ..., on the rows of samples.
Camera ground_camera(Projection proj) {
    Camera c = test::camera_at({32.0, 6.0, 0.0}, 0.0, -20.0, 60.0, 48, 96);
    c.projection = proj;
    return c;
}

// Every terrain pixel whose ray meets the ground nearer than Z = edge - tol
// is lit, farther than edge + tol shadowed; returns the pixels checked.
int expect_edge_at(const ColorImage& color, const DepthImage& depth, const Camera& cam, double edge, double tol,
                   const char* what) {
    int checked = 0;
    for (int r = 0; r < cam.height; ++r)
        for (int c = 0; c < cam.width; ++c) {
            const glm::dvec3 ray = cam.ray(cam.u_of(c), cam.v_of(r));
            if (depth.at(c, r) >= 1.0f || ray.y >= 0) continue;
            const double z = cam.eye.z + (-cam.eye.y / ray.y) * ray.z;
            if (std::abs(z - edge) <= tol) continue;
            ++checked;
            EXPECT_EQ(color.at(c, r), z < edge ? kLit : kShadowed) << what << ": pixel " << c << "," << r << ", ground Z " << z;
        }
    return checked;
}

} // namespace

// Rows 31 (lit) and 32 (shadowed): the mesh's shadow ends at Z = 31.5. The
// shear camera's slices are on the sample rows, so its edge is there exactly
// (before: at Z = 31, where sample 32's span begins); the tilt camera's are
// not, so its edge is between the midpoints of two slices a cell apart,
// within half a cell of it.
TEST(FrontFace, ShadowEndsHalfwayBetweenALitAndAShadowedSample) {
    const ShadowedGround g;
    const Environment env;
    ColorImage color;
    DepthImage depth;
    for (SurfaceModel surface : {SurfaceModel::Blocks, SurfaceModel::Bilinear}) {
        FloatingHorizon fh(g.terrain);
        fh.set_colors(&g.colors, g.light_mask());
        RaycastOptions opt;
        opt.surface = surface;
        const Camera shear = ground_camera(Projection::Shear);
        fh.render(shear, env, opt, color, depth);
        EXPECT_GT(expect_edge_at(color, depth, shear, 31.5, 1e-3, "shear"), 1000);
        const Camera tilt = ground_camera(Projection::Tilt);
        fh.render(tilt, env, opt, color, depth);
        EXPECT_GT(expect_edge_at(color, depth, tilt, 31.5, 0.5, "tilt exact"), 1000);
        opt.tilt = TiltMethod::Guedes;
        fh.render(tilt, env, opt, color, depth);
        EXPECT_GT(expect_edge_at(color, depth, tilt, 31.5, 0.5, "tilt guedes"), 1000);
        render_floating_horizon_literal(g.terrain, env, shear, surface, color, depth, nullptr, &g.colors, nullptr,
                                        g.light_mask());
        EXPECT_GT(expect_edge_at(color, depth, shear, 31.5, 1e-3, "literal"), 1000);
    }
    // Without the mask, the far sample's light paints its whole span.
    FloatingHorizon fh(g.terrain);
    fh.set_colors(&g.colors);
    const Camera shear = ground_camera(Projection::Shear);
    fh.render(shear, env, {}, color, depth);
    EXPECT_GT(expect_edge_at(color, depth, shear, 31.0, 1e-3, "shear without the mask"), 1000);
}

namespace {

// The demo island lit by a low sun with its shadows: colors and light mask.
struct LitDemo {
    DataSet ds = make_demo_island({257});
    Environment env;
    TerrainLighting lighting{ds.terrain};
    const std::vector<Rgb8>* colors = nullptr;
    LitDemo() {
        env = ds.environment;
        env.sun_dir = sun_direction(250.0, 12.0);
        env.shadows = true;
        colors = lighting.colors(env);
    }
};

bool same_images(const ColorImage& c1, const DepthImage& d1, const ColorImage& c2, const DepthImage& d2) {
    return std::memcmp(c1.pixels.data(), c2.pixels.data(), c1.pixels.size() * sizeof(Rgb8)) == 0 &&
           std::memcmp(d1.pixels.data(), d2.pixels.data(), d1.pixels.size() * sizeof(float)) == 0;
}

} // namespace

// A skipped run leaves its last sample unread: the next sample's near half
// reads it back, so skipping still paints every bit as the full cast does.
TEST(FrontFace, SameImageWithAndWithoutSkipping) {
    LitDemo demo;
    ASSERT_NE(demo.lighting.light_mask().shadowed, nullptr);
    FloatingHorizon fh(demo.ds.terrain);
    fh.set_colors(demo.colors, demo.lighting.light_mask());
    ColorImage c1, c2;
    DepthImage d1, d2;
    RaycastStats s1, s2;
    for (Projection proj : {Projection::Shear, Projection::Tilt})
        for (SurfaceModel surface : {SurfaceModel::Blocks, SurfaceModel::Bilinear})
            for (double heading = 0; heading < 360; heading += 45)
                for (double pitch : {-30.0, -12.0, 0.0}) {
                    RaycastOptions skip, full;
                    skip.surface = full.surface = surface;
                    full.skip_runs = false;
                    const Camera cam = test::across_terrain(demo.ds.terrain, heading, pitch, proj);
                    fh.render(cam, demo.env, skip, c1, d1, &s1);
                    fh.render(cam, demo.env, full, c2, d2, &s2);
                    EXPECT_TRUE(same_images(c1, d1, c2, d2)) << "heading " << heading << " pitch " << pitch;
                    EXPECT_LE(s1.samples_visited, s2.samples_visited);
                }
}

// The cast compiled for x86-64-v3 paints the near halves as the portable one does.
TEST(FrontFace, SameImageOnEveryInstructionSet) {
    if (!cast_kernel_available(CastKernel::X86_64_v3)) GTEST_SKIP() << "no x86-64-v3 on this CPU";
    LitDemo demo;
    FloatingHorizon fh(demo.ds.terrain);
    fh.set_colors(demo.colors, demo.lighting.light_mask());
    ColorImage c1, c2;
    DepthImage d1, d2;
    for (Projection proj : {Projection::Shear, Projection::Tilt})
        for (SurfaceModel surface : {SurfaceModel::Blocks, SurfaceModel::Bilinear})
            for (double heading = 0; heading < 360; heading += 45) {
                RaycastOptions portable, v3;
                portable.surface = v3.surface = surface;
                portable.kernel = CastKernel::Portable;
                v3.kernel = CastKernel::X86_64_v3;
                Camera cam = test::across_terrain(demo.ds.terrain, heading, -20.0, proj);
                cam.width = 480;
                cam.height = 270;
                fh.render(cam, demo.env, portable, c1, d1);
                fh.render(cam, demo.env, v3, c2, d2);
                EXPECT_TRUE(same_images(c1, d1, c2, d2)) << "heading " << heading;
            }
}

// The literal transcription splits the spans where the fast caster does:
// the same pixels, as without the mask (FloatingHorizonVsLiteral).
TEST(FrontFace, LiteralAndFastCasterAgree) {
    LitDemo demo;
    FloatingHorizon fh(demo.ds.terrain);
    fh.set_colors(demo.colors, demo.lighting.light_mask());
    ColorImage cf, cl;
    DepthImage df, dl;
    for (SurfaceModel surface : {SurfaceModel::Blocks, SurfaceModel::Bilinear})
        for (double heading = 0; heading < 360; heading += 45) {
            const Camera cam = test::across_terrain(demo.ds.terrain, heading, -20.0, Projection::Shear);
            RaycastOptions opt;
            opt.surface = surface;
            fh.render(cam, demo.env, opt, cf, df);
            render_floating_horizon_literal(demo.ds.terrain, demo.env, cam, surface, cl, dl, nullptr, demo.colors,
                                            nullptr, demo.lighting.light_mask());
            long long close = 0;
            for (std::size_t i = 0; i < cf.pixels.size(); ++i) {
                const Rgb8 a = cf.pixels[i], b = cl.pixels[i];
                close += std::abs(a.r - b.r) <= 2 && std::abs(a.g - b.g) <= 2 && std::abs(a.b - b.b) <= 2;
            }
            EXPECT_GE(double(close) / double(cf.pixels.size()), 0.999) << "heading " << heading;
        }
}
