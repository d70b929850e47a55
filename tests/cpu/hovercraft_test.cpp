// Hovercraft physics of CMSC 23700 project 2a sec. 3.2 on height fields small enough to work
// the expected values out by hand, plus the map-edge and surface properties on
// the demo island.
#include "core/DemoIsland.h"
#include "core/Error.h"
#include "core/Terrain.h"
#include "sim/FlightSession.h"
#include "sim/Hovercraft.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace overflight;

namespace {

// 5x5 samples, 10 m apart, height = column index metres: a plane rising 0.1 m
// per metre to the east (+X), flat along Z. Extent 40 x 40 m.
Terrain tilted_plane() {
    Terrain t(5, 5, 10.0f, 1.0f);
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j) t.raw(i, j) = std::uint16_t(j);
    return t;
}

Terrain flat(int n = 9, float hs = 10.0f) { return Terrain(n, n, hs, 1.0f); }

constexpr Controls kNone{};
constexpr Controls kAccel{.accelerate = true};
constexpr Controls kBrake{.brake = true};
constexpr Controls kLeft{.left = true};
constexpr Controls kRight{.right = true};

} // namespace

TEST(HovercraftSlope, TiltedPlaneBothMethods) {
    const Terrain t = tilted_plane();
    for (SlopeMethod m : {SlopeMethod::Ahead, SlopeMethod::TriangleNormal}) {
        SCOPED_TRACE(to_string(m));
        // East (h = 90) climbs 0.1 per metre: s = (1, 0.1, 0) / sqrt(1.01).
        glm::dvec3 s = slope_vector(t, 20, 20, 90, m);
        EXPECT_NEAR(s.x, 1 / std::sqrt(1.01), 1e-12);
        EXPECT_NEAR(s.y, 0.1 / std::sqrt(1.01), 1e-12);
        EXPECT_NEAR(s.z, 0.0, 1e-12);
        // West descends.
        s = slope_vector(t, 20, 20, 270, m);
        EXPECT_NEAR(s.y, -0.1 / std::sqrt(1.01), 1e-12);
        // South (h = 0) runs along the contour: no rise, s = (0, 0, 1).
        s = slope_vector(t, 20, 20, 0, m);
        EXPECT_NEAR(s.y, 0.0, 1e-12);
        EXPECT_NEAR(s.z, 1.0, 1e-12);
        // North-east (h = 135): rise 0.1 sin 135 = 0.0707107 per metre.
        s = slope_vector(t, 20, 20, 135, m);
        const double rise = 0.1 * std::sqrt(0.5);
        EXPECT_NEAR(s.y, rise / std::sqrt(1 + rise * rise), 1e-12);
    }
}

TEST(HovercraftSlope, TriangleOfTheBintreeMesh) {
    // 3x3, 1 m apart, zero but for the centre sample at 4 m. Cell (0,0) has
    // r+c even: diagonal (0,0)-(1,1); cell (0,1) is odd: diagonal (0,2)-(1,1).
    Terrain t(3, 3, 1.0f, 1.0f);
    t.raw(1, 1) = 4;
    // (x 0.75, z 0.25) is in the upper-right triangle of cell (0,0): corners
    // 0 (0,0), 0 (0,1), 4 (1,1): dh/dx = 0, dh/dz = 4, height 4 * 0.25 = 1.
    EXPECT_NEAR(mesh_height(t, 0.75, 0.25), 1.0, 1e-12);
    EXPECT_NEAR(t.height_bilinear(0.75f, 0.25f), 0.75f, 1e-6f); // bilinear differs: 4 * .75 * .25
    // (0.25, 0.75): lower-left triangle, corners 0 (0,0), 0 (1,0), 4 (1,1): dh/dx = 4, height 1.
    EXPECT_NEAR(mesh_height(t, 0.25, 0.75), 1.0, 1e-12);
    // (1.25, 0.25): upper-left triangle of cell (0,1), corners 0 (0,1), 0 (0,2), 4 (1,1):
    // dh/dx = 0, dh/dz = 4, height 1. (1.75, 0.75): lower-right triangle, corners
    // 0 (0,2), 4 (1,1), 0 (1,2): dh/dx = -4, dh/dz = 0, height 4 - 4 * 0.75 = 1.
    EXPECT_NEAR(mesh_height(t, 1.25, 0.25), 1.0, 1e-12);
    EXPECT_NEAR(mesh_height(t, 1.75, 0.75), 1.0, 1e-12);
    EXPECT_NEAR(mesh_height(t, 1.0, 1.0), 4.0, 1e-12);
    // Second method at (0.75, 0.25): facing south the triangle rises 4 per metre,
    // s = (0, 4, 1) / sqrt(17); facing east it is level, s = (1, 0, 0).
    glm::dvec3 s = slope_vector(t, 0.75, 0.25, 0, SlopeMethod::TriangleNormal);
    EXPECT_NEAR(s.y, 4 / std::sqrt(17.0), 1e-12);
    EXPECT_NEAR(s.z, 1 / std::sqrt(17.0), 1e-12);
    s = slope_vector(t, 0.75, 0.25, 90, SlopeMethod::TriangleNormal);
    EXPECT_NEAR(s.y, 0.0, 1e-12);
    // First method at (0.75, 0.25) facing east, probe 0.25 m: bilinear 4*1*.25 - 0.75 = 0.25
    // over 0.25 m, rise 1: s = (1, 1, 0) / sqrt 2.
    s = slope_vector(t, 0.75, 0.25, 90, SlopeMethod::Ahead, 0.25);
    EXPECT_NEAR(s.y, std::sqrt(0.5), 1e-6);
}

