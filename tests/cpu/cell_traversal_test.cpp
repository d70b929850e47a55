// The cell traversal's exact jumps (raycast/CellTraversal.h) against the
// loop they replace, and the mirrored rays of the water pass marched with the
// max-height pyramid's skipping against the plain cell march: the same
// pixels, bit for bit, on a literal height field and on the demo island.
#include "core/DemoIsland.h"
#include "raycast/CellTraversal.h"
#include "raycast/HeightPyramid.h"
#include "raycast/RayMarcher.h"
#include "raycast/WaterPass.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

using namespace overflight;

namespace {

double loop_sum(double x, double step, long long k) {
    for (long long i = 0; i < k; ++i) x += step;
    return x;
}

long long loop_count(double x, double step, double v, bool inclusive, long long limit) {
    long long n = 0;
    for (; n < limit && (inclusive ? x <= v : x < v); ++n) x += step;
    return n;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

} // namespace

TEST(CellTraversal, AccumulateIsTheLoopsRoundedSums) {
    // 0.1 is not a binary fraction: ten rounded sums of it from 0 are not 1.
    EXPECT_EQ(accumulate(0.0, 0.1, 10), 0.9999999999999999);
    EXPECT_EQ(accumulate(0.25, 0.5, 3), 1.75); // exact in binary
    EXPECT_EQ(accumulate(3.0, 0.7, 0), 3.0);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> start(-0.01, 1.0), step(1e-6, 0.05);
    for (int n = 0; n < 2000; ++n) {
        const double x = start(rng), s = step(rng);
        const long long k = std::uniform_int_distribution<long long>(0, 3000)(rng);
        ASSERT_TRUE(same_bits(accumulate(x, s, k), loop_sum(x, s, k))) << x << " " << s << " " << k;
    }
    // A step half-way between two units in the last place of the sums (a tie).
    EXPECT_TRUE(same_bits(accumulate(1.0, 0x1p-53 * 3.0, 1000), loop_sum(1.0, 0x1p-53 * 3.0, 1000)));
}

TEST(CellTraversal, CountBelowCountsTheLoopsValues) {
    EXPECT_EQ(count_below(0.0, 0.1, 0.3, false, 100).count, 3);        // 0, 0.1, 0.2; 0.30000000000000004 is not
    EXPECT_EQ(count_below(0.0, 0.25, 0.5, false, 100).count, 2);       // 0, 0.25
    EXPECT_EQ(count_below(0.0, 0.25, 0.5, true, 100).count, 3);        // and 0.5
    EXPECT_EQ(count_below(0.0, 0.25, 0.5, true, 2).count, 2);          // at most the limit
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> start(0.0, 1.0), step(1e-5, 0.05), span(0.0, 1.5);
    for (int n = 0; n < 2000; ++n) {
        const double x = start(rng), s = step(rng), v = x + span(rng);
        const long long limit = std::uniform_int_distribution<long long>(0, 2000)(rng);
        for (bool inclusive : {false, true}) {
            const Passed p = count_below(x, s, v, inclusive, limit);
            ASSERT_EQ(p.count, loop_count(x, s, v, inclusive, limit)) << x << " " << s << " " << v << " " << limit;
            ASSERT_TRUE(same_bits(p.next, loop_sum(x, s, p.count)));
        }
    }
    // On a value of the loop itself: strict and inclusive differ by one.
    const double v = loop_sum(0.3, 0.001, 500);
    EXPECT_EQ(count_below(0.3, 0.001, v, false, 1000).count, 500);
    EXPECT_EQ(count_below(0.3, 0.001, v, true, 1000).count, 501);
}

namespace {

// 7x7 samples one unit apart: a ring of 4 around a pit of 0 with a peak of
// 6 at (row 1, col 5), the rest 1; colors tell the samples apart.
Terrain literal() {
    const int h[7][7] = {{1, 1, 1, 1, 1, 1, 1}, {1, 4, 4, 4, 4, 6, 1}, {1, 4, 0, 0, 0, 4, 1},
                         {1, 4, 0, 0, 0, 4, 1}, {1, 4, 0, 0, 0, 4, 1}, {1, 4, 4, 4, 4, 4, 1},
                         {1, 1, 1, 1, 1, 1, 1}};
    Terrain t(7, 7, 1.0f);
    for (int r = 0; r < 7; ++r)
        for (int c = 0; c < 7; ++c) {
            t.raw(r, c) = std::uint16_t(h[r][c]);
            t.color(r, c) = {std::uint8_t(30 * r), std::uint8_t(30 * c), 100};
        }
    return t;
}

// Rising segments from random points at random heights: the same hit
// (point bit for bit, color) with and without the pyramid.
void expect_same_rising_hits(const Terrain& t, int segments, std::uint64_t seed) {
    const HeightPyramid pyramid(t, 31);
    const Environment env;
    RayMarcher plain(t, env), skipping(t, env);
    skipping.set_pyramid(&pyramid);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> x(0.0, t.width()), z(0.0, t.depth()), unit(-1.0, 1.0);
    std::uniform_real_distribution<double> y(t.min_height(), t.max_height()), rise(0.001, 0.5);
    int hits = 0;
    for (int n = 0; n < segments; ++n) {
        const glm::dvec3 a(x(rng), y(rng), z(rng));
        const glm::dvec3 d(unit(rng), rise(rng), unit(rng));
        const glm::dvec3 b = a + d * (2.0 * (t.width() + t.depth()));
        const RayMarcher::Hit p = plain.intersect(a, b, SurfaceModel::Blocks);
        const RayMarcher::Hit s = skipping.intersect(a, b, SurfaceModel::Blocks);
        ASSERT_EQ(p.hit, s.hit) << n;
        if (!p.hit) continue;
        ++hits;
        ASSERT_TRUE(same_bits(p.point.x, s.point.x) && same_bits(p.point.y, s.point.y) &&
                    same_bits(p.point.z, s.point.z))
            << n;
        ASSERT_EQ(p.surface.r, s.surface.r);
        ASSERT_EQ(p.surface.g, s.surface.g);
        ASSERT_EQ(p.surface.b, s.surface.b);
    }
    EXPECT_GT(hits, segments / 20); // both outcomes are exercised
}

// The water pass's images with and without skipping: identical.
void expect_same_water(const Terrain& t, const Camera& camera, double level, long long min_flooded) {
    Environment env;
    env.water = true;
    env.water_level = float(level);
    ColorImage dry;
    DepthImage dry_depth;
    RayMarcher(t, env).render(camera, SurfaceModel::Blocks, dry, dry_depth);
    WaterPass pass(t);
    ColorImage plain = dry, skipping = dry;
    DepthImage plain_depth = dry_depth, skipping_depth = dry_depth;
    pass.set_skipping(false);
    const long long flooded = pass.apply(camera, env, SurfaceModel::Blocks, plain, plain_depth);
    pass.set_skipping(true);
    EXPECT_EQ(pass.apply(camera, env, SurfaceModel::Blocks, skipping, skipping_depth), flooded);
    EXPECT_GE(flooded, min_flooded);
    EXPECT_TRUE(plain.pixels == skipping.pixels);
    EXPECT_TRUE(plain_depth.pixels == skipping_depth.pixels);
}

} // namespace

TEST(PyramidSkipping, RisingHitsOnALiteralAreThePlainMarchs) { expect_same_rising_hits(literal(), 20000, 1); }

TEST(PyramidSkipping, RisingHitsOnTheDemoAreThePlainMarchs) {
    DemoOptions options;
    options.size = 257;
    expect_same_rising_hits(make_demo_island(options).terrain, 20000, 2);
}

TEST(PyramidSkipping, WaterOnALiteralIsThePlainMarchs) {
    Camera camera;
    camera.eye = {3.1, 9.0, -1.2}; // south of the pit, looking north into it and at the peak
    camera.heading = 0.0;
    camera.pitch = -45.0;
    camera.width = 96;
    camera.height = 64;
    camera.near = 0.1;
    camera.far = 50.0;
    expect_same_water(literal(), camera, 2.0, 500);
}

TEST(PyramidSkipping, WaterOnTheDemoIsThePlainMarchs) {
    DemoOptions options;
    options.size = 257;
    const DataSet demo = make_demo_island(options);
    const Terrain& t = demo.terrain;
    Camera camera;
    camera.eye = {0.2 * t.width(), double(t.max_height()) * 0.8, 0.1 * t.depth()};
    camera.heading = 45.0;
    camera.pitch = -12.0;
    camera.width = 320;
    camera.height = 180;
    camera.far = 2.0 * (t.width() + t.depth());
    expect_same_water(t, camera, 0.5 * (t.min_height() + t.max_height()), 5000);
}
