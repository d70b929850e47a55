#pragma once
// The lowest and highest sample of a terrain's grid (every `stride`-th
// sample) over any rectangle of it: a rectangle of at most 64 samples from
// the samples themselves (exact), a larger one from min/max blocks of 8, 16,
// 32 ... samples per side, the at most 2 x 2 blocks of the finest size that
// holds it within two blocks per side, so a query costs at most 64 reads
// whatever its size. The blocks' bounds are conservative (they hold more
// samples than the rectangle), never narrower than its samples.
//
// Based on: the min-max mipmaps of height-field ray casting (a coarse cell
// bounds every sample under it), as in Tevs, Ihrke, Seidel, "Maximum Mipmaps
// for Fast, Accurate, and Scalable Dynamic Height Field Rendering" (I3D 2008),
// with the minimum kept beside the maximum.
#include "core/Terrain.h"

#include <utility>
#include <vector>

namespace overflight {

class HeightBounds {
public:
    HeightBounds() = default;
    // Of the samples (z * stride, x * stride) of `terrain`, x in
    // [0, (cols - 1) / stride], z in [0, (rows - 1) / stride]. Reads every
    // such sample once (in parallel); keeps a reference to `terrain`, whose
    // heights must not change while this object is used.
    HeightBounds(const Terrain& terrain, int stride);

    // [lowest, highest] of the grid's samples with x0 <= x <= x1 and
    // z0 <= z <= z1 (grid indices within the grid, x0 <= x1, z0 <= z1).
    std::pair<float, float> range(int x0, int z0, int x1, int z1) const;

private:
    static constexpr int kFirstLevel = 3; // blocks of 8 samples
    static constexpr int kExact = 64;     // samples of a rectangle read one by one
    const Terrain* terrain_ = nullptr;
    int stride_ = 1;
    struct Level {
        int cols = 0, rows = 0;
        std::vector<std::pair<float, float>> range; // per block, row-major
    };
    std::vector<Level> levels_; // blocks of 2^(kFirstLevel + i) samples, down to one block
};

} // namespace overflight
