// One horizon sweep per sun direction shared by the renderers of a terrain
// (core/SharedSunShadow.h): the sweep count, concurrent callers, results held
// across a move of the sun, and the ray casters' light from the shared mask
// equal to the light from their own sweep.
#include "core/DemoIsland.h"
#include "core/SharedSunShadow.h"
#include "core/SunLight.h"

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <atomic>

using namespace overflight;

namespace {

const DataSet& island() {
    static const DataSet ds = [] {
        DemoOptions o;
        o.size = 257;
        return make_demo_island(o);
    }();
    return ds;
}

} // namespace

TEST(SharedSunShadow, OneSweepPerDirection) {
    const Terrain& t = island().terrain;
    SharedSunShadow shared(t);
    const glm::vec3 a = sun_at_hour(9.0), b = sun_at_hour(9.5);
    const auto first = shared.get(a);
    EXPECT_EQ(shared.get(a * 3.0f), first); // any length: the same direction
    EXPECT_EQ(shared.sweeps(), 1);
    ShadowCeiling ceiling;
    std::vector<std::uint8_t> mask;
    sweep_shadow(t, a, ceiling, mask);
    EXPECT_TRUE(first->ceiling.ceiling == ceiling.ceiling);
    EXPECT_EQ(first->mask, mask);

    // The sun moves on: a new sweep; the result still held stays as it was.
    const auto second = shared.get(b);
    EXPECT_EQ(shared.sweeps(), 2);
    EXPECT_NE(second, first);
    EXPECT_EQ(first->mask, mask);
    sweep_shadow(t, b, ceiling, mask);
    EXPECT_EQ(second->mask, mask);
    EXPECT_TRUE(second->ceiling.ceiling == ceiling.ceiling);
}

// Many callers at once for one new direction: one sweep, one result.
TEST(SharedSunShadow, ConcurrentCallersShareOneSweep) {
    SharedSunShadow shared(island().terrain);
    const glm::vec3 sun = sun_at_hour(15.0);
    std::atomic<const SunShadow*> seen{nullptr};
    std::atomic<int> different{0};
    tbb::parallel_for(0, 16, [&](int) {
        const auto r = shared.get(sun);
        const SunShadow* expected = nullptr;
        if (!seen.compare_exchange_strong(expected, r.get()) && expected != r.get()) ++different;
    });
    EXPECT_EQ(shared.sweeps(), 1);
    EXPECT_EQ(different.load(), 0);
}

// The ray casters' lighting and light mask from the shared sweep are their
// lighting and mask from their own, byte for byte, along a day's arc; the
// shared sweep runs once per direction for two lightings (two renderers of
// one terrain).
TEST(SharedSunShadow, LightingFromTheSharedMaskIsTheSame) {
    const Terrain& t = island().terrain;
    SharedSunShadow shared(t);
    TerrainLighting own(t), a(t, LightOutput::Colors, &shared), b(t, LightOutput::Light, &shared),
        own_light(t, LightOutput::Light);
    Environment env = island().environment;
    env.shadows = true;
    for (double hour = 7.0; hour <= 17.0; hour += 2.5) {
        env.sun_dir = sun_at_hour(hour);
        EXPECT_TRUE(*a.colors(env) == *own.colors(env)) << "hour " << hour;
        EXPECT_TRUE(*b.colors(env) == *own_light.colors(env)) << "hour " << hour;
        // The mask the front faces read (FrontFace.h) is the shared one.
        const LightMask mine = a.light_mask(), theirs = own.light_mask();
        ASSERT_TRUE(mine.shadowed && theirs.shadowed && mine.other_colors && theirs.other_colors);
        EXPECT_TRUE(*mine.shadowed == *theirs.shadowed) << "hour " << hour;
        EXPECT_TRUE(*mine.other_colors == *theirs.other_colors) << "hour " << hour;
    }
    EXPECT_EQ(shared.sweeps(), 5);
}
