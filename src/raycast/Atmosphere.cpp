// Based on: CMSC 23700 project 2a (GL_EXP fog, sky), Szenberg 1997 sec. 5. See Atmosphere.h.
#include "raycast/Atmosphere.h"

#include <glm/exponential.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace overflight {

Rgb8 to_rgb8(const glm::vec3& c) {
    auto q = [](float v) { return std::uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
    return Rgb8{q(c.r), q(c.g), q(c.b)};
}

Rgb8 sky_color_from_sine(const Environment& env, double sin_elevation) {
    const float t = float(std::clamp(sin_elevation, 0.0, 1.0));
    return to_rgb8(env.sky_horizon + t * (env.sky_zenith - env.sky_horizon));
}

Rgb8 sky_color(const Environment& env, const glm::dvec3& dir) {
    return sky_color_from_sine(env, dir.y / glm::length(dir));
}

Rgb8 aerial_rgb(const AerialFrame& f, Rgb8 surface, const glm::dvec3& offset) {
    const glm::dvec3 s = glm::dvec3(surface.r, surface.g, surface.b) / 255.0;
    return to_rgb8(glm::vec3(aerial_perspective(f, s, offset)));
}

Rgb8 aerial_sky_rgb(const AerialFrame& f, const glm::dvec3& dir) { return to_rgb8(glm::vec3(aerial_sky(f, dir))); }

double fog_factor(const Environment& env, double distance) {
    if (!(env.fog_density > 0.0f)) return 1.0;
    return std::exp(-double(env.fog_density) * distance);
}

Rgb8 apply_fog(const Environment& env, Rgb8 surface, double f) {
    const glm::vec3 s = glm::vec3(surface.r, surface.g, surface.b) / 255.0f;
    return to_rgb8(float(f) * s + (1.0f - float(f)) * env.fog_color);
}

void FogTable::build(float density, float max_distance) {
    // A flight or a benchmark asks for the same table every frame.
    if (!table_.empty() && density == density_ && max_distance == max_distance_) return;
    density_ = density;
    max_distance_ = max_distance;
    enabled_ = density > 0.0f && max_distance > 0.0f;
    table_.resize(std::size_t(kEntries) + 1);
    if (!enabled_) {
        std::fill(table_.begin(), table_.end(), std::uint32_t(256));
        inv_step_ = 0.0f;
        return;
    }
    const double step = double(max_distance) / kEntries;
    inv_step_ = float(1.0 / step);
    for (int i = 0; i <= kEntries; ++i)
        table_[std::size_t(i)] = std::uint32_t(std::lround(256.0 * std::exp(-double(density) * step * i)));
}

void SkyTable::build(const Environment& env) {
    if (!table_.empty() && env.sky_horizon == horizon_ && env.sky_zenith == zenith_) return;
    horizon_ = env.sky_horizon;
    zenith_ = env.sky_zenith;
    table_.resize(kEntries);
    for (int i = 0; i < kEntries; ++i) table_[std::size_t(i)] = pack_rgb(sky_color_from_sine(env, double(i) / (kEntries - 1)));
}

namespace {

// 10 bits per channel of a [0,1] weight scaled to 0..256.
std::uint32_t pack_weights(const glm::dvec3& w) {
    std::uint32_t out = 0;
    for (int c = 0; c < 3; ++c) out |= std::uint32_t(std::lround(256.0 * std::clamp(w[c], 0.0, 1.0))) << (10 * c);
    return out;
}

std::uint32_t pack_color(const glm::dvec3& c) { return pack_rgb(to_rgb8(glm::vec3(c))); }

} // namespace

void AerialTables::build(const AerialFrame& f, float dy_lo, float dy_hi) {
    if (!(dy_hi > dy_lo)) dy_hi = dy_lo + 1.0f;
    dy_lo_ = dy_lo;
    const double dy_step = double(dy_hi - dy_lo) / (kHeights - 1);
    inv_dy_step_ = float(1.0 / dy_step);
    // The air column's range: up to where every channel keeps 1/1024 (the
    // last entry, all but zero, stands for anything further). It depends on
    // the coefficients alone, so a flight rebuilds only the small tables.
    const double least = std::min({f.beta.x, f.beta.y, f.beta.z});
    const double x_step = (least > 0.0 ? std::log(1024.0) / least : 1.0) / kColumns;
    column_.resize(kHeights);
    for (int j = 0; j < kHeights; ++j)
        column_[std::size_t(j)] =
            float(f.eye_density * height_factor((dy_lo + dy_step * j) / f.scale_height) / x_step);
    if (transmit_.empty() || f.beta != built_.beta) {
        transmit_.resize(std::size_t(kColumns) + 1);
        for (int i = 0; i <= kColumns; ++i) transmit_[std::size_t(i)] = pack_weights(glm::exp(-f.beta * (x_step * i)));
    }
    if (haze_.empty() || f.sun != built_.sun || f.rayleigh_light != built_.rayleigh_light ||
        f.haze_light != built_.haze_light || f.g != built_.g) {
        haze_.resize(kPhases);
        for (int p = 0; p < kPhases; ++p) haze_[std::size_t(p)] = pack_color(haze_color(f, 2.0 * p / (kPhases - 1) - 1.0));
    }
    if (opacity_.empty() || f.beta != built_.beta || f.eye_density != built_.eye_density ||
        f.scale_height != built_.scale_height) {
        opacity_.resize(kSkies);
        for (int q = 0; q < kSkies; ++q) opacity_[std::size_t(q)] = pack_weights(sky_opacity(f, double(q) / (kSkies - 1)));
    }
    built_ = f;
}

} // namespace overflight
