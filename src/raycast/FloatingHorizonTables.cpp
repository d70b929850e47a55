// Based on: Szenberg, Gattass, Carvalho, "An Algorithm for the Visualization
// of a Terrain with Objects", SIBGRAPI 1997, Algorithm 1, sec. 5.2, eq. 7,
// Algorithm 2; Guedes, "Integrating Polygonal Objects on Voxel Based Terrain
// Models", Algorithm 1. See FloatingHorizonTables.h.
#include "raycast/FloatingHorizonTables.h"

#include "core/Parallel.h"
#include "raycast/DepthVector.h"
#include "raycast/RowSearch.h"

#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace overflight {

namespace {
constexpr float kInf = std::numeric_limits<float>::infinity();
}

ViewAxes view_axes(const Camera& camera, double h_scale) {
    const glm::dvec3 F = camera.forward(), R = camera.right();
    ViewAxes v;
    v.eye_gx = camera.eye.x / h_scale;
    v.eye_gz = camera.eye.z / h_scale;
    v.eye_y = camera.eye.y;
    v.fx = F.x;
    v.fz = F.z;
    v.rx = R.x;
    v.rz = R.z;
    return v;
}

void place_slices(const SlicePlacement& p, Slices& out) {
    const double hs = p.h_scale;
    out.d.clear();
    out.level.clear();
    out.uniform = !p.lod && !(p.near_step_pixels > 0.0);
    if (out.uniform) {
        const long long count = (long long)std::floor((p.d_last - p.d_first) / hs + 1e-9) + 1;
        out.d.resize(std::size_t(std::max(count, 1LL)));
        for (std::size_t k = 0; k < out.d.size(); ++k) out.d[k] = p.d_first + hs * double(k);
        out.level.assign(out.d.size(), 0);
        out.even = int(out.d.size());
    } else {
        out.even = 0;
        const double lod_cells = p.fp_h * hs * std::max(p.lod_pixels, 1e-3);
        const double near_px = p.near_step_pixels;
        for (double d = p.d_first; d <= p.d_last + 1e-9;) {
            int L = 0;
            while (p.lod && L < p.lod_levels && d >= lod_cells * double(2 << L)) ++L;
            out.d.push_back(d);
            out.level.push_back(std::uint8_t(L));
            double step = hs * double(1 << L);
            if (near_px > 0.0) step = std::min(step, std::max(hs / 8.0, near_px * d / p.fp_h));
            if (L == 0 && step == hs && out.even + 1 == int(out.d.size())) {
                ++out.even;
                d = p.d_first + hs * double(out.even); // as the uniform slices are placed
            } else d += step;
        }
    }
    out.step = out.even > 0 ? hs : 0.0;
    const std::size_t n = out.d.size();
    out.df.resize(n);
    // Evenly spaced: in float as d_first + step k, which the shear resolve may
    // compute rather than read (ShearResolveTables::d_step).
    for (std::size_t k = 0; k < n; ++k)
        out.df[k] = int(k) < out.even ? float(p.d_first) + float(hs) * float(k) : float(out.d[k]);
}

void slice_slopes(const std::vector<double>& d, const Terrain& terrain, float max_height, double eye_y,
                  SliceSlopes& out) {
    const std::size_t n = d.size();
    out.a.resize(n);
    out.b.resize(n);
    out.smax.resize(n);
    const double vs = terrain.v_scale(), y0 = terrain.y_offset();
    out.v_scale = vs;
    out.base = y0 - eye_y;
    float running = -kInf;
    for (std::size_t k = n; k-- > 0;) {
        const double inv = 1.0 / d[k];
        out.a[k] = float(vs * inv);
        out.b[k] = float((y0 - eye_y) * inv);
        // Rounded up so that float rounding can never stop a column early.
        running = std::max(running, std::nextafter(float((max_height - eye_y) * inv), kInf));
        out.smax[k] = running;
    }
}

void slice_window_depths(const Camera& camera, const Slices& slices, std::vector<float>& out) {
    const std::size_t n = slices.d.size();
    if (slices.uniform) {
        depth_vector(camera, slices.d[0], slices.step, int(n), out);
        return;
    }
    out.resize(n);
    for (std::size_t k = 0; k < n; ++k) out[k] = float(camera.window_depth(slices.d[k]));
}

