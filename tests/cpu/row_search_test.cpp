// RowSearch: the row a Floating Horizon sample paints up to (Szenberg 1997,
// Algorithm 1, lines 9-15) is the first row whose slope is not below the
// sample's, the same index as std::lower_bound on the row table, whether the
// rows are evenly spaced in slope (shear) or not (tilt), for samples below,
// inside and above the image.
#include "raycast/RowSearch.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace overflight;

namespace {

// The rows' slopes (n of them) and the +inf sentinel.
std::vector<float> with_sentinel(std::vector<float> rows) {
    rows.push_back(std::numeric_limits<float>::infinity());
    return rows;
}

void expect_lower_bound(const std::vector<float>& rows, float sigma) {
    const int n = int(rows.size()) - 1;
    const RowSearch search(rows.data(), n);
    const int want = int(std::lower_bound(rows.begin(), rows.begin() + n, sigma) - rows.begin());
    ASSERT_EQ(search.first_not_below(sigma), want) << "sigma " << sigma << " n " << n;
    // From the caller's own guess, whatever it is.
    for (int guess : {0, n / 3, n, std::clamp(want - 1, 0, n), std::clamp(want + 1, 0, n)})
        ASSERT_EQ(search.first_not_below(sigma, guess), want) << "sigma " << sigma << " n " << n << " guess " << guess;
}

// Slopes of a shear camera's rows, bottom-up, as the Floating Horizon makes them
// (shear_rows in raycast/FloatingHorizonTables.h).
std::vector<float> shear_rows(int H, double fp, double shift) {
    std::vector<float> m(static_cast<std::size_t>(H));
    for (int j = 0; j < H; ++j) m[std::size_t(j)] = float((H * 0.5 - ((H - 1 - j) + 0.5) + shift) / fp);
    return with_sentinel(m);
}

void expect_random_samples(const std::vector<float>& rows, std::mt19937& rng) {
    const int n = int(rows.size()) - 1;
    const float lo = rows[0], hi = rows[std::size_t(n) - 1];
    const float span = std::max(hi - lo, 1e-3f);
    std::uniform_real_distribution<float> around(lo - span, hi + span);
    std::uniform_int_distribution<int> pick(0, n - 1);
    for (int i = 0; i < 2000; ++i) {
        expect_lower_bound(rows, around(rng));
        // On a row's slope and one float step either side of it.
        const float m = rows[std::size_t(pick(rng))];
        expect_lower_bound(rows, m);
        expect_lower_bound(rows, std::nextafter(m, -1e30f));
        expect_lower_bound(rows, std::nextafter(m, 1e30f));
    }
    for (float far : {-1e30f, -1e6f, 1e6f, 1e30f, std::numeric_limits<float>::max()}) expect_lower_bound(rows, far);
}

} // namespace

TEST(RowSearch, ShearRowsMatchLowerBound) {
    std::mt19937 rng(7);
    for (int H : {1, 2, 3, 24, 1080}) {
        for (double shift : {0.0, -400.0, 900.0}) expect_random_samples(shear_rows(H, 1662.8, shift), rng);
    }
}

TEST(RowSearch, UnevenAndRepeatedRowsMatchLowerBound) {
    std::mt19937 rng(11);
    // Tilt-like rows: tan of evenly spaced angles.
    std::vector<float> tilt(700);
    for (std::size_t j = 0; j < tilt.size(); ++j) tilt[j] = float(std::tan(-1.2 + 2.3 * double(j) / double(tilt.size())));
    expect_random_samples(with_sentinel(tilt), rng);
    // Random non-decreasing rows with repeats.
    std::uniform_int_distribution<int> step(0, 3);
    std::vector<float> steps(300);
    float m = -2.0f;
    for (float& v : steps) {
        m += 0.01f * float(step(rng));
        v = m;
    }
    expect_random_samples(with_sentinel(steps), rng);
    // All rows equal.
    expect_random_samples(with_sentinel(std::vector<float>(50, 0.25f)), rng);
}
