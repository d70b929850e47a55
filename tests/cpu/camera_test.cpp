// The camera contract of DESIGN sec. 2: rays, GL matrices and window depth agree.
#include "core/Camera.h"
#include "core/Error.h"

#include <glm/gtc/matrix_access.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace overflight;

namespace {

// Projects with the OpenGL matrices and the default viewport/depth range, as GL would.
glm::dvec3 gl_window(const Camera& cam, const glm::dvec3& p) {
    const glm::dvec4 clip = cam.projection_matrix() * cam.view_matrix() * glm::dvec4(p, 1.0);
    const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
    // Window x from the left, y from the TOP (GL's y is from the bottom), depth in [0,1].
    return {(ndc.x + 1) * 0.5 * cam.width, cam.height - (ndc.y + 1) * 0.5 * cam.height, (ndc.z + 1) * 0.5};
}

Camera make_camera(Projection proj, double heading, double pitch) {
    Camera c;
    c.eye = {100, 50, 200};
    c.heading = heading;
    c.pitch = pitch;
    c.fov = 70;
    c.width = 320;
    c.height = 200;
    c.near = 0.5;
    c.far = 3000;
    c.projection = proj;
    return c;
}

} // namespace

TEST(Camera, HeadingConvention) {
    Camera c;
    c.heading = 0;
    EXPECT_NEAR(c.forward().z, 1.0, 1e-12); // south
    EXPECT_NEAR(c.right().x, -1.0, 1e-12);  // facing south, west is on the right
    c.heading = 90;
    EXPECT_NEAR(c.forward().x, 1.0, 1e-12); // east
    c.heading = 180;
    EXPECT_NEAR(c.forward().z, -1.0, 1e-12); // north
}

TEST(Camera, RayThroughPixelProjectsBackToIt) {
    for (Projection proj : {Projection::Shear, Projection::Tilt}) {
        for (double pitch : {-30.0, 0.0, 15.0}) {
            const Camera c = make_camera(proj, 37, pitch);
            for (int row : {0, 57, 199}) {
                for (int col : {0, 100, 319}) {
                    const glm::dvec3 p = c.eye + 123.0 * c.ray(c.u_of(col), c.v_of(row));
                    const auto pr = c.project(p);
                    EXPECT_NEAR(pr.col, col + 0.5, 1e-9);
                    EXPECT_NEAR(pr.row, row + 0.5, 1e-9);
                    EXPECT_NEAR(c.view_depth(p), 123.0, 1e-9);
                }
            }
        }
    }
}

TEST(Camera, MatchesOpenGLMatricesOnRandomPoints) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> d(-2000, 2000);
    for (Projection proj : {Projection::Shear, Projection::Tilt}) {
        for (double heading : {0.0, 45.0, 200.0, 315.0}) {
            for (double pitch : {-30.0, 0.0, 10.0}) {
                const Camera c = make_camera(proj, heading, pitch);
                int checked = 0;
                while (checked < 200) {
                    const glm::dvec3 p(d(rng), d(rng) * 0.2, d(rng));
                    const auto pr = c.project(p);
                    if (!pr.in_front || c.view_depth(p) < c.near || c.view_depth(p) > c.far) continue;
                    const glm::dvec3 w = gl_window(c, p);
                    EXPECT_NEAR(pr.col, w.x, 0.01);
                    EXPECT_NEAR(pr.row, w.y, 0.01);
                    EXPECT_NEAR(pr.depth, w.z, 1e-9);
                    ++checked;
                }
            }
        }
    }
}

TEST(Camera, WindowDepthIsSzenbergEquation7) {
    Camera c;
    c.near = 1;
    c.far = 1000;
    EXPECT_DOUBLE_EQ(c.window_depth(1), 0.0);
    EXPECT_DOUBLE_EQ(c.window_depth(1000), 1.0);
    EXPECT_NEAR(c.window_depth(10), (1000.0 - 1000.0 / 10.0) / 999.0, 1e-15);
    EXPECT_NEAR(c.view_depth_of_window(c.window_depth(321.5)), 321.5, 1e-9);
}

TEST(Camera, RejectsUnusableCameras) {
    auto rejects = [](auto mutate) {
        Camera c;
        mutate(c);
        EXPECT_THROW(c.validate(), Error);
    };
    rejects([](Camera& c) { c.far = c.near; });
    rejects([](Camera& c) { c.fov = 0; });
    rejects([](Camera& c) { c.fov = 180; });
    rejects([](Camera& c) { c.pitch = 89; });
    rejects([](Camera& c) { c.pitch = -90; });
    rejects([](Camera& c) { c.width = 0; });
    rejects([](Camera& c) { c.height = 16385; });
    rejects([](Camera& c) { c.eye.x = NAN; });
    Camera ok;
    EXPECT_NO_THROW(ok.validate());
}
