// The chase camera of CMSC 23700 project 2a sec. 3.2 (last paragraph): behind and above the
// vehicle, aimed at a point ahead, with exponentially damped pitch.
#include "core/Terrain.h"
#include "sim/ChaseCamera.h"
#include "sim/Hovercraft.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace overflight;

namespace {
constexpr double kPi = 3.14159265358979323846;

// 65x65 samples 1 m apart: flat at 0 for z < 32, then a ramp rising 0.5 m per
// metre southwards (+Z).
Terrain ramp() {
    Terrain t(65, 65, 1.0f, 0.5f);
    for (int i = 0; i < 65; ++i)
        for (int j = 0; j < 65; ++j) t.raw(i, j) = std::uint16_t(i < 32 ? 0 : i - 32);
    return t;
}
} // namespace

TEST(ChaseCamera, BehindAndAboveLookingLevelOnTheFlat) {
    const Terrain t(65, 65, 1.0f, 1.0f);
    Hovercraft hc(t, 32, 32, 90); // facing east
    ChaseCamera chase; // 12 behind, 4 above, looks 30 ahead
    Camera cam;
    chase.reset(t, hc.state(), cam);
    EXPECT_NEAR(cam.eye.x, 32 - 12, 1e-9);
    EXPECT_NEAR(cam.eye.z, 32, 1e-9);
    EXPECT_NEAR(cam.eye.y, 2 + 4, 1e-9);
    EXPECT_DOUBLE_EQ(cam.heading, 90);
    // Look-at point 30 m ahead at vehicle height 2: down by atan(4 / 42).
    EXPECT_NEAR(cam.pitch, -std::atan(4.0 / 42.0) * 180 / kPi, 1e-9);
    // The vehicle is in view, below the image centre.
    cam.width = 320;
    cam.height = 200;
    const Camera::Projected p = cam.project({hc.state().x, hc.state().y, hc.state().z});
    EXPECT_TRUE(p.in_front);
    EXPECT_NEAR(p.col, 160, 1e-6);
    EXPECT_GT(p.row, 100);
    EXPECT_LT(p.row, 200);
}

TEST(ChaseCamera, PitchFollowsASlopeWithExponentialDamping) {
    const Terrain t = ramp();
    // Facing south at z = 10: the look-at point (z = 40) is 4 m up the ramp.
    HovercraftState s;
    s.x = 32;
    s.z = 10;
    s.heading = 0;
    s.y = 2;
    ChaseParams params;
    params.smoothing = 0.25;
    ChaseCamera chase(params);
    const double target = chase.target_pitch(t, s);
    EXPECT_NEAR(target, std::atan2((4.0 + 2.0) - 6.0, 42.0) * 180 / kPi, 1e-9); // level: eye at 6, target at 6
    // Start from the flat view, then put the look-at point on the ramp.
    Camera cam;
    HovercraftState flat = s;
    flat.z = 0;
    chase.reset(t, flat, cam);
    const double p0 = cam.pitch;
    s.z = 20; // look-at at z = 50: 9 m up the ramp, eye (z = 8) at 6
    const double t1 = chase.target_pitch(t, s);
    EXPECT_NEAR(t1, std::atan2(11.0 - 6.0, 42.0) * 180 / kPi, 1e-9);
    // After dt = tau the pitch covered 1 - 1/e of the way, and never overshoots.
    chase.update(t, s, 0.25, cam);
    EXPECT_NEAR(cam.pitch, p0 + (t1 - p0) * (1 - std::exp(-1.0)), 1e-9);
    for (int i = 0; i < 100; ++i) {
        chase.update(t, s, 0.05, cam);
        EXPECT_LE(cam.pitch, t1 + 1e-12);
    }
    EXPECT_NEAR(cam.pitch, t1, 1e-6);
}

TEST(ChaseCamera, DampingIsFrameRateIndependent) {
    const Terrain t = ramp();
    HovercraftState a;
    a.x = 32;
    a.z = 0;
    a.y = 2;
    HovercraftState b = a;
    b.z = 20;
    ChaseCamera one, many;
    Camera c1, c2;
    one.reset(t, a, c1);
    many.reset(t, a, c2);
    one.update(t, b, 0.2, c1);
    for (int i = 0; i < 8; ++i) many.update(t, b, 0.025, c2);
    EXPECT_NEAR(c1.pitch, c2.pitch, 1e-9);
}

TEST(ChaseCamera, EyeStaysAboveTheGroundBehind) {
    // Vehicle at the foot of the ramp facing north (away from it): the eye 12 m
    // behind is over the ramp, which is higher than the vehicle.
    const Terrain t = ramp();
    HovercraftState s;
    s.x = 32;
    s.z = 36;
    s.heading = 180;
    s.y = ground_height(t, s.x, s.z) + 2;
    ChaseCamera chase;
    Camera cam;
    chase.reset(t, s, cam);
    EXPECT_NEAR(cam.eye.z, 48, 1e-9);
    EXPECT_GE(cam.eye.y, ground_height(t, cam.eye.x, cam.eye.z) + 1.0 - 1e-9);
    EXPECT_GT(cam.eye.y, s.y + 4); // the ramp (8 m at z = 48) pushed it up
    EXPECT_LE(std::abs(cam.pitch), 60.0);
    EXPECT_NO_THROW(cam.validate());
}
