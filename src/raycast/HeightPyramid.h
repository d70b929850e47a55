#pragma once
// Mip pyramids of a height field for the Floating Horizon's distance LOD:
// heights by maximum (a coarse voxel is never lower than any sample it covers,
// so distant silhouettes are never lost, only widened) and colors by mean.
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
        std::vector<std::uint32_t> colors;  // mean color, packed 0x00BBGGRR
    };

    HeightPyramid() = default;
    // Builds levels 1..max_level (level 0 is the terrain itself), stopping at 1x1.
    HeightPyramid(const Terrain& terrain, int max_level);

    int levels() const { return int(levels_.size()); } // coarse levels held (level L is levels_[L-1])
    const Level& level(int L) const { return levels_[std::size_t(L - 1)]; }

private:
    std::vector<Level> levels_;
};

} // namespace overflight
