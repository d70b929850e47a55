#pragma once
// The variance tree of split-only ROAM: for every triangle of the binary
// triangle tree over a (2^N+1)^2 height field, the largest world-space error
// of linear interpolation at the hypotenuse midpoints of the triangle and of
// all its descendants. It is computed once per terrain; the per-frame
// tessellation (RoamMesh) divides it by distance to get a screen-space error.
//
// Based on: CMSC 23700 project 2a sec. 5 and 5.1 ("compute a
// variance tree that contains the world-space variance information"), after
// Duchaineau et al., "ROAMing terrain", IEEE Visualization 1997, sec. 6
// (nested world-space bounds, here the scalar hypotenuse-midpoint form).
//
// Bintree layout (shared with RoamMesh). A triangle is (apex, v0, v1) with its
// hypotenuse v0-v1, listed counter-clockwise seen from above. With n = 2^N:
//   root 0 = (NE, NW, SE) and root 1 = (SW, SE, NW): the first split is the
//   NW-SE diagonal, so cell (0, 0) is cut from (0, 0) to (1, 1) and diagonals
//   alternate in a checkerboard at full resolution (DESIGN sec. 3).
//   Splitting at the hypotenuse midpoint m gives child 0 = (m, apex, v0) and
//   child 1 = (m, v1, apex); both keep the winding.
// Levels: roots are level 0; level 2N triangles are half grid cells and cannot
// be split, so the tree holds levels 0 .. 2N-1 ("splittable" levels).
// Implicit heap index: root 0 is node 2, root 1 is node 3, the children of
// node k are 2k and 2k+1; a triangle of level L has an index in [2^(L+1), 2^(L+2)).
#include "core/Terrain.h"

#include <cstdint>
#include <vector>

namespace overflight {

class RoamVarianceTree {
public:
    // Default: nodes down to level 20, i.e. 2^22 uint16 = 8 MiB whatever the
    // terrain size; a 4097^2 field (24 levels) then shares the bound of its
    // level-20 ancestor among the last three levels.
    static constexpr int kDefaultMaxDepth = 20;

    RoamVarianceTree() = default;
    // Builds the tree of a square (2^N+1)^2 height field, storing levels
    // 0 .. min(max_depth, 2N-1). Throws Error("roam", ...) when the terrain is
    // not (2^N+1)^2 or max_depth is outside 0..28. Parallel over subtrees (oneTBB).
    RoamVarianceTree(const Terrain& terrain, int max_depth = kDefaultMaxDepth);

    // N of the (2^N+1)^2 grid.
    int grid_log2() const { return grid_log2_; }
    // Deepest level with a stored node.
    int stored_depth() const { return stored_depth_; }
    // Level of the half-cell triangles (2N): nothing below can be split.
    int finest_level() const { return 2 * grid_log2_; }

    // Node index of a triangle of level `level` whose index would be `node` if
    // every level were stored: the node itself, or its ancestor at stored_depth().
    std::uint32_t stored_node(std::uint32_t node, int level) const {
        return level <= stored_depth_ ? node : node >> (level - stored_depth_);
    }
    // Bound in raw height units (ceil of the exact half-unit value, so it never
    // underestimates), of a stored node index (2 .. 2^(stored_depth+2)-1).
    std::uint16_t raw(std::uint32_t node) const { return nodes_[node]; }
    // The same bound in world units (raw * v_scale).
    float world(std::uint32_t node) const { return float(nodes_[node]) * v_scale_; }
    // The stored bounds, indexed like raw() (for prefetching).
    const std::uint16_t* data() const { return nodes_.data(); }
    // Bytes held by the tree.
    std::size_t memory_bytes() const { return nodes_.size() * sizeof(std::uint16_t); }

private:
    int grid_log2_ = 0;
    int stored_depth_ = 0;
    float v_scale_ = 1.0f;
    std::vector<std::uint16_t> nodes_;
};

} // namespace overflight
