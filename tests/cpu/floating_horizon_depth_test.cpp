// The depth vector of Szenberg 1997 (eq. 7, Algorithm 2) against OpenGL's own
// projection math (glm::frustum, glm::lookAt, the default depth range).
#include "core/Camera.h"
#include "raycast/DepthVector.h"

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>

#include <random>

using namespace overflight;

TEST(DepthVector, MatchesGlProjectionOnRandomPoints) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    for (int trial = 0; trial < 200; ++trial) {
        Camera cam;
        cam.eye = {U(rng) * 1000, U(rng) * 300, U(rng) * 1000};
        cam.heading = U(rng) * 360;
        cam.pitch = -40 + 70 * U(rng);
        cam.fov = 30 + 60 * U(rng);
        cam.width = 320;
        cam.height = 200;
        cam.near = 0.5 + 5 * U(rng);
        cam.far = cam.near + 100 + 4000 * U(rng);
        const double step = 0.5 + 20 * U(rng);
        const int count = int((cam.far - cam.near) / step) + 1;
        std::vector<float> depth;
        depth_vector(cam, cam.near, step, count, depth);
        ASSERT_EQ(int(depth.size()), count);
        // GL math built here from the frustum of DESIGN sec. 2 (shear: off-axis).
        const double t = std::tan(glm::radians(cam.fov) * 0.5), asp = double(cam.height) / cam.width;
        const double sh = std::tan(glm::radians(cam.pitch));
        const glm::dmat4 P = glm::frustum(-cam.near * t, cam.near * t, cam.near * (-asp * t + sh),
                                          cam.near * (asp * t + sh), cam.near, cam.far);
        const glm::dvec3 F = cam.forward();
        const glm::dmat4 V = glm::lookAt(cam.eye, cam.eye + F, glm::dvec3(0, 1, 0));
        for (int s = 0; s < 20; ++s) {
            const int k = int(U(rng) * count) % count;
            const double d = cam.near + k * step;
            // A random point of slice k: anywhere sideways and vertically in the plane at view depth d.
            const glm::dvec3 p = cam.eye + d * F + (U(rng) - 0.5) * d * cam.right() + glm::dvec3(0, (U(rng) - 0.5) * d, 0);
            const glm::dvec4 clip = P * V * glm::dvec4(p, 1.0);
            const double gl_depth = (clip.z / clip.w + 1.0) * 0.5;
            EXPECT_NEAR(depth[std::size_t(k)], gl_depth, 2e-6 + 1e-6 * std::abs(gl_depth)) << "trial " << trial << " k " << k;
        }
        EXPECT_NEAR(depth.front(), 0.0f, 1e-6); // first slice at near
    }
}

TEST(DepthVector, LastSliceAtFarIsOne) {
    Camera cam;
    cam.near = 1;
    cam.far = 2049;
    std::vector<float> depth;
    depth_vector(cam, 1.0, 1.0, 2049, depth);
    EXPECT_FLOAT_EQ(depth.back(), 1.0f);
    for (std::size_t k = 1; k < depth.size(); ++k) ASSERT_GT(depth[k], depth[k - 1]); // strictly increasing
}
