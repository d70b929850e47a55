#pragma once
// The imagery tiles a quadtree frame shows (core/TiledImagery.h), on the GPU:
// one mipmapped RGBA texture array (texture unit 12), a layer per tile, and
// a page table (unit 13) over the frame's tiles' rectangle of the tile grid
// giving each tile's layer and the world position of its first texel.
// terrain_albedo() in kFrameGlsl takes a fragment's tile from its triangle
// (StreamedMesh's per-vertex tile, MeshArrays::tiles: one tile per
// triangle, so the texture coordinates' derivatives never mix two tiles'
// origins, which with anisotropic filtering drew a line of coarse texels
// along every seam on Mesa), samples the tile's layer (trilinear,
// anisotropic where the GL offers it; the tile holds its neighbours'
// texels for a margin around its cells) and hands over to the per-vertex
// colors past the tile's coarsest level, as the whole-terrain imagery
// (ImageryTexture) shows the same texels.
//
// Based on: Williams, "Pyramidal Parametrics" (SIGGRAPH 1983); Tanner,
// Migdal, Jones, "The Clipmap" (SIGGRAPH 1998, sec. 3: only the texels near
// the viewer resident, addressed through a small table); OpenGL 4.5 core
// (texture arrays, textureGrad).
#include "core/TiledImagery.h"
#include "gl/GlProgram.h"

#include <glm/vec4.hpp>

#include <memory>
#include <vector>

namespace overflight::gl {

class TiledImageryTexture {
public:
    static constexpr GLuint kArrayUnit = 12; // `imagery_tiles` in kFrameGlsl
    static constexpr GLuint kPageUnit = 13;  // `imagery_pages` in kFrameGlsl

    // Makes the frame's tiles resident (uploading the new ones into free
    // layers, growing the array when they do not fit) and rewrites the page
    // table; binds both. A frame without tiles binds nothing.
    void update(const TileImageryFrame& frame);
    // The two vectors of the frame block (tile_imagery, tile_imagery_size);
    // zero without tiles this frame.
    glm::vec4 uniform() const { return uniform_; }
    glm::vec4 size_uniform() const { return size_uniform_; }
    int resident() const { return int(layers_.size()); }

private:
    Texture array_, pages_;
    int capacity_ = 0, page_cols_ = 0, page_rows_ = 0;
    ImageryTileLayout layout_;
    std::vector<std::shared_ptr<const TileImagery>> layers_; // what each layer holds (null: free)
    glm::vec4 uniform_{0.0f}, size_uniform_{0.0f};
};

} // namespace overflight::gl
