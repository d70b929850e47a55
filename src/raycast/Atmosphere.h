#pragma once
// Sky, fog and atmosphere shared by every terrain ray caster (fast, literal, reference),
// so that voxel images match the mesh renderers pixel for pixel.
//
// Based on: the hovercraft project (CMSC 23700 project 2a), "GL_EXP fog and skybox", and
// Szenberg 1997 sec. 5 (the ray-cast image is composited with GL primitives,
// so fog must be computed the way a GL fragment shader computes it).
//
// Conventions (the GL layer uses the same ones):
//   fog factor  f = exp(-density * distance), distance = eye-space distance
//               |P - eye| of the surface point hit through the pixel centre
//               (GLSL: length(eye_pos)), color = f * surface + (1 - f) * fog;
//   sky         mix(sky_horizon, sky_zenith, clamp(sin(elevation), 0, 1)),
//               elevation of the pixel-centre ray; no fog on the sky;
//   atmosphere  (Environment::atmosphere, instead of both) the aerial
//               perspective and sky of core/AerialPerspective.h, exactly
//               (aerial_rgb) or from per-frame tables (AerialTables).
#include "core/AerialPerspective.h"
#include "core/DataSet.h"
#include "core/Image.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace overflight {

// Packs a color as 0x00BBGGRR (the internal format of the ray casters' buffers).
inline std::uint32_t pack_rgb(Rgb8 c) { return std::uint32_t(c.r) | (std::uint32_t(c.g) << 8) | (std::uint32_t(c.b) << 16); }
inline Rgb8 unpack_rgb(std::uint32_t p) {
    return Rgb8{std::uint8_t(p & 0xFF), std::uint8_t((p >> 8) & 0xFF), std::uint8_t((p >> 16) & 0xFF)};
}
// A [0,1] float color to 8 bits, rounded and clamped.
Rgb8 to_rgb8(const glm::vec3& c);

// Sky color for a ray direction (any length, must not be zero).
Rgb8 sky_color(const Environment& env, const glm::dvec3& dir);
// Sky color from the sine of the ray's elevation angle.
Rgb8 sky_color_from_sine(const Environment& env, double sin_elevation);

// The exact aerial perspective (core/AerialPerspective.h) on 8-bit colors,
// for the ray casters that evaluate every pixel: a surface point at offset
// (point - eye) from the eye, and the sky along a ray direction (not zero).
Rgb8 aerial_rgb(const AerialFrame& f, Rgb8 surface, const glm::dvec3& offset);
Rgb8 aerial_sky_rgb(const AerialFrame& f, const glm::dvec3& dir);

// GL_EXP fog factor for an eye distance: exp(-density * distance), 1 without fog.
double fog_factor(const Environment& env, double distance);
// Blends a surface color towards the fog color by factor f (1 = no fog), rounding to nearest.
Rgb8 apply_fog(const Environment& env, Rgb8 surface, double f);

// exp(-density * distance) tabulated over [0, max_distance] as 8.8 fixed-point
// blend weights (0..256), nearest entry, rebuilt per frame without allocating
// once sized: the fast ray caster needs one fog factor per painted pixel and
// exp() there would cost more than the ray casting itself. With 4096 entries
// the factor is off by at most density*max_distance/8192 + 1/512, under one
// color level for density * max_distance <= 8. Entries are 32-bit so that a
// vectorised loop can gather them.
class FogTable {
public:
    // Rebuilds only when density or max_distance changed.
    void build(float density, float max_distance);
    bool enabled() const { return enabled_; }
    // Blend weight of the surface color, 0..256, for a distance >= 0 (past max_distance clamps).
    std::uint32_t weight(float distance) const {
        const float x = distance * inv_step_ + 0.5f;
        return table_[std::size_t(x < float(kEntries) ? int(x) : kEntries)];
    }

    // The table behind weight(), for loops that look it up themselves:
    // weight(x) = entries()[min(int(x * inv_step() + 0.5), kEntries)].
    const std::uint32_t* entries() const { return table_.data(); }
    float inv_step() const { return inv_step_; }

    static constexpr int kEntries = 4096;

private:
    bool enabled_ = false;
    float density_ = 0.0f, max_distance_ = 0.0f; // what the table was built for
    float inv_step_ = 0.0f;
    std::vector<std::uint32_t> table_;
};

// The sky gradient tabulated over sin(elevation) in [0, 1], packed colors,
// nearest entry (kEntries levels: finer than the 8-bit color steps).
class SkyTable {
public:
    // Rebuilds only when the environment's sky colors changed.
    void build(const Environment& env);
    // Sky color for the sine of a ray's elevation. Converted before it is
    // clamped (|sine| <= 1 keeps the conversion in range), so that loops over
    // it vectorise.
    std::uint32_t color(float sine) const { return lookup(table_.data(), sine); }
    static std::uint32_t lookup(const std::uint32_t* entries, float sine) {
        const int x = int(sine * float(kEntries - 1) + 0.5f);
        return entries[x < 0 ? 0 : (x > kEntries - 1 ? kEntries - 1 : x)];
    }
    const std::uint32_t* entries() const { return table_.data(); }

    static constexpr int kEntries = 1024;

private:
    glm::vec3 horizon_{0.0f}, zenith_{0.0f}; // what the table was built for
    std::vector<std::uint32_t> table_;
};

