#pragma once
// A water surface: the horizontal plane y = level over the terrain, drawn as
// an animated mirror. The model every terrain method shares (the ray casters
// evaluate it per pixel in raycast/WaterPass.h, the GL programs through its
// GLSL twin in gl/WaterPlane.cpp, term for term):
//
//   waves    the plane's normal tilted by the slope of a few summed sine
//            waves h(x, z, t) = sum_i a_i sin(k_i . (x, z) - w_i t) (Tessendorf,
//            "Simulating Ocean Water", SIGGRAPH course notes 2001, sec. 3: a
//            sum of waves; here four fixed ones, deterministic in t), with
//            wavelengths in cells of the height field so they show at any
//            scale: N = normalize(-dh/dx, 1, -dh/dz);
//   Fresnel  the share of reflected light F = F0 + (1 - F0)(1 - cos)^5 (Schlick,
//            "An Inexpensive BRDF Model for Physically-based Rendering",
//            Eurographics 1994, eq. 24), F0 = 0.02 (water, n = 1.33), cos the
//            cosine between the view ray and N;
//   shallows the light from below: the bottom's color seen through a path p
//            of water (the view ray from the surface to the terrain behind
//            it), Beer-Lambert T_c = exp(-absorption_c p), mixed with the
//            deep-water color: body = bottom T + deep light (1 - T), light =
//            the sun and ambient light of a level surface (core/SunLight.h);
//   color    mix(body, reflected, F) + a sun glint sun_color F max(R . L, 0)^256,
//            `reflected` the color seen along the mirrored ray R (sky or
//            terrain), then fog or the atmosphere like any terrain point.
//
// No GL, no I/O.
#include "core/DataSet.h"
#include "core/Terrain.h"

#include <glm/vec3.hpp>

#include <string>

namespace overflight {

// Water's reflectance at normal incidence (n = 1.33: ((n - 1)/(n + 1))^2).
inline constexpr float kWaterF0 = 0.02f;
// Light absorbed per world unit of water path, per channel (red first).
inline constexpr float kWaterAbsorption[3] = {0.30f, 0.08f, 0.05f};
// The albedo of deep water (what a path long enough to absorb the bottom shows).
inline constexpr float kWaterDeep[3] = {0.02f, 0.10f, 0.14f};

// Schlick's Fresnel factor for the cosine of the angle of incidence
// (clamped to [0, 1]): kWaterF0 at normal incidence, 1 at grazing.
float water_fresnel(float cos_incidence);

// The unit normal of the waves at world (x, z), `time` seconds in; the
// waves' lengths are 1.7 to 6.1 cells of `cell` (the terrain's h_scale) and
// their slopes at most 0.06 together. The same (x, z, time) always gives
// the same normal.
glm::vec3 water_normal(float x, float z, double time, float cell);

// What water_color needs of one point of the surface.
struct WaterSample {
    glm::vec3 view{0.0f, -1.0f, 0.0f}; // unit, from the eye towards the point
    glm::vec3 normal{0.0f, 1.0f, 0.0f}; // water_normal there
    glm::vec3 reflected{0.0f};          // color along the mirrored ray, [0, 1]
    glm::vec3 bottom{0.0f};             // the terrain's color under the point, lit, [0, 1]
    float path = 0.0f;                  // view ray's length in the water (to the terrain behind), >= 0
};

// The mirrored direction of `view` at `normal`, lifted to at least 0.01
// above the horizon (a wave never mirrors the ray into the water).
glm::vec3 water_reflect(const glm::vec3& view, const glm::vec3& normal);

// The surface's color before fog or atmosphere, [0, 1] (may exceed 1 in
// the glint; callers clamp).
glm::vec3 water_color(const Environment& env, const WaterSample& s);

// The level `--water` alone floods to: the data set's sea level
// (Environment::sea_level) if it gives one; else 0 when the terrain's
// heights span it; else (a DEM whose sea is no-data, filled at its lowest
// height) one height step (v_scale) above the lowest sample.
double default_water_level(const Terrain& terrain, const Environment& env);

// Why `level` cannot be the water's (not finite, or outside the terrain's
// heights [min, max]: all dry or all flooded), or "" when it can.
std::string water_level_problem(const Terrain& terrain, double level);

} // namespace overflight
