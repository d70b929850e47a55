#pragma once
// The cells of a height field a segment crosses, in order: the traversal of
// Amanatides and Woo, "A Fast Voxel Traversal Algorithm for Ray Tracing"
// (Eurographics 1987), in the cell space of RayMarcher (cell (ix, iz) is
// [ix, ix+1) x [iz, iz+1) around sample (row iz, col ix)), plus an exact jump
// over a block of cells for max-mipmap skipping.
//
// The traversal keeps the segment parameters of the next x and z boundaries
// and adds a fixed step to one of them per cell, each sum rounded. Those
// rounded sums, not the exact boundary parameters, decide which cell comes
// next and where a hit lies, so a jump over k cells must reproduce the k
// roundings: accumulate() and count_below() do, in a few operations per
// binade of the parameters (within one binade every rounded sum adds the
// same multiple of the binade's unit in the last place).
#include <glm/vec3.hpp>

namespace overflight {

// x after `k` (>= 0) times `x = x + step` (step > 0), as the loop rounds it.
double accumulate(double x, double step, long long k);

// How many of the loop's values x, x + step, (x + step) + step, ... (step > 0)
// among the first `limit` are below v (< v, or <= v when `inclusive`), and
// the loop's value after as many steps (accumulate(x, step, count)).
struct Passed {
    long long count = 0;
    double next = 0.0;
};
Passed count_below(double x, double step, double v, bool inclusive, long long limit);

struct CellTraversal {
    int ix = 0, iz = 0;               // the current cell
    int sx = 1, sz = 1;               // the direction of travel on each axis
    double next_x = 0.0, next_z = 0.0; // parameters of the next x and z boundary
    double step_x = 0.0, step_z = 0.0; // parameter per cell on each axis (infinite: never)

    // The cell of a + t0 d (clamped to the cols x rows grid; h_scale world
    // units per cell) and its first boundaries after t0.
    CellTraversal(const glm::dvec3& a, const glm::dvec3& d, double h_scale, int cols, int rows, double t0);

    // Moves to the next cell: across the nearer boundary, x on a tie.
    void advance() {
        if (next_x <= next_z) {
            ix += sx;
            next_x += step_x;
        } else {
            iz += sz;
            next_z += step_z;
        }
    }

    // Moves to the first cell outside the block [x0, x1) x [z0, z1) (which
    // holds the current cell) exactly as repeated advance() would; returns
    // the parameter where the segment leaves the block.
    double leave_block(int x0, int x1, int z0, int z1);
};

} // namespace overflight
