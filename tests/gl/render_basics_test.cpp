// The GL renderer against the camera contract (DESIGN sec. 2) on tiny
// hand-checkable terrains: a real GL 4.5 context, GL matrices vs core Camera
// projection, depth vs the ray caster's depth vector, light and fog values.
#include "core/Camera.h"
#include "core/DataSet.h"
#include "gl/GlContext.h"
#include "gl/HeadlessRenderer.h"
#include "gl/RenderTarget.h"
#include "gl/FrameUniforms.h"
#include "gl/StreamedMesh.h"
#include "methods/TerrainMethod.h"
#include "raycast/DepthVector.h"

#include <epoxy/gl.h>
#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

using namespace overflight;

namespace {

// A flat 5x5 terrain at world height 100 (raw 100, vs 1), 10 m cells, one color.
DataSet flat_terrain(Rgb8 color = {200, 100, 50}) {
    DataSet d;
    d.terrain = Terrain(5, 5, 10.0f);
    for (auto& h : d.terrain.heights()) h = 100;
    for (auto& c : d.terrain.colors()) c = color;
    // Sun straight overhead, white, no ambient, no fog: a flat top is lit by exactly 1.
    d.environment.sun_dir = {0, 1, 0};
    d.environment.sun_color = {1, 1, 1};
    d.environment.ambient = {0, 0, 0};
    d.environment.fog_density = 0;
    return d;
}

Camera looking_down_on_flat() {
    Camera c;
    c.eye = {20, 120, -5};
    c.heading = 0; // south, over the terrain
    c.pitch = -40;
    c.fov = 60;
    c.width = 64;
    c.height = 48;
    c.near = 1;
    c.far = 500;
    return c;
}

// View depth of the plane y = 100 through pixel (col, row), or -1 if the ray misses it upward.
double plane_view_depth(const Camera& c, int col, int row) {
    const glm::dvec3 dir = c.ray(c.u_of(col), c.v_of(row));
    if (dir.y >= 0) return -1;
    return (100.0 - c.eye.y) / dir.y; // component along the view axis is 1
}

} // namespace

TEST(GlContext, HeadlessIsRealOpenGL45Core) {
    gl::HeadlessContext ctx; // must not skip: CI has Mesa
    const std::string renderer = gl::Context::renderer();
    const std::string version = gl::Context::version();
    std::printf("GL_RENDERER: %s\nGL_VERSION: %s\nEGL platform: %s\n", renderer.c_str(), version.c_str(),
                ctx.platform().c_str());
    EXPECT_FALSE(renderer.empty());
    GLint major = 0, minor = 0, profile = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    EXPECT_GE(major * 10 + minor, 45);
    EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
}

