#include "sim/Hovercraft.h"

#include "core/Error.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

namespace overflight {

namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

// Grid coordinates of world (x, z), clamped to the map, split into the cell
// (r0, c0) and the fractions inside it.
struct CellPoint {
    int r0, c0;
    double fx, fz;
};

CellPoint locate(const Terrain& t, double x, double z) {
    const double gx = std::clamp(x / double(t.h_scale()), 0.0, double(t.cols() - 1));
    const double gz = std::clamp(z / double(t.h_scale()), 0.0, double(t.rows() - 1));
    const int c0 = std::min(int(gx), t.cols() - 2);
    const int r0 = std::min(int(gz), t.rows() - 2);
    return {r0, c0, gx - c0, gz - r0};
}

double sample(const Terrain& t, int r, int c) {
    return double(t.v_scale()) * double(t.raw(r, c)) + double(t.y_offset());
}

// The bilinear surface of Terrain::height_bilinear in double precision: the
// Ahead method differences two heights one metre apart, which float position
// rounding (8 mm at 100 km) would turn into noise on large maps.
double bilinear(const Terrain& t, double x, double z) {
    const CellPoint p = locate(t, x, z);
    const double h00 = sample(t, p.r0, p.c0), h01 = sample(t, p.r0, p.c0 + 1);
    const double h10 = sample(t, p.r0 + 1, p.c0), h11 = sample(t, p.r0 + 1, p.c0 + 1);
    const double top = h00 + (h01 - h00) * p.fx;
    const double bottom = h10 + (h11 - h10) * p.fx;
    return top + (bottom - top) * p.fz;
}

// Plane of the mesh triangle containing a point: height at the cell's (r0, c0)
// corner plus the gradient (dh/dx, dh/dz) per world unit.
struct TrianglePlane {
    double h0, dhdx, dhdz;
    CellPoint at;
};

TrianglePlane triangle_plane(const Terrain& t, double x, double z) {
    const CellPoint p = locate(t, x, z);
    const double hs = t.h_scale();
    const double h00 = sample(t, p.r0, p.c0), h01 = sample(t, p.r0, p.c0 + 1);
    const double h10 = sample(t, p.r0 + 1, p.c0), h11 = sample(t, p.r0 + 1, p.c0 + 1);
    TrianglePlane plane{};
    plane.at = p;
    if ((p.r0 + p.c0) % 2 == 0) {
        // Diagonal (r0, c0)-(r0+1, c0+1).
        if (p.fx >= p.fz) { // upper-right triangle: h00, h01, h11
            plane.dhdx = (h01 - h00) / hs;
            plane.dhdz = (h11 - h01) / hs;
        } else {            // lower-left triangle: h00, h10, h11
            plane.dhdx = (h11 - h10) / hs;
            plane.dhdz = (h10 - h00) / hs;
        }
        plane.h0 = h00;
    } else {
        // Diagonal (r0, c0+1)-(r0+1, c0).
        if (p.fx + p.fz <= 1.0) { // upper-left triangle: h00, h01, h10
            plane.dhdx = (h01 - h00) / hs;
            plane.dhdz = (h10 - h00) / hs;
            plane.h0 = h00;
        } else {                  // lower-right triangle: h01, h10, h11
            plane.dhdx = (h11 - h10) / hs;
            plane.dhdz = (h11 - h01) / hs;
            // Extrapolate the plane back to the (r0, c0) corner.
            plane.h0 = h01 - plane.dhdx * hs;
        }
    }
    return plane;
}

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

} // namespace

const char* to_string(SlopeMethod m) {
    return m == SlopeMethod::Ahead ? "ahead" : "triangle-normal";
}

double wrap_heading(double degrees) {
    double h = std::fmod(degrees, 360.0);
    if (h < 0) h += 360.0;
    return h >= 360.0 ? 0.0 : h; // fmod of a tiny negative can round up to 360
}

double mesh_height(const Terrain& terrain, double x, double z) {
    const TrianglePlane plane = triangle_plane(terrain, x, z);
    const double hs = terrain.h_scale();
    return plane.h0 + plane.dhdx * plane.at.fx * hs + plane.dhdz * plane.at.fz * hs;
}

