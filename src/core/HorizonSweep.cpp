// Based on: Stewart, "Fast Horizon Computation at All Points of a Terrain
// with Visibility and Shading Applications" (IEEE TVCG 1998). See HorizonSweep.h.
#include "core/HorizonSweep.h"

#include "core/CpuFeatures.h"
#include "core/Parallel.h"

#include <glm/geometric.hpp>

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
// Sun lines per band (64 samples across): see sweep_band.
constexpr int kBand = 128;

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

// A block of kBlock consecutive grid lines (plus the next one, for the
// crossings between the last and it) over the positions [base, top] a band
// reads on them: world heights in a contiguous array, one row per grid line,
// with entry top + 1 repeating top's so that a crossing on the last sample
// may read its neighbour (weighted 0). With the sun lines across columns a
// grid line's samples lie a whole row apart in memory, a stride that maps
// them to a handful of cache sets; the block reads the grid in runs along
// the rows instead (a cache line of heights at a time) and writes the
// block's ceilings back the same way.
constexpr int kBlock = 32;

struct BandScratch {
    std::vector<float> state[kLines]; // state[phase][j - first[phase]]: sun line kLines j + phase
    std::vector<float> heights, out;  // [line of the block][position - base]
    int p0[kBlock] = {}, p1[kBlock] = {}; // the samples each grid line of the block writes
};

