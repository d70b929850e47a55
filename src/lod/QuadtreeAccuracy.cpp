// Based on: Zamri ("Results", accuracy against full resolution);
// DESIGN sec. 2 (window depth) and sec. 3 (full-resolution mesh).
#include "lod/QuadtreeAccuracy.h"

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace overflight {

MeshArrays full_resolution_mesh(const Terrain& t) {
    MeshArrays m;
    m.positions.reserve(t.heights().size());
    for (int i = 0; i < t.rows(); ++i)
        for (int j = 0; j < t.cols(); ++j)
            m.positions.emplace_back(float(double(t.h_scale()) * j), t.sample_height(i, j), float(double(t.h_scale()) * i));
    m.indices.reserve(std::size_t(t.rows() - 1) * std::size_t(t.cols() - 1) * 6);
    for (int i = 0; i + 1 < t.rows(); ++i)
        for (int j = 0; j + 1 < t.cols(); ++j) {
            const auto a = std::uint32_t(t.index(i, j)), b = std::uint32_t(t.index(i, j + 1));
            const auto c = std::uint32_t(t.index(i + 1, j)), d = std::uint32_t(t.index(i + 1, j + 1));
            // Counter-clockwise seen from above: a (NW) -> c (SW) -> ... ; the
            // diagonal alternates in a checkerboard like the bintree split.
            if ((i + j) % 2 == 0) m.indices.insert(m.indices.end(), {a, c, d, a, d, b});
            else m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
        }
    return m;
}

namespace {

// Rasterises one screen-space triangle (x right, y down in pixels, z window depth).
void raster_triangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, DepthImage& img) {
    const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    if (area == 0 || !std::isfinite(area)) return;
    const int x0 = std::max(0, int(std::floor(std::min({a.x, b.x, c.x}))));
    const int x1 = std::min(img.width - 1, int(std::ceil(std::max({a.x, b.x, c.x}))));
    const int y0 = std::max(0, int(std::floor(std::min({a.y, b.y, c.y}))));
    const int y1 = std::min(img.height - 1, int(std::ceil(std::max({a.y, b.y, c.y}))));
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
            const double px = x + 0.5, py = y + 0.5;
            const double w0 = ((b.x - px) * (c.y - py) - (b.y - py) * (c.x - px)) / area;
            const double w1 = ((c.x - px) * (a.y - py) - (c.y - py) * (a.x - px)) / area;
            const double w2 = 1.0 - w0 - w1;
            if (w0 < 0 || w1 < 0 || w2 < 0) continue;
            // Window depth is affine in screen space, so linear interpolation is exact.
            const double z = w0 * a.z + w1 * b.z + w2 * c.z;
            if (z < 0 || z > 1) continue;
            float& d = img.at(x, y);
            if (z < d) d = float(z);
        }
}

} // namespace

DepthImage rasterize_depth(const MeshArrays& mesh, const Camera& camera) {
    DepthImage img(camera.width, camera.height, 1.0f);
    const glm::dmat4 clip = camera.projection_matrix() * camera.view_matrix();
    auto to_screen = [&](const glm::dvec4& p) {
        const glm::dvec3 ndc = glm::dvec3(p) / p.w;
        return glm::dvec3((ndc.x + 1) * 0.5 * camera.width, (1 - ndc.y) * 0.5 * camera.height, ndc.z * 0.5 + 0.5);
    };
    // Each vertex is shared by several triangles: transform it once.
    std::vector<glm::dvec4> clip_pos(mesh.positions.size());
    for (std::size_t k = 0; k < clip_pos.size(); ++k) clip_pos[k] = clip * glm::dvec4(glm::dvec3(mesh.positions[k]), 1.0);
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        glm::dvec4 v[3];
        for (int k = 0; k < 3; ++k) v[k] = clip_pos[mesh.indices[t + std::size_t(k)]];
        // Clip against the near plane z >= -w (Sutherland-Hodgman, one plane).
        glm::dvec4 poly[4];
        int n = 0;
        for (int k = 0; k < 3; ++k) {
            const glm::dvec4& p = v[k];
            const glm::dvec4& q = v[(k + 1) % 3];
            const double dp = p.z + p.w, dq = q.z + q.w;
            if (dp >= 0) poly[n++] = p;
            if ((dp >= 0) != (dq >= 0)) poly[n++] = p + (q - p) * (dp / (dp - dq));
        }
        if (n < 3) continue;
        const glm::dvec3 s0 = to_screen(poly[0]);
        for (int k = 1; k + 1 < n; ++k) raster_triangle(s0, to_screen(poly[k]), to_screen(poly[k + 1]), img);
    }
    return img;
}

