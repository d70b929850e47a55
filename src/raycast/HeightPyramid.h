#pragma once
// Mip pyramids of a height field: heights by maximum (a coarse voxel is never
// lower than any sample it covers) and, optionally, colors by mean. The
// Floating Horizon uses the heights to skip runs of slices that cannot rise
// above the horizon (exact: a bound, never a sample) and both for its distance
// LOD (distant silhouettes are never lost, only widened).
//
// Based on: Szenberg 1997 sec. 8 (aliasing of distant samples) and the usual
// max-mipmap of height-field ray casting; level L cell (I, J) covers samples
// rows [I 2^L, (I+1) 2^L) x cols [J 2^L, (J+1) 2^L), clipped to the grid.
#include "core/Terrain.h"

#include <cstdint>
#include <vector>

namespace overflight {

class HeightPyramid {
public:
    struct Level {
        int rows = 0, cols = 0;
        std::vector<std::uint16_t> heights; // max of the covered samples
        std::vector<std::uint32_t> colors;  // mean color, packed 0x00BBGGRR (empty without with_colors)
    };

    HeightPyramid() = default;
    // Builds levels 1..max_level (level 0 is the terrain itself), stopping at 1x1.
    // `colors`: level 0's colors, packed, one per sample (the terrain's, or
    // the sun-lit ones the ray casters paint); null: the levels' colors stay empty.
    HeightPyramid(const Terrain& terrain, int max_level, const std::uint32_t* colors = nullptr);

    int levels() const { return int(levels_.size()); } // coarse levels held (level L is levels_[L-1])
    int rows() const { return rows_; }                 // level 0 (the terrain)
    int cols() const { return cols_; }
    const Level& level(int L) const { return levels_[std::size_t(L - 1)]; }

private:
    int rows_ = 0, cols_ = 0;
    std::vector<Level> levels_;
};

} // namespace overflight