// The aerial perspective and sky of core/AerialPerspective.h tabulated once
// per frame for one eye, so that a ray caster evaluates them per pixel with
// table lookups and integer blends, nearest entry, no exp() (Environment::
// atmosphere). T = exp(-beta rho0 d G(dy / H)) is one function of the air
// column X = rho0 d G(dy / H) per channel, and G depends on the height
// difference alone, so three 1-D tables replace a (distance, height,
// direction) volume:
//   column[j]   rho0 G(dy_j / H) over the terrain's height range below and
//               above the eye (kHeights entries), so that X = d column[j];
//   transmit[i] T at X = i X_step, 10 bits per channel 0..256 (kColumns + 1
//               entries up to where the least absorbed channel keeps 1/1024,
//               nearest entry within 1 color level);
//   haze[p]     C at cos theta = 2 p / (kPhases - 1) - 1, packed 0x00BBGGRR;
//   opacity[q]  V at sine q / (kSkies - 1), 10 bits per channel 0..256.
// A terrain pixel is then (surface T + C (256 - T) + 128) >> 8 per channel,
// a sky pixel (V C + 128) >> 8. Entries are 32-bit so that vectorised loops
// can gather them. Measured against the exact model in the tests.
class AerialTables {
public:
    // Builds for a frame: heights dy in [dy_lo, dy_hi] relative to the eye
    // (clamped beyond). The large tables are rebuilt only when what they
    // depend on changed (a benchmark's frames, a flight's transmittance).
    void build(const AerialFrame& frame, float dy_lo, float dy_hi);

    // A terrain pixel: packed surface color, eye distance, height relative to
    // the eye, cosine of the ray's angle to the sun.
    std::uint32_t terrain(std::uint32_t surface, float distance, float dy, float cos_sun) const {
        const float x = distance * column_[std::size_t(height_index(dy))] + 0.5f;
        const int i = int(x < float(kColumns) ? x : float(kColumns));
        return blend(surface, transmit_[std::size_t(i)], haze_[std::size_t(phase_index(cos_sun))]);
    }
    // A sky pixel: elevation sine and cosine to the sun of its ray.
    std::uint32_t sky(float sine, float cos_sun) const {
        return shade_sky(opacity_[std::size_t(sky_index(sine))], haze_[std::size_t(phase_index(cos_sun))]);
    }

    // The indices, for loops that look the tables up themselves.
    int height_index(float dy) const { return clamp_index((dy - dy_lo_) * inv_dy_step_ + 0.5f, kHeights - 1); }
    static int phase_index(float cos_sun) { return clamp_index((cos_sun + 1.0f) * kPhaseScale + 0.5f, kPhases - 1); }
    static int sky_index(float sine) { return clamp_index(sine * float(kSkies - 1) + 0.5f, kSkies - 1); }
    // Converted after clamping in float, so that any input is in range.
    static int clamp_index(float x, int last) { return int(x < 0.0f ? 0.0f : (x > float(last) ? float(last) : x)); }

    // Per channel: surface T + haze (256 - T), T 10-bit fields of t.
    static std::uint32_t blend(std::uint32_t surface, std::uint32_t t, std::uint32_t haze) {
        std::uint32_t out = 0;
        for (int c = 0; c < 3; ++c) {
            const std::uint32_t w = (t >> (10 * c)) & 0x3FFu, s = (surface >> (8 * c)) & 0xFFu, h = (haze >> (8 * c)) & 0xFFu;
            out |= ((s * w + h * (256u - w) + 128u) >> 8) << (8 * c);
        }
        return out;
    }
    // Per channel: (V haze + 128) >> 8, V 10-bit fields of v.
    static std::uint32_t shade_sky(std::uint32_t v, std::uint32_t haze) {
        std::uint32_t out = 0;
        for (int c = 0; c < 3; ++c)
            out |= ((((v >> (10 * c)) & 0x3FFu) * ((haze >> (8 * c)) & 0xFFu) + 128u) >> 8) << (8 * c);
        return out;
    }

    const float* column() const { return column_.data(); }
    const std::uint32_t* transmit() const { return transmit_.data(); }
    const std::uint32_t* haze() const { return haze_.data(); }
    const std::uint32_t* opacity() const { return opacity_.data(); }
    float dy_lo() const { return dy_lo_; }
    float inv_dy_step() const { return inv_dy_step_; }

    static constexpr int kHeights = 256, kColumns = 4096, kPhases = 1024, kSkies = 1024;
    static constexpr float kPhaseScale = 0.5f * float(kPhases - 1);

private:
    AerialFrame built_;
    float dy_lo_ = 0.0f, inv_dy_step_ = 0.0f;
    std::vector<float> column_;
    std::vector<std::uint32_t> transmit_, haze_, opacity_;
};

// Per-channel blend towards the fog color with the surface weight a in 0..256.
inline std::uint32_t fog_blend(std::uint32_t surface, std::uint32_t fog, std::uint32_t a) {
    const std::uint32_t b = 256 - a;
    // Red and blue share one multiply (SWAR): each product stays below 2^16.
    const std::uint32_t rb = (((surface & 0xFF00FFu) * a + (fog & 0xFF00FFu) * b + 0x800080u) >> 8) & 0xFF00FFu;
    const std::uint32_t g = (((surface & 0x00FF00u) * a + (fog & 0x00FF00u) * b + 0x008000u) >> 8) & 0x00FF00u;
    return rb | g;
}

} // namespace overflight
