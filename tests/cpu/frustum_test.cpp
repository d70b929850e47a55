// Gribb-Hartmann plane extraction and Zamri's plane/sphere test (Fig. 4.1) on
// hand-built frustums whose planes can be written down directly.
#include "lod/Frustum.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

using namespace overflight;

namespace {

void expect_plane(const Plane& p, glm::dvec3 n, double d) {
    EXPECT_NEAR(p.normal.x, n.x, 1e-12);
    EXPECT_NEAR(p.normal.y, n.y, 1e-12);
    EXPECT_NEAR(p.normal.z, n.z, 1e-12);
    EXPECT_NEAR(p.d, d, 1e-12);
}

} // namespace

// glm::ortho(-1, 1, -1, 1, 1, 10) with an identity modelview is the box
// -1 <= x <= 1, -1 <= y <= 1, -10 <= z <= -1 (the eye looks down -z), so the
// inward unit planes are x + 1 >= 0, 1 - x >= 0, y + 1 >= 0, 1 - y >= 0,
// -z - 1 >= 0 (near), z + 10 >= 0 (far).
TEST(Frustum, OrthographicPlanesByHand) {
    const Frustum f = Frustum::from_matrix(glm::ortho(-1.0, 1.0, -1.0, 1.0, 1.0, 10.0));
    expect_plane(f.planes[Frustum::Left], {1, 0, 0}, 1);
    expect_plane(f.planes[Frustum::Right], {-1, 0, 0}, 1);
    expect_plane(f.planes[Frustum::Bottom], {0, 1, 0}, 1);
    expect_plane(f.planes[Frustum::Top], {0, -1, 0}, 1);
    expect_plane(f.planes[Frustum::Near], {0, 0, -1}, -1);
    expect_plane(f.planes[Frustum::Far], {0, 0, 1}, 10);
}

// glm::frustum(-1, 1, -1, 1, 1, 10): the side planes pass through the eye
// and the near-plane corners (+-1, +-1, -1), a 45 degree pyramid. The left
// plane contains (0,0,0) and (-1, y, -1): inward normal (1, 0, -1)/sqrt 2, d = 0.
// Normalisation matters: the raw Gribb-Hartmann row sum is (2, 0, -2)-ish
// scaled by the projection; after dividing by |(a,b,c)| the distance of
// (0, 0, -5) to the left plane is 5/sqrt 2.
TEST(Frustum, PerspectivePlanesAreNormalised) {
    const Frustum f = Frustum::from_matrix(glm::frustum(-1.0, 1.0, -1.0, 1.0, 1.0, 10.0));
    const double s = 1.0 / std::sqrt(2.0);
    expect_plane(f.planes[Frustum::Left], {s, 0, -s}, 0);
    expect_plane(f.planes[Frustum::Right], {-s, 0, -s}, 0);
    expect_plane(f.planes[Frustum::Bottom], {0, s, -s}, 0);
    expect_plane(f.planes[Frustum::Top], {0, -s, -s}, 0);
    expect_plane(f.planes[Frustum::Near], {0, 0, -1}, -1);
    expect_plane(f.planes[Frustum::Far], {0, 0, 1}, 10);
    EXPECT_NEAR(f.planes[Frustum::Left].distance({0, 0, -5}), 5 * s, 1e-12);
}

TEST(Frustum, SphereClassificationThreeOutcomes) {
    const Frustum f = Frustum::from_matrix(glm::ortho(-1.0, 1.0, -1.0, 1.0, 1.0, 10.0));
    // Centre (0,0,-5): nearest planes are the four sides at distance 1.
    EXPECT_EQ(f.classify({0, 0, -5}, 0.5), Containment::AllInside);
    EXPECT_EQ(f.classify({0, 0, -5}, 1.5), Containment::Intersect);
    // Centre (5,0,-5): right plane distance 1 - 5 = -4 < -1.
    EXPECT_EQ(f.classify({5, 0, -5}, 1.0), Containment::AllOutside);
    // Touching from outside: distance exactly -r is not outside (conservative).
    EXPECT_EQ(f.classify({2, 0, -5}, 1.0), Containment::Intersect);
}

