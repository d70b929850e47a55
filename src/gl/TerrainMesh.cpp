// Based on: Szenberg et al. 1997 sec. 3 (Z-buffer terrain), DESIGN sec. 3 (`mesh`).
#include "gl/TerrainMesh.h"

#include "core/Error.h"

#include <glm/gtc/matrix_access.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace overflight::gl {

namespace {

const char* const kMeshVs = R"(
layout(location = 0) in float height;
layout(location = 1) in vec4 packed_normal;
layout(location = 2) in vec4 color;
// x, y = first column and row of the chunk, z = vertices per chunk row,
// w = the chunk's base vertex (gl_VertexID includes it in OpenGL).
uniform ivec4 chunk;
out vec3 v_world;
out vec3 v_normal;
out vec3 v_color;
void main() {
    int local = gl_VertexID - chunk.w;
    int col = chunk.x + local % chunk.z;
    int row = chunk.y + local / chunk.z;
    v_world = vec3(grid.x * float(col), height, grid.x * float(row));
    v_normal = packed_normal.xyz;
    v_color = color.rgb;
    gl_Position = clip_of(v_world);
}
)";

struct PackedVertex {
    float height;
    std::uint32_t normal; // GL_INT_2_10_10_10_REV, signed normalised
    Rgb8 color;
    std::uint8_t pad;
};
static_assert(sizeof(PackedVertex) == 12);

std::uint32_t pack_snorm10(const glm::vec3& n) {
    auto q = [](float v) { return std::uint32_t(int(std::lround(std::clamp(v, -1.0f, 1.0f) * 511.0f)) & 0x3ff); };
    return q(n.x) | (q(n.y) << 10) | (q(n.z) << 20);
}

} // namespace

void append_cell_triangles(std::vector<std::uint32_t>& out, int row, int col, int stride) {
    const auto v = [stride](int r, int c) { return std::uint32_t(r * stride + c); };
    // Counter-clockwise seen from above (+Y): with X east and Z south, going
    // (r, c) -> (r+1, c) -> (r+1, c+1) turns counter-clockwise looking down.
    if (bintree_main_diagonal(row, col)) {
        out.insert(out.end(), {v(row, col), v(row + 1, col), v(row + 1, col + 1)});
        out.insert(out.end(), {v(row, col), v(row + 1, col + 1), v(row, col + 1)});
    } else {
        out.insert(out.end(), {v(row, col), v(row + 1, col), v(row, col + 1)});
        out.insert(out.end(), {v(row, col + 1), v(row + 1, col), v(row + 1, col + 1)});
    }
}

bool box_in_frustum(const glm::dmat4& clip, const glm::dvec3& lo, const glm::dvec3& hi) {
    const glm::dvec4 r0 = glm::row(clip, 0), r1 = glm::row(clip, 1), r2 = glm::row(clip, 2), r3 = glm::row(clip, 3);
    const glm::dvec4 planes[6] = {r3 + r0, r3 - r0, r3 + r1, r3 - r1, r3 + r2, r3 - r2};
    for (const glm::dvec4& p : planes) {
        // The box corner farthest along the plane normal (the "p-vertex").
        const glm::dvec3 c(p.x >= 0 ? hi.x : lo.x, p.y >= 0 ? hi.y : lo.y, p.z >= 0 ? hi.z : lo.z);
        if (p.x * c.x + p.y * c.y + p.z * c.z + p.w < 0) return false;
    }
    return true;
}

