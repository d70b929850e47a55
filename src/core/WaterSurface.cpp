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

namespace {

// The four waves: direction (unit), wavelength in cells, slope amplitude
// a_i |k_i| and angular speed in radians per second. Directions spread so
// that no crest pattern lines up; the slopes sum to 0.06.
struct Wave {
    float dx, dz, cells, slope, speed;
};
constexpr Wave kWaves[4] = {
    {0.80f, 0.60f, 6.1f, 0.020f, 1.1f},
    {-0.45f, 0.89f, 3.7f, 0.016f, 1.7f},
    {0.96f, -0.28f, 2.3f, 0.014f, 2.3f},
    {-0.71f, -0.71f, 1.7f, 0.010f, 2.9f},
};

} // namespace

float water_fresnel(float cos_incidence) {
    const float c = std::clamp(cos_incidence, 0.0f, 1.0f);
    const float m = 1.0f - c;
    return kWaterF0 + (1.0f - kWaterF0) * m * m * m * m * m;
}

glm::vec3 water_normal(float x, float z, double time, float cell) {
    // dh/dx of a sin(k d.(x, z) - w t) is a k d_x cos(...): slope d_x cos(...).
    float gx = 0.0f, gz = 0.0f;
    for (const Wave& w : kWaves) {
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

glm::vec3 water_color(const Environment& env, const WaterSample& s) {
    const float fresnel = water_fresnel(-glm::dot(s.view, s.normal));
    const glm::vec3 light = sample_light(env, glm::vec3(0.0f, 1.0f, 0.0f), true);
    glm::vec3 body;
    for (int c = 0; c < 3; ++c) {
        const float t = std::exp(-kWaterAbsorption[c] * std::max(s.path, 0.0f));
        body[c] = s.bottom[c] * t + kWaterDeep[c] * light[c] * (1.0f - t);
    }
    glm::vec3 color = body + (s.reflected - body) * fresnel;
    const glm::vec3 sun = glm::normalize(env.sun_dir);
    if (sun.y > 0.0f) {
        const float glint = std::max(glm::dot(water_reflect(s.view, s.normal), sun), 0.0f);
        color += env.sun_color * (fresnel * std::pow(glint, 256.0f));
    }
    return color;
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
