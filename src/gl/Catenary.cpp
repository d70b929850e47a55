// Based on: DESIGN sec. 5 (cables as catenaries with a sag); the catenary
// y = a cosh(x / a) of a uniform cable under its own weight.
#include "gl/Catenary.h"

#include "core/Error.h"

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <cmath>

namespace overflight::gl {

double catenary_parameter(double span, double sag) {
    if (!(span > 0) || !(sag > 0) || !std::isfinite(span) || !std::isfinite(sag))
        throw Error("line", "span and sag must be positive numbers");
    // g(a) = a (cosh(L/2a) - 1) decreases from +inf (a -> 0) to 0 (a -> inf).
    const auto g = [&](double a) { return a * (std::cosh(span / (2 * a)) - 1.0); };
    double lo = span / 1000.0, hi = span;
    while (g(lo) < sag) lo *= 0.5;       // extreme sags: a smaller than L/1000
    while (g(hi) > sag) hi *= 2.0;        // shallow sags: a large
    for (int i = 0; i < 200 && hi - lo > 1e-12 * hi; ++i) {
        const double mid = 0.5 * (lo + hi);
        (g(mid) > sag ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

double catenary_drop(double span, double sag, double s) {
    if (!(sag > 0)) return 0.0;
    const double a = catenary_parameter(span, sag);
    return a * (std::cosh(span / (2 * a)) - std::cosh((s - span / 2) / a));
}

std::vector<glm::dvec3> catenary_points(const glm::dvec3& a, const glm::dvec3& b, double sag, int segments) {
    if (segments < 1) throw Error("line", "a cable needs at least one segment");
    const double span = glm::length(glm::dvec2(b.x - a.x, b.z - a.z));
    const bool hangs = sag > 0 && span > 0;
    const double param = hangs ? catenary_parameter(span, sag) : 0.0;
    std::vector<glm::dvec3> out;
    out.reserve(std::size_t(segments) + 1);
    for (int k = 0; k <= segments; ++k) {
        const double t = double(k) / segments;
        glm::dvec3 p = a + t * (b - a);
        if (hangs) p.y -= param * (std::cosh(span / (2 * param)) - std::cosh((t * span - span / 2) / param));
        out.push_back(p);
    }
    out.front() = a;
    out.back() = b;
    return out;
}

} // namespace overflight::gl
