// Based on: Hoffman, Preetham, "Rendering Outdoor Light Scattering in Real
// Time" (GDC 2002); Henyey, Greenstein, "Diffuse radiation in the galaxy"
// (1941); Kasten, Young, "Revised optical air mass tables and approximation
// formula" (Applied Optics, 1989). See AerialPerspective.h.
#include "core/AerialPerspective.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace overflight {

namespace {

constexpr double kInvGamma = 1.0 / 2.2;

// Twilight: the sunlight fades out between the horizon and this elevation sine below it.
constexpr double kTwilightSine = 0.1;

double display(double light) { return std::pow(1.0 - std::exp(-light), kInvGamma); }

} // namespace

double air_mass(double sin_elevation) {
    const double s = std::clamp(sin_elevation, 0.0, 1.0);
    const double degrees = std::asin(s) * (180.0 / 3.14159265358979323846);
    return 1.0 / (s + 0.50572 * std::pow(degrees + 6.07995, -1.6364));
}

double height_factor(double x) {
    x = std::max(x, -40.0);
    if (std::abs(x) < 1e-3) return 1.0 - x * (0.5 - x / 6.0);
    return (1.0 - std::exp(-x)) / x;
}

glm::dvec2 phases(double g, double c) {
    const double rayleigh = 0.75 * (1.0 + c * c);
    const double hg = (1.0 - g * g) / std::pow(1.0 + g * g - 2.0 * g * c, 1.5);
    return {rayleigh, hg};
}

AerialFrame aerial_frame(const Environment& env, double eye_y) {
    const AtmosphereParams& a = env.air;
    AerialFrame f;
    f.sun = glm::length(env.sun_dir) > 0.0f ? glm::normalize(glm::dvec3(env.sun_dir)) : glm::dvec3(0.0, 1.0, 0.0);
    f.beta = glm::dvec3(a.rayleigh) + double(a.haze);
    f.scale_height = a.scale_height;
    f.eye_density = std::exp(-eye_y / f.scale_height);
    f.g = a.haze_g;
    const double twilight = std::clamp(1.0 + f.sun.y / kTwilightSine, 0.0, 1.0);
    const double column = f.eye_density * f.scale_height * air_mass(f.sun.y);
    for (int c = 0; c < 3; ++c) {
        const double light = double(a.exposure) * a.sunlight[c] * height_factor(f.beta[c] * column) * twilight;
        f.rayleigh_light[c] = light * a.rayleigh[c] / f.beta[c];
        f.haze_light[c] = light * a.haze / f.beta[c];
    }
    return f;
}

glm::dvec3 transmittance(const AerialFrame& f, double distance, double dy) {
    const double column = f.eye_density * distance * height_factor(dy / f.scale_height);
    return glm::exp(-f.beta * column);
}

glm::dvec3 haze_color(const AerialFrame& f, double cos_theta) {
    const glm::dvec2 p = phases(f.g, cos_theta);
    const glm::dvec3 light = f.rayleigh_light * p.x + f.haze_light * p.y;
    return {display(light.x), display(light.y), display(light.z)};
}

glm::dvec3 sky_opacity(const AerialFrame& f, double sine) {
    if (!(sine > 0.0)) return glm::dvec3(1.0);
    const glm::dvec3 tau = f.beta * (f.eye_density * f.scale_height / sine);
    return {display(tau.x), display(tau.y), display(tau.z)};
}

glm::dvec3 aerial_perspective(const AerialFrame& f, const glm::dvec3& surface, const glm::dvec3& offset) {
    const double d = glm::length(offset);
    if (!(d > 0.0)) return surface;
    const glm::dvec3 t = transmittance(f, d, offset.y);
    return surface * t + (1.0 - t) * haze_color(f, glm::dot(offset, f.sun) / d);
}

glm::dvec3 aerial_sky(const AerialFrame& f, const glm::dvec3& dir) {
    const glm::dvec3 u = glm::normalize(dir);
    return sky_opacity(f, u.y) * haze_color(f, glm::dot(u, f.sun));
}

} // namespace overflight
