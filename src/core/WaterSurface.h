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
//   shallows the light from below: the bottom seen through a path p of
//            water, p = (level - bottom height) / -view.y (the water's depth
//            under the point, along the view ray), Beer-Lambert
//            T_c = exp(-absorption_c p), mixed with the deep-water color:
//            body = bottom T + deep light (1 - T), light = the sun and
//            ambient light of a level surface (core/SunLight.h);
//   color    mix(body, reflected, F) + a sun glint sun_color F max(R . L, 0)^256,
//            `reflected` the color seen along the mirrored ray R (sky or
//            terrain), then fog or the atmosphere like any terrain point.
//   As drawn the bottom is the color the renderer already has behind the
//   water (the terrain under it, fogged to its own distance): with
//   W_c = T_c (1 - F) the weight of the bottom, the pixel is
//       mix(fogged(surface), behind, W),  surface = (color - bottom W) / (1 - W),
//   which a GL blend (ONE, ONE_MINUS_SRC_ALPHA) does and the ray casters do
//   per pixel (W < 1: F >= F0).
//
// Under water (the eye below the level; the GL programs through fogged() and
// the water pass, the ray casters in raycast/WaterPass.h):
//   extinction  everything seen is dimmed over its path p in the water by
//            the same Beer-Lambert law towards the deep water's light:
//            c' = c T + deep light (1 - T), T_c = exp(-absorption_c p), applied
//            after the air's fog to what the renderer painted (objects too);
//   surface    seen from below (rays rising to the plane before the terrain)
//            it is opaque at the plane's depth: inside Snell's window (the
//            view ray refracts into air, n = 1.33) the sky along the refracted
//            ray times (1 - F) plus the depths' light times F, F Schlick's at
//            the refracted angle; outside it (total internal reflection) the
//            depths' light alone; then the extinction over the eye's path to
//            it. The terrain above the water is not seen through the surface
//            (the sky only), a simplification;
//   where no terrain is hit and no surface over the terrain (below the
//            horizon, or rising to the level beyond the terrain's edge), the
//            depths' light.
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

// The summed sine waves of water_normal: direction (unit), wavelength in
// cells, slope amplitude a_i |k_i| and angular speed in radians per second.
// Directions spread so that no crest pattern lines up; the slopes sum to 0.06.
struct WaterWave {
    float dx, dz, cells, slope, speed;
};
inline constexpr WaterWave kWaterWaves[4] = {
    {0.80f, 0.60f, 6.1f, 0.020f, 1.1f},
    {-0.45f, 0.89f, 3.7f, 0.016f, 1.7f},
    {0.96f, -0.28f, 2.3f, 0.014f, 2.3f},
    {-0.71f, -0.71f, 1.7f, 0.010f, 2.9f},
};

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
    float path = 0.0f;                  // view ray's length in the water to the bottom, >= 0
};

// What covers a water pixel: the water's own light, fogged like a terrain
// point, over `behind` (the bottom) weighted by W per channel.
struct WaterLight {
    glm::vec3 surface{0.0f}; // (color - bottom W) / (1 - W), before fog, [0, 1] but for the glint
    glm::vec3 behind{0.0f};  // W = T (1 - F)
};

// The path of a view ray `view` (unit, downwards) in water of depth `depth` (>= 0).
float water_path(float depth, const glm::vec3& view);

// The mirrored direction of `view` at `normal`, lifted to at least 0.01
// above the horizon (a wave never mirrors the ray into the water).
glm::vec3 water_reflect(const glm::vec3& view, const glm::vec3& normal);

// The surface's light (WaterLight) for one point.
WaterLight water_light(const Environment& env, const WaterSample& s);

// Water's index of refraction (air = 1).
inline constexpr float kWaterIndex = 1.33f;

// The light of deep water: kWaterDeep times the sun and ambient light of a
// level surface (1 with Environment::baked).
glm::vec3 water_deep_light(const Environment& env);

// The length of the segment from `eye` (below `level`) to `point` that lies
// under the level.
double underwater_path(const glm::dvec3& eye, const glm::dvec3& point, double level);

// `color` ([0, 1]) seen through `path` world units of water: c T + deep light (1 - T).
glm::vec3 underwater_color(const Environment& env, const glm::vec3& color, float path);

// The direction a view ray `view` (unit, rising) from under the water takes
// into the air through the waves' `normal`; zero under total internal reflection.
glm::vec3 water_refract_up(const glm::vec3& view, const glm::vec3& normal);

// The surface seen from below (before the extinction): `sky` ([0, 1]) is
// the sky's color along water_refract_up(view, normal), unused when that is zero.
glm::vec3 water_underside(const Environment& env, const glm::vec3& view, const glm::vec3& normal, const glm::vec3& sky);

// The level `--water` alone floods to: the data set's sea level
// (Environment::sea_level) if it gives one; else 0 when the terrain's
// heights span it; else (a DEM whose sea is no-data, filled at its lowest
// height) one height step (v_scale) above the lowest sample.
double default_water_level(const Terrain& terrain, const Environment& env);

// Why `level` cannot be the water's (not finite, or outside the terrain's
// heights [min, max]: all dry or all flooded), or "" when it can.
std::string water_level_problem(const Terrain& terrain, double level);

} // namespace overflight