TEST(Hovercraft, FirstStepsUphillFromRestByHand) {
    // On the tilted plane heading east, accelerating from rest:
    //   g  = 9.8 * 0.1 / sqrt(1.01)                       = 0.9751364464
    // step 1: a = 8, f = 6e-4, v' = 0 - 0.01 (6e-4 + g)   = -0.0097573645
    //         v1 = v' + 0.01 * 8                         =  0.0702426355
    //         x1 = 20 + 0.01 * v1                         = 20.0007024264
    // step 2: a = 8 - v1^2/16                             =  7.9996916233
    //         f = 6e-4 + 2e-4 v1 + 4e-4 v1^2              =  0.0006160221
    //         v2 = v1 - 0.01 (f + g) + 0.01 a             =  0.1404820271
    //         x2 = x1 + 0.01 v2                           = 20.0021072466
    // step 3: v3 = 0.2107119682, x3 = 20.0042143663
    const Terrain t = tilted_plane();
    for (SlopeMethod m : {SlopeMethod::Ahead, SlopeMethod::TriangleNormal}) {
        SCOPED_TRACE(to_string(m));
        HovercraftParams p;
        p.slope = m;
        Hovercraft hc(t, 20, 20, 90, p);
        EXPECT_DOUBLE_EQ(hc.state().y, 2.0 + 2.0); // terrain 2 m at x = 20, plus 2 m altitude
        hc.step(kAccel);
        EXPECT_NEAR(hc.state().velocity, 0.0702426355, 1e-9);
        EXPECT_NEAR(hc.state().x, 20.0007024264, 1e-9);
        EXPECT_NEAR(hc.state().z, 20.0, 1e-12);
        EXPECT_DOUBLE_EQ(hc.state().heading, 90.0);
        hc.step(kAccel);
        EXPECT_NEAR(hc.state().velocity, 0.1404820271, 1e-9);
        EXPECT_NEAR(hc.state().x, 20.0021072466, 1e-9);
        hc.step(kAccel);
        EXPECT_NEAR(hc.state().velocity, 0.2107119682, 1e-9);
        EXPECT_NEAR(hc.state().x, 20.0042143663, 1e-9);
        EXPECT_NEAR(hc.state().y, 2.0 + 2.00042143663, 1e-5); // float terrain lookup
    }
}

TEST(Hovercraft, FlatFirstStepAndRestStaysAtRest) {
    const Terrain t = flat();
    Hovercraft hc(t, 40, 40, 0);
    hc.step(kNone);
    EXPECT_EQ(hc.state().velocity, 0.0); // friction alone cannot push it backwards
    EXPECT_EQ(hc.state().x, 40.0);
    EXPECT_EQ(hc.state().z, 40.0);
    // Accelerating on the flat: v1 = 0.01 (8 - 6e-4) = 0.079994, straight south.
    hc.step(kAccel);
    EXPECT_NEAR(hc.state().velocity, 0.079994, 1e-12);
    EXPECT_NEAR(hc.state().z, 40.00079994, 1e-12);
    EXPECT_NEAR(hc.state().x, 40.0, 1e-12);
}

