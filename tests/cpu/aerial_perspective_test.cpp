// The exponential-height atmosphere (core/AerialPerspective.h) at points
// worked out by hand, and the ray caster's tables of it (raycast/Atmosphere.h,
// AerialTables) against the exact model.
#include "core/AerialPerspective.h"
#include "raycast/Atmosphere.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

using namespace overflight;

namespace {

// Air only (no haze), beta = (1, 2, 3) 1e-4 per unit, H = 1000, g = 0.5,
// exposure 1, a white sun at the zenith.
Environment hand_air() {
    Environment env;
    env.atmosphere = true;
    env.air.rayleigh = {1e-4f, 2e-4f, 3e-4f};
    env.air.haze = 0.0f;
    env.air.scale_height = 1000.0f;
    env.air.haze_g = 0.5f;
    env.air.exposure = 1.0f;
    env.sun_dir = {0.0f, 2.0f, 0.0f}; // normalised on use
    env.air.sunlight = {1.0f, 1.0f, 1.0f};
    env.sun_color = {0.0f, 0.0f, 0.0f}; // the lighting's, not the atmosphere's
    return env;
}

void expect_near3(const glm::dvec3& got, double r, double g, double b, double tol = 1e-6) {
    EXPECT_NEAR(got.x, r, tol);
    EXPECT_NEAR(got.y, g, tol);
    EXPECT_NEAR(got.z, b, tol);
}

int max_channel_difference(Rgb8 a, Rgb8 b) {
    return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
}

} // namespace

// G(x) = (1 - e^-x) / x: G(0) = 1, G(ln 2) = (1 - 1/2) / ln 2 = 0.7213475,
// G(-ln 2) = (1 - 2) / -ln 2 = 1 / ln 2 = 1.4426950; a tiny x takes the series.
TEST(AerialPerspective, HeightFactor) {
    EXPECT_EQ(height_factor(0.0), 1.0);
    EXPECT_NEAR(height_factor(std::log(2.0)), 0.7213475204, 1e-9);
    EXPECT_NEAR(height_factor(-std::log(2.0)), 1.4426950409, 1e-9);
    EXPECT_NEAR(height_factor(1e-4), 1.0 - 0.5e-4 + 1e-8 / 6.0, 1e-12); // 1 - x/2 + x^2/6
}

// Rayleigh 3/4 (1 + c^2): 1.5 along the sun, 0.75 across it. Henyey-Greenstein
// with g = 1/2: (1 - 1/4) / (1 + 1/4 - c)^1.5 = 0.75 / 0.125 = 6 at c = 1,
// 0.75 / 3.375 = 0.2222 at c = -1, 1 everywhere with g = 0.
TEST(AerialPerspective, PhaseFunctions) {
    EXPECT_NEAR(phases(0.5, 1.0).x, 1.5, 1e-12);
    EXPECT_NEAR(phases(0.5, 1.0).y, 6.0, 1e-12);
    EXPECT_NEAR(phases(0.5, -1.0).y, 0.75 / 3.375, 1e-12);
    EXPECT_NEAR(phases(0.0, 0.0).x, 0.75, 1e-12);
    EXPECT_NEAR(phases(0.0, 0.3).y, 1.0, 1e-12);
}

// Kasten and Young: 1 / (sin a + 0.50572 (a + 6.07995)^-1.6364), a in degrees:
// 0.99971 at the zenith, 37.92 at the horizon (and below it), 1.9943 at 30 degrees.
TEST(AerialPerspective, AirMass) {
    EXPECT_NEAR(air_mass(1.0), 0.9997120, 1e-6);
    EXPECT_NEAR(air_mass(0.0), 37.919608, 1e-5);
    EXPECT_NEAR(air_mass(-0.5), 37.919608, 1e-5);
    EXPECT_NEAR(air_mass(0.5), 1.9942929, 1e-6);
}

// The eye at y0 = 1000 ln 2, so rho0 = exp(-ln 2) = 1/2.
//   sunlight E_c = G(k_c), k_c = beta_c rho0 H m(90 deg) = beta_c 500 0.999712
//                = (0.0499856, 0.0999712, 0.1499568): (1 - e^-k) / k
//                = (0.975418, 0.951639, 0.928633), all Rayleigh: R = E, M = 0;
//   a point 1000 away and 1000 ln 2 below: tau_c = beta_c rho0 1000 G(-ln 2)
//                = beta_c 721.3475, T = (0.930406, 0.865654, 0.805410);
//   its ray's cosine to the sun is -ln 2 = -0.693147: P_R = 0.75 (1 + 0.480453),
//   C_c = (1 - exp(-E_c P_R))^(1/2.2); color = 0.5 T + (1 - T) C
//                = (0.522877, 0.543465, 0.561949);
//   the zenith sky: V_c = (1 - exp(-beta_c rho0 H))^(1/2.2) = (0.253343, 0.343294, 0.408202)
//   times C_c at P_R = 1.5: (0.224763, 0.303049, 0.358526).
TEST(AerialPerspective, HandWorkedFrame) {
    const Environment env = hand_air();
    const AerialFrame f = aerial_frame(env, 1000.0 * std::log(2.0));
    EXPECT_NEAR(f.eye_density, 0.5, 1e-12);
    expect_near3(f.rayleigh_light, 0.9754185, 0.9516393, 0.9286330);
    expect_near3(f.haze_light, 0.0, 0.0, 0.0);
    const double dy = -1000.0 * std::log(2.0);
    expect_near3(transmittance(f, 1000.0, dy), 0.9304055, 0.8656544, 0.8054096);
    const glm::dvec3 offset(std::sqrt(1e6 - dy * dy), dy, 0.0);
    expect_near3(aerial_perspective(f, glm::dvec3(0.5), offset), 0.5228766, 0.5434654, 0.5619487);
    expect_near3(sky_opacity(f, 1.0), 0.2533425, 0.3432942, 0.4082024);
    expect_near3(aerial_sky(f, {0.0, 3.0, 0.0}), 0.2247632, 0.3030485, 0.3585265);
    // At and below the horizon the sky is the haze color itself.
    expect_near3(sky_opacity(f, -0.2), 1.0, 1.0, 1.0);
    const glm::dvec3 below = haze_color(f, -0.1 / std::sqrt(1.01));
    expect_near3(aerial_sky(f, {1.0, -0.1, 0.0}), below.x, below.y, below.z, 1e-12);
}

