#pragma once
// What a mesh-producing algorithm (full-resolution grid, ROAM, Röttger's
// quadtree) hands to a renderer: plain arrays that the GL layer only uploads
// (the CDLOD way). Positions are world coordinates (DESIGN sec. 1).
#include "core/Image.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace overflight {

struct MeshArrays {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;  // unit, one per position
    std::vector<Rgb8> colors;        // one per position
    std::vector<std::uint32_t> indices; // triangle list, counter-clockwise seen from above
    // Optional, empty or one per position: the tile a vertex belongs to, as
    // (row << 16) | column (lod/TileSet.h with imagery tiles), so that each
    // triangle samples one tile's imagery.
    std::vector<std::uint32_t> tiles;
    std::size_t triangle_count() const { return indices.size() / 3; }
    void clear() { positions.clear(); normals.clear(); colors.clear(); indices.clear(); tiles.clear(); }
};

} // namespace overflight
