// The terrain's sun shadows (core/HorizonSweep.h): literal masks worked out by
// hand on 5x5 height fields, and agreement with a brute-force ray towards the
// sun from every sample on the demo island and on real DEMs.
#include "core/DemoIsland.h"
#include "core/HorizonSweep.h"
#include "core/SunLight.h"
#include "io/LoadTerrain.h"
#include "TestSupport.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>

using namespace overflight;

namespace {

Terrain grid5(const int (&h)[5][5], float v_scale) {
    Terrain t(5, 5, 1.0f, v_scale);
    for (int r = 0; r < 5; ++r)
        for (int c = 0; c < 5; ++c) t.raw(r, c) = std::uint16_t(h[r][c]);
    return t;
}

void expect_mask(const Terrain& t, const glm::vec3& sun, const int (&expected)[5][5]) {
    ShadowCeiling c;
    sweep_shadow_ceiling(t, sun, c);
    const std::vector<std::uint8_t> mask = shadow_mask(t, c);
    for (int r = 0; r < 5; ++r)
        for (int col = 0; col < 5; ++col)
            EXPECT_EQ(int(mask[t.index(r, col)]), expected[r][col]) << "row " << r << " col " << col;
}

// Brute force: a ray from each sample towards the sun, tested against the
// terrain at every grid line it crosses (columns and rows, in order, until it
// leaves the map or rises above every sample), where the height field is
// linear between two samples whatever the surface model (DESIGN sec. 3: mesh
// and bilinear agree there). Shadowed iff the terrain is above the ray at one.
// With `interior`, also in quarter-cell steps on the bilinear surface between
// them (the cells' insides, where the surface models differ).
bool ray_blocked(const Terrain& t, int row, int col, const glm::vec3& sun, float top, bool interior) {
    const double horizontal = std::hypot(double(sun.x), double(sun.z));
    const double dx = sun.x / horizontal, dz = sun.z / horizontal, slope = sun.y / horizontal;
    const double hs = t.h_scale();
    const double x0 = hs * col, z0 = hs * row, y0 = t.sample_height(row, col);
    auto blocked_at = [&](double s) {
        const double x = x0 + s * dx, z = z0 + s * dz, y = y0 + s * slope;
        if (!t.contains(float(x), float(z)) || y > top) return -1;
        return t.height_bilinear(float(x), float(z)) > y ? 1 : 0;
    };
    // Distances to the next column and row crossings.
    const double sx = std::abs(dx) > 1e-12 ? hs / std::abs(dx) : 1e300, sz = std::abs(dz) > 1e-12 ? hs / std::abs(dz) : 1e300;
    double next_x = sx, next_z = sz, last = 0;
    for (;;) {
        const double s = std::min(next_x, next_z);
        if (interior)
            for (double q = last + 0.25 * hs; q < s; q += 0.25 * hs)
                if (const int b = blocked_at(q); b != 0) return b > 0;
        const int b = blocked_at(s);
        if (b != 0) return b > 0;
        last = s;
        if (next_x <= s) next_x += sx;
        if (next_z <= s) next_z += sz;
    }
}

// Share of samples (every `stride`-th row and column) where the sweep and the
// brute-force ray agree.
double agreement(const Terrain& t, const glm::vec3& sun, int stride, bool interior = false) {
    ShadowCeiling c;
    sweep_shadow_ceiling(t, sun, c);
    const glm::vec3 unit = glm::normalize(sun);
    const float top = t.max_height();
    std::atomic<long long> same{0}, total{0}, shadowed{0};
    tbb::parallel_for(0, (t.rows() + stride - 1) / stride, [&](int i) {
        const int row = i * stride;
        long long s = 0, n = 0, sh = 0;
        for (int col = 0; col < t.cols(); col += stride) {
            const bool sweep = c.shadowed(row, col, t.sample_height(row, col));
            s += sweep == ray_blocked(t, row, col, unit, top, interior);
            sh += sweep;
            ++n;
        }
        same += s;
        total += n;
        shadowed += sh;
    });
    std::printf("  sun %.0f/%.0f%s: %.3f %% agree, %.1f %% shadowed\n", sun_angles(sun).azimuth, sun_angles(sun).elevation,
                interior ? " (and inside the cells)" : "",
                100.0 * double(same) / double(total), 100.0 * double(shadowed) / double(total));
    return double(same) / double(total);
}

// The sweep against the rays over the grid lines (>= 99.5 %), and, printed
// for the record, against rays that also look inside the cells.
void expect_agreement(const Terrain& t, int stride) {
    for (const auto& [az, el] : {std::pair{30.0, 8.0}, {135.0, 20.0}, {250.0, 12.0}, {300.0, 35.0}, {90.0, 5.0}}) {
        EXPECT_GE(agreement(t, sun_direction(az, el), stride), 0.995) << "sun " << az << "/" << el;
        agreement(t, sun_direction(az, el), stride, true);
    }
}

} // namespace