void shear_rows(const Camera& camera, Rows& out) {
    const int H = camera.height;
    const double fp = camera.focal_px();
    const double shift = fp * std::tan(glm::radians(camera.pitch));
    out.count = H;
    out.even = true; // m_j = (v_j + shift) / fp
    out.m.resize(std::size_t(H) + 1);
    for (int j = 0; j < H; ++j) out.m[std::size_t(j)] = float((camera.v_of(H - 1 - j) + shift) / fp);
    out.m[std::size_t(H)] = kInf;
}

void tilt_rows(const Camera& camera, TiltRows& t) {
    const int H = camera.height;
    const double fp = camera.focal_px();
    const double p = glm::radians(camera.pitch), sp = std::sin(p), cp = std::cos(p);
    t.w.resize(std::size_t(H));
    t.m.resize(std::size_t(H));
    double w_top = -1;
    for (int r = 0; r < H; ++r) {
        const double v = camera.v_of(r);
        t.w[std::size_t(r)] = cp - (v / fp) * sp;
        t.m[std::size_t(r)] = (sp + (v / fp) * cp) / t.w[std::size_t(r)];
        w_top = std::max(w_top, t.w[std::size_t(r)]);
    }
    // Keeping w >= w_max/4 bounds the planes cast to 4 kTiltPlanes times the
    // image width.
    const double w_cut = std::max(w_top * 0.25, 1e-3);
    t.j_lo = H;
    t.j_hi = 0;
    t.w_min = w_top;
    t.w_max = 0;
    for (int j = 0; j < H; ++j) {
        const double w = t.w[std::size_t(H - 1 - j)];
        if (w >= w_cut) {
            t.j_lo = std::min(t.j_lo, j);
            t.j_hi = std::max(t.j_hi, j + 1);
            t.w_min = std::min(t.w_min, w);
            t.w_max = std::max(t.w_max, w);
        }
    }
    if (t.j_hi <= t.j_lo) t.j_lo = t.j_hi = 0;
}

void tilt_cast_rows(const TiltRows& t, Rows& out) {
    const int H = int(t.m.size()), rc = t.j_hi - t.j_lo;
    out.count = rc;
    out.even = false; // tilted rows are not evenly spaced in slope (RowSearch would walk)
    out.m.resize(std::size_t(rc) + 1);
    for (int i = 0; i < rc; ++i) out.m[std::size_t(i)] = float(t.m[std::size_t(H - 1 - (t.j_lo + i))]);
    out.m[std::size_t(rc)] = kInf;
}

void shear_column_planes(const Camera& camera, std::vector<double>& a) {
    const double fp = camera.focal_px();
    a.resize(std::size_t(camera.width));
    for (int c = 0; c < camera.width; ++c) a[std::size_t(c)] = camera.u_of(c) / fp;
}

double tilt_column_planes(const Camera& camera, const TiltRows& t, std::vector<double>& a) {
    const int W = camera.width, rc = t.j_hi - t.j_lo;
    const double fp = camera.focal_px();
    const double fp_h = fp * t.w_max * kTiltPlanes;
    const double a_max = rc > 0 ? (W * 0.5) / (fp * t.w_min) : 0.0;
    const int ws = rc > 0 ? std::max(1, int(std::ceil(2.0 * a_max * fp_h))) : 0;
    a.resize(std::size_t(ws));
    for (int i = 0; i < ws; ++i) a[std::size_t(i)] = (i + 0.5 - ws * 0.5) / fp_h;
    return fp_h;
}

void guedes_column_planes(const Camera& camera, std::vector<double>& a) {
    const double fp = camera.focal_px();
    const double cp = std::cos(glm::radians(camera.pitch));
    a.resize(std::size_t(camera.width));
    for (int c = 0; c < camera.width; ++c) a[std::size_t(c)] = camera.u_of(c) / (fp * cp);
}

