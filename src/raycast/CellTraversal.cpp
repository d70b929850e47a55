// Based on: Amanatides and Woo (1987); IEEE 754 round-to-nearest addition.
// See CellTraversal.h.
#include "raycast/CellTraversal.h"

#include <algorithm>
#include <bit>
#include <cfloat>
#include <climits>
#include <cmath>
#include <cstdint>
#include <limits>

namespace overflight {

namespace {

// Where the loop x, x + step, ... is linear: its values are exactly x + i c
// for i = 0..n. With u the unit in the last place of x's binade [2^e, 2^(e+1))
// and step < x, every x' = x + i c (a multiple of u) rounds x' + step to
// x' + c, c = step rounded to a multiple of u, while x' + c stays in the
// binade; except when step lies half-way between two multiples of u, where
// the rounding to even depends on x' (n = 0 then: the caller steps singly).
struct LinearRun {
    double c = 0.0;
    long long n = 0;
};

LinearRun linear_run(double x, double step) {
    if (!(x >= DBL_MIN && x < DBL_MAX && step > 0.0 && step < x)) return {};
    const double binade = std::bit_cast<double>(std::bit_cast<std::uint64_t>(x) & 0x7FF0000000000000ull); // 2^e
    const double u = binade * 0x1p-52, top = binade * 2.0;
    // The first rounded sum less x is c (exact: x <= x + step < 2 x), unless it left the binade.
    const double c = (x + step) - x;
    if (!(x + c < top) || std::abs(step - c) * 2.0 == u) return {};
    if (c == 0.0) return {0.0, LLONG_MAX}; // x + step rounds back to x, for ever
    const double room = (top - x) / c;
    long long n = room >= 9e15 ? (long long)9e15 : (long long)room;
    while (n > 0 && !(x + double(n) * c < top)) --n;
    while (x + double(n + 1) * c < top) ++n;
    return {c, n};
}

// Below this many steps the loop itself is cheaper than a linear run.
constexpr long long kShortLoop = 8;

} // namespace

double accumulate(double x, double step, long long k) {
    if (!std::isfinite(x)) return x; // an axis the segment never crosses
    for (; k > 0 && k <= kShortLoop; --k) x += step;
    while (k > 0) {
        const LinearRun run = linear_run(x, step);
        if (run.n > 0) {
            const long long m = std::min(run.n, k);
            x += double(m) * run.c;
            k -= m;
        } else {
            x += step;
            --k;
        }
    }
    return x;
}

long long count_below(double x, double step, double v, bool inclusive, long long limit) {
    auto below = [&](double y) { return inclusive ? y <= v : y < v; };
    long long i = 0; // x is the loop's value i; values 0..i-1 are below
    if (limit <= kShortLoop) {
        for (; i < limit && below(x); ++i) x += step;
        return i;
    }
    while (i < limit) {
        if (!below(x)) return i;
        const LinearRun run = linear_run(x, step);
        const long long m = std::min(run.n, limit - 1 - i);
        if (m <= 0) {
            x += step;
            ++i;
            continue;
        }
        if (run.c == 0.0) return limit;
        // The first j in 1..m with x + j c not below, from the estimate (v - x) / c.
        const double guess = (v - x) / run.c;
        long long j = guess >= double(m) ? m : std::max(1LL, (long long)guess);
        while (j > 1 && !below(x + double(j - 1) * run.c)) --j;
        while (j <= m && below(x + double(j) * run.c)) ++j;
        if (j <= m) return i + j;
        x += double(m) * run.c;
        i += m;
    }
    return limit;
}

CellTraversal::CellTraversal(const glm::dvec3& a, const glm::dvec3& d, double hs, int cols, int rows, double t0) {
    auto qx = [&](double s) { return (a.x + s * d.x) / hs + 0.5; };
    auto qz = [&](double s) { return (a.z + s * d.z) / hs + 0.5; };
    ix = std::clamp(int(std::floor(qx(t0))), 0, cols - 1);
    iz = std::clamp(int(std::floor(qz(t0))), 0, rows - 1);
    const double inf = std::numeric_limits<double>::infinity();
    const double dqx = d.x / hs, dqz = d.z / hs;
    sx = dqx > 0 ? 1 : -1;
    sz = dqz > 0 ? 1 : -1;
    next_x = dqx == 0 ? inf : ((dqx > 0 ? ix + 1 : ix) - (a.x / hs + 0.5)) / dqx;
    next_z = dqz == 0 ? inf : ((dqz > 0 ? iz + 1 : iz) - (a.z / hs + 0.5)) / dqz;
    step_x = dqx == 0 ? inf : std::abs(1.0 / dqx);
    step_z = dqz == 0 ? inf : std::abs(1.0 / dqz);
    // Boundaries crossed before t0 (the clip started inside a cell) are skipped.
    while (next_x <= t0) next_x += step_x;
    while (next_z <= t0) next_z += step_z;
}

double CellTraversal::leave_block(int x0, int x1, int z0, int z1) {
    // advance() merges the two boundary sequences, x first on ties: the
    // segment leaves through x at the mx-th x boundary unless the mz-th z
    // boundary comes strictly earlier.
    const long long mx = sx > 0 ? x1 - ix : ix - x0 + 1, mz = sz > 0 ? z1 - iz : iz - z0 + 1;
    const double exit_x = accumulate(next_x, step_x, mx - 1), exit_z = accumulate(next_z, step_z, mz - 1);
    if (exit_x <= exit_z) {
        const long long n = count_below(next_z, step_z, exit_x, false, mz - 1); // z boundaries before
        iz += sz * int(n);
        next_z = accumulate(next_z, step_z, n);
        ix += sx * int(mx);
        next_x = exit_x + step_x;
        return exit_x;
    }
    const long long n = count_below(next_x, step_x, exit_z, true, mx - 1); // x boundaries before (ties: x first)
    ix += sx * int(n);
    next_x = accumulate(next_x, step_x, n);
    iz += sz * int(mz);
    next_z = exit_z + step_z;
    return exit_z;
}

} // namespace overflight
