#pragma once
// What the two casts of the tilted camera share (private to src/raycast):
// they cast vertical planes with the tilted rows' ray slopes as their rows
// (TiltRows), into a whole-image scratch, column-major, and resolve each
// tilted pixel from the plane that stands for it. The rows whose rays point
// too steeply up or down for vertical planes (outside TiltRows' [j_lo, j_hi))
// are handed to the ray marcher, pixel by pixel.
//
// Based on: Guedes, "Integrating Polygonal Objects on Voxel Based Terrain
// Models", Algorithm 1 (the pitched camera's per-row ray slopes), over the
// Floating Horizon of Szenberg, Gattass, Carvalho, "An Algorithm for the
// Visualization of a Terrain with Objects", SIBGRAPI 1997, Algorithm 1.
#include "core/Parallel.h"
#include "raycast/FloatingHorizonState.h"
#include "raycast/RayMarcher.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>

namespace overflight {

// The frame's tables once s.tilt_rows and the column planes
// (s.frame.columns.a) are set: slices over [near w_min, far w_max] along F
// (fp_h: planes per unit of a), the columns clipped to the terrain, the rows
// cast, the fog's range and the scratch sized for columns x rows.
void prepare_tilt(FloatingHorizonState& s, const Camera& camera, const Environment& env,
                  const RaycastOptions& options, double fp_h);

// Resolves the tilted image. For image row r cast as row i of the planes,
// row_hits(r, i) returns a callable hit(c, dv, rgb): true when pixel c's ray
// meets the terrain within the far plane, at view depth dv along F', with
// the packed color rgb as seen from the eye (FloatingHorizonState::hit_color). Those pixels get that color and dv's window
// depth; the others the sky and depth 1; rows not cast, the ray marcher's
// pixels (counted in stats.fallback_pixels).
template <class RowHits>
void resolve_tilt(const FloatingHorizonState& s, const Camera& camera, const Environment& env, SurfaceModel surface,
                  const RowHits& row_hits, ColorImage& color, DepthImage& depth, RaycastStats& stats) {
    const auto t0 = Clock::now();
    const int W = camera.width, H = camera.height;
    const TiltRows& tr = s.tilt_rows;
    const double fp = camera.focal_px();
    const double p = glm::radians(camera.pitch), sp = std::sin(p), cp = std::cos(p);
    const double fs = glm::dot(camera.view_axis(), s.sun), us = glm::dot(camera.view_up(), s.sun);
    const double rs = glm::dot(camera.right(), s.sun);
    RayMarcher marcher(s.terrain.terrain, env);
    marcher.set_colors(s.terrain.source_colors);
    const RayMarcher::Frame mf = marcher.frame(camera);
    std::atomic<long long> painted{0};
    std::atomic<int> fallback{0};
    parallel::for_each_index(0, H, [&](int r) {
        const int j = H - 1 - r;
        long long px = 0;
        if (j < tr.j_lo || j >= tr.j_hi) {
            for (int c = 0; c < W; ++c) {
                marcher.shade_pixel(camera, mf, surface, c, r, color.at(c, r), depth.at(c, r));
                px += depth.at(c, r) < 1.0f;
            }
            fallback += W;
            painted += px;
            return;
        }
        const auto hit = row_hits(r, j - tr.j_lo);
        const double v = camera.v_of(r);
        const double up = sp + (v / fp) * cp;
        const double row_sun = fs + (v / fp) * us; // (F' + (v/fp) U') . sun
        for (int c = 0; c < W; ++c) {
            double dv = 0;
            std::uint32_t rgb = 0;
            if (hit(c, dv, rgb)) {
                color.at(c, r) = unpack_rgb(rgb);
                depth.at(c, r) = float(camera.window_depth(std::max(dv, camera.near)));
                ++px;
            } else {
                const double u = camera.u_of(c);
                const double len = std::sqrt(1.0 + (u / fp) * (u / fp) + (v / fp) * (v / fp)); // per unit F' depth
                color.at(c, r) = unpack_rgb(s.sky_color(float(up / len), float((row_sun + (u / fp) * rs) / len)));
                depth.at(c, r) = 1.0f;
            }
        }
        painted += px;
    });
    stats.pixels_painted = painted;
    stats.fallback_pixels = fallback;
    stats.ms_resolve = ms_since(t0);
}

} // namespace overflight