DepthAgreement compare_depth(const DepthImage& test, const DepthImage& ref, const Camera& camera, double tolerance) {
    DepthAgreement a;
    for (std::size_t i = 0; i < ref.pixels.size() && i < test.pixels.size(); ++i) {
        const bool ref_hit = ref.pixels[i] < 1.0f, test_hit = test.pixels[i] < 1.0f;
        if (ref_hit != test_hit) ++a.coverage_mismatch;
        if (!ref_hit) continue;
        ++a.terrain_pixels;
        if (!test_hit) continue;
        const double dr = camera.view_depth_of_window(ref.pixels[i]);
        const double dt = camera.view_depth_of_window(test.pixels[i]);
        if (std::abs(dt - dr) <= tolerance * dr) ++a.agreeing;
    }
    return a;
}

ScreenError screen_space_error(const MeshArrays& mesh, const Terrain& t, const Camera& camera) {
    ScreenError e;
    if (mesh.positions.empty()) return e;
    // Mesh vertices sit on samples, so their grid coordinates are integers
    // and the point-in-triangle tests below are exact.
    const double hs = t.h_scale();
    std::vector<std::array<int, 2>> grid(mesh.positions.size());
    int r0 = std::numeric_limits<int>::max(), c0 = r0, r1 = std::numeric_limits<int>::min(), c1 = r1;
    for (std::size_t k = 0; k < grid.size(); ++k) {
        grid[k] = {int(std::lround(mesh.positions[k].z / hs)), int(std::lround(mesh.positions[k].x / hs))};
        r0 = std::min(r0, grid[k][0]), r1 = std::max(r1, grid[k][0]);
        c0 = std::min(c0, grid[k][1]), c1 = std::max(c1, grid[k][1]);
    }
    r0 = std::max(r0, 0), c0 = std::max(c0, 0), r1 = std::min(r1, t.rows() - 1), c1 = std::min(c1, t.cols() - 1);
    if (r0 > r1 || c0 > c1) return e;
    const int w = c1 - c0 + 1;
    // Height of the mesh above each sample of its bounding box (NaN: not covered).
    std::vector<float> mesh_y(std::size_t(r1 - r0 + 1) * std::size_t(w), std::numeric_limits<float>::quiet_NaN());
    for (std::size_t k = 0; k + 2 < mesh.indices.size(); k += 3) {
        const std::uint32_t ia = mesh.indices[k], ib = mesh.indices[k + 1], ic = mesh.indices[k + 2];
        const auto a = grid[ia], b = grid[ib], c = grid[ic];
        const long long area = (long long)(b[1] - a[1]) * (c[0] - a[0]) - (long long)(b[0] - a[0]) * (c[1] - a[1]);
        if (area == 0) continue;
        const int i0 = std::max(std::min({a[0], b[0], c[0]}), r0), i1 = std::min(std::max({a[0], b[0], c[0]}), r1);
        const int j0 = std::max(std::min({a[1], b[1], c[1]}), c0), j1 = std::min(std::max({a[1], b[1], c[1]}), c1);
        for (int i = i0; i <= i1; ++i)
            for (int j = j0; j <= j1; ++j) {
                // Barycentric weights times the doubled area, in integers.
                const long long wa = (long long)(b[1] - j) * (c[0] - i) - (long long)(b[0] - i) * (c[1] - j);
                const long long wb = (long long)(c[1] - j) * (a[0] - i) - (long long)(c[0] - i) * (a[1] - j);
                const long long wc = area - wa - wb;
                if (area > 0 ? (wa < 0 || wb < 0 || wc < 0) : (wa > 0 || wb > 0 || wc > 0)) continue;
                const double y = (double(wa) * mesh.positions[ia].y + double(wb) * mesh.positions[ib].y +
                                  double(wc) * mesh.positions[ic].y) / double(area);
                mesh_y[std::size_t(i - r0) * std::size_t(w) + std::size_t(j - c0)] = float(y);
            }
    }
    std::vector<double> errors;
    double sum = 0.0;
    for (int i = r0; i <= r1; ++i)
        for (int j = c0; j <= c1; ++j) {
            const float my = mesh_y[std::size_t(i - r0) * std::size_t(w) + std::size_t(j - c0)];
            if (std::isnan(my)) continue;
            const glm::dvec3 p(hs * j, t.sample_height(i, j), hs * i);
            const Camera::Projected s = camera.project(p);
            if (!s.in_front || s.depth < 0 || s.depth > 1 || s.col < 0 || s.row < 0 || s.col >= camera.width ||
                s.row >= camera.height)
                continue;
            const Camera::Projected m = camera.project({p.x, double(my), p.z});
            if (!m.in_front) continue;
            const double px = std::hypot(m.col - s.col, m.row - s.row);
            errors.push_back(px);
            sum += px;
            e.max_px = std::max(e.max_px, px);
        }
    e.samples = (long long)errors.size();
    if (errors.empty()) return e;
    e.mean_px = sum / double(errors.size());
    auto q = errors.begin() + std::ptrdiff_t(0.99 * double(errors.size() - 1));
    std::nth_element(errors.begin(), q, errors.end());
    e.p99_px = *q;
    return e;
}

} // namespace overflight