namespace {

// std::lower_bound (kUpper: std::upper_bound) of d over the slices' depths.
// Within the evenly spaced first slices the spacing gives the answer to
// within a slice or two, which a short walk makes exact; elsewhere, bisection
// (two bisections per column over the 10 k slices of a 4K view with LOD took
// about 0.1 ms of the frame's 0.17 ms setup).
template <bool kUpper>
int slice_bound(const Slices& slices, double d) {
    const std::vector<double>& v = slices.d;
    // Whether slice depth x lies before the answer (the predicate the std
    // algorithms partition by, NaN included).
    const auto before = [d](double x) { return kUpper ? !(d < x) : x < d; };
    if (slices.even > 0 && d >= v[0] && d <= v[std::size_t(slices.even) - 1]) {
        std::size_t k = std::min(std::size_t((d - v[0]) / slices.step), std::size_t(slices.even) - 1);
        while (k > 0 && !before(v[k - 1])) --k;
        while (k < v.size() && before(v[k])) ++k;
        return int(k);
    }
    return int(std::partition_point(v.begin(), v.end(), before) - v.begin());
}

} // namespace

void clip_columns(const ViewAxes& view, const Terrain& terrain, const Slices& slices, Columns& columns) {
    const double hs = terrain.h_scale();
    const std::vector<double>& a = columns.a;
    const std::size_t n = a.size();
    columns.ux.resize(n);
    columns.uz.resize(n);
    columns.k0.resize(n);
    columns.k1.resize(n);
    const double gx_max = terrain.cols() - 1, gz_max = terrain.rows() - 1;
    // Narrows [lo_d, hi_d] to where e + d u is in [0, hi].
    auto range = [](double e, double u, double hi, double& lo_d, double& hi_d) {
        if (u == 0.0) {
            if (e < 0.0 || e > hi) hi_d = -1.0;
            return;
        }
        double t0 = (0.0 - e) / u, t1 = (hi - e) / u;
        if (t0 > t1) std::swap(t0, t1);
        lo_d = std::max(lo_d, t0);
        hi_d = std::min(hi_d, t1);
    };
    parallel::for_each_range(std::size_t(0), n, std::size_t(512), [&](std::size_t begin, std::size_t end) {
        for (std::size_t c = begin; c < end; ++c) {
            const double ux = (view.fx + a[c] * view.rx) / hs, uz = (view.fz + a[c] * view.rz) / hs;
            columns.ux[c] = ux;
            columns.uz[c] = uz;
            double lo = 0.0, hi = std::numeric_limits<double>::infinity();
            range(view.eye_gx, ux, gx_max, lo, hi);
            range(view.eye_gz, uz, gz_max, lo, hi);
            if (hi < lo) {
                columns.k0[c] = columns.k1[c] = 0;
                continue;
            }
            // Grow by a hair so that a slice exactly on the edge stays in; a sample
            // that far out still rounds to an edge sample (blocks) or is clamped (bilinear).
            lo -= 1e-9 * (1.0 + lo);
            hi += 1e-9 * (1.0 + hi);
            columns.k0[c] = slice_bound<false>(slices, lo);
            columns.k1[c] = slice_bound<true>(slices, hi);
            if (columns.k1[c] < columns.k0[c]) columns.k1[c] = columns.k0[c];
        }
    });
}

void slice_guesses(const SliceSlopes& slopes, const Rows& rows, std::vector<SliceGuess>& out) {
    const RowSearch search(rows.m.data(), rows.count);
    const std::size_t n = slopes.a.size();
    out.resize(n);
    const double one = double(std::int64_t(1) << kGuessBits);
    for (std::size_t k = 0; k < n; ++k) {
        const double a = double(slopes.a[k]) * search.inv_step();
        const double b = (double(slopes.b[k]) - search.m0()) * search.inv_step() + 1.0;
        SliceGuess& g = out[k];
        g.ga = std::llround(std::clamp(a, -0x1p20, 0x1p20) * one);
        g.gb = std::llround(std::clamp(b, -0x1p36, 0x1p36) * one);
        g.a = slopes.a[k];
        g.b = slopes.b[k];
    }
}

float shear_fog_reach(const Camera& camera, const Rows& rows) {
    const double fp = camera.focal_px();
    const double a_edge = (camera.width * 0.5) / fp;
    const double m_edge = std::max(std::abs(rows.m[0]), std::abs(rows.m[std::size_t(rows.count) - 1]));
    return float(camera.far * std::sqrt(1.0 + a_edge * a_edge + m_edge * m_edge) * 1.001);
}

float tilt_fog_reach(const Camera& camera) {
    const double fp = camera.focal_px();
    const double lmax = std::sqrt(1.0 + std::pow(camera.width * 0.5 / fp, 2) + std::pow(camera.height * 0.5 / fp, 2));
    return float(camera.far * lmax * 1.001);
}

} // namespace overflight