// The box test on the same box frustum -1 <= x, y <= 1, -10 <= z <= -1:
// each outcome, and a thin box beside a corner that its bounding sphere would
// touch (sphere: INTERSECT) but that lies wholly outside the right plane.
TEST(Frustum, BoxClassificationThreeOutcomes) {
    const Frustum f = Frustum::from_matrix(glm::ortho(-1.0, 1.0, -1.0, 1.0, 1.0, 10.0));
    EXPECT_EQ(f.classify_box({-0.5, -0.5, -6}, {0.5, 0.5, -4}), Containment::AllInside);
    EXPECT_EQ(f.classify_box({0.5, -0.5, -6}, {1.5, 0.5, -4}), Containment::Intersect);
    EXPECT_EQ(f.classify_box({2, -0.5, -6}, {3, 0.5, -4}), Containment::AllOutside);
    EXPECT_EQ(f.classify_box({-0.5, -0.5, -12}, {0.5, 0.5, -11}), Containment::AllOutside); // beyond far
    // A box spanning the whole frustum intersects every plane, but is not outside.
    EXPECT_EQ(f.classify_box({-5, -5, -20}, {5, 5, 5}), Containment::Intersect);
    // Touching from outside (x = 1 exactly) is not outside: conservative.
    EXPECT_EQ(f.classify_box({1, -0.5, -6}, {2, 0.5, -4}), Containment::Intersect);
    // A box 0.1 thick along x at x in [1.05, 1.15], z spanning [-9, -2]: its
    // bounding sphere (radius ~3.5) reaches inside, the box does not.
    const glm::dvec3 lo(1.05, -0.5, -9), hi(1.15, 0.5, -2);
    EXPECT_EQ(f.classify(0.5 * (lo + hi), 0.5 * glm::length(hi - lo)), Containment::Intersect);
    EXPECT_EQ(f.classify_box(lo, hi), Containment::AllOutside);
}

// Zamri's Fig. 4.1 returns INTERSECT at the first straddled plane. This
// sphere straddles the left plane (distance 0) and lies wholly beyond the
// far plane (distance 10 - 12 = -2 < -1.5): it must be culled.
TEST(Frustum, StraddleThenOutsideIsOutside) {
    const Frustum f = Frustum::from_matrix(glm::ortho(-1.0, 1.0, -1.0, 1.0, 1.0, 10.0));
    EXPECT_EQ(f.classify({-1, 0, -12}, 1.5), Containment::AllOutside);
}

// The shared camera: eye at the origin facing south (+Z), 90 degree fov, a
// square image, near 1, far 100. Points ahead are inside, behind are outside.
TEST(Frustum, FromCameraMatchesProjection) {
    Camera cam;
    cam.eye = {0, 0, 0};
    cam.heading = 0;
    cam.pitch = 0;
    cam.fov = 90;
    cam.width = cam.height = 100;
    cam.near = 1;
    cam.far = 100;
    const Frustum f = Frustum::from_camera(cam);
    EXPECT_EQ(f.classify({0, 0, 50}, 1), Containment::AllInside);
    EXPECT_EQ(f.classify({0, 0, -50}, 1), Containment::AllOutside);
    EXPECT_EQ(f.classify({0, 0, 150}, 10), Containment::AllOutside); // beyond far
    EXPECT_EQ(f.classify({0, 0, 100}, 10), Containment::Intersect);  // across far
    // 45 degrees to the side is the edge of a 90 degree fov: a sphere there straddles.
    EXPECT_EQ(f.classify({-50, 0, 50}, 1), Containment::Intersect);
    // Every point projected inside the image is inside all six planes.
    for (double x = -40; x <= 40; x += 20)
        for (double y = -40; y <= 40; y += 20) {
            const glm::dvec3 p(x, y, 60);
            const auto pr = cam.project(p);
            ASSERT_TRUE(pr.col > 0 && pr.col < 100 && pr.row > 0 && pr.row < 100);
            for (const Plane& pl : f.planes) EXPECT_GT(pl.distance(p), 0);
        }
}
