#pragma once
// The aerial perspective and the sky of core/AerialPerspective.h in GLSL,
// term for term, once for every GPU that draws them: the native shaders
// (gl/GlProgram.cpp, GLSL 4.50) and the web page's WebGL2 shaders (GLSL ES
// 3.00), into whose site `overflight web` writes it as atmosphere.glsl. It
// is valid in both: it reads the includer's `eye` and `sun_dir` (vec3 or
// vec4) and `air_beta`, `air_rayleigh`, `air_haze` (vec4, as
// core/AerialPerspective.h's AerialFrame lays them out).
//
// Based on: N. Hoffman, A. J. Preetham, "Rendering Outdoor Light Scattering
// in Real Time", GDC 2002 (extinction and in-scattering, Rayleigh and
// Henyey-Greenstein phases).

namespace overflight::gl {

inline constexpr const char* kAtmosphereGlsl = R"(
float height_factor(float x) {
    x = max(x, -40.0);
    return abs(x) < 1e-3 ? 1.0 - x * (0.5 - x / 6.0) : (1.0 - exp(-x)) / x;
}
vec3 haze_color(float c) {
    float g = air_rayleigh.a;
    float rayleigh = 0.75 * (1.0 + c * c);
    float hg = (1.0 - g * g) / pow(1.0 + g * g - 2.0 * g * c, 1.5);
    return pow(1.0 - exp(-(air_rayleigh.rgb * rayleigh + air_haze.rgb * hg)), vec3(1.0 / 2.2));
}
vec3 aerial(vec3 color, vec3 world) {
    vec3 v = world - eye.xyz;
    float d = length(v);
    if (!(d > 0.0)) return color;
    vec3 t = exp(-air_beta.rgb * (d * height_factor(v.y / air_beta.a)));
    return color * t + (1.0 - t) * haze_color(dot(v, sun_dir.xyz) / d);
}
vec3 air_sky(vec3 dir) {
    vec3 u = normalize(dir);
    vec3 opacity = u.y > 0.0 ? pow(1.0 - exp(-air_beta.rgb * (air_beta.a / u.y)), vec3(1.0 / 2.2)) : vec3(1.0);
    return opacity * haze_color(dot(u, sun_dir.xyz));
}
)";

} // namespace overflight::gl
