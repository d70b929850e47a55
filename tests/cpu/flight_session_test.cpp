// The flight of `fly` without a window (sim/FlightSession): scripted keys,
// fixed-step physics, toggles and commands, the chase camera and the record.
#include "core/DemoIsland.h"
#include "core/Error.h"
#include "core/SunLight.h"
#include "sim/FlightSession.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>

using namespace overflight;

namespace {

const DataSet& island() {
    static const DataSet d = make_demo_island({.size = 65});
    return d;
}

FlightSessionOptions scripted(long long frames, std::vector<ScriptedPress> presses) {
    FlightSessionOptions o;
    o.frames = frames;
    o.script = KeyScript(std::move(presses));
    return o;
}

// Runs an unattended session to its end; returns the commands per frame.
std::vector<std::vector<Key>> fly(FlightSession& s) {
    std::vector<std::vector<Key>> commands;
    while (!s.finished()) {
        commands.push_back(s.begin_frame());
        s.advance(0.0); // unattended: the wall clock is ignored
        s.end_frame();
    }
    return commands;
}

} // namespace

TEST(FlightSession, ScriptedFlightIsTheSimulationOfItsPhysicsSteps) {
    const DataSet& d = island();
    FlightSession s(d.terrain, d.environment, scripted(90, {{Key::Accelerate, 0, 90}, {Key::Left, 30, 60}}));
    fly(s);
    ASSERT_EQ(s.record().frames.size(), 90u);
    // 90 frames of 1/60 s in 10 ms steps: 150 steps, give or take the rounding of the accumulator.
    EXPECT_NEAR(double(s.physics_steps()), 150.0, 1.0);

    // The same keys on a bare Hovercraft, the steps of each frame drained from
    // a clock fed 1/60 s per frame: the frame a step falls in decides its keys.
    Hovercraft h(d.terrain, d.terrain.width() * 0.5, d.terrain.depth() * 0.5, 0.0);
    FixedStepClock clock(0.01);
    long long steps_total = 0;
    for (int frame = 0; frame < 90; ++frame) {
        const int steps = clock.advance(1.0 / 60.0);
        steps_total += steps;
        for (int i = 0; i < steps; ++i) h.step(Controls{true, false, frame >= 30 && frame < 60, false});
    }
    EXPECT_EQ(s.physics_steps(), steps_total);
    const FlightFrame& last = s.record().frames.back();
    EXPECT_EQ(last.x, h.state().x);
    EXPECT_EQ(last.z, h.state().z);
    EXPECT_EQ(last.velocity, h.state().velocity);
    EXPECT_EQ(last.vehicle_heading, h.state().heading);
    EXPECT_GT(last.velocity, 1.0);
    EXPECT_NEAR(last.time, 90.0 / 60.0, 1e-9);
    EXPECT_TRUE(last.keys.accelerate);
    EXPECT_FALSE(last.keys.left);
    EXPECT_TRUE(s.record().frames[45].keys.left);
}

TEST(FlightSession, SameScriptSameFlightBitForBit) {
    const DataSet& d = island();
    const auto script = std::vector<ScriptedPress>{{Key::Accelerate, 0, 50}, {Key::Right, 10, 40}, {Key::Brake, 45, 60}};
    FlightSession a(d.terrain, d.environment, scripted(60, script));
    FlightSession b(d.terrain, d.environment, scripted(60, script));
    fly(a);
    fly(b);
    EXPECT_EQ(a.record(), b.record());
    // The chase camera follows above the ground, behind the vehicle, looking along its heading.
    for (const FlightFrame& f : a.record().frames) {
        EXPECT_GT(f.eye.y, d.terrain.height_bilinear(float(f.eye.x), float(f.eye.z)));
        EXPECT_TRUE(std::isfinite(f.pitch) && std::abs(f.pitch) < 89.0);
    }
}

TEST(FlightSession, CommandKeysToggleTheViewOrReachTheCaller) {
    const DataSet& d = island();
    FlightSession s(d.terrain, d.environment,
                    scripted(10, {{Key::Fog, 2, 3},
                                  {Key::Wireframe, 3, 4},
                                  {Key::Lighting, 3, 4},
                                  {Key::NextMethod, 5, 6},
                                  {Key::DetailUp, 5, 6},
                                  {Key::Screenshot, 7, 9},
                                  {Key::Hud, 8, 9}}));
    const FogMode fog0 = s.toggles().fog;
    std::vector<ViewToggles> toggles;
    std::vector<std::vector<Key>> commands;
    while (!s.finished()) {
        commands.push_back(s.begin_frame());
        toggles.push_back(s.toggles());
        s.advance(0.0);
        s.end_frame();
    }
    ASSERT_EQ(commands.size(), 10u);
    EXPECT_EQ(toggles[1].fog, fog0);
    EXPECT_EQ(toggles[2].fog, next_fog_mode(fog0));
    EXPECT_FALSE(toggles[2].wireframe);
    EXPECT_TRUE(toggles[3].wireframe);
    EXPECT_FALSE(toggles[3].lighting);
    EXPECT_TRUE(toggles[7].hud);
    EXPECT_FALSE(toggles[8].hud);
    // Commands fire once, on their first frame, in the order of the keys.
    EXPECT_EQ(commands[5], (std::vector<Key>{Key::DetailUp, Key::NextMethod}));
    EXPECT_EQ(commands[7], (std::vector<Key>{Key::Screenshot}));
    EXPECT_TRUE(commands[8].empty());
    // The environment follows the toggles: no lighting = the terrain's colors as they are.
    EXPECT_TRUE(s.environment().baked);
    EXPECT_EQ(s.environment().fog_density > 0, next_fog_mode(fog0) == FogMode::Exp);
    EXPECT_EQ(s.environment().atmosphere, next_fog_mode(fog0) == FogMode::Atmosphere);
}