TEST(SunDirection, AzimuthClockwiseFromNorth) {
    const glm::vec3 north = sun_direction(0, 0), east = sun_direction(90, 0), up = sun_direction(0, 90);
    EXPECT_NEAR(north.z, -1.0f, 1e-6f); // north is -Z
    EXPECT_NEAR(east.x, 1.0f, 1e-6f);   // east is +X
    EXPECT_NEAR(up.y, 1.0f, 1e-6f);
    const SunAngles a = sun_angles(sun_direction(250, 12));
    EXPECT_NEAR(a.azimuth, 250.0, 1e-4);
    EXPECT_NEAR(a.elevation, 12.0, 1e-4);
}

// A north-south ridge in column 1 (2 at the ends, 3 between, and a bump of 1
// east of it) under a sun in the west whose rays drop 0.8 per cell: the ridge
// of 3 shadows 3 - 0.8 k > 0 for k = 1, 2, 3 cells east of it, the ridge of 2
// only k = 1, 2; the bump (1 < 3 - 0.8) is shadowed too; west of the ridge
// and the ridge itself see the sun.
TEST(HorizonSweep, RidgeUnderAWesternSun) {
    const int h[5][5] = {{0, 2, 0, 0, 0}, {0, 3, 0, 0, 0}, {0, 3, 1, 0, 0}, {0, 3, 0, 0, 0}, {0, 2, 0, 0, 0}};
    const int expected[5][5] = {{0, 0, 1, 1, 0}, {0, 0, 1, 1, 1}, {0, 0, 1, 1, 1}, {0, 0, 1, 1, 1}, {0, 0, 1, 1, 0}};
    expect_mask(grid5(h, 1.0f), sun_direction(270.0, glm::degrees(std::atan(0.8))), expected);
}

// The same ridge with the sun in the east: the ridge shadows the western
// edge (2 - 0.8 > 0), the bump (1 - 0.8 < 3) does not reach the ridge, and
// nothing rises east of the bump.
TEST(HorizonSweep, RidgeUnderAnEasternSun) {
    const int h[5][5] = {{0, 2, 0, 0, 0}, {0, 3, 0, 0, 0}, {0, 3, 1, 0, 0}, {0, 3, 0, 0, 0}, {0, 2, 0, 0, 0}};
    const int expected[5][5] = {{1, 0, 0, 0, 0}, {1, 0, 0, 0, 0}, {1, 0, 0, 0, 0}, {1, 0, 0, 0, 0}, {1, 0, 0, 0, 0}};
    expect_mask(grid5(h, 1.0f), sun_direction(90.0, glm::degrees(std::atan(0.8))), expected);
}

