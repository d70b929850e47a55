// The hovercraft on water (Hovercraft::set_water_level): it rides on the
// higher of the terrain and the water, the paper's physics otherwise as on
// the terrain.
#include "core/Terrain.h"
#include "sim/FlightSession.h"
#include "sim/Hovercraft.h"

#include <gtest/gtest.h>

using namespace overflight;

namespace {

// 5x5 samples, 10 m apart, height = column index metres: rising 0.1 m per
// metre to the east. Water at 2.5 m covers x < 25.
Terrain tilted_plane() {
    Terrain t(5, 5, 10.0f, 1.0f);
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j) t.raw(i, j) = std::uint16_t(j);
    return t;
}

constexpr Controls kAccel{.accelerate = true};

} // namespace

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
