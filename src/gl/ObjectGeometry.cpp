// Based on: Szenberg et al. 1997 sec. 5 and 7 (objects over the terrain), DESIGN sec. 5.
#include "gl/ObjectGeometry.h"

#include "core/Error.h"
#include "gl/Catenary.h"
#include "sim/VehicleBody.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>

namespace overflight::gl {

namespace {

// Local frame of an object: origin at its base centre, axes rotated by heading.
struct Frame {
    glm::dvec3 origin, ax, ay{0, 1, 0}, az;
    glm::dvec3 operator()(double x, double y, double z) const { return origin + x * ax + y * ay + z * az; }
};

Frame frame_of(double x, double y, double z, double heading_deg) {
    const double h = glm::radians(heading_deg);
    Frame f;
    f.origin = {x, y, z};
    f.az = {std::sin(h), 0, std::cos(h)};
    f.ax = {std::cos(h), 0, -std::sin(h)};
    return f;
}

double base_y(const SceneObject& o, const Terrain& t) {
    return o.y ? *o.y : double(t.height_bilinear(float(o.x), float(o.z)));
}

void add_polygon(MeshArrays& m, std::initializer_list<glm::dvec3> corners, Rgb8 color) {
    // Fan from the first corner; corners counter-clockwise seen from outside.
    const glm::dvec3* c = corners.begin();
    glm::dvec3 n = glm::cross(c[1] - c[0], c[2] - c[0]);
    n = glm::length(n) > 0 ? glm::normalize(n) : glm::dvec3(0, 1, 0);
    const auto base = std::uint32_t(m.positions.size());
    for (const glm::dvec3& p : corners) {
        m.positions.emplace_back(p);
        m.normals.emplace_back(n);
        m.colors.push_back(color);
    }
    for (std::uint32_t k = 1; k + 1 < corners.size(); ++k) m.indices.insert(m.indices.end(), {base, base + k, base + k + 1});
}

// An axis-aligned (in the local frame) box [x0,x1] x [y0,y1] x [z0,z1].
void add_box(MeshArrays& m, const Frame& f, double x0, double x1, double y0, double y1, double z0, double z1, Rgb8 c) {
    const auto p = [&](int bits) { return f(bits & 1 ? x1 : x0, bits & 2 ? y1 : y0, bits & 4 ? z1 : z0); };
    // Same corner numbering and counter-clockwise faces as BlockTerrain.
    add_polygon(m, {p(2), p(6), p(7), p(3)}, c); // +Y
    add_polygon(m, {p(0), p(1), p(5), p(4)}, c); // -Y
    add_polygon(m, {p(1), p(3), p(7), p(5)}, c); // +X
    add_polygon(m, {p(0), p(4), p(6), p(2)}, c); // -X
    add_polygon(m, {p(4), p(5), p(7), p(6)}, c); // +Z
    add_polygon(m, {p(0), p(2), p(3), p(1)}, c); // -Z
}

Rgb8 scaled(Rgb8 c, double k) {
    auto s = [k](std::uint8_t v) { return std::uint8_t(std::clamp(std::lround(v * k), 0L, 255L)); };
    return {s(c.r), s(c.g), s(c.b)};
}

void add_house(MeshArrays& m, const Frame& f, const SceneObject& o) {
    const double w = o.width / 2, d = o.depth / 2, wall = 0.6 * o.height, top = o.height;
    add_box(m, f, -w, w, 0, wall, -d, d, o.color);
    const Rgb8 roof{150, 60, 45};
    add_polygon(m, {f(w, wall, -d), f(0, top, -d), f(0, top, d), f(w, wall, d)}, roof);    // east slope
    add_polygon(m, {f(-w, wall, d), f(0, top, d), f(0, top, -d), f(-w, wall, -d)}, roof);  // west slope
    add_polygon(m, {f(-w, wall, d), f(w, wall, d), f(0, top, d)}, o.color);               // gable +Z
    add_polygon(m, {f(w, wall, -d), f(-w, wall, -d), f(0, top, -d)}, o.color);            // gable -Z
}

void add_vehicle(MeshArrays& m, const Frame& f, const SceneObject& o) {
    const double w = o.width / 2, d = o.depth / 2, h = o.height;
    add_box(m, f, -w, w, 0, 0.35 * h, -d, d, scaled(o.color, 0.35));                 // skirt
    add_box(m, f, -0.85 * w, 0.85 * w, 0.35 * h, 0.7 * h, -0.9 * d, 0.9 * d, o.color); // body
    add_box(m, f, -0.5 * w, 0.5 * w, 0.7 * h, h, -0.45 * d, 0.2 * d, scaled(o.color, 0.7)); // cabin
}

void add_line(ObjectGeometry& g, const glm::dvec3& a, const glm::dvec3& b, Rgb8 c) {
    g.line_points.emplace_back(a);
    g.line_points.emplace_back(b);
    g.line_colors.push_back(c);
    g.line_colors.push_back(c);
}

// A lattice tower of `height` in the local frame f, cross-arm along local X.
void add_tower(ObjectGeometry& g, const Frame& f, double height, Rgb8 c) {
    constexpr int kPanels = 6;
    const double w0 = 0.12 * height, w1 = 0.04 * height, arm = tower_arm(height);
    const auto ring = [&](int k) { return w0 + (w1 - w0) * (double(k) / kPanels); };
    const auto corner = [&](int k, int q) {
        const double w = ring(k), y = height * double(k) / kPanels;
        return f(q == 0 || q == 3 ? -w : w, y, q < 2 ? -w : w);
    };
    for (int k = 0; k < kPanels; ++k)
        for (int q = 0; q < 4; ++q) {
            add_line(g, corner(k, q), corner(k + 1, q), c);                 // leg
            add_line(g, corner(k + 1, q), corner(k + 1, (q + 1) % 4), c);   // ring
            add_line(g, corner(k, q), corner(k + 1, (q + 1) % 4), c);       // bracing
        }
    add_line(g, f(-arm, height, 0), f(arm, height, 0), c);                       // cross-arm
    add_line(g, f(-arm, height, 0), f(-w1, 0.85 * height, 0), c);
    add_line(g, f(arm, height, 0), f(w1, 0.85 * height, 0), c);
}

// A piece of geometry (an object, a tower, a span of cables) is bounded by
// the triangle and line vertices added between begin_piece and end_piece.
struct PieceStart {
    std::size_t triangles, lines;
};

PieceStart begin_piece(const ObjectGeometry& g) { return {g.triangles.positions.size(), g.line_points.size()}; }

// `box_caster`: the piece's bounds are one of g.casters too.
void end_piece(ObjectGeometry& g, PieceStart from, bool box_caster = true) {
    WorldBox b{glm::vec3(HUGE_VALF), glm::vec3(-HUGE_VALF)};
    auto grow = [&](const std::vector<glm::vec3>& points, std::size_t first) {
        for (std::size_t i = first; i < points.size(); ++i) {
            b.lo = glm::min(b.lo, points[i]);
            b.hi = glm::max(b.hi, points[i]);
        }
    };
    grow(g.triangles.positions, from.triangles);
    grow(g.line_points, from.lines);
    if (!(b.lo.x <= b.hi.x)) return;
    g.bounds.push_back(b);
    if (!box_caster) return;
    std::vector<glm::vec3>& corners = g.casters.emplace_back();
    for (int c = 0; c < 8; ++c) corners.emplace_back(c & 1 ? b.hi.x : b.lo.x, c & 2 ? b.hi.y : b.lo.y, c & 4 ? b.hi.z : b.lo.z);
}

} // namespace

std::vector<glm::dvec3> box_corners(const SceneObject& o, const Terrain& t) {
    const Frame f = frame_of(o.x, base_y(o, t), o.z, o.heading);
    std::vector<glm::dvec3> out;
    for (int bits = 0; bits < 8; ++bits)
        out.push_back(f(bits & 1 ? o.width / 2 : -o.width / 2, bits & 2 ? o.height : 0.0,
                        bits & 4 ? o.depth / 2 : -o.depth / 2));
    return out;
}

ObjectGeometry build_object_geometry(const Scene& scene, const Terrain& t) {
    ObjectGeometry g;
    for (const SceneObject& o : scene.objects) {
        const PieceStart piece = begin_piece(g);
        const Frame f = frame_of(o.x, base_y(o, t), o.z, o.heading);
        switch (o.kind) {
        case ObjectKind::Box:
            add_box(g.triangles, f, -o.width / 2, o.width / 2, 0, o.height, -o.depth / 2, o.depth / 2, o.color);
            break;
        case ObjectKind::House: add_house(g.triangles, f, o); break;
        case ObjectKind::Vehicle: add_vehicle(g.triangles, f, o); break;
        case ObjectKind::Tower: add_tower(g, f, o.height, o.color); break;
        case ObjectKind::Model: {
            if (!o.model) throw Error(o.model_path, "the model was not loaded with the scene");
            const MeshArrays& model = *o.model;
            const auto base = std::uint32_t(g.triangles.positions.size());
            for (std::size_t i = 0; i < model.positions.size(); ++i) {
                const glm::dvec3 p = glm::dvec3(model.positions[i]) * o.scale;
                const glm::dvec3 n = glm::dvec3(model.normals[i]);
                g.triangles.positions.emplace_back(f(p.x, p.y, p.z));
                g.triangles.normals.emplace_back(glm::normalize(n.x * f.ax + n.y * f.ay + n.z * f.az));
                g.triangles.colors.push_back(model.colors[i]);
            }
            for (std::uint32_t i : model.indices) g.triangles.indices.push_back(base + i);
            break;
        }
        }
        end_piece(g, piece);
    }
    for (const TransmissionLine& line : scene.lines) {
        const std::size_t n = line.points.size();
        std::vector<Frame> towers;
        for (std::size_t k = 0; k < n; ++k) {
            // Cross-arm across the line: perpendicular to the mean direction of the adjacent spans.
            const glm::dvec2 prev = line.points[k > 0 ? k - 1 : k], next = line.points[k + 1 < n ? k + 1 : k];
            glm::dvec2 dir = next - prev;
            if (glm::length(dir) == 0) dir = {0, 1};
            const double heading = glm::degrees(std::atan2(dir.x, dir.y));
            const double x = line.points[k].x, z = line.points[k].y;
            towers.push_back(frame_of(x, double(t.height_bilinear(float(x), float(z))), z, heading));
            const PieceStart piece = begin_piece(g);
            add_tower(g, towers.back(), line.height, Rgb8{110, 110, 115});
            end_piece(g, piece);
        }
        const double arm = tower_arm(line.height);
        for (std::size_t k = 0; k + 1 < n; ++k) {
            const PieceStart piece = begin_piece(g);
            for (double side : {-arm, 0.0, arm}) {
                const auto pts = catenary_points(towers[k](side, line.height, 0), towers[k + 1](side, line.height, 0),
                                                 line.sag, kCableSegments);
                for (std::size_t i = 0; i + 1 < pts.size(); ++i) add_line(g, pts[i], pts[i + 1], line.color);
                for (std::size_t i = 0; i + 1 < pts.size(); i += kCasterSegments) {
                    std::vector<glm::vec3>& run = g.casters.emplace_back();
                    for (std::size_t j = i; j <= std::min(i + kCasterSegments, pts.size() - 1); ++j)
                        run.emplace_back(pts[j]);
                }
            }
            end_piece(g, piece, false);
        }
    }
    return g;
}

MeshArrays player_vehicle_model() {
    SceneObject v;
    v.kind = ObjectKind::Vehicle;
    v.width = VehicleBody::kWidth;
    v.height = VehicleBody::kHeight;
    v.depth = VehicleBody::kLength;
    v.color = Rgb8{215, 75, 35};
    MeshArrays m;
    add_vehicle(m, frame_of(0, 0, 0, 0), v);
    return m;
}

} // namespace overflight::gl