// A pillar of 2.5 at (1, 1) under a north-western sun whose rays drop 1 per
// diagonal step (tan e = 1 / sqrt 2): its shadow runs south-east over (2, 2)
// (2.5 - 1 > 0) and (3, 3) (2.5 - 2 > 0), not (4, 4) (2.5 - 3 < 0).
TEST(HorizonSweep, PillarUnderANorthWesternSun) {
    const int h[5][5] = {{0, 0, 0, 0, 0}, {0, 5, 0, 0, 0}, {0, 0, 0, 0, 0}, {0, 0, 0, 0, 0}, {0, 0, 0, 0, 0}};
    const int expected[5][5] = {{0, 0, 0, 0, 0}, {0, 0, 0, 0, 0}, {0, 0, 1, 0, 0}, {0, 0, 0, 1, 0}, {0, 0, 0, 0, 0}};
    expect_mask(grid5(h, 0.5f), sun_direction(315.0, glm::degrees(std::atan(1.0 / std::sqrt(2.0)))), expected);
}

// The ceiling holds for any point above a sample, not only the sample: above
// the first sample east of the ridge (3 - 0.8 = 2.2) a point at 2 is in the
// shadow, a point at 2.5 is not.
TEST(HorizonSweep, CeilingAboveASample) {
    const int h[5][5] = {{0, 2, 0, 0, 0}, {0, 3, 0, 0, 0}, {0, 3, 1, 0, 0}, {0, 3, 0, 0, 0}, {0, 2, 0, 0, 0}};
    ShadowCeiling c;
    sweep_shadow_ceiling(grid5(h, 1.0f), sun_direction(270.0, glm::degrees(std::atan(0.8))), c);
    EXPECT_NEAR(c.at(1, 2), 2.2f, 1e-5f);
    EXPECT_TRUE(c.shadowed(1, 2, 2.0f));
    EXPECT_FALSE(c.shadowed(1, 2, 2.5f));
    EXPECT_EQ(c.at(1, 0), ShadowCeiling::kOpen); // the map's edge towards the sun
}

// A sun at or below the horizon shadows everything; a sun in the zenith nothing.
TEST(HorizonSweep, SunBelowTheHorizonAndInTheZenith) {
    const int h[5][5] = {{0, 2, 0, 0, 0}, {0, 3, 0, 0, 0}, {0, 3, 1, 0, 0}, {0, 3, 0, 0, 0}, {0, 2, 0, 0, 0}};
    int all[5][5], none[5][5] = {};
    for (auto& row : all)
        for (int& v : row) v = 1;
    expect_mask(grid5(h, 1.0f), sun_direction(200.0, -3.0), all);
    expect_mask(grid5(h, 1.0f), sun_direction(200.0, 0.0), all);
    expect_mask(grid5(h, 1.0f), sun_direction(0.0, 90.0), none);
}

// Baked lighting leaves the terrain's colors alone; a sun below the horizon
// leaves ambient light.
TEST(SunLight, BakedAndNight) {
    const Terrain t(5, 5, 1.0f);
    Environment env;
    TerrainLighting lighting(t);
    EXPECT_NE(lighting.colors(env), nullptr);
    bake_lighting(env);
    EXPECT_TRUE(lighting_is_baked(env));
    EXPECT_EQ(lighting.colors(env), nullptr);
    Environment night;
    night.sun_dir = sun_direction(90, -10);
    EXPECT_EQ(sample_light(night, glm::vec3(1, 0, 0), true), night.ambient);
    Environment day;
    day.sun_dir = glm::vec3(0, 1, 0);
    EXPECT_EQ(sample_light(day, glm::vec3(0, 1, 0), true), day.ambient + day.sun_color);
    EXPECT_EQ(sample_light(day, glm::vec3(0, 1, 0), false), day.ambient);
}

TEST(HorizonSweep, AgreesWithRaysOnTheDemo) {
    DemoOptions o;
    o.size = 513;
    const DataSet ds = make_demo_island(o);
    expect_agreement(ds.terrain, 1);
}

TEST(HorizonSweep, AgreesWithRaysOnCraterLake) {
    OVERFLIGHT_SHARED_FILE(path, "bt/crater_0513.bt");
    expect_agreement(load_terrain(path).terrain, 1);
}