// Sweeps the sun lines [J0, J1] over every grid line, in sweep order. Each
// sun line keeps the exact ceiling of the points on it (a running maximum);
// sample p of grid line k lies between the sun lines J and J + 1 that cross
// k around it and gets the ceilings of the two interpolated, written for
// the samples whose J is in [J0, J1).
//
// A band is a few dozen samples wide, so that what it touches of a block of
// grid lines stays in the first-level cache. Each family of sun lines (J =
// kLines j + phase) keeps its ceilings contiguous in j, so that the inner
// loops run over contiguous arrays and vectorize.
//
// The block's results go to `ceiling` (world heights) and/or `mask` (1 where
// the sample's own height is below its ceiling), whichever is not null: the
// block holds both the sample's height and its ceiling, so the mask needs
// neither read again.
[[gnu::always_inline]] inline void sweep_band_body(const Terrain& t, const SweepGrid& g, int J0, int J1,
                                                   float* ceiling, std::uint8_t* mask, BandScratch& b) {
    int first[kLines];
    for (int phase = 0; phase < kLines; ++phase) {
        first[phase] = ceil_div(J0 - phase, kLines);
        b.state[phase].assign(std::size_t(std::max(0, floor_div(J1 - phase, kLines) - first[phase] + 1)), ShadowCeiling::kOpen);
    }
    const int last = g.length - 1;
    const std::uint16_t* raw = t.heights().data();
    const float vs = t.v_scale(), y0 = t.y_offset();
    const std::size_t cols = g.stride_line == 1 ? g.stride_pos : g.stride_line;
    for (int k0 = 0; k0 < g.lines; k0 += kBlock) {
        const int n_lines = std::min(kBlock, g.lines - k0), n_load = std::min(kBlock + 1, g.lines - k0);
        // What grid line k reads lies within 2 samples of the band's sun
        // lines' crossings [J0 / kLines + x, J1 / kLines + x], x = k slope.
        const double x_a = double(k0) * g.slope, x_b = double(k0 + n_load - 1) * g.slope;
        const int base = std::max(0, int(std::floor(double(J0) / kLines + std::min(x_a, x_b))) - 2);
        const int top = std::min(last, int(std::ceil(double(J1) / kLines + std::max(x_a, x_b))) + 2);
        if (top < base) continue; // the band's sun lines are off the grid here
        const int width = top - base + 2;
        b.heights.resize(std::size_t(n_load) * std::size_t(width));
        b.out.resize(std::size_t(n_lines) * std::size_t(width));
        float* const H = b.heights.data();
        const int line0 = g.first + g.step * k0;
        if (g.stride_line == 1) { // grid lines are columns: runs along each row
            for (int p = base; p <= top; ++p) {
                const std::uint16_t* src = raw + std::size_t(p) * cols + std::size_t(line0);
                for (int i = 0; i < n_load; ++i) H[i * width + (p - base)] = vs * float(src[i * g.step]) + y0;
            }
        } else {
            for (int i = 0; i < n_load; ++i) {
                const std::uint16_t* src = raw + std::size_t(line0 + g.step * i) * cols;
                for (int p = base; p <= top; ++p) H[i * width + (p - base)] = vs * float(src[p]) + y0;
            }
        }
        for (int i = 0; i < n_load; ++i) H[i * width + width - 1] = H[i * width + width - 2];

        for (int i = 0; i < n_lines; ++i) {
            const int k = k0 + i;
            const bool more = k + 1 < g.lines;
            const float* here = H + i * width - base; // here[pos], pos in [base, top + 1]
            const float* next = here + width;         // the next grid line's, when `more`
            const double x = double(k) * g.slope;
            // Samples: sample p lies between sun lines J and J + 1, a fraction f
            // of the way, with J = kLines p + shift.
            const double u = -kLines * x;
            const int shift = int(std::floor(u));
            const float f = float(u - shift);
            const int p0 = std::max(0, ceil_div(J0 - shift, kLines)), p1 = std::min(g.length, ceil_div(J1 - shift, kLines));
            b.p0[i] = p0;
            b.p1[i] = p1;
            if (p0 < p1) {
                // Sun line J of sample p is family phase_a's j = p + da, J + 1 family phase_b's p + db.
                const int phase_a = shift - kLines * floor_div(shift, kLines), phase_b = (phase_a + 1) % kLines;
                const int n = p1 - p0;
                const float* A = b.state[phase_a].data() + (p0 + floor_div(shift, kLines) - first[phase_a]);
                const float* B = b.state[phase_b].data() + (p0 + floor_div(shift + 1, kLines) - first[phase_b]);
                float* c = b.out.data() + i * width + (p0 - base); // c[m]: sample p0 + m
                if (f == 0.0f) {
                    for (int m = 0; m < n; ++m) c[m] = A[m]; // on sun line J
                } else {
                    for (int m = 0; m < n; ++m) c[m] = A[m] + f * (B[m] - A[m]);
                    if (p0 == 0) c[0] = B[0];                // sun line J is off the grid
                    if (p1 == g.length) c[n - 1] = A[n - 1]; // sun line J + 1 is beyond the grid
                }
            }
            for (int phase = 0; phase < kLines; ++phase) {
                // This family crosses this grid line at positions j + offset.
                const double offset = double(phase) / kLines + x;
                const int fl = int(std::floor(offset));
                const float fr = float(offset - fl);
                const int j_lo = std::max(ceil_div(J0 - phase, kLines), int(std::ceil(-offset)));
                const int j_hi = std::min(floor_div(J1 - phase, kLines), int(std::floor(double(last) - offset)));
                if (j_lo > j_hi) continue;
                float* S = b.state[phase].data() + (j_lo - first[phase]); // S[m]: sun line kLines (j_lo + m) + phase
                const int n = j_hi - j_lo + 1;
                const float rise = g.rise;
                // The sun lines on this grid line (0 <= j + offset <= length - 1)
                // meet the terrain here: their ceiling for the next grid line.
                const float* h = here + (j_lo + fl);
                for (int m = 0; m < n; ++m) {
                    const float ha = h[m], hb = h[m + 1];
                    S[m] = std::max(ha + fr * (hb - ha), S[m]) - rise;
                }
                // Between this grid line and the next a sun line may cross a
                // grid line of the other family, position m0, a fraction t of
                // the way: there too the height is exact, up-sun of the next crossing.
                if (!more || g.slope == 0.0) continue;
                const double next_offset = offset + g.slope;
                const double m0 = g.slope > 0 ? std::floor(next_offset) : std::ceil(next_offset);
                if (!(g.slope > 0 ? m0 > offset && m0 < next_offset : m0 < offset && m0 > next_offset)) continue;
                const float t_cross = float((m0 - offset) / g.slope);
                const float rest = (1.0f - t_cross) * rise;
                const int mo = int(m0);
                const int m_lo = std::max(j_lo, -mo) - j_lo, m_hi = std::min(j_hi, last - mo) - j_lo;
                const float* ha_at = here + (j_lo + mo);
                const float* hb_at = next + (j_lo + mo);
                for (int m = m_lo; m <= m_hi; ++m) {
                    const float ha = ha_at[m], hb = hb_at[m];
                    S[m] = std::max(S[m], ha + t_cross * (hb - ha) - rest);
                }
            }
        }

        // The block's ceilings back into the grid, as floats, as the mask or both.
        const float* O = b.out.data();
        if (mask) {
            // here[p] of line i is the sample's own height (Terrain::sample_height).
            if (g.stride_line == 1) {
                int lo = g.length, hi = 0;
                for (int i = 0; i < n_lines; ++i)
                    if (b.p0[i] < b.p1[i]) lo = std::min(lo, b.p0[i]), hi = std::max(hi, b.p1[i]);
                for (int p = lo; p < hi; ++p) {
                    std::uint8_t* dst = mask + std::size_t(p) * cols + std::size_t(line0);
                    for (int i = 0; i < n_lines; ++i)
                        if (p >= b.p0[i] && p < b.p1[i])
                            dst[i * g.step] = H[i * width + (p - base)] < O[i * width + (p - base)] ? 1 : 0;
                }
            } else {
                for (int i = 0; i < n_lines; ++i) {
                    const float* h = H + i * width - base;
                    const float* c = O + i * width - base;
                    std::uint8_t* dst = mask + std::size_t(line0 + g.step * i) * cols;
                    for (int p = b.p0[i]; p < b.p1[i]; ++p) dst[p] = h[p] < c[p] ? 1 : 0;
                }
            }
        }
        if (!ceiling) continue;
        if (g.stride_line == 1) {
            int lo = g.length, hi = 0;
            for (int i = 0; i < n_lines; ++i)
                if (b.p0[i] < b.p1[i]) lo = std::min(lo, b.p0[i]), hi = std::max(hi, b.p1[i]);
            for (int p = lo; p < hi; ++p) {
                float* dst = ceiling + std::size_t(p) * cols + std::size_t(line0);
                for (int i = 0; i < n_lines; ++i)
                    if (p >= b.p0[i] && p < b.p1[i]) dst[i * g.step] = O[i * width + (p - base)];
            }
        } else {
            for (int i = 0; i < n_lines; ++i)
                if (b.p0[i] < b.p1[i])
                    std::copy(O + i * width + (b.p0[i] - base), O + i * width + (b.p1[i] - base),
                              ceiling + std::size_t(line0 + g.step * i) * cols + std::size_t(b.p0[i]));
        }
    }
}

