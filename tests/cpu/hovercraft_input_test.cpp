// Sampled keys (CMSC 23700 project 2a sec. 3.1 and footnote 1), scripted presses (DESIGN
// sec. 6 --press) and the 100 Hz fixed-step clock (CMSC 23700 project 2a sec. 3.2).
#include "core/Error.h"
#include "core/Terrain.h"
#include "sim/FixedStepClock.h"
#include "sim/Hovercraft.h"
#include "sim/KeyScript.h"
#include "sim/KeyState.h"

#include <gtest/gtest.h>

using namespace overflight;

TEST(KeyState, TapBetweenTwoStepsIsSeenByExactlyOneStep) {
    KeyState keys;
    keys.press(Key::Accelerate);
    keys.release(Key::Accelerate); // released before any step ran
    EXPECT_TRUE(keys.sample().accelerate);
    EXPECT_FALSE(keys.sample().accelerate); // and only once
}

TEST(KeyState, HeldKeyIsSeenByEveryStepUntilReleased) {
    KeyState keys;
    keys.press(Key::Left);
    for (int i = 0; i < 5; ++i) EXPECT_TRUE(keys.sample().left);
    keys.release(Key::Left);
    EXPECT_FALSE(keys.sample().left);
    EXPECT_EQ(keys.held(), Controls{});
}

TEST(KeyState, RepeatIsIgnoredAndKeysAreIndependent) {
    KeyState keys;
    keys.press(Key::Right);
    keys.press(Key::Right); // key repeat: no second press is recorded
    keys.press(Key::Right);
    keys.press(Key::Brake);
    keys.release(Key::Right);
    const Controls c = keys.sample();
    EXPECT_TRUE(c.right);
    EXPECT_TRUE(c.brake);
    EXPECT_FALSE(c.accelerate);
    EXPECT_FALSE(c.left);
    const Controls d = keys.sample();
    EXPECT_FALSE(d.right);
    EXPECT_TRUE(d.brake);
    // Command keys are not vehicle controls.
    keys.press(Key::Fog);
    EXPECT_EQ(keys.sample(), (Controls{.brake = true}));
}

TEST(KeyState, NamesRoundTrip) {
    for (int i = 0; i < kKeyCount; ++i) EXPECT_EQ(key_from_name(key_name(Key(i))), Key(i));
    EXPECT_FALSE(key_from_name("warp"));
    EXPECT_TRUE(is_vehicle_key(Key::Right));
    EXPECT_FALSE(is_vehicle_key(Key::Fog));
}

TEST(KeyScript, ParsesAndHoldsWithTheEndExcluded) {
    const ScriptedPress p = parse_press("accelerate:0-100");
    EXPECT_EQ(p.key, Key::Accelerate);
    EXPECT_EQ(p.from, 0);
    EXPECT_EQ(p.to, 100);
    const KeyScript script({p, parse_press("left:50-60"), parse_press("next-method:7-8")});
    EXPECT_TRUE(script.controls_at(0).accelerate);
    EXPECT_TRUE(script.controls_at(99).accelerate);
    EXPECT_FALSE(script.controls_at(100).accelerate);
    EXPECT_FALSE(script.controls_at(49).left);
    EXPECT_TRUE(script.controls_at(50).left);
    EXPECT_FALSE(script.controls_at(60).left);
    EXPECT_TRUE(script.starts_at(Key::NextMethod, 7));
    EXPECT_FALSE(script.starts_at(Key::NextMethod, 8));
    EXPECT_FALSE(script.starts_at(Key::Left, 51));
}

TEST(KeyScript, BadSpecsNameTheOption) {
    for (const char* bad : {"accelerate", "warp:0-10", "left:5-5", "left:9-3", "left:-1-3", "left:a-b",
                            "left:1-", "left:1-2x", ":0-1"}) {
        SCOPED_TRACE(bad);
        try {
            parse_press(bad);
            ADD_FAILURE() << "accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.subject(), "key press");
        }
    }
}

TEST(FixedStepClock, StepsAreIndependentOfTheFrameRate) {
    // One simulated second is 100 steps at 20, 60, 144 and 1000 frames per second.
    for (int fps : {20, 60, 144, 1000}) {
        SCOPED_TRACE(fps);
        FixedStepClock clock(0.01);
        int steps = 0;
        for (int f = 0; f < fps; ++f) steps += clock.advance(1.0 / fps);
        EXPECT_EQ(steps, 100);
        EXPECT_LT(clock.alpha(), 1e-6 + 1.0);
    }
}

TEST(FixedStepClock, RemainderCarriesOverAndStallsAreCapped) {
    FixedStepClock clock(0.01, 25);
    EXPECT_EQ(clock.advance(0.004), 0);
    EXPECT_NEAR(clock.alpha(), 0.4, 1e-9);
    EXPECT_EQ(clock.advance(0.007), 1); // 11 ms: one step, 1 ms left
    EXPECT_NEAR(clock.alpha(), 0.1, 1e-9);
    EXPECT_EQ(clock.advance(-5.0), 0);  // a clock going backwards adds nothing
    EXPECT_EQ(clock.advance(3.0), 25);  // a 3 s stall: 25 steps, the rest dropped
    EXPECT_NEAR(clock.dropped(), 3.0 + 0.001 - 0.25 - clock.alpha() * 0.01, 1e-9);
    EXPECT_EQ(clock.advance(1e300), 25); // absurd input stays sane
    EXPECT_GE(clock.alpha(), 0.0);
    EXPECT_LT(clock.alpha(), 1.0);
    EXPECT_THROW(FixedStepClock(0.0), Error);
}

TEST(FixedStepClock, SameFlightAtDifferentFrameRates) {
    // The physics only sees steps: a flight driven by 30 fps frames and by
    // 240 fps frames ends in the same state bit for bit.
    Terrain t(9, 9, 10.0f, 1.0f);
    for (int i = 0; i < 9; ++i)
        for (int j = 0; j < 9; ++j) t.raw(i, j) = std::uint16_t(i * j);
    auto fly = [&](int fps) {
        Hovercraft hc(t, 10, 10, 45);
        FixedStepClock clock(0.01);
        KeyScript script({parse_press("accelerate:0-150"), parse_press("left:80-120")});
        long long step = 0;
        for (int f = 0; f < 2 * fps; ++f) {
            for (int n = clock.advance(1.0 / fps); n > 0; --n, ++step) hc.step(script.controls_at(step));
        }
        EXPECT_EQ(step, 200);
        return hc.state();
    };
    const HovercraftState a = fly(30), b = fly(240);
    EXPECT_EQ(a.x, b.x);
    EXPECT_EQ(a.z, b.z);
    EXPECT_EQ(a.velocity, b.velocity);
    EXPECT_EQ(a.heading, b.heading);
}