double ground_height(const Terrain& terrain, double x, double z) {
    return std::max(double(terrain.height_bilinear(float(x), float(z))), mesh_height(terrain, x, z));
}

glm::dvec3 slope_vector(const Terrain& terrain, double x, double z, double heading,
                        SlopeMethod method, double probe) {
    const double dx = std::sin(heading * kDegToRad);
    const double dz = std::cos(heading * kDegToRad);
    double rise; // per unit of horizontal travel
    if (method == SlopeMethod::Ahead) {
        // First method: <d_x, H(p + d) - H(p), d_z> with |d| = probe.
        rise = (bilinear(terrain, x + probe * dx, z + probe * dz) - bilinear(terrain, x, z)) / probe;
    } else {
        // Second method: n . <sin h, y, cos h> = 0 with n = (-dh/dx, 1, -dh/dz)
        // gives y = dh/dx sin h + dh/dz cos h.
        const TrianglePlane plane = triangle_plane(terrain, x, z);
        rise = plane.dhdx * dx + plane.dhdz * dz;
    }
    return glm::normalize(glm::dvec3(dx, rise, dz));
}

Hovercraft::Hovercraft(const Terrain& terrain, double x, double z, double heading,
                       const HovercraftParams& params)
    : terrain_(&terrain), params_(params) {
    if (!std::isfinite(x) || !std::isfinite(z) || x < 0 || z < 0 || x > terrain.width() ||
        z > terrain.depth())
        throw Error("vehicle start", "position " + number(x) + "," + number(z) + " is outside the terrain (X 0.." +
                                number(terrain.width()) + ", Z 0.." + number(terrain.depth()) + ")");
    if (!std::isfinite(heading)) throw Error("vehicle heading", "must be a finite number of degrees");
    state_.x = x;
    state_.z = z;
    state_.heading = wrap_heading(heading);
    state_.velocity = 0;
    state_.y = ground_height(terrain, x, z) + params_.altitude;
}

void Hovercraft::step(const Controls& keys) {
    const HovercraftParams& k = params_;
    HovercraftState& s = state_;
    const double dt = k.step;

    // Seed 003 sec. 3.2: friction and gravity first, then acceleration and/or braking.
    const double v = s.velocity;
    const double a = std::max(0.0, k.accel_max - v * v / k.accel_div);
    const double f = k.f0 + k.f1 * v + k.f2 * v * v;
    const bool afloat = water_ && ground_height(*terrain_, s.x, s.z) < *water_;
    const double g = afloat ? 0.0 : k.gravity * slope_vector(*terrain_, s.x, s.z, s.heading, k.slope, k.probe).y;
    double vn = v - dt * (f + g);
    if (keys.accelerate) vn += dt * a;
    if (keys.brake) vn -= dt * k.brake;
    vn = std::max(0.0, vn);

    // The new velocity sets the turn rate: slow vehicles turn faster.
    const double turn = k.turn_factor / (vn * vn + k.turn_limit);
    double h = s.heading;
    if (keys.left) h += turn;
    if (keys.right) h -= turn;

    const double rad = h * kDegToRad;
    double x = s.x + dt * vn * std::sin(rad);
    double z = s.z + dt * vn * std::cos(rad);

    // Bounce off the map edge: mirror the position and the heading component
    // normal to that edge.
    const double w = terrain_->width(), d = terrain_->depth();
    bool bounced = false;
    if (x < 0) { x = -x; h = -h; bounced = true; }
    else if (x > w) { x = 2 * w - x; h = -h; bounced = true; }
    if (z < 0) { z = -z; h = 180.0 - h; bounced = true; }
    else if (z > d) { z = 2 * d - z; h = 180.0 - h; bounced = true; }
    if (bounced) {
        ++bounces_;
        // A step longer than the map itself (absurd speeds on a tiny map) stays on it.
        x = std::clamp(x, 0.0, w);
        z = std::clamp(z, 0.0, d);
    }

    s.velocity = vn;
    s.heading = wrap_heading(h);
    s.x = x;
    s.z = z;
    s.y = std::max(ground_height(*terrain_, x, z), water_.value_or(-kWorldLimit)) + k.altitude;
}

} // namespace overflight