void sweep_band_portable(const Terrain& t, const SweepGrid& g, int J0, int J1, float* ceiling, std::uint8_t* mask,
                         BandScratch& b) {
    sweep_band_body(t, g, J0, J1, ceiling, mask, b);
}

#if defined(__x86_64__) && defined(__GNUC__)
#define OVERFLIGHT_SWEEP_AVX2 1
// The same compiled for AVX2 (8 lanes rather than SSE2's 4; no FMA, so the
// same bits), picked at run time.
__attribute__((target("avx2"))) void sweep_band_avx2(const Terrain& t, const SweepGrid& g, int J0, int J1,
                                                     float* ceiling, std::uint8_t* mask, BandScratch& b) {
    sweep_band_body(t, g, J0, J1, ceiling, mask, b);
}
// And for AVX-512 (16 lanes; still no FMA, so the same bits).
__attribute__((target("avx512f,avx512bw,avx512dq,avx512vl"))) void
sweep_band_avx512(const Terrain& t, const SweepGrid& g, int J0, int J1, float* ceiling, std::uint8_t* mask,
                  BandScratch& b) {
    sweep_band_body(t, g, J0, J1, ceiling, mask, b);
}
#endif

void sweep_band(const Terrain& t, const SweepGrid& g, int J0, int J1, float* ceiling, std::uint8_t* mask,
                BandScratch& b) {
#if OVERFLIGHT_SWEEP_AVX2
    static const bool avx512 = cpu_has_avx512();
    static const bool avx2 = __builtin_cpu_supports("avx2");
    if (avx512) {
        sweep_band_avx512(t, g, J0, J1, ceiling, mask, b);
        return;
    }
    if (avx2) {
        sweep_band_avx2(t, g, J0, J1, ceiling, mask, b);
        return;
    }
#endif
    sweep_band_portable(t, g, J0, J1, ceiling, mask, b);
}

