#pragma once
// Transmission-line cables hang as catenaries (DESIGN sec. 5: `line` with a
// `sag`). For a span of horizontal length L between supports at equal height,
// the cable is y(s) = y0 - sag + a (cosh((s - L/2) / a) - 1), s in [0, L], whose
// parameter a (horizontal tension over weight per length) solves
//     a (cosh(L / (2a)) - 1) = sag.
// Between supports at different heights the same curve is hung below the
// straight chord (sag measured vertically from the chord at mid-span, the
// usual convention for inclined spans). CPU only, no GL.
//
// Based on: Szenberg et al. 1997 sec. 7 (transmission lines among the objects)
// and DESIGN sec. 5.
#include <glm/vec3.hpp>

#include <vector>

namespace overflight::gl {

// The catenary parameter a for a span and a mid-span sag, both > 0 (solved
// by bisection to double precision). Throws Error("line", ...) otherwise.
double catenary_parameter(double span, double sag);

// Vertical drop of the cable below the chord at horizontal distance s from
// the first support: a (cosh(L/(2a)) - cosh((s - L/2)/a)); 0 at both ends, sag at s = L/2.
double catenary_drop(double span, double sag, double s);

// Points of the cable from support a to support b (world, Y up) in `segments`
// equal horizontal steps (segments + 1 points, first == a, last == b). A sag of
// 0 gives the straight chord.
std::vector<glm::dvec3> catenary_points(const glm::dvec3& a, const glm::dvec3& b, double sag, int segments);

} // namespace overflight::gl