// f cycles off -> GL_EXP fog -> atmosphere -> off; the environment follows.
TEST(FlightSession, FogKeyCyclesFogAndAtmosphere) {
    DataSet d = island();
    d.environment.fog_density = 0;
    FlightSession s(d.terrain, d.environment, scripted(4, {{Key::Fog, 1, 2}, {Key::Fog, 2, 3}, {Key::Fog, 3, 4}}));
    std::vector<FogMode> modes;
    std::vector<Environment> envs;
    while (!s.finished()) {
        s.begin_frame();
        modes.push_back(s.toggles().fog);
        envs.push_back(s.environment());
        s.advance(0.0);
        s.end_frame();
    }
    EXPECT_EQ(modes, (std::vector<FogMode>{FogMode::Off, FogMode::Exp, FogMode::Atmosphere, FogMode::Off}));
    EXPECT_EQ(envs[0].fog_density, 0.0f);
    EXPECT_GT(envs[1].fog_density, 0.0f);
    EXPECT_FALSE(envs[1].atmosphere);
    EXPECT_TRUE(envs[2].atmosphere);
    EXPECT_EQ(envs[2].fog_density, 0.0f);
    EXPECT_FALSE(envs[3].atmosphere);
    EXPECT_STREQ(to_string(FogMode::Atmosphere), "atmosphere");
    // An environment with the atmosphere on starts in that mode (fly --atmosphere).
    d.environment.atmosphere = true;
    EXPECT_EQ(FlightSession(d.terrain, d.environment, scripted(1, {})).toggles().fog, FogMode::Atmosphere);
}

// `s` toggles the terrain's shadows; `t` and `T` move the sun half an hour
// along the day arc from where the data set's sun is.
TEST(FlightSession, ShadowsAndTimeOfDayKeys) {
    const DataSet& d = island();
    FlightSession s(d.terrain, d.environment,
                    scripted(5, {{Key::Shadows, 1, 2}, {Key::SunLater, 2, 3}, {Key::SunLater, 3, 4}, {Key::SunEarlier, 4, 5}}));
    std::vector<Environment> env;
    while (!s.finished()) {
        s.begin_frame();
        env.push_back(s.environment());
        s.advance(0.0);
        s.end_frame();
    }
    ASSERT_EQ(env.size(), 5u);
    EXPECT_FALSE(env[0].shadows);
    EXPECT_TRUE(env[1].shadows);
    EXPECT_EQ(env[1].sun_dir, d.environment.sun_dir);
    const double hour = hour_of_sun(d.environment.sun_dir);
    const auto near = [](const glm::vec3& a, const glm::vec3& b) { return glm::length(a - b) < 1e-5f; };
    EXPECT_TRUE(near(env[2].sun_dir, sun_at_hour(hour + 0.5)));
    EXPECT_TRUE(near(env[3].sun_dir, sun_at_hour(hour + 1.0)));
    EXPECT_TRUE(near(env[4].sun_dir, sun_at_hour(hour + 0.5)));
}

TEST(FlightSession, InteractiveTimeIsTheWallClockBoundedPerFrame) {
    const DataSet& d = island();
    FlightSession s(d.terrain, d.environment, FlightSessionOptions{});
    EXPECT_FALSE(s.unattended());
    s.begin_frame();
    s.advance(0.05); // 5 steps
    EXPECT_EQ(s.physics_steps(), 5);
    s.advance(10.0); // a stalled frame counts as 0.25 s at most
    EXPECT_EQ(s.physics_steps(), 30);
    EXPECT_FALSE(s.finished());
}

TEST(FlightSession, ATapBetweenTwoFramesIsSeenByOneStep) {
    const DataSet& d = island();
    FlightSession s(d.terrain, d.environment, FlightSessionOptions{});
    s.begin_frame();
    s.press(Key::Accelerate);
    s.release(Key::Accelerate);
    s.advance(0.03);
    s.end_frame();
    EXPECT_TRUE(s.record().frames.back().keys.accelerate);
    s.begin_frame();
    s.advance(0.03);
    s.end_frame();
    EXPECT_FALSE(s.record().frames.back().keys.accelerate);
}

TEST(FlightSession, AStartOffTheMapIsRefusedBeforeAnyFrame) {
    const DataSet& d = island();
    FlightSessionOptions o;
    o.start = VehicleStart{true, -100.0, 10.0, 0.0};
    EXPECT_THROW(FlightSession(d.terrain, d.environment, o), overflight::Error);
}
