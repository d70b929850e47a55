// Based on: Stewart, "Fast Horizon Computation at All Points of a Terrain
// with Visibility and Shading Applications" (IEEE TVCG 1998). See HorizonSweep.h.
#include "core/HorizonSweep.h"

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace overflight {

namespace {

// Sun lines per sample spacing: a sample between two sun lines half a
// spacing apart gets their ceilings interpolated (one line per spacing
// disagreed with rays to the sun on up to 0.8 % of the samples, two on 0.2 %:
// tests/cpu/horizon_sweep_test.cpp).
constexpr int kLines = 2;

int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
int ceil_div(int a, int b) { return -floor_div(-a, b); }

// The grid as the sweep walks it: `lines` grid lines of `length` samples
// each, swept from the one nearest the sun (`first`) in steps of `step`
// lines. Sun rays are straight lines in the grid plane: sun line J crosses
// grid line k of the sweep order at position J / kLines + k * slope
// (|slope| <= 1), and a sun ray rises by `rise` world units from one grid
// line to the next.
struct SweepGrid {
    int lines = 0, length = 0;
    int first = 0, step = 1;
    double slope = 0;
    float rise = 0;
    std::size_t stride_line = 0, stride_pos = 0; // sample index = line * stride_line + pos * stride_pos
    int J_min = 0, J_max = 0; // the sun lines that cross the grid

    std::size_t index(int line, int pos) const { return std::size_t(line) * stride_line + std::size_t(pos) * stride_pos; }
};

SweepGrid sweep_grid(const Terrain& t, const glm::vec3& sun) {
    SweepGrid g;
    const float horizontal = std::hypot(sun.x, sun.z);
    const float tan_elevation = sun.y / horizontal;
    const std::size_t cols = std::size_t(t.cols());
    // Sweep across the grid lines the sun's azimuth crosses more often, so
    // that a sun line moves at most one sample along each.
    const bool lines_are_columns = std::abs(sun.x) >= std::abs(sun.z);
    float along, across; // sun direction along the grid lines and across them
    if (lines_are_columns) {
        g.lines = t.cols();
        g.length = t.rows();
        g.stride_line = 1;
        g.stride_pos = cols;
        across = sun.x;
        along = sun.z;
    } else {
        g.lines = t.rows();
        g.length = t.cols();
        g.stride_line = cols;
        g.stride_pos = 1;
        across = sun.z;
        along = sun.x;
    }
    // The grid line nearest the sun first: with the sun towards +X (+Z), the
    // last column (row). Away from the sun a sun line moves by -along/|across|.
    g.first = across > 0 ? g.lines - 1 : 0;
    g.step = across > 0 ? -1 : 1;
    double slope = std::clamp(-double(along) / std::abs(double(across)), -1.0, 1.0);
    // A sun due east or on a diagonal gives a slope of 0 or +-1 up to the
    // rounding of its sine and cosine; taken as exact, so that the sun lines
    // run through the samples.
    for (const double exact : {-1.0, 0.0, 1.0})
        if (std::abs(slope - exact) < 1e-5) slope = exact;
    g.slope = slope;
    g.rise = float(t.h_scale() * std::sqrt(1.0 + slope * slope) * double(tan_elevation));
    const double drift = slope * double(g.lines - 1);
    g.J_min = int(std::floor(kLines * std::min(0.0, -drift)));
    g.J_max = int(std::ceil(kLines * (double(g.length - 1) + std::max(0.0, -drift))));
    return g;
}

// Sweeps the sun lines [J0, J1] over every grid line, in sweep order. Each
// sun line keeps the exact ceiling of the points on it (a running maximum);
// sample p of grid line k lies between the sun lines J and J + 1 that cross
// k around it and gets the ceilings of the two interpolated, written for
// the samples whose J is in [J0, J1). `state`: scratch.
void sweep_lines(const Terrain& t, const SweepGrid& g, int J0, int J1, float* ceiling, std::vector<float>& state) {
    state.assign(std::size_t(J1 - J0 + 1), ShadowCeiling::kOpen);
    float* const S0 = state.data();
    const auto S = [S0, J0](int J) -> float& { return S0[J - J0]; }; // sun line J's ceiling, J in [J0, J1]
    const std::uint16_t* raw = t.heights().data();
    const float vs = t.v_scale(), y0 = t.y_offset();
    const int last = g.length - 1;
    auto height = [&](int line, int pos) { return vs * float(raw[g.index(line, pos)]) + y0; };
    for (int k = 0; k < g.lines; ++k) {
        const int line = g.first + g.step * k;
        const double x = double(k) * g.slope;
        // Samples: sample p lies between sun lines J and J + 1, a fraction f
        // of the way, with J = kLines p + shift.
        const double u = -kLines * x;
        const int shift = int(std::floor(u));
        const float f = float(u - shift);
        const int p0 = std::max(0, ceil_div(J0 - shift, kLines)), p1 = std::min(g.length, ceil_div(J1 - shift, kLines));
        for (int p = p0; p < p1; ++p) {
            const int J = kLines * p + shift;
            float c;
            if (f == 0.0f || p == last) c = S(J);     // on sun line J, or sun line J + 1 beyond the grid
            else if (p == 0) c = S(J + 1);             // sun line J is off the grid
            else c = S(J) + f * (S(J + 1) - S(J));
            ceiling[g.index(line, p)] = c;
        }
        // Each family of sun lines (J = kLines j + phase) crosses this grid
        // line at positions j + offset.
        for (int phase = 0; phase < kLines; ++phase) {
            const double offset = double(phase) / kLines + x;
            const int fl = int(std::floor(offset));
            const float fr = float(offset - fl);
            const int j_lo = std::max(ceil_div(J0 - phase, kLines), int(std::ceil(-offset)));
            const int j_hi = std::min(floor_div(J1 - phase, kLines), int(std::floor(double(last) - offset)));
            // The sun lines on this grid line (0 <= j + offset <= length - 1)
            // meet the terrain here: their ceiling for the next grid line.
            for (int j = j_lo; j <= j_hi; ++j) {
                const int ia = j + fl, ib = std::min(ia + 1, last);
                const float ha = height(line, ia), hb = height(line, ib);
                float& s = S(kLines * j + phase);
                s = std::max(ha + fr * (hb - ha), s) - g.rise;
            }
            // Between this grid line and the next a sun line may cross a
            // grid line of the other family, position m, a fraction t of the
            // way: there too the height is exact, up-sun of the next crossing.
            if (k + 1 == g.lines || g.slope == 0.0) continue;
            const double next_offset = offset + g.slope;
            const double m0 = g.slope > 0 ? std::floor(next_offset) : std::ceil(next_offset);
            if (!(g.slope > 0 ? m0 > offset && m0 < next_offset : m0 < offset && m0 > next_offset)) continue;
            const float t_cross = float((m0 - offset) / g.slope);
            const float rest = (1.0f - t_cross) * g.rise;
            const int next = line + g.step, mo = int(m0);
            for (int j = std::max(j_lo, -mo); j <= std::min(j_hi, last - mo); ++j) {
                const float ha = height(line, j + mo), hb = height(next, j + mo);
                float& s = S(kLines * j + phase);
                s = std::max(s, ha + t_cross * (hb - ha) - rest);
            }
        }
    }
}

} // namespace

void sweep_shadow_ceiling(const Terrain& t, const glm::vec3& sun_dir, ShadowCeiling& out) {
    out.rows = t.rows();
    out.cols = t.cols();
    out.sun_dir = glm::length(sun_dir) > 0 ? glm::normalize(sun_dir) : glm::vec3(0, 1, 0);
    out.ceiling.resize(std::size_t(t.rows()) * std::size_t(t.cols()));
    const glm::vec3 sun = out.sun_dir;
    if (!(sun.y > 0)) { // below the horizon: nothing is lit by the sun
        std::fill(out.ceiling.begin(), out.ceiling.end(), std::numeric_limits<float>::infinity());
        return;
    }
    if (std::hypot(sun.x, sun.z) <= 1e-6f * sun.y) { // in the zenith: no cast shadows
        std::fill(out.ceiling.begin(), out.ceiling.end(), ShadowCeiling::kOpen);
        return;
    }
    const SweepGrid g = sweep_grid(t, sun);
    float* ceiling = out.ceiling.data();
    // Sun lines are independent: bands of them in parallel, a few per worker
    // for balance, each band sweeping the first line of the next one as well
    // (the samples between the two need both).
    const int workers = tbb::this_task_arena::max_concurrency();
    const int count = g.J_max - g.J_min + 1;
    const int bands = std::clamp(count / 256, 1, 4 * std::max(1, workers));
    const int band = (count + bands - 1) / bands;
    tbb::parallel_for(0, bands, [&](int b) {
        const int J0 = g.J_min + b * band, J1 = std::min(g.J_max + 1, J0 + band);
        if (J0 >= J1) return;
        thread_local std::vector<float> state;
        sweep_lines(t, g, J0, J1, ceiling, state);
    });
}

std::vector<std::uint8_t> shadow_mask(const Terrain& t, const ShadowCeiling& c) {
    std::vector<std::uint8_t> mask(std::size_t(t.rows()) * std::size_t(t.cols()));
    tbb::parallel_for(0, t.rows(), [&](int row) {
        for (int col = 0; col < t.cols(); ++col)
            mask[t.index(row, col)] = c.shadowed(row, col, t.sample_height(row, col)) ? 1 : 0;
    });
    return mask;
}

} // namespace overflight