TEST(Hovercraft, DownhillFromRestSlidesUphillDoesNot) {
    const Terrain t = tilted_plane();
    // Facing west (downhill) with no key: v1 = -0.01 (6e-4 - g) = 0.0097453645.
    Hovercraft down(t, 20, 20, 270);
    down.step(kNone);
    EXPECT_NEAR(down.state().velocity, 0.0097453645, 1e-9);
    EXPECT_LT(down.state().x, 20.0);
    // Facing east (uphill) it stays put.
    Hovercraft up(t, 20, 20, 90);
    up.step(kNone);
    EXPECT_EQ(up.state().velocity, 0.0);
    EXPECT_EQ(up.state().x, 20.0);
}

TEST(Hovercraft, UphillSlowsDownhillSpeedsUp) {
    // The same throttle for one second on a plane: uphill < level < downhill.
    // Start close to the far edge so no run reaches it.
    const Terrain t = tilted_plane();
    Hovercraft up(t, 10, 20, 90), level(t, 20, 10, 0), down(t, 30, 20, 270);
    for (int i = 0; i < 100; ++i) {
        up.step(kAccel);
        level.step(kAccel);
        down.step(kAccel);
    }
    EXPECT_LT(up.state().velocity, level.state().velocity);
    EXPECT_LT(level.state().velocity, down.state().velocity);
    // With the engine off, a moving vehicle slows going uphill and gains going down.
    const double vu = up.state().velocity, vd = down.state().velocity;
    up.step(kNone);
    down.step(kNone);
    EXPECT_LT(up.state().velocity, vu);
    EXPECT_GT(down.state().velocity, vd);
}

TEST(Hovercraft, TurningLeftIncreasesHeadingRightDecreases) {
    const Terrain t = flat();
    // At rest the turn is t / l = 24 / 32 = 0.75 degrees per step.
    Hovercraft left(t, 40, 40, 0), right(t, 40, 40, 0);
    left.step(kLeft);
    right.step(kRight);
    EXPECT_DOUBLE_EQ(left.state().heading, 0.75);
    EXPECT_DOUBLE_EQ(right.state().heading, 359.25);
    // Turning uses the NEW velocity: accelerating from rest, v1 = 0.079994,
    // dh = 24 / (0.079994^2 + 32) = 0.7498500525.
    Hovercraft both(t, 40, 40, 10);
    both.step(Controls{.accelerate = true, .left = true});
    EXPECT_NEAR(both.state().heading, 10.7498500525, 1e-9);
    // The step moves along the new heading: (sin, cos) of 10.7498500525 degrees.
    const double h = 10.7498500525 * 3.14159265358979323846 / 180;
    EXPECT_NEAR(both.state().x, 40 + 0.01 * 0.079994 * std::sin(h), 1e-12);
    EXPECT_NEAR(both.state().z, 40 + 0.01 * 0.079994 * std::cos(h), 1e-12);
    // Left and right together cancel.
    Hovercraft none(t, 40, 40, 10);
    none.step(Controls{.left = true, .right = true});
    EXPECT_DOUBLE_EQ(none.state().heading, 10.0);
    // Faster vehicles turn slower: t / (v^2 + l).
    Hovercraft fast(t, 40, 40, 0), slow(t, 40, 40, 0);
    for (int i = 0; i < 200; ++i) fast.step(kAccel);
    const double h0 = fast.state().heading;
    fast.step(kLeft);
    slow.step(kLeft);
    EXPECT_LT(fast.state().heading - h0, slow.state().heading);
    EXPECT_GT(fast.state().heading - h0, 0.0);
}

