// Tilt, Guedes: each column is the vertical plane of its pixel on the centre
// row (a = u / (fp cos p)); every row j of it is a ray of slope dz[j] in that
// plane. Per voxel step the ray height grows by step*dz[row] and the depth
// along F' by step*(cos VA - dz sin VA) (VA = -pitch: Guedes' view angle is
// positive looking down); climbing a pixel raises the ray by
// ph = v*(dz[row+1] - dz[row]) and the depth by -ph sin VA. The printed
// algorithm stores d after the climb (the next row's depth); here each pixel
// gets the depth of its own ray. Its error is that pixels off the centre row
// are not in that plane (measured against the ray marcher, see README).
//
// Based on: Guedes, "Integrating Polygonal Objects on Voxel Based Terrain
// Models", Algorithm 1, over the Floating Horizon of Szenberg, Gattass,
// Carvalho, "An Algorithm for the Visualization of a Terrain with Objects",
// SIBGRAPI 1997, Algorithm 1.
#include "core/Parallel.h"
#include "raycast/FloatingHorizonTilt.h"
#include "raycast/FrontFace.h"

#include <cstring>
#include <limits>

namespace overflight {

namespace {

std::uint32_t float_bits(float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}
float bits_float(std::uint32_t u) {
    float f;
    std::memcpy(&f, &u, sizeof f);
    return f;
}

// Guedes' Algorithm 1 for column c: fogged (or aerial) colors and the view depth along
// F' (as float bits) of rows [0, returned) go to out_c/out_d. Returns the rows
// painted; `visited` receives the samples read. Where the light mask changes
// between the previous voxel's sample and this one, the rows whose rays pass
// below the point where the mesh's light changes take the previous one's
// light (FrontFace.h).
int cast_guedes_column(const FloatingHorizonState& s, const Camera& camera, int c, std::uint32_t* out_c,
                       std::uint32_t* out_d, long long& visited) {
    const CastFrame& f = s.frame;
    const Terrain& t = s.terrain.terrain;
    const int rc = f.rows.count;
    const float* dz = f.rows.m.data();
    const int k0 = f.columns.k0[std::size_t(c)], k1 = f.columns.k1[std::size_t(c)];
    if (rc == 0 || k0 >= k1) return 0;
    const double p = glm::radians(camera.pitch), sp = std::sin(p), cp = std::cos(p);
    const double hs = t.h_scale(), ey = f.view.eye_y;
    const double ux = f.columns.ux[std::size_t(c)], uz = f.columns.uz[std::size_t(c)];
    const double a = f.columns.a[std::size_t(c)];
    const double lat = std::sqrt(1.0 + a * a); // horizontal length per unit F
    const double lat_sun = glm::dot(camera.forward() + a * camera.right(), s.sun); // per unit F
    // The state as if stepped from the eye to the first slice inside the terrain.
    double v = f.slices.d[std::size_t(k0)];
    double x = f.view.eye_gx + v * ux, y = f.view.eye_gz + v * uz;
    double z = ey + v * dz[0];
    double d = v * (cp + dz[0] * sp);
    const double dx = hs * ux, dy = hs * uz;
    int row = 0;
    int k = k0;
    const Rgb8* other = s.terrain.other_colors;
    // The previous voxel's position, sample and height (none at k0).
    double prev_x = 0, prev_y = 0, prev_h = 0;
    std::size_t prev_ci = 0;
    for (; k < k1; ++k) {
        const std::size_t ci = std::size_t(int(y + 0.5)) * std::size_t(t.cols()) + std::size_t(int(x + 0.5));
        const double h = t.v_scale() * double(t.heights()[ci]) + t.y_offset();
        if (h > z) {
            const std::uint32_t word = s.terrain.colors[ci];
            std::uint32_t col = word & kRgbBits, near_col = col;
            // Rows whose ray slope is below where the light changes take near_col.
            double below = -std::numeric_limits<double>::infinity();
            if (other && k > k0 && light_changes(s.terrain.colors[prev_ci], word)) {
                const std::uint32_t* colors = s.terrain.colors.data();
                const double cross = cell_crossing(prev_x + 0.5, prev_y + 0.5, x + 0.5, y + 0.5,
                                               (word & kShadowedBit) == 0, [&](int cell_col, int cell_row) {
                                                   return (colors[std::size_t(cell_row) * std::size_t(t.cols()) + std::size_t(cell_col)] &
                                                           kShadowedBit) != 0;
                                               });
                below = (0.5 * (prev_h + h) - ey) / (v - (1.0 - cross) * hs);
                near_col = pack_rgb(other[ci]);
            }
            if (s.imagery.bound()) { // the light times the imagery at the ray's ground point
                const Rgba8 albedo = s.imagery.at(float(x * hs), float(y * hs), s.imagery.level(k, row));
                col = modulate_light(col, albedo);
                near_col = modulate_light(near_col, albedo);
            }
            do {
                const double dist = std::sqrt(v * v * lat * lat + (z - ey) * (z - ey));
                out_c[row] = s.hit_color((z - ey) / v < below ? near_col : col, float(dist), float(z - ey),
                                         float((v * lat_sun + (z - ey) * s.sun.y) / dist));
                out_d[row] = float_bits(float(d));
                if (row + 1 >= rc) {
                    ++row;
                    break;
                }
                const double ph = v * (double(dz[std::size_t(row) + 1]) - dz[std::size_t(row)]);
                ++row;
                z += ph;      // update ray height
                d += ph * sp; // d -= ph sin(VA)
            } while (h > z);
            if (row >= rc) break;
        }
        prev_x = x;
        prev_y = y;
        prev_ci = ci;
        prev_h = h;
        x += dx;
        y += dy;
        v += hs;
        z += hs * dz[std::size_t(row)];
        d += hs * (cp + dz[std::size_t(row)] * sp); // cos VA - dz sin VA
    }
    visited += k - k0;
    return row;
}

} // namespace

void cast_tilt_guedes(FloatingHorizonState& s, const Camera& camera, const Environment& env,
                      const RaycastOptions& options, ColorImage& color, DepthImage& depth, RaycastStats& stats) {
    auto t0 = Clock::now();
    const int W = camera.width;
    tilt_rows(camera, s.tilt_rows);
    guedes_column_planes(camera, s.frame.columns.a);
    RaycastOptions opt = options;
    opt.lod = false; // Guedes' incremental depth steps one cell per voxel
    opt.near_step_pixels = 0.0;
    prepare_tilt(s, camera, env, opt, camera.focal_px());
    const std::size_t rc = std::size_t(s.frame.rows.count);
    stats.ms_setup = ms_since(t0);
    stats.columns = W;

    t0 = Clock::now();
    std::atomic<long long> visited{0};
    parallel::for_each_index(0, W, [&](int c) {
        long long n = 0;
        s.tilt_jend[std::size_t(c)] = cast_guedes_column(s, camera, c, s.tilt_color.data() + std::size_t(c) * rc,
                                                         s.tilt_slice.data() + std::size_t(c) * rc, n);
        visited += n;
    });
    stats.samples_visited = visited;
    stats.ms_cast = ms_since(t0);

    // Each pixel from its own column, at the depth stored with it.
    auto row_hits = [&](int, int i) {
        return [&s, &camera, i, rc](int c, double& dv, std::uint32_t& rgb) {
            if (i >= s.tilt_jend[std::size_t(c)]) return false;
            const std::size_t e = std::size_t(c) * rc + std::size_t(i);
            dv = double(bits_float(s.tilt_slice[e]));
            if (!(dv <= camera.far)) return false;
            rgb = s.tilt_color[e];
            return true;
        };
    };
    resolve_tilt(s, camera, env, options.surface, row_hits, color, depth, stats);
}

} // namespace overflight
