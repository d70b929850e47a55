#pragma once
// How far up a sample paints its column in the Floating Horizon: the first
// row whose ray is not below the sample.
//
// Based on: Szenberg 1997, Algorithm 1, lines 9-15: a sample of slope sigma
// (its height over the eye per unit of view depth) paints rows from the
// current horizon j up while sigma > m_j. The row slopes m_j never decrease,
// so the horizon ends at max(j, first row with m_j >= sigma): a search in the
// row table rather than a loop that compares row by row.
//
// The shear camera's rows are evenly spaced in slope (m_j = (v_j + shift) /
// fp), so a linear guess from the table's ends is within a row of the answer;
// the guess is then corrected against the table itself, so the result is
// exact for any non-decreasing table (the tilt camera's rows are not evenly
// spaced: the correction then takes more steps, never a different answer).
// A caller that can guess sooner (from what sigma is computed from) passes its
// own guess; the correction is the same.
#include <algorithm>

namespace overflight {

class RowSearch {
public:
    // rows[0..n]: non-decreasing, rows[n] = +inf (the sentinel above the top row).
    RowSearch(const float* rows, int n) : rows_(rows), n_(n), m0_(rows[0]) {
        const double span = n > 1 ? double(rows[n - 1]) - double(rows[0]) : 0.0;
        inv_step_ = span > 0.0 ? float(double(n - 1) / span) : 0.0f;
    }

    // The first j in [0, n] with rows[j] >= sigma (n: above the top row).
    // sigma must be finite.
    int first_not_below(float sigma) const {
        // The guess ceil((sigma - m_0) / step), clamped to [0, n] (t >= -1, so
        // the truncation is a floor).
        const float t = std::min(std::max((sigma - m0_) * inv_step_, -1.0f), float(n_));
        return first_not_below(sigma, std::min(int(t + 1.0f), n_));
    }
    // The same from any guess in [0, n]; the closer, the fewer steps.
    int first_not_below(float sigma, int guess) const {
        int e = guess;
        while (e > 0 && rows_[e - 1] >= sigma) --e;
        while (rows_[e] < sigma) ++e; // stops at the sentinel
        return e;
    }

    // The guess above is 1 + (sigma - m0()) * inv_step(), rounded down.
    float m0() const { return m0_; }
    float inv_step() const { return inv_step_; }

private:
    const float* rows_;
    int n_;
    float m0_;
    float inv_step_ = 0.0f;
};

} // namespace overflight