TEST(Hovercraft, BrakingReachesZeroAndNeverGoesNegative) {
    const Terrain t = flat(33, 10.0f);
    Hovercraft hc(t, 160, 20, 0);
    for (int i = 0; i < 300; ++i) hc.step(kAccel);
    double v = hc.state().velocity;
    ASSERT_GT(v, 5.0);
    int steps = 0;
    while (hc.state().velocity > 0 && steps < 100000) {
        hc.step(kBrake);
        ASSERT_LT(hc.state().velocity, v); // strictly slowing every step
        ASSERT_GE(hc.state().velocity, 0.0);
        v = hc.state().velocity;
        ++steps;
    }
    EXPECT_EQ(hc.state().velocity, 0.0);
    const glm::dvec2 stopped(hc.state().x, hc.state().z);
    for (int i = 0; i < 50; ++i) {
        hc.step(kBrake);
        EXPECT_EQ(hc.state().velocity, 0.0);
    }
    EXPECT_EQ(hc.state().x, stopped.x);
    EXPECT_EQ(hc.state().z, stopped.y);
    // Braking and accelerating together: both terms apply, v1 = 0.01 (8 - 6e-4 - 0.6).
    Hovercraft both(t, 160, 160, 0);
    both.step(Controls{.accelerate = true, .brake = true});
    EXPECT_NEAR(both.state().velocity, 0.073994, 1e-12);
}

TEST(Hovercraft, TopSpeedOnTheFlatIsBoundedByTheSpeedLimit) {
    // a = 8 - v^2/16 vanishes at v = sqrt(128) = 11.31; friction keeps it below.
    const Terrain t = flat(65, 10.0f);
    Hovercraft hc(t, 320, 0, 0);
    for (int i = 0; i < 5000; ++i) hc.step(kAccel); // 50 s, 500 m of 640
    EXPECT_LT(hc.state().velocity, std::sqrt(128.0));
    EXPECT_GT(hc.state().velocity, 10.0);
}

TEST(Hovercraft, BouncesOffEveryEdge) {
    const Terrain t = flat(5, 10.0f); // 40 x 40 m
    struct Case { double x, z, heading, expected_heading; };
    // Heading reflected: h -> -h at west/east edges, h -> 180 - h at north/south.
    for (const Case c : {Case{39.99, 20, 90, 270}, Case{0.01, 20, 270, 90},
                         Case{20, 39.99, 0, 180}, Case{20, 0.01, 180, 0}}) {
        SCOPED_TRACE(c.heading);
        Hovercraft hc(t, c.x, c.z, c.heading);
        for (int i = 0; i < 30; ++i) hc.step(kAccel); // far enough to cross the edge
        EXPECT_EQ(hc.bounces(), 1);
        EXPECT_NEAR(hc.state().heading, c.expected_heading, 1e-9);
        EXPECT_GE(hc.state().x, 0.0);
        EXPECT_LE(hc.state().x, 40.0);
        EXPECT_GE(hc.state().z, 0.0);
        EXPECT_LE(hc.state().z, 40.0);
    }
    // A corner flips both components: from heading 45 (south-east) to 225.
    Hovercraft corner(t, 39.999, 39.999, 45);
    for (int i = 0; i < 30; ++i) corner.step(kAccel);
    EXPECT_NEAR(corner.state().heading, 225.0, 1e-9);
}

TEST(Hovercraft, RejectsAStartOffTheMap) {
    const Terrain t = flat(5, 10.0f);
    EXPECT_THROW(Hovercraft(t, -1, 20, 0), Error);
    EXPECT_THROW(Hovercraft(t, 20, 40.5, 0), Error);
    EXPECT_THROW(Hovercraft(t, std::nan(""), 20, 0), Error);
    EXPECT_THROW(Hovercraft(t, 20, 20, std::numeric_limits<double>::infinity()), Error);
    EXPECT_NO_THROW(Hovercraft(t, 40, 0, 0)); // the edge itself is on the map
    EXPECT_DOUBLE_EQ(Hovercraft(t, 20, 20, -90).state().heading, 270.0);
}

