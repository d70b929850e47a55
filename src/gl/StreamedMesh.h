#pragma once
// A triangle mesh in core MeshArrays form (world positions, unit normals,
// colors, triangle list) held in GL buffers and drawn lit and fogged exactly
// like the full-resolution TerrainMesh. For per-frame meshes (ROAM, Röttger's
// quadtree, tiles: call upload() every frame; buffers only grow, so a steady
// triangle budget allocates nothing per frame) and for static ones (objects,
// models: upload once).
//
// Based on: DESIGN sec. 3 (mesh renderers output plain arrays the GL layer
// only uploads) and Szenberg et al. 1997 sec. 5 (objects drawn with the Z-buffer).
#include "core/MeshArrays.h"
#include "gl/GlProgram.h"

namespace overflight::gl {

class StreamedMesh {
public:
    StreamedMesh();
    // Copies the arrays into GL buffers, replacing the previous contents.
    // Throws Error("mesh", ...) when normals/colors do not match positions or
    // an index is out of range.
    void upload(const MeshArrays& mesh);
    // Draws the last upload (Frame block must be bound). Returns triangles drawn.
    long long draw() const;
    long long triangle_count() const { return index_count_ / 3; }

private:
    void ensure(Buffer& buffer, std::size_t& capacity, std::size_t bytes);
    Buffer positions_, normals_, colors_, indices_, tiles_;
    std::size_t cap_positions_ = 0, cap_normals_ = 0, cap_colors_ = 0, cap_indices_ = 0, cap_tiles_ = 0;
    GLsizei index_count_ = 0;
    VertexArray vao_;
    Program program_;
};

// Flat-shaded world-space GL lines (towers, cables), fogged but not lit.
class LineBatch {
public:
    LineBatch();
    // points[2k], points[2k+1] is segment k; one color per point.
    void upload(const std::vector<glm::vec3>& points, const std::vector<Rgb8>& colors);
    void draw() const;

private:
    Buffer points_, colors_;
    GLsizei count_ = 0;
    VertexArray vao_;
    Program program_;
};

} // namespace overflight::gl
