// Based on: CMSC 23700 project 2a (GL_EXP fog, sky), Szenberg 1997 sec. 5. See Atmosphere.h.
#include "raycast/Atmosphere.h"

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

} // namespace overflight