TerrainMesh::TerrainMesh(const Terrain& t) : h_scale_(t.h_scale()) {
    const int cells_x = t.cols() - 1, cells_z = t.rows() - 1;
    // Chunk shapes: full, and the narrower last column / shorter last row.
    std::vector<std::uint32_t> all_indices;
    auto shape_of = [&](int cx, int cz) {
        for (std::size_t s = 0; s < shapes_.size(); ++s)
            if (shapes_[s].cells_x == cx && shapes_[s].cells_z == cz) return int(s);
        const std::size_t first = all_indices.size();
        for (int r = 0; r < cz; ++r)
            for (int c = 0; c < cx; ++c) append_cell_triangles(all_indices, r, c, cx + 1);
        shapes_.push_back({cx, cz, GLsizei(all_indices.size() - first), first * sizeof(std::uint16_t)});
        return int(shapes_.size() - 1);
    };
    long long total_vertices = 0;
    for (int row0 = 0; row0 < cells_z; row0 += kChunkCells)
        for (int col0 = 0; col0 < cells_x; col0 += kChunkCells) {
            const int cx = std::min(kChunkCells, cells_x - col0), cz = std::min(kChunkCells, cells_z - row0);
            chunks_.push_back({col0, row0, cx, cz, GLint(total_vertices), shape_of(cx, cz), 0, 0});
            total_vertices += (long long)(cx + 1) * (cz + 1);
        }
    std::vector<std::uint16_t> idx16(all_indices.begin(), all_indices.end());
    indices_ = make_buffer();
    glNamedBufferStorage(indices_.get(), GLsizeiptr(idx16.size() * 2), idx16.data(), 0);

    vertices_ = make_buffer();
    glGetError();
    glNamedBufferStorage(vertices_.get(), GLsizeiptr(total_vertices * GLsizeiptr(sizeof(PackedVertex))), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    if (glGetError() == GL_OUT_OF_MEMORY)
        throw Error("opengl", "not enough memory for a " + std::to_string(t.rows()) + "x" + std::to_string(t.cols()) +
                                  " mesh");
    // Chunks are filled one at a time from one reused staging vector.
    std::vector<PackedVertex> staging;
    for (Chunk& ch : chunks_) {
        staging.clear();
        float lo = t.sample_height(ch.row0, ch.col0), hi = lo;
        for (int r = ch.row0; r <= ch.row0 + ch.cells_z; ++r)
            for (int c = ch.col0; c <= ch.col0 + ch.cells_x; ++c) {
                const float h = t.sample_height(r, c);
                lo = std::min(lo, h);
                hi = std::max(hi, h);
                staging.push_back({h, pack_snorm10(t.sample_normal(r, c)), t.color(r, c), 255});
            }
        ch.y_min = lo;
        ch.y_max = hi;
        glNamedBufferSubData(vertices_.get(), GLintptr(ch.base_vertex) * GLintptr(sizeof(PackedVertex)),
                             GLsizeiptr(staging.size() * sizeof(PackedVertex)), staging.data());
    }

    vao_ = make_vertex_array();
    glVertexArrayVertexBuffer(vao_.get(), 0, vertices_.get(), 0, sizeof(PackedVertex));
    glVertexArrayElementBuffer(vao_.get(), indices_.get());
    glEnableVertexArrayAttrib(vao_.get(), 0);
    glVertexArrayAttribFormat(vao_.get(), 0, 1, GL_FLOAT, GL_FALSE, offsetof(PackedVertex, height));
    glEnableVertexArrayAttrib(vao_.get(), 1);
    glVertexArrayAttribFormat(vao_.get(), 1, 4, GL_INT_2_10_10_10_REV, GL_TRUE, offsetof(PackedVertex, normal));
    glEnableVertexArrayAttrib(vao_.get(), 2);
    glVertexArrayAttribFormat(vao_.get(), 2, 4, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(PackedVertex, color));
    for (GLuint a = 0; a < 3; ++a) glVertexArrayAttribBinding(vao_.get(), a, 0);

    program_ = make_program("terrain-mesh", kMeshVs, kLitFragmentGlsl);
    chunk_loc_ = glGetUniformLocation(program_.get(), "chunk");
}

TerrainMesh::DrawStats TerrainMesh::draw(const glm::dmat4& clip) const {
    DrawStats s;
    s.chunks_total = int(chunks_.size());
    glUseProgram(program_.get());
    glBindVertexArray(vao_.get());
    for (const Chunk& ch : chunks_) {
        const glm::dvec3 lo(h_scale_ * ch.col0, ch.y_min, h_scale_ * ch.row0);
        const glm::dvec3 hi(h_scale_ * (ch.col0 + ch.cells_x), ch.y_max, h_scale_ * (ch.row0 + ch.cells_z));
        if (!box_in_frustum(clip, lo, hi)) continue;
        const Shape& sh = shapes_[std::size_t(ch.shape)];
        glUniform4i(chunk_loc_, ch.col0, ch.row0, ch.cells_x + 1, ch.base_vertex);
        glDrawElementsBaseVertex(GL_TRIANGLES, sh.count, GL_UNSIGNED_SHORT,
                                 reinterpret_cast<const void*>(sh.offset_bytes), ch.base_vertex);
        ++s.chunks_drawn;
        s.triangles += sh.count / 3;
    }
    return s;
}

} // namespace overflight::gl
