#pragma once
// The terrain as a set of blocks (the papers' voxels, DESIGN sec. 3 `blocks`)
// drawn with OpenGL's Z-buffer in the five representations of Szenberg sec. 3,
// the baselines of Table 2:
//   (a) Points      one GL point at the centre of each block's top face
//   (b) TopFaces    the flat top face of each block (hs x hs, centred on the sample)
//   (c) FrontFaces  the two vertical faces of each block that face the eye
//   (d) Segments    a vertical GL line from the terrain's lowest height to each sample
//   (e) Blocks      the whole block, 6 faces (back faces culled by GL)
// Vertical faces and segments reach down to the terrain's minimum height. The
// geometry is generated in the vertex shader from gl_VertexID and two textures
// (heights, colors), so nothing but the height field lives in GL memory.
//
// Based on: Szenberg, Gattass, Carvalho 1997, sec. 2 (blocks), sec. 3 (Fig. 2,
// representations a-e) and sec. 7 (Table 2).
#include "core/Terrain.h"
#include "gl/GlProgram.h"

#include <array>

namespace overflight::gl {

enum class BlockMethod { Points, TopFaces, FrontFaces, Segments, Blocks };

const char* to_string(BlockMethod m);

class BlockTerrain {
public:
    explicit BlockTerrain(const Terrain& terrain);
    // Draws every sample in representation m (Frame block must be bound).
    // Returns the primitives issued (points, lines or triangles).
    long long draw(BlockMethod m) const;

private:
    int rows_, cols_;
    Texture heights_, colors_;
    VertexArray vao_;
    std::array<Program, 5> programs_;
};

} // namespace overflight::gl
