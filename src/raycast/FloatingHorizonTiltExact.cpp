// Tilt, exact: every tilted row r is one ray slope m_r in every vertical plane
// (see TiltRows), so a floating horizon over vertical planes with the rows'
// slopes as its rows gives each tilted pixel's first hit exactly, in the plane
// nearest to its own (planes spaced at most 1/kTiltPlanes tilted pixel apart,
// so the sideways error is at most a quarter pixel). Slices cover
// [near w_min, far w_max] along F; a hit past the far plane along F' is sky,
// as GL would clip it.
//
// Based on: Szenberg, Gattass, Carvalho, "An Algorithm for the Visualization
// of a Terrain with Objects", SIBGRAPI 1997, Algorithm 1 and sec. 5.2, over
// the per-row ray slopes of Guedes, "Integrating Polygonal Objects on Voxel
// Based Terrain Models", Algorithm 1.
#include "core/Parallel.h"
#include "raycast/FloatingHorizonTilt.h"

namespace overflight {

void cast_tilt_exact(FloatingHorizonState& s, const Camera& camera, const Environment& env,
                     const RaycastOptions& options, ColorImage& color, DepthImage& depth, RaycastStats& stats) {
    auto t0 = Clock::now();
    const CastFrame& f = s.frame;
    tilt_rows(camera, s.tilt_rows);
    const double fp_h = tilt_column_planes(camera, s.tilt_rows, s.frame.columns.a);
    prepare_tilt(s, camera, env, options, fp_h);
    const int ws = int(f.columns.a.size());
    const std::size_t cstride = std::size_t(f.rows.count); // column stride of the scratch
    stats.ms_setup = ms_since(t0);
    stats.columns = ws;

    t0 = Clock::now();
    std::atomic<long long> visited{0};
    const int blocks = (ws + kShearBlock - 1) / kShearBlock;
    parallel::for_each_index(0, blocks, [&](int b) {
        const int c0 = b * kShearBlock, c1 = std::min(ws, c0 + kShearBlock);
        const std::size_t off = std::size_t(c0) * cstride;
        visited += cast_columns(s.terrain, f, options, c0, c1, s.tilt_color.data() + off, s.tilt_slice.data() + off,
                                s.tilt_jend.data() + c0, std::ptrdiff_t(cstride), 1);
    });
    if (s.imagery.bound()) {
        // The light of each cast pixel times the imagery under it (ImageryTexels.h); plane cs runs along F + a R.
        const glm::dvec3 F = camera.forward(), R = camera.right();
        const DrapeFrame frame{&s.imagery, f.slices.df.data(), f.slices.df[0], f.rows.m.data(), float(camera.eye.x),
                               float(camera.eye.z)};
        parallel::for_each_index(0, ws, [&](int cs) {
            const double a = f.columns.a[std::size_t(cs)];
            const std::size_t off = std::size_t(cs) * cstride;
            drape_column(frame, float(F.x + a * R.x), float(F.z + a * R.z), s.tilt_color.data() + off,
                         s.tilt_slice.data() + off, s.tilt_jend[std::size_t(cs)], 1);
        });
    }
    stats.samples_visited = visited;
    stats.ms_cast = ms_since(t0);

    // Each tilted pixel from the plane nearest to its ray, fogged (or seen
    // through the air) at the eye distance of the cast ray (plane cs, row i)
    // at its slice.
    const double fp = camera.focal_px();
    const double f_sun = glm::dot(camera.forward(), s.sun), r_sun = glm::dot(camera.right(), s.sun);
    const float sun_y = float(s.sun.y);
    auto row_hits = [&](int r, int i) {
        const double w = s.tilt_rows.w[std::size_t(r)];
        const float m_i = f.rows.m[std::size_t(i)];
        const double scale = fp_h / (fp * w);
        return [&s, &f, &camera, w, m_i, scale, i, ws, cstride, f_sun, r_sun, sun_y](int c, double& dv,
                                                                                    std::uint32_t& rgb) {
            const double u = camera.u_of(c);
            const int cs = std::clamp(int(std::floor(u * scale + ws * 0.5)), 0, ws - 1);
            if (i >= s.tilt_jend[std::size_t(cs)]) return false;
            const std::size_t e = std::size_t(cs) * cstride + std::size_t(i);
            const std::uint32_t k = s.tilt_slice[e];
            dv = f.slices.d[k] / w; // view depth along F'
            if (!(dv <= camera.far)) return false;
            const double a = f.columns.a[std::size_t(cs)];
            const float cast_len = std::sqrt(float(1.0 + a * a) + m_i * m_i);
            const float cos_sun = (float(f_sun + a * r_sun) + m_i * sun_y) / cast_len;
            rgb = s.hit_color(s.tilt_color[e], f.slices.df[k] * cast_len, f.slices.df[k] * m_i, cos_sun);
            return true;
        };
    };
    resolve_tilt(s, camera, env, options.surface, row_hits, color, depth, stats);
}

} // namespace overflight