TEST(GlProjection, RandomPointsLandOnTheCorePixelWithTheRaycasterDepth) {
    gl::HeadlessContext ctx;
    DataSet data = flat_terrain();
    gl::FrameUniforms frame;
    gl::StreamedMesh mesh;
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> U(-1, 1);
    for (Projection proj : {Projection::Shear, Projection::Tilt}) {
        Camera cam;
        cam.eye = {500, 300, 400};
        cam.heading = 123;
        cam.pitch = proj == Projection::Shear ? 12 : -25;
        cam.fov = 75;
        cam.width = 97;
        cam.height = 61;
        cam.near = 2;
        cam.far = 3000;
        cam.projection = proj;
        gl::RenderTarget target(cam.width, cam.height);
        frame.update(cam, data.environment, data.terrain);
        frame.bind();
        target.bind();
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glClearDepth(1.0);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        const gl::FrameBlock& fb = frame.block();

        // Random points inside the frustum, at view depths 10..2000.
        MeshArrays points;
        std::vector<Camera::Projected> expect;
        std::vector<double> view_depths;
        while (points.positions.size() < 40) {
            const double d = 10 + 1990 * (0.5 + 0.5 * U(rng));
            const glm::dvec3 p = cam.eye + d * cam.ray(U(rng) * cam.width * 0.45, U(rng) * cam.height * 0.45);
            const auto pr = cam.project(p);
            // Same pixel within 0.01 px: the float GL matrix (as the shaders use it) vs core double math.
            const glm::vec4 clip = fb.view_proj * glm::vec4(glm::vec3(p - cam.eye), 1.0f);
            const double gx = (clip.x / clip.w + 1) * 0.5 * cam.width;
            const double gy = cam.height - (clip.y / clip.w + 1) * 0.5 * cam.height;
            EXPECT_NEAR(gx, pr.col, 0.01);
            EXPECT_NEAR(gy, pr.row, 0.01);
            // Rasterised points: keep those clear of pixel edges so the pixel is unambiguous.
            const double fx = pr.col - std::floor(pr.col), fy = pr.row - std::floor(pr.row);
            if (fx < 0.05 || fx > 0.95 || fy < 0.05 || fy > 0.95) continue;
            points.positions.emplace_back(p);
            points.normals.emplace_back(0, 1, 0);
            points.colors.push_back({255, 255, 255});
            expect.push_back(pr);
            view_depths.push_back(cam.view_depth(p));
        }
        // Each point becomes a quad 0.04 px wide facing the camera, drawn in
        // glPolygonMode(GL_POINT) so that its corners rasterise as 1-px points
        // in the pixel that holds the projected point.
        MeshArrays quads;
        const glm::dvec3 R = cam.right(), U2 = cam.view_up();
        for (std::size_t i = 0; i < points.positions.size(); ++i) {
            const glm::dvec3 p(points.positions[i]);
            const double s = 0.02 * view_depths[i] / cam.focal_px();
            const auto base = std::uint32_t(quads.positions.size());
            for (glm::dvec3 o : {-R - U2, R - U2, R + U2, -R + U2}) {
                quads.positions.emplace_back(p + s * o);
                quads.normals.emplace_back(0, 1, 0);
                quads.colors.push_back({255, 255, 255});
            }
            quads.indices.insert(quads.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
        }
        glPolygonMode(GL_FRONT_AND_BACK, GL_POINT);
        mesh.upload(quads);
        mesh.draw();
        glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
        ColorImage color;
        DepthImage depth;
        target.read_color(color);
        target.read_depth(depth);
        std::vector<float> dv;
        for (std::size_t i = 0; i < expect.size(); ++i) {
            const int col = int(std::floor(expect[i].col)), row = int(std::floor(expect[i].row));
            EXPECT_EQ(color.at(col, row).r, 255) << "point " << i << " at " << col << "," << row;
            // Depth vector of the ray caster (Szenberg Algorithm 2) for this view depth.
            depth_vector(cam, view_depths[i], 1.0, 1, dv);
            EXPECT_NEAR(depth.at(col, row), dv[0], 2e-6) << "point " << i;
        }
    }
}

TEST(Compositor, FlatTerrainDepthAndLightAreExactForMeshAndBlocks) {
    DataSet data = flat_terrain();
    gl::HeadlessRenderer renderer(data.terrain, Scene{});
    const Camera cam = looking_down_on_flat();
    for (ResidentSurface m : {ResidentSurface::Mesh, ResidentSurface::TopFaces, ResidentSurface::Blocks}) {
        ColorImage color;
        DepthImage depth;
        renderer.render(MethodOutput::resident(m), cam, data.environment, {}, color, &depth);
        int checked = 0;
        for (int row = 0; row < cam.height; row += 3)
            for (int col = 0; col < cam.width; col += 3) {
                const double d = plane_view_depth(cam, col, row);
                if (d < 0) continue;
                const glm::dvec3 hit = cam.eye + d * cam.ray(cam.u_of(col), cam.v_of(row));
                // Inside the mesh's extent by more than a pixel's footprint.
                if (hit.x < 1 || hit.x > 39 || hit.z < 1 || hit.z > 39) continue;
                ++checked;
                EXPECT_NEAR(depth.at(col, row), cam.window_depth(d), 1e-5) << to_string(m) << " " << col << "," << row;
                const Rgb8 c = color.at(col, row);
                EXPECT_NEAR(c.r, 200, 1);
                EXPECT_NEAR(c.g, 100, 1);
                EXPECT_NEAR(c.b, 50, 1);
            }
        EXPECT_GT(checked, 20) << to_string(m);
    }
}

TEST(Compositor, FogAndSkyFollowTheStatedFormulas) {
    DataSet data = flat_terrain({100, 100, 100});
    data.environment.fog_density = 0.02f;
    data.environment.fog_color = {1, 0, 0};
    data.environment.sky_horizon = {0, 1, 0};
    data.environment.sky_zenith = {0, 0, 1};
    gl::HeadlessRenderer renderer(data.terrain, Scene{});
    Camera cam = looking_down_on_flat();
    cam.pitch = 0; // the upper half of the image is sky
    cam.eye.y = 110;
    ColorImage color;
    DepthImage depth;
    renderer.render(MethodOutput::resident(ResidentSurface::Mesh), cam, data.environment, {}, color, &depth);
    // Sky pixel: s = sin(elevation) of the pixel-centre ray.
    const int col = 40, sky_row = 3;
    const glm::dvec3 dir = glm::normalize(cam.ray(cam.u_of(col), cam.v_of(sky_row)));
    EXPECT_EQ(depth.at(col, sky_row), 1.0f);
    EXPECT_NEAR(color.at(col, sky_row).g, 255 * (1 - dir.y), 1.0);
    EXPECT_NEAR(color.at(col, sky_row).b, 255 * dir.y, 1.0);
    // Terrain pixel: lit 100 grey, fog f = exp(-0.02 * |P - eye|) towards red.
    const int row = cam.height - 2;
    const double d = plane_view_depth(cam, col, row);
    ASSERT_GT(d, 0);
    const double dist = d * glm::length(cam.ray(cam.u_of(col), cam.v_of(row)));
    const double f = std::exp(-0.02 * dist);
    EXPECT_NEAR(color.at(col, row).r, 100 * f + 255 * (1 - f), 1.5);
    EXPECT_NEAR(color.at(col, row).g, 100 * f, 1.5);
}
