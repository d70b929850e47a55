// Based on: Szenberg 1997, Algorithm 1, Algorithm 2, sec. 5.2 and 6. See
// FloatingHorizonLiteral.h. The line numbers in comments are the paper's.
#include "raycast/FloatingHorizonLiteral.h"

#include "core/Error.h"
#include "raycast/Atmosphere.h"
#include "raycast/DepthVector.h"
#include "raycast/FrontFace.h"
#include "raycast/ImageryTexels.h"

#include <glm/trigonometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

namespace overflight {

void render_floating_horizon_literal(const Terrain& terrain, const Environment& env, const Camera& camera,
                                     SurfaceModel surface, ColorImage& color, DepthImage& depth, RaycastStats* stats,
                                     const std::vector<Rgb8>* colors, const ImageryPyramid* imagery,
                                     const LightMask& mask) {
    const auto t0 = std::chrono::steady_clock::now();
    camera.validate();
    if (camera.projection != Projection::Shear)
        throw Error("projection", "voxel-literal implements the papers' vertical view plane only (use shear)");
    const int W = camera.width, H = camera.height;
    color.resize(W, H);
    depth.resize(W, H);
    const double hs = terrain.h_scale();
    const double dpk = camera.focal_px(); // sec. 6 [a]: the same d_pk for every column
    const double n = camera.near, f = camera.far;
    const int slices = int(std::floor((f - n) / hs + 1e-9)) + 1;
    std::vector<float> Depth;
    depth_vector(camera, n, hs, slices, Depth); // Algorithm 2
    const glm::dvec3 F = camera.forward(), R = camera.right();
    // Pixels from the bottom pixel's centre up to the horizon: Fig. 6's pitch.
    const double pitch = H * 0.5 - 0.5 - dpk * std::tan(glm::radians(camera.pitch));
    long long visited = 0, painted = 0;
    const AerialFrame air = aerial_frame(env, camera.eye.y);
    const double texel = imagery ? imagery->texel_size(0) : 1.0;
    const int levels = imagery ? imagery->levels() : 1;

    for (int col = 0; col < W; ++col) {
        const double a = camera.u_of(col) / dpk;
        // sec. 5.2 / 6 [b]: unit step along F, scaled by 1/cos(theta_k) sideways.
        const double dx = hs * (F.x + a * R.x), dy = hs * (F.z + a * R.z);
        // Line 1, placed one step before the first slice so that line 6 lands on `near`.
        double x = camera.eye.x + (n - hs) * (F.x + a * R.x);
        double y = camera.eye.z + (n - hs) * (F.z + a * R.z);
        int j = 0;                   // line 2: bottom pixel
        double m = pitch / dpk;      // line 3: first horizon (downward slope per unit distance)
        double z = camera.eye.y - (n - hs) * m;
        int i = 0;                   // line 4
        // The previous slice's sample (its index and height), when it was on the terrain.
        bool prev_on = false;
        std::size_t prev_index = 0;
        double prev_x = 0, prev_y = 0, prev_h = 0;
        while (i < slices && j < H) { // line 5 (a full column ends the loop too)
            const double dist = n + i * hs;
            y += dy; x += dx; z -= hs * m; // line 6
            const bool on = terrain.contains(float(x), float(y));
            if (on) {
                ++visited;
                const double h = surface == SurfaceModel::Blocks ? terrain.height_nearest(float(x), float(y))
                                                                 : terrain.height_bilinear(float(x), float(y)); // line 7
                const int ci = std::lround(y / hs), cj = std::lround(x / hs);
                const std::size_t index = terrain.index(ci, cj);
                if (h > z) { // line 8
                    const Rgb8 own = colors ? (*colors)[index] : terrain.color(ci, cj); // line 9
                    // Where the light mask changes from the previous sample,
                    // rays below the point where the mesh's light changes
                    // (the ray's crossing from the previous sample's cell into
                    // this one's, at the slope's height there) show this
                    // sample under the previous one's light (FrontFace.h).
                    const bool split = mask.shadowed && prev_on &&
                                       (*mask.shadowed)[index] != (*mask.shadowed)[prev_index];
                    const double cross =
                        split ? cell_crossing(prev_x / hs + 0.5, prev_y / hs + 0.5, x / hs + 0.5, y / hs + 0.5,
                                              (*mask.shadowed)[prev_index] != 0,
                                              [&](int cell_col, int cell_row) { return (*mask.shadowed)[terrain.index(cell_row, cell_col)] != 0; })
                              : 0.5;
                    const double d_mid = dist - (1.0 - cross) * hs;
                    const double h_mid = surface == SurfaceModel::Blocks ? 0.5 * (prev_h + h) : prev_h + cross * (h - prev_h);
                    do {
                        const Rgb8 c = split && camera.eye.y - d_mid * m < h_mid ? (*mask.other_colors)[index] : own;
                        const int row = H - 1 - j;
                        // Fog at the eye distance of this pixel's ray at this slice.
                        const double len = std::sqrt(1.0 + a * a + m * m);
                        Rgb8 lit = c;
                        if (imagery) {
                            // The light times the imagery where this pixel's ray meets the
                            // sample's height, within the cell it stands for (ImageryTexels.h).
                            const double d = m > 0 ? std::clamp((camera.eye.y - h) / m, dist - hs, dist) : dist;
                            // The longer side of the pixel's trace on level ground.
                            const double footprint = dist / (dpk * (m > 0 ? std::max(m, 1.0 / 1024.0) : 1.0));
                            const int level = mip_level_for_footprint(footprint, texel, levels);
                            lit = modulate_light(c, imagery->nearest(camera.eye.x + d * (F.x + a * R.x),
                                                                     camera.eye.z + d * (F.z + a * R.z), level));
                        }
                        color.at(col, row) = env.atmosphere ? aerial_rgb(air, lit, dist * (F + a * R + glm::dvec3(0, -m, 0)))
                                                            : apply_fog(env, lit, fog_factor(env, dist * len)); // line 11
                        depth.at(col, row) = Depth[std::size_t(i)];                          // line 11A
                        ++painted;
                        j += 1;          // line 12
                        m -= 1.0 / dpk;  // line 13
                        z += dist / dpk; // line 14 (the distance of slice i)
                    } while (h > z && j < H);
                }
                prev_index = index;
                prev_x = x;
                prev_y = y;
                prev_h = h;
            }
            prev_on = on;
            i += 1; // line 16
        }
        for (; j < H; ++j) { // above the last horizon: sky
            const int row = H - 1 - j;
            const glm::dvec3 dir = F + a * R + glm::dvec3(0, -m, 0);
            color.at(col, row) = env.atmosphere ? aerial_sky_rgb(air, dir) : sky_color(env, dir);
            depth.at(col, row) = 1.0f;
            m -= 1.0 / dpk;
        }
    }
    if (stats) {
        *stats = RaycastStats{};
        stats->columns = W;
        stats->slices = slices;
        stats->samples = (long long)W * slices;
        stats->samples_visited = visited;
        stats->pixels_painted = painted;
        stats->ms_total = stats->ms_cast =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    }
}

} // namespace overflight
