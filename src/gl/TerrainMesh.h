#pragma once
// The `mesh` surface of DESIGN sec. 3 at full resolution: two triangles per
// grid cell with diagonals alternating as in the binary-triangle-tree split,
// per-vertex color (Terrain::colors) and normal (Terrain::sample_normal),
// uploaded once and drawn in square chunks of kChunkCells cells, each culled
// against the view frustum by its bounding box.
//
// A vertex stores only its height, a packed normal and its color (12 bytes);
// X and Z follow from the vertex's place in its chunk, so a 4097^2 terrain
// takes about 205 MB of vertex memory and one 16-bit index list per chunk
// shape is shared by all chunks.
//
// Based on: Szenberg et al. 1997 sec. 3 and 7 (terrain drawn by OpenGL's
// Z-buffer as the baseline of the ray caster), DESIGN sec. 3 (`mesh`), the
// ROAM bintree diagonal pattern (CMSC 23700 project 2a).
#include "core/Terrain.h"
#include "gl/GlProgram.h"

#include <glm/mat4x4.hpp>

#include <cstdint>
#include <vector>

namespace overflight::gl {

// Diagonal of grid cell (row, col) of the bintree triangulation: true when the
// cell is split from (row, col) to (row+1, col+1), false for (row, col+1) to
// (row+1, col). Full-resolution bintree diagonals meet at the centre of every
// 2x2 block, i.e. they alternate in a checkerboard: cell (0, 0) is split from
// (0, 0) to (1, 1).
inline bool bintree_main_diagonal(int row, int col) { return ((row + col) & 1) == 0; }

// Appends the 6 indices (two counter-clockwise-from-above triangles) of cell
// (row, col) of a grid whose vertex (r, c) has index r * stride + c.
void append_cell_triangles(std::vector<std::uint32_t>& out, int row, int col, int stride);

// True when the axis-aligned box [lo, hi] is at least partly inside the frustum
// of the clip matrix `clip` (planes extracted as in Gribb and Hartmann 2001).
bool box_in_frustum(const glm::dmat4& clip, const glm::dvec3& lo, const glm::dvec3& hi);

class TerrainMesh {
public:
    static constexpr int kChunkCells = 128; // even, so chunk-local parity equals global parity

    // Uploads the whole terrain. Throws Error("opengl", ...) if the GL cannot hold it.
    explicit TerrainMesh(const Terrain& terrain);

    struct DrawStats {
        int chunks_total = 0;
        int chunks_drawn = 0;
        long long triangles = 0;
    };
    // Draws the chunks whose boxes meet the frustum of `clip` (world -> clip
    // space; Camera projection * view). Frame block must be bound.
    DrawStats draw(const glm::dmat4& clip) const;

private:
    struct Chunk {
        int col0, row0;     // first sample
        int cells_x, cells_z;
        GLint base_vertex;
        int shape;          // index into shapes_
        float y_min, y_max; // bounding box heights
    };
    struct Shape {
        int cells_x, cells_z;
        GLsizei count;
        std::size_t offset_bytes;
    };
    float h_scale_ = 1;
    std::vector<Chunk> chunks_;
    std::vector<Shape> shapes_;
    Buffer vertices_, indices_;
    VertexArray vao_;
    Program program_;
    GLint chunk_loc_ = -1;
};

} // namespace overflight::gl