TEST(Hovercraft, MillionRandomKeyStepsStayOnTheMapAndAboveTheSurface) {
    // Demo island 257 (2.56 km, mountains to 1.4 km): random key combinations
    // held for random spells, as a person would press them, long enough to
    // reach speed, climb, slide down slopes and bounce off the edges.
    const DataSet ds = make_demo_island({.size = 257});
    const Terrain& t = ds.terrain;
    for (SlopeMethod m : {SlopeMethod::Ahead, SlopeMethod::TriangleNormal}) {
        SCOPED_TRACE(to_string(m));
        HovercraftParams p;
        p.slope = m;
        Hovercraft hc(t, ds.start.x, ds.start.z, ds.start.heading, p);
        std::mt19937 rng(m == SlopeMethod::Ahead ? 7u : 8u);
        const long steps = m == SlopeMethod::Ahead ? 1000000 : 200000;
        Controls keys;
        long hold = 0, failures = 0;
        double max_v = 0;
        for (long i = 0; i < steps; ++i) {
            if (hold-- <= 0) {
                const unsigned r = rng();
                // Accelerate most of the time so the vehicle actually travels.
                keys = Controls{(r & 3u) != 0, (r & 12u) == 12u, (r & 16u) != 0, (r & 32u) != 0};
                hold = long(rng() % 300);
            }
            hc.step(keys);
            const HovercraftState& s = hc.state();
            const bool ok = std::isfinite(s.velocity) && s.velocity >= 0 && s.x >= 0 && s.z >= 0 &&
                            s.x <= t.width() && s.z <= t.depth() && s.heading >= 0 && s.heading < 360 &&
                            s.y >= double(t.height_bilinear(float(s.x), float(s.z))) + 2.0 - 1e-3 &&
                            s.y >= mesh_height(t, s.x, s.z) + 2.0 - 1e-9;
            if (!ok && failures++ < 5)
                ADD_FAILURE() << "step " << i << ": x " << s.x << " z " << s.z << " y " << s.y << " v "
                              << s.velocity << " h " << s.heading;
            max_v = std::max(max_v, s.velocity);
        }
        EXPECT_EQ(failures, 0);
        EXPECT_GT(max_v, 5.0); // it did get going
        RecordProperty(std::string("bounces_") + to_string(m), std::to_string(hc.bounces()));
    }
}

// On water (Hovercraft::set_water_level) the vehicle rides on the higher of the
// terrain and the water, the paper's physics otherwise as on the terrain.
TEST(HovercraftWater, RidesOnTheWaterAndItsLevelSurface) {
    const Terrain t = tilted_plane();
    Hovercraft hc(t, 10, 20, 90); // terrain 1 m, heading east (uphill)
    hc.set_water_level(2.5);
    hc.step(kAccel);
    // Over water the surface is level: no gravity term. v1 = 0.01 (8 - 6e-4).
    EXPECT_NEAR(hc.state().velocity, 0.079994, 1e-12);
    EXPECT_NEAR(hc.state().x, 10.00079994, 1e-12);
    EXPECT_DOUBLE_EQ(hc.state().y, 2.5 + 2.0); // the water, plus 2 m altitude
    // Without water the same step climbs the terrain (g = 0.9751364464):
    // v1 = 0.01 (8 - 6e-4 - g) = 0.0702426355, and rides 2 m above it.
    Hovercraft dry(t, 10, 20, 90);
    dry.step(kAccel);
    EXPECT_NEAR(dry.state().velocity, 0.0702426355, 1e-9);
    EXPECT_NEAR(dry.state().y, 1.00007024264 + 2.0, 1e-5);
    // Above the water line (terrain 3 m at x = 30) the terrain is the ground.
    Hovercraft shore(t, 30, 20, 90);
    shore.set_water_level(2.5);
    shore.step(kAccel);
    EXPECT_NEAR(shore.state().velocity, 0.0702426355, 1e-9);
    EXPECT_NEAR(shore.state().y, 3.00007024264 + 2.0, 1e-5);
}

TEST(HovercraftWater, TheWaterKeyFloodsToTheSeaLevelAndLiftsTheVehicle) {
    const Terrain t = tilted_plane(); // heights 0..4: the sea level is 0
    Environment env;
    env.sea_level = 2.5f;
    FlightSessionOptions o;
    o.frames = 3;
    o.start = {true, 10.0, 20.0, 90.0};
    o.script = KeyScript({parse_press("water:1-2")});
    FlightSession s(t, env, o);
    ASSERT_EQ(s.water_level(), 2.5);
    s.begin_frame();
    s.advance(0.0);
    EXPECT_FALSE(s.environment().water);
    s.end_frame();
    s.begin_frame();
    s.advance(0.0);
    EXPECT_TRUE(s.environment().water);
    EXPECT_EQ(s.environment().water_level, 2.5f);
    EXPECT_DOUBLE_EQ(s.vehicle().y, 4.5);
}
