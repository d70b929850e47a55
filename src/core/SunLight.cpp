// Based on: CMSC 23700 hovercraft project sec. 4.1 (sun and ambient light). See SunLight.h.
#include "core/SunLight.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <glm/gtc/constants.hpp>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace overflight {

namespace {

glm::vec3 unit_sun(const Environment& env) {
    return glm::length(env.sun_dir) > 0 ? glm::normalize(env.sun_dir) : glm::vec3(0, 1, 0);
}

bool same_light(const Environment& a, const Environment& b) {
    return a.sun_dir == b.sun_dir && a.sun_color == b.sun_color && a.ambient == b.ambient && a.shadows == b.shadows &&
           a.baked == b.baked;
}

std::uint8_t channel(std::uint8_t albedo, float light) {
    const float v = float(albedo) * light + 0.5f;
    return std::uint8_t(v > 0.0f ? std::min(v, 255.0f) : 0.0f);
}

} // namespace

glm::vec3 sun_direction(double azimuth_deg, double elevation_deg) {
    const double az = glm::radians(azimuth_deg), el = glm::radians(elevation_deg);
    return glm::vec3(float(std::sin(az) * std::cos(el)), float(std::sin(el)), float(-std::cos(az) * std::cos(el)));
}

SunAngles sun_angles(const glm::vec3& sun_dir) {
    const glm::dvec3 d = glm::normalize(glm::dvec3(sun_dir));
    SunAngles a;
    a.elevation = glm::degrees(std::asin(std::clamp(d.y, -1.0, 1.0)));
    a.azimuth = glm::degrees(std::atan2(d.x, -d.z));
    if (a.azimuth < 0) a.azimuth += 360.0;
    return a;
}

glm::vec3 sun_at_hour(double hour) {
    // Azimuth sweeps east -> south -> west by day and goes on round the north by night.
    const double day = (hour - 6.0) / 12.0; // 0 at sunrise, 1 at sunset
    return sun_direction(std::fmod(90.0 + 180.0 * day + 360.0, 360.0), kNoonElevation * std::sin(glm::pi<double>() * day));
}

double hour_of_sun(const glm::vec3& sun_dir) {
    // By day the arc's azimuth runs from 90 (east) to 270 (west); a northern
    // sun is taken to the nearer end.
    const double az = std::clamp(sun_angles(sun_dir).azimuth, 90.0, 270.0);
    return 6.0 + 12.0 * (az - 90.0) / 180.0;
}

void bake_lighting(Environment& env) { env.baked = true; }

bool lighting_is_baked(const Environment& env) { return env.baked; }

glm::vec3 sample_light(const Environment& env, const glm::vec3& n, bool lit) {
    const glm::vec3 sun = unit_sun(env);
    const float lambert = sun.y > 0 && lit ? std::max(glm::dot(n, sun), 0.0f) : 0.0f;
    return env.ambient + env.sun_color * lambert;
}

void light_colors(const Terrain& t, const Environment& env, const ShadowCeiling* shadow, std::vector<Rgb8>& out,
                  LightOutput output) {
    const bool light_only = output == LightOutput::Light;
    out.resize(t.colors().size());
    const glm::vec3 sun = unit_sun(env);
    const bool day = sun.y > 0;
    const int rows = t.rows(), cols = t.cols();
    const float vs = t.v_scale(), y0 = t.y_offset(), hs = t.h_scale();
    const std::uint16_t* raw = t.heights().data();
    tbb::parallel_for(0, rows, [&](int row) {
        // Terrain::sample_normal, written out over one row.
        const int r0 = std::max(row - 1, 0), r1 = std::min(row + 1, rows - 1);
        const std::uint16_t* above = raw + t.index(r0, 0);
        const std::uint16_t* here = raw + t.index(row, 0);
        const std::uint16_t* below = raw + t.index(r1, 0);
        const float inv_dz = 1.0f / (hs * float(r1 - r0));
        for (int col = 0; col < cols; ++col) {
            const int c0 = std::max(col - 1, 0), c1 = std::min(col + 1, cols - 1);
            const float dhdx = vs * (float(here[c1]) - float(here[c0])) / (hs * float(c1 - c0));
            const float dhdz = vs * (float(below[col]) - float(above[col])) * inv_dz;
            const float h = vs * float(here[col]) + y0;
            const bool lit = day && (!shadow || !shadow->shadowed(row, col, h));
            float lambert = 0.0f;
            if (lit) lambert = std::max((sun.y - dhdx * sun.x - dhdz * sun.z) / std::sqrt(dhdx * dhdx + 1.0f + dhdz * dhdz), 0.0f);
            const glm::vec3 light = env.ambient + env.sun_color * lambert;
            const std::size_t i = t.index(row, col);
            const Rgb8 a = light_only ? Rgb8{128, 128, 128} : t.colors()[i];
            out[i] = Rgb8{channel(a.r, light.r), channel(a.g, light.g), channel(a.b, light.b)};
        }
    });
}

const std::vector<Rgb8>* TerrainLighting::colors(const Environment& env) {
    if (valid_ && same_light(env, lit_for_)) return baked_ ? nullptr : &colors_;
    valid_ = true;
    lit_for_ = env;
    ++version_;
    baked_ = lighting_is_baked(env);
    if (baked_ && output_ == LightOutput::Light) {
        colors_.assign(terrain_.colors().size(), Rgb8{128, 128, 128});
        baked_ = false; // the light of 1 is what to paint
        return &colors_;
    }
    if (baked_) return nullptr;
    const ShadowCeiling* shadow = nullptr;
    if (env.shadows) {
        const glm::vec3 sun = unit_sun(env);
        if (!shadow_valid_ || shadow_.sun_dir != sun) sweep_shadow_ceiling(terrain_, sun, shadow_);
        shadow_valid_ = true;
        shadow = &shadow_;
    }
    light_colors(terrain_, env, shadow, colors_, output_);
    return &colors_;
}

} // namespace overflight