// Properties the sky must show: the zenith bluer than the horizon, the sun's
// side brighter, the low sun warmer than the high one, night dark.
TEST(AerialPerspective, SkyFollowsTheSun) {
    Environment env;
    env.atmosphere = true;
    env.sun_dir = {0.0f, 1.0f, 1.0f}; // 45 degrees up, south
    const AerialFrame f = aerial_frame(env, 0.0);
    const glm::dvec3 zenith = aerial_sky(f, {0, 1, 0}), horizon = aerial_sky(f, {1, 0, 0});
    EXPECT_GT(zenith.z / zenith.x, horizon.z / horizon.x);
    const glm::dvec3 towards = aerial_sky(f, {0, 0.2, 1}), away = aerial_sky(f, {0, 0.2, -1});
    EXPECT_GT(towards.x + towards.y + towards.z, away.x + away.y + away.z);
    env.sun_dir = {0.0f, 0.05f, 1.0f}; // 3 degrees up
    const AerialFrame low = aerial_frame(env, 0.0);
    EXPECT_GT(low.rayleigh_light.x / low.rayleigh_light.z, f.rayleigh_light.x / f.rayleigh_light.z);
    env.sun_dir = {0.0f, -0.2f, 1.0f}; // 11 degrees below the horizon
    const glm::dvec3 night = aerial_sky(aerial_frame(env, 0.0), {0, 0.2, 1});
    EXPECT_EQ(night, glm::dvec3(0.0));
}

// The haze thins with altitude: the same 20 km ray seen from 3000 m up keeps
// more of the surface than from sea level.
TEST(AerialPerspective, HigherEyeSeesFurther) {
    Environment env;
    env.atmosphere = true;
    const glm::dvec3 low = transmittance(aerial_frame(env, 0.0), 20000.0, 0.0);
    const glm::dvec3 high = transmittance(aerial_frame(env, 3000.0), 20000.0, 0.0);
    for (int c = 0; c < 3; ++c) EXPECT_GT(high[c], low[c]);
    EXPECT_LT(low.z, low.x); // blue is lost first
}

// The tables within one color level of the exact model, nearest entry,
// over distances, heights above and below the eye, directions and skies.
TEST(AerialTables, MatchTheExactModel) {
    Environment env;
    env.atmosphere = true;
    env.sun_dir = {-0.4f, 0.3f, 0.8f};
    const double eye_y = 1500.0;
    const AerialFrame f = aerial_frame(env, eye_y);
    AerialTables tables;
    tables.build(f, -1500.0f, 2500.0f);
    const Rgb8 surface{180, 120, 60};
    int worst = 0;
    for (double d : {1.0, 100.0, 1000.0, 5000.0, 20000.0, 60000.0, 200000.0})
        for (double dy : {-1500.0, -700.0, -30.0, 0.0, 400.0, 2500.0}) {
            if (std::abs(dy) > d) continue;
            const double h = std::sqrt(d * d - dy * dy);
            for (double az : {0.0, 1.0, 2.5, 4.0}) {
                const glm::dvec3 offset(h * std::cos(az), dy, h * std::sin(az));
                const double c = glm::dot(offset, f.sun) / d;
                const Rgb8 exact = aerial_rgb(f, surface, offset);
                const Rgb8 table = unpack_rgb(tables.terrain(pack_rgb(surface), float(d), float(dy), float(c)));
                worst = std::max(worst, max_channel_difference(exact, table));
            }
        }
    EXPECT_LE(worst, 1);
    int worst_sky = 0;
    for (double s : {-0.3, 0.0, 0.002, 0.05, 0.2, 0.6, 1.0})
        for (double az : {0.0, 1.0, 2.5, 4.0}) {
            const double h = std::sqrt(std::max(0.0, 1.0 - s * s));
            const glm::dvec3 dir(h * std::cos(az), s, h * std::sin(az));
            const Rgb8 exact = aerial_sky_rgb(f, dir);
            const Rgb8 table = unpack_rgb(tables.sky(float(s), float(glm::dot(dir, f.sun))));
            worst_sky = std::max(worst_sky, max_channel_difference(exact, table));
        }
    EXPECT_LE(worst_sky, 2);
}