TEST(HorizonSweep, AgreesWithRaysOnMountRainier) {
    OVERFLIGHT_SHARED_FILE(path, "srtm/mt_rainier_90m.tif");
    expect_agreement(load_terrain(path).terrain, 3);
}

TEST(HorizonSweep, AgreesWithRaysOnMountStHelens) {
    OVERFLIGHT_SHARED_FILE(path, "usgs-dem/SainteHelens.dem");
    expect_agreement(load_terrain(path).terrain, 1);
}

// light_colors is sample_light with Terrain::sample_normal at every sample,
// lit where the ceiling leaves the sample in the sun (within one color level).
TEST(SunLight, LightColorsPerSample) {
    Terrain t(9, 9, 2.0f, 0.5f, 10.0f);
    for (int r = 0; r < 9; ++r)
        for (int c = 0; c < 9; ++c) {
            t.raw(r, c) = std::uint16_t((r * 7 + c * 13) % 11 + (r == 4 ? 30 : 0));
            t.color(r, c) = Rgb8{std::uint8_t(20 * r), std::uint8_t(200 - 10 * c), 128};
        }
    Environment env;
    env.sun_dir = sun_direction(20.0, 25.0);
    ShadowCeiling ceiling;
    sweep_shadow_ceiling(t, env.sun_dir, ceiling);
    std::vector<Rgb8> lit;
    light_colors(t, pack_normals(t), env, &ceiling, lit);
    int shadowed = 0;
    for (int r = 0; r < 9; ++r)
        for (int c = 0; c < 9; ++c) {
            const bool sun = !ceiling.shadowed(r, c, t.sample_height(r, c));
            shadowed += !sun;
            const glm::vec3 light = sample_light(env, t.sample_normal(r, c), sun);
            const Rgb8 a = t.color(r, c), got = lit[t.index(r, c)];
            EXPECT_NEAR(got.r, std::min(255.0f, a.r * light.r), 1.0f) << r << "," << c;
            EXPECT_NEAR(got.g, std::min(255.0f, a.g * light.g), 1.0f) << r << "," << c;
            EXPECT_NEAR(got.b, std::min(255.0f, a.b * light.b), 1.0f) << r << "," << c;
        }
    EXPECT_GT(shadowed, 0); // the ridge in row 4 shadows the rows north of it
}

// The packed normals (core/PackedNormals.h) against Terrain::sample_normal
// in full precision on the demo island, under five suns: every channel of
// every sample within one color level, and the packing's own error within
// half a step per component.
TEST(SunLight, PackedNormalsWithinOneLevelOnTheDemo) {
    DemoOptions o;
    o.size = 513;
    const DataSet ds = make_demo_island(o);
    const Terrain& t = ds.terrain;
    const PackedNormals normals = pack_normals(t);
    float worst_component = 0.0f;
    for (std::size_t i = 0; i < normals.packed.size(); i += 7) {
        const glm::vec3 d = PackedNormals::unpack(normals.packed[i]) - t.sample_normal(int(i) / t.cols(), int(i) % t.cols());
        worst_component = std::max({worst_component, std::abs(d.x), std::abs(d.y), std::abs(d.z)});
    }
    EXPECT_LE(worst_component, 0.5f / PackedNormals::kScale + 1e-6f);
    for (const auto& [az, el] : {std::pair{30.0, 8.0}, {135.0, 20.0}, {250.0, 12.0}, {300.0, 35.0}, {90.0, 60.0}}) {
        Environment env = ds.environment;
        env.sun_dir = sun_direction(az, el);
        ShadowCeiling ceiling;
        sweep_shadow_ceiling(t, env.sun_dir, ceiling);
        std::vector<Rgb8> lit;
        light_colors(t, normals, env, &ceiling, lit);
        int worst = 0;
        long long differ = 0;
        for (int r = 0; r < t.rows(); ++r)
            for (int c = 0; c < t.cols(); ++c) {
                const glm::vec3 light = sample_light(env, t.sample_normal(r, c), !ceiling.shadowed(r, c, t.sample_height(r, c)));
                const Rgb8 a = t.color(r, c), got = lit[t.index(r, c)];
                const auto exact = [](std::uint8_t albedo, float l) { return int(std::clamp(albedo * l + 0.5f, 0.0f, 255.0f)); };
                const int d = std::max({std::abs(got.r - exact(a.r, light.r)), std::abs(got.g - exact(a.g, light.g)),
                                        std::abs(got.b - exact(a.b, light.b))});
                worst = std::max(worst, d);
                differ += d > 0;
            }
        std::printf("  sun %.0f/%.0f: packed normals differ by at most %d level on %.3f %% of the samples\n", az, el, worst,
                    100.0 * double(differ) / double(t.rows() * t.cols()));
        EXPECT_LE(worst, 1) << "sun " << az << "/" << el;
    }
}

