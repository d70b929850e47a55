#pragma once
// Aerial perspective and the sky of an exponential-height atmosphere
// (Environment::air), evaluated exactly: the reference that the ray caster's
// tables (raycast/Atmosphere.h, AerialTables) approximate and that the GLSL of
// every GL program (gl/GlProgram.cpp, aerial() and air_sky()) writes again
// term for term, with the per-frame constants of AerialFrame as uniforms.
//
// The model (Hoffman, Preetham, "Rendering Outdoor Light Scattering in Real
// Time", GDC 2002: L = L0 Fex + Lin, single scattering of sunlight by air
// (Rayleigh phase) and haze (Henyey-Greenstein phase), extinction equal to
// scattering), with a density exp(-y / H) instead of their constant one:
//
//   optical depth from the eye (height y0) to a point at distance d and
//   height y0 + dy, per channel c:
//       tau_c = beta_c rho0 d G(dy / H),  rho0 = exp(-y0 / H),  G(x) = (1 - e^-x) / x (G(0) = 1),
//   which is the integral of beta_c exp(-y / H) along the straight segment;
//   transmittance T_c = exp(-tau_c);
//   haze color of a view direction at angle theta from the sun
//       C_c = display(R_c P_R(cos theta) + M_c P_M(cos theta)),
//       R_c = exposure E_c rayleigh_c / beta_c, M_c = exposure E_c haze / beta_c,
//       P_R = 3/4 (1 + cos^2),  P_M = (1 - g^2) / (1 + g^2 - 2 g cos)^1.5 (both average 1),
//       display(L) = (1 - exp(-L))^(1/2.2) (exposure, then gamma);
//   sunlight E_c = sunlight_c G(k_c) t, k_c = beta_c rho0 H m(sun elevation):
//   the sun's transmittance exp(-k_c u) down to the air of density u rho0
//   (u <= 1, Kasten and Young's air mass m, "Revised optical air mass tables
//   and approximation formula", Applied Optics 28, 1989), averaged over the
//   air above the eye weighted by its density (the integral of exp(-k u) du
//   over u in [0, 1]), which is exactly how a sky ray of any elevation weighs
//   the air it scatters in; t fades it out from the horizon to 5.7 degrees
//   below it (twilight). Warm and dim at low sun;
//   a terrain point:  color_c = surface_c T_c + (1 - T_c) C_c  (blended in
//   display space, as GL fog is);
//   the sky along a ray of elevation sine s:  sky_c = V_c(s) C_c with the
//   opacity of the whole atmosphere above, V_c = (1 - exp(-beta_c rho0 H / s))^(1/2.2)
//   (s > 0; 1 at and below the horizon). At the horizon V = 1 and far
//   terrain, T -> 0, meet the sky in the same color C; the zenith is bluer
//   (V grows with beta_c), the sun's side brighter (P_M), the opposite side
//   and the low sun darker and redder (E).
// All colors are [0,1] RGB; surface colors are display colors (as stored).
#include "core/DataSet.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace overflight {

// What the model needs per frame for one eye height.
struct AerialFrame {
    glm::dvec3 sun{0.0, 1.0, 0.0}; // unit, towards the sun
    glm::dvec3 beta{0.0};          // extinction rayleigh_c + haze, per world unit at height 0
    double scale_height = 1.0;     // H
    double eye_density = 1.0;      // rho0 = exp(-y0 / H)
    glm::dvec3 rayleigh_light{0.0}; // R_c
    glm::dvec3 haze_light{0.0};     // M_c
    double g = 0.0;                 // haze asymmetry
};

// The frame's constants for an eye at world height eye_y.
AerialFrame aerial_frame(const Environment& env, double eye_y);

// Kasten and Young's relative air mass for the sun's elevation sine (clamped
// to the horizon below it): 1 at the zenith, about 38 at the horizon.
double air_mass(double sin_elevation);

// G(x) = (1 - e^-x) / x with G(0) = 1 (a series for |x| < 1e-3); x is
// clamped to >= -40 (a ray down 40 scale heights, beyond any terrain).
double height_factor(double x);

// Normalised phase functions (average 1 over the sphere): x = Rayleigh,
// y = Henyey-Greenstein with asymmetry g.
glm::dvec2 phases(double g, double cos_theta);

// T_c from the eye to a point at distance d whose height is the eye's + dy.
glm::dvec3 transmittance(const AerialFrame& f, double distance, double dy);

// C_c of a view direction at cos_theta from the sun.
glm::dvec3 haze_color(const AerialFrame& f, double cos_theta);

// V_c of a ray of elevation sine s.
glm::dvec3 sky_opacity(const AerialFrame& f, double sine);

// The color of a surface point at offset (point - eye) from the eye.
glm::dvec3 aerial_perspective(const AerialFrame& f, const glm::dvec3& surface, const glm::dvec3& offset);

// The sky along a ray direction (any length, not zero).
glm::dvec3 aerial_sky(const AerialFrame& f, const glm::dvec3& dir);

} // namespace overflight
