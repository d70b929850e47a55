// Based on: Tessendorf, "Simulating Ocean Water" (2001), sec. 3; Schlick,
// "An Inexpensive BRDF Model for Physically-based Rendering" (1994), eq. 24.
// See WaterSurface.h.
#include "core/WaterSurface.h"

#include "core/SunLight.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace overflight {

float water_fresnel(float cos_incidence) {
    const float c = std::clamp(cos_incidence, 0.0f, 1.0f);
    const float m = 1.0f - c;
    return kWaterF0 + (1.0f - kWaterF0) * m * m * m * m * m;
}

glm::vec3 water_normal(float x, float z, double time, float cell) {
    // dh/dx of a sin(k d.(x, z) - w t) is a k d_x cos(...): slope d_x cos(...).
    float gx = 0.0f, gz = 0.0f;
    for (const WaterWave& w : kWaterWaves) {
        const double k = 2.0 * 3.14159265358979323846 / (double(w.cells) * double(cell));
        const double phase = k * (double(w.dx) * x + double(w.dz) * z) - double(w.speed) * time;
        const float c = float(std::cos(phase));
        gx += w.slope * w.dx * c;
        gz += w.slope * w.dz * c;
    }
    return glm::normalize(glm::vec3(-gx, 1.0f, -gz));
}

glm::vec3 water_reflect(const glm::vec3& view, const glm::vec3& normal) {
    glm::vec3 r = view - 2.0f * glm::dot(view, normal) * normal;
    if (r.y < 0.01f) r = glm::normalize(glm::vec3(r.x, 0.01f * std::hypot(r.x, r.z), r.z));
    return r;
}

float water_path(float depth, const glm::vec3& view) { return std::max(depth, 0.0f) / std::max(-view.y, 1e-3f); }

WaterLight water_light(const Environment& env, const WaterSample& s) {
    const float fresnel = water_fresnel(-glm::dot(s.view, s.normal));
    const glm::vec3 light = env.baked ? glm::vec3(1.0f) : sample_light(env, glm::vec3(0.0f, 1.0f, 0.0f), true);
    WaterLight out;
    glm::vec3 own = s.reflected * fresnel; // everything but the bottom
    for (int c = 0; c < 3; ++c) {
        const float t = std::exp(-kWaterAbsorption[c] * std::max(s.path, 0.0f));
        own[c] += kWaterDeep[c] * light[c] * (1.0f - t) * (1.0f - fresnel);
        out.behind[c] = t * (1.0f - fresnel);
    }
    const glm::vec3 sun = glm::normalize(env.sun_dir);
    if (sun.y > 0.0f && !env.baked) {
        const float glint = std::max(glm::dot(water_reflect(s.view, s.normal), sun), 0.0f);
        own += env.sun_color * (fresnel * std::pow(glint, 256.0f));
    }
    out.surface = own / (glm::vec3(1.0f) - out.behind);
    return out;
}

glm::vec3 water_deep_light(const Environment& env) {
    const glm::vec3 light = env.baked ? glm::vec3(1.0f) : sample_light(env, glm::vec3(0.0f, 1.0f, 0.0f), true);
    return glm::vec3(kWaterDeep[0], kWaterDeep[1], kWaterDeep[2]) * light;
}

double underwater_path(const glm::dvec3& eye, const glm::dvec3& point, double level) {
    const double length = glm::length(point - eye);
    if (!(point.y > level)) return length;
    // Only the part up to the level: the fraction (level - eye) / (point - eye) of it.
    return length * std::clamp((level - eye.y) / (point.y - eye.y), 0.0, 1.0);
}

glm::vec3 underwater_color(const Environment& env, const glm::vec3& color, float path) {
    const glm::vec3 deep = water_deep_light(env);
    glm::vec3 out;
    for (int c = 0; c < 3; ++c) {
        const float t = std::exp(-kWaterAbsorption[c] * std::max(path, 0.0f));
        out[c] = color[c] * t + deep[c] * (1.0f - t);
    }
    return out;
}

glm::vec3 water_refract_up(const glm::vec3& view, const glm::vec3& normal) {
    // GLSL's refract(I, N, eta) with N = -normal facing the ray, eta = n_water / n_air.
    const glm::vec3 n = -normal;
    const float d = glm::dot(n, view), eta = kWaterIndex;
    const float k = 1.0f - eta * eta * (1.0f - d * d);
    if (k < 0.0f) return glm::vec3(0.0f);
    return eta * view - (eta * d + std::sqrt(k)) * n;
}

glm::vec3 water_underside(const Environment& env, const glm::vec3& view, const glm::vec3& normal, const glm::vec3& sky) {
    const glm::vec3 deep = water_deep_light(env);
    const glm::vec3 t = water_refract_up(view, normal);
    if (t == glm::vec3(0.0f)) return deep;
    const float f = water_fresnel(glm::dot(t, normal));
    return sky * (1.0f - f) + deep * f;
}

double default_water_level(const Terrain& terrain, const Environment& env) {
    if (env.sea_level) return double(*env.sea_level);
    if (terrain.min_height() <= 0.0f && terrain.max_height() >= 0.0f) return 0.0;
    return double(terrain.min_height()) + double(terrain.v_scale());
}

std::string water_level_problem(const Terrain& terrain, double level) {
    std::ostringstream out;
    if (!std::isfinite(level)) return "the level must be a finite number";
    if (level < double(terrain.min_height()) || level > double(terrain.max_height())) {
        out << level << " is outside the terrain's heights " << terrain.min_height() << ".." << terrain.max_height();
        return out.str();
    }
    return "";
}

} // namespace overflight