// The mask the sweep writes as it goes (sweep_shadow_mask) is the ceiling's
// mask (shadow_mask) sample for sample, for suns across both sweep axes,
// both directions, a diagonal, the zenith and below the horizon; the light
// from it is the light from the ceiling, byte for byte.
TEST(HorizonSweep, MaskSweepIsTheCeilingsMask) {
    DemoOptions o;
    o.size = 257;
    const DataSet ds = make_demo_island(o);
    const Terrain& t = ds.terrain;
    const PackedNormals normals = pack_normals(t);
    for (const auto& [az, el] : {std::pair{30.0, 8.0}, {135.0, 20.0}, {225.0, 10.0}, {250.0, 12.0}, {300.0, 35.0},
                                 {90.0, 60.0}, {0.0, 90.0}, {120.0, -5.0}}) {
        Environment env = ds.environment;
        env.sun_dir = sun_direction(az, el);
        ShadowCeiling ceiling;
        sweep_shadow_ceiling(t, env.sun_dir, ceiling);
        std::vector<std::uint8_t> mask;
        sweep_shadow_mask(t, env.sun_dir, mask);
        EXPECT_EQ(mask, shadow_mask(t, ceiling)) << "sun " << az << "," << el;
        std::vector<Rgb8> from_ceiling, from_mask;
        light_colors(t, normals, env, &ceiling, from_ceiling);
        light_colors(t, normals, env, mask, from_mask);
        EXPECT_TRUE(from_ceiling == from_mask) << "sun " << az << "," << el;
    }
}

// The one-pass sweep of both (sweep_shadow) writes what the two sweeps write
// apart, bit for bit, for the same suns (the zenith and below the horizon
// included).
TEST(HorizonSweep, OnePassIsBothSweeps) {
    DemoOptions o;
    o.size = 257;
    const DataSet ds = make_demo_island(o);
    const Terrain& t = ds.terrain;
    ShadowCeiling both;
    std::vector<std::uint8_t> both_mask;
    for (const auto& [az, el] : {std::pair{30.0, 8.0}, {135.0, 20.0}, {225.0, 10.0}, {250.0, 12.0}, {300.0, 35.0},
                                 {90.0, 60.0}, {0.0, 90.0}, {120.0, -5.0}}) {
        const glm::vec3 sun = sun_direction(az, el);
        ShadowCeiling ceiling;
        sweep_shadow_ceiling(t, sun, ceiling);
        std::vector<std::uint8_t> mask;
        sweep_shadow_mask(t, sun, mask);
        sweep_shadow(t, sun, both, both_mask); // storage reused from the previous sun
        EXPECT_TRUE(both.ceiling == ceiling.ceiling) << "sun " << az << "," << el;
        EXPECT_TRUE(both.sun_dir == ceiling.sun_dir);
        EXPECT_EQ(both_mask, mask) << "sun " << az << "," << el;
    }
}