glm::vec3 unit_sun(const glm::vec3& sun_dir) {
    return glm::length(sun_dir) > 0 ? glm::normalize(sun_dir) : glm::vec3(0, 1, 0);
}

// Sun lines are independent: narrow bands of them (BandScratch) in
// parallel, each band sweeping the first line of the next one as well
// (the samples between the two need both). The sun is above the horizon
// and off the zenith.
void sweep_bands(const Terrain& t, const glm::vec3& sun, float* ceiling, std::uint8_t* mask) {
    const SweepGrid g = sweep_grid(t, sun);
    const int bands = (g.J_max - g.J_min + kBand) / kBand;
    parallel::for_each_index(0, bands, [&](int b) {
        const int J0 = g.J_min + b * kBand, J1 = std::min(g.J_max + 1, J0 + kBand);
        if (J0 >= J1) return;
        thread_local BandScratch scratch;
        sweep_band(t, g, J0, J1, ceiling, mask, scratch);
    });
}

bool below_horizon(const glm::vec3& sun) { return !(sun.y > 0); }
bool in_zenith(const glm::vec3& sun) { return std::hypot(sun.x, sun.z) <= 1e-6f * sun.y; }

// Sizes the outputs that are not null and sweeps into them; a sun at or below
// the horizon shadows everything, a sun in the zenith nothing.
void sweep(const Terrain& t, const glm::vec3& sun_dir, ShadowCeiling* ceiling, std::vector<std::uint8_t>* mask) {
    const glm::vec3 sun = unit_sun(sun_dir);
    const std::size_t n = std::size_t(t.rows()) * std::size_t(t.cols());
    if (ceiling) {
        ceiling->rows = t.rows();
        ceiling->cols = t.cols();
        ceiling->sun_dir = sun;
        ceiling->ceiling.resize(n);
    }
    if (mask) mask->resize(n);
    if (below_horizon(sun) || in_zenith(sun)) {
        const bool all = below_horizon(sun);
        if (ceiling)
            std::fill(ceiling->ceiling.begin(), ceiling->ceiling.end(),
                      all ? std::numeric_limits<float>::infinity() : ShadowCeiling::kOpen);
        if (mask) std::fill(mask->begin(), mask->end(), all ? 1 : 0);
        return;
    }
    sweep_bands(t, sun, ceiling ? ceiling->ceiling.data() : nullptr, mask ? mask->data() : nullptr);
}

} // namespace

void sweep_shadow_ceiling(const Terrain& t, const glm::vec3& sun_dir, ShadowCeiling& out) {
    sweep(t, sun_dir, &out, nullptr);
}

void sweep_shadow_mask(const Terrain& t, const glm::vec3& sun_dir, std::vector<std::uint8_t>& mask) {
    sweep(t, sun_dir, nullptr, &mask);
}

void sweep_shadow(const Terrain& t, const glm::vec3& sun_dir, ShadowCeiling& ceiling, std::vector<std::uint8_t>& mask) {
    sweep(t, sun_dir, &ceiling, &mask);
}

std::vector<std::uint8_t> shadow_mask(const Terrain& t, const ShadowCeiling& c) {
    std::vector<std::uint8_t> mask(std::size_t(t.rows()) * std::size_t(t.cols()));
    parallel::for_each_index(0, t.rows(), [&](int row) {
        for (int col = 0; col < t.cols(); ++col)
            mask[t.index(row, col)] = c.shadowed(row, col, t.sample_height(row, col)) ? 1 : 0;
    });
    return mask;
}

} // namespace overflight
