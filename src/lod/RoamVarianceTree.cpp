// Based on: CMSC 23700 project 2a sec. 5 (variance tree), Duchaineau et al. 1997 sec. 6.
#include "lod/RoamVarianceTree.h"

#include "core/Error.h"
#include "core/Parallel.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

namespace overflight {

namespace {

struct Builder {
    const std::uint16_t* h;
    int finest;          // 2N
    int stored;          // deepest stored level
    std::uint16_t* out;  // heap-indexed nodes

    // Returns the bound of triangle (apex ga, hypotenuse g0-g1) at `level`.
    // Vertices are grid indices row * size + col: the hypotenuse midpoint of a
    // splittable triangle is then (g0 + g1) / 2 exactly, because both its row
    // and column sums are even.
    std::uint16_t build(std::uint32_t ga, std::uint32_t g0, std::uint32_t g1, int level, std::uint32_t node) const {
        const std::uint32_t m = (g0 + g1) / 2;
        // Error of the linear interpolation at m in half raw units, rounded up
        // to whole units so the stored bound never underestimates.
        const int twice = std::abs(2 * int(h[m]) - int(h[g0]) - int(h[g1]));
        std::uint16_t v = std::uint16_t((twice + 1) / 2);
        if (level + 1 < finest) {
            const bool store_children = level + 1 <= stored;
            const std::uint32_t n0 = store_children ? 2 * node : 0, n1 = store_children ? 2 * node + 1 : 0;
            std::uint16_t c0 = 0, c1 = 0;
            if (level < 8) {
                parallel::invoke([&] { c0 = build(m, ga, g0, level + 1, n0); },
                                 [&] { c1 = build(m, g1, ga, level + 1, n1); });
            } else {
                c0 = build(m, ga, g0, level + 1, n0);
                c1 = build(m, g1, ga, level + 1, n1);
            }
            v = std::max({v, c0, c1});
        }
        if (level <= stored) out[node] = v;
        return v;
    }
};

} // namespace

RoamVarianceTree::RoamVarianceTree(const Terrain& terrain, int max_depth) {
    if (terrain.rows() != terrain.cols() || !is_pow2_plus1(terrain.rows()) || terrain.rows() < 3)
        throw Error("roam", "variance tree needs a (2^N+1)^2 height field, got " + std::to_string(terrain.rows()) +
                                "x" + std::to_string(terrain.cols()));
    if (max_depth < 0 || max_depth > 28)
        throw Error("roam", "variance depth " + std::to_string(max_depth) + " is outside 0..28");
    const int size = terrain.rows();
    while ((1 << grid_log2_) + 1 < size) ++grid_log2_;
    stored_depth_ = std::min(max_depth, finest_level() - 1);
    v_scale_ = std::abs(terrain.v_scale());
    nodes_.assign(std::size_t(1) << (stored_depth_ + 2), 0);

    const std::uint32_t n = std::uint32_t(size - 1);
    const std::uint32_t s = std::uint32_t(size);
    const std::uint32_t nw = 0, ne = n, sw = n * s, se = n * s + n;
    const Builder b{terrain.heights().data(), finest_level(), stored_depth_, nodes_.data()};
    parallel::invoke([&] { b.build(ne, nw, se, 0, 2); }, [&] { b.build(sw, se, nw, 0, 3); });
}

} // namespace overflight
