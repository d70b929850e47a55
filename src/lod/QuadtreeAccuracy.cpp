// Based on: Zamri, seed 001 ("Results", accuracy against full resolution);
// DESIGN sec. 2 (window depth) and sec. 3 (full-resolution mesh).
#include "lod/QuadtreeAccuracy.h"

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>

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
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        glm::dvec4 v[3];
        for (int k = 0; k < 3; ++k) v[k] = clip * glm::dvec4(glm::dvec3(mesh.positions[mesh.indices[t + std::size_t(k)]]), 1.0);
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

} // namespace overflight
