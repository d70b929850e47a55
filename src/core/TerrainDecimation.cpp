// Point-sampled heights, box-filtered colors (see the header).
#include "core/TerrainDecimation.h"

#include "core/Error.h"

#include <algorithm>

namespace overflight {

int decimation_factor(int rows, int cols, int max_size) {
    const int side = std::max(rows, cols);
    if (side <= max_size) return 1;
    // (side - 1) / f + 1 <= max_size  <=>  f >= (side - 1) / (max_size - 1).
    return (side - 1 + max_size - 2) / (max_size - 1);
}

std::string decimation_problem(int rows, int cols, int factor) {
    const int shorter = std::min(rows, cols);
    if ((shorter - 1) / factor + 1 >= 2) return {};
    return std::to_string(cols) + "x" + std::to_string(rows) + " samples cannot be decimated by " +
           std::to_string(factor) + ": the shorter side would keep a single sample";
}

Terrain decimate_terrain(const Terrain& t, int f) {
    if (f <= 1) return t;
    if (const std::string problem = decimation_problem(t.rows(), t.cols(), f); !problem.empty())
        throw Error("terrain", problem);
    const int rows = (t.rows() - 1) / f + 1, cols = (t.cols() - 1) / f + 1;
    Terrain o(rows, cols, t.h_scale() * float(f), t.v_scale(), t.y_offset());
    // The block around kept sample k: source samples k f - f/2 .. k f + (f-1)/2, clamped.
    const int before = f / 2, after = (f - 1) / 2;
    for (int i = 0; i < rows; ++i) {
        const int r0 = std::max(0, i * f - before), r1 = std::min(t.rows() - 1, i * f + after);
        for (int j = 0; j < cols; ++j) {
            o.raw(i, j) = t.raw(i * f, j * f);
            const int c0 = std::max(0, j * f - before), c1 = std::min(t.cols() - 1, j * f + after);
            unsigned r = 0, g = 0, b = 0, n = 0;
            for (int si = r0; si <= r1; ++si)
                for (int sj = c0; sj <= c1; ++sj) {
                    const Rgb8 c = t.color(si, sj);
                    r += c.r;
                    g += c.g;
                    b += c.b;
                    ++n;
                }
            o.color(i, j) = Rgb8{std::uint8_t((r + n / 2) / n), std::uint8_t((g + n / 2) / n), std::uint8_t((b + n / 2) / n)};
        }
    }
    return o;
}

} // namespace overflight
