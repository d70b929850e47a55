// Based on: Amanatides and Woo (1987); IEEE 754 round-to-nearest addition.
// See CellTraversal.h.
#include "raycast/CellTraversal.h"

#include "core/BitCast.h"

#include <algorithm>
#include <cfloat>
#include <climits>
#include <cmath>
#include <cstdint>
#include <limits>

namespace overflight {

namespace {

// Where the loop x, x + step, ... is linear: from a value x in the binade
// [2^e, top = 2^(e+1)), with u its unit in the last place and step < x,
// every x' = x + i c (a multiple of u) rounds x' + step to x' + c, c = step
// rounded to a multiple of u, as long as x' + c < top; except when step lies
// half-way between two multiples of u, where the rounding to even depends on
// x' (no run then: the caller steps singly).
struct LinearRun {
    bool ok = false;
    double c = 0.0, top = 0.0;
    // The largest n with x + n c < top (c > 0): the run's last value.
    long long length(double x) const {
        const double room = (top - x) / c;
        long long n = room >= 9e15 ? (long long)9e15 : (long long)room;
        while (n > 0 && !(x + double(n) * c < top)) --n;
        while (x + double(n + 1) * c < top) ++n;
        return n;
    }
};

LinearRun linear_run(double x, double step) {
    if (!(x >= DBL_MIN && x < DBL_MAX && step > 0.0 && step < x)) return {};
    const double binade = bit_cast<double>(bit_cast<std::uint64_t>(x) & 0x7FF0000000000000ull); // 2^e
    const double u = binade * 0x1p-52, top = binade * 2.0;
    // The first rounded sum less x is c (exact: x <= x + step < 2 x), unless it left the binade.
    const double c = (x + step) - x;
    if (!(x + c < top) || std::abs(step - c) * 2.0 == u) return {};
    return {true, c, top};
}

// Below this many steps the loop itself is cheaper than a linear run.
constexpr long long kShortLoop = 8;

} // namespace

double accumulate(double x, double step, long long k) {
    if (!std::isfinite(x)) return x; // an axis the segment never crosses
    while (k > kShortLoop) {
        const LinearRun run = linear_run(x, step);
        if (!run.ok) {
            x += step;
            --k;
            continue;
        }
        if (run.c == 0.0) return x; // x + step rounds back to x, for ever
        // k c is exact when x + k c < top (a multiple of u below 2^(e+1)).
        if (x + double(k) * run.c < run.top) return x + double(k) * run.c;
        const long long n = run.length(x);
        x += double(n) * run.c;
        k -= n;
        if (n == 0) {
            x += step;
            --k;
        }
    }
    for (; k > 0; --k) x += step;
    return x;
}

Passed count_below(double x, double step, double v, bool inclusive, long long limit) {
    auto below = [&](double y) { return inclusive ? y <= v : y < v; };
    long long i = 0; // x is the loop's value i; values 0..i-1 are below
    while (limit - i > kShortLoop) {
        if (!below(x)) return {i, x};
        const LinearRun run = linear_run(x, step);
        if (!run.ok) {
            x += step;
            ++i;
            continue;
        }
        if (run.c == 0.0) return {limit, x};
        long long m = limit - 1 - i; // values x + j c, j = 1..m, are the loop's
        if (!(x + double(m) * run.c < run.top)) m = run.length(x);
        if (m == 0) {
            x += step;
            ++i;
            continue;
        }
        // The first j in 1..m with x + j c not below, from the estimate (v - x) / c.
        const double guess = (v - x) / run.c;
        long long j = guess >= double(m) ? m : std::max(1LL, (long long)guess);
        while (j > 1 && !below(x + double(j - 1) * run.c)) --j;
        while (j <= m && below(x + double(j) * run.c)) ++j;
        if (j <= m) return {i + j, x + double(j) * run.c};
        x += double(m) * run.c;
        i += m;
    }
    for (; i < limit && below(x); ++i) x += step;
    return {i, x};
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
    auto through_x = [&](double exit_x, const Passed& z) {
        iz += sz * int(z.count);
        next_z = z.next;
        ix += sx * int(mx);
        next_x = exit_x + step_x;
        return exit_x;
    };
    auto through_z = [&](double exit_z, const Passed& x) {
        ix += sx * int(x.count);
        next_x = x.next;
        iz += sz * int(mz);
        next_z = exit_z + step_z;
        return exit_z;
    };
    // The side the unrounded sums reach first, checked by counting the other
    // axis's boundaries before its exit (fewer than all: that side it is).
    if (next_x + double(mx - 1) * step_x <= next_z + double(mz - 1) * step_z) {
        const double exit_x = accumulate(next_x, step_x, mx - 1);
        const Passed z = count_below(next_z, step_z, exit_x, false, mz);
        if (z.count < mz) return through_x(exit_x, z);
        const double exit_z = accumulate(next_z, step_z, mz - 1);
        return through_z(exit_z, count_below(next_x, step_x, exit_z, true, mx - 1));
    }
    const double exit_z = accumulate(next_z, step_z, mz - 1);
    const Passed x = count_below(next_x, step_x, exit_z, true, mx);
    if (x.count < mx) return through_z(exit_z, x);
    const double exit_x = accumulate(next_x, step_x, mx - 1);
    return through_x(exit_x, count_below(next_z, step_z, exit_x, false, mz - 1));
}

} // namespace overflight
