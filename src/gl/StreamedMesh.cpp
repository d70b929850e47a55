// Based on: DESIGN sec. 3 (plain arrays uploaded per frame) and Szenberg et al. 1997 sec. 5.
#include "gl/StreamedMesh.h"

#include "core/Error.h"

#include <algorithm>
#include <string>

namespace overflight::gl {

namespace {

const char* const kMeshVs = R"(
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 color;
layout(location = 3) in uint tile;
out vec3 v_world;
out vec3 v_normal;
out vec3 v_color;
flat out uint v_tile;
void main() {
    v_world = position;
    v_normal = normal;
    v_color = color;
    v_tile = tile;
    gl_Position = clip_of(position);
}
)";

// kLitFragmentGlsl, with the triangle's tile for the imagery tiles: one
// tile for every fragment of a triangle, so that the derivatives of its
// texture coordinates never mix two tiles.
const char* const kMeshFs = R"(
in vec3 v_world;
in vec3 v_normal;
in vec3 v_color;
flat in uint v_tile;
out vec4 frag;
void main() {
    albedo_tile = ivec2(int(v_tile & 0xFFFFu), int(v_tile >> 16));
    frag = vec4(shade(v_color, v_normal, v_world), 1.0);
}
)";

const char* const kLineVs = R"(
layout(location = 0) in vec3 position;
layout(location = 2) in vec3 color;
out vec3 v_world;
out vec3 v_color;
void main() {
    v_world = position;
    v_color = color;
    gl_Position = clip_of(position);
}
)";

const char* const kLineFs = R"(
in vec3 v_world;
in vec3 v_color;
out vec4 frag;
void main() { frag = vec4(fogged(v_color, v_world), 1.0); }
)";

} // namespace

StreamedMesh::StreamedMesh()
    : positions_(make_buffer()), normals_(make_buffer()), colors_(make_buffer()), indices_(make_buffer()),
      tiles_(make_buffer()), vao_(make_vertex_array()), program_(make_program("streamed-mesh", kMeshVs, kMeshFs)) {
    glEnableVertexArrayAttrib(vao_.get(), 0);
    glVertexArrayAttribFormat(vao_.get(), 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao_.get(), 0, 0);
    glEnableVertexArrayAttrib(vao_.get(), 1);
    glVertexArrayAttribFormat(vao_.get(), 1, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao_.get(), 1, 1);
    glEnableVertexArrayAttrib(vao_.get(), 2);
    glVertexArrayAttribFormat(vao_.get(), 2, 3, GL_UNSIGNED_BYTE, GL_TRUE, 0);
    glVertexArrayAttribBinding(vao_.get(), 2, 2);
    glEnableVertexArrayAttrib(vao_.get(), 3);
    glVertexArrayAttribIFormat(vao_.get(), 3, 1, GL_UNSIGNED_INT, 0);
    glVertexArrayAttribBinding(vao_.get(), 3, 3);
}

void StreamedMesh::ensure(Buffer& buffer, std::size_t& capacity, std::size_t bytes) {
    if (bytes <= capacity && capacity != 0) {
        // Orphan: the driver may still read last frame's data.
        glInvalidateBufferData(buffer.get());
        return;
    }
    capacity = std::max<std::size_t>({bytes, capacity * 2, 256});
    glNamedBufferData(buffer.get(), GLsizeiptr(capacity), nullptr, GL_STREAM_DRAW);
}

void StreamedMesh::upload(const MeshArrays& mesh) {
    const std::size_t n = mesh.positions.size();
    if (mesh.normals.size() != n || mesh.colors.size() != n)
        throw Error("mesh", "normals and colors must have one entry per position");
    if (mesh.indices.size() % 3 != 0) throw Error("mesh", "index count is not a multiple of 3");
    if (!mesh.tiles.empty() && mesh.tiles.size() != n) throw Error("mesh", "tiles must be empty or one per position");
    if (!mesh.indices.empty() && *std::max_element(mesh.indices.begin(), mesh.indices.end()) >= n)
        throw Error("mesh", "index out of range of " + std::to_string(n) + " positions");
    ensure(positions_, cap_positions_, n * sizeof(glm::vec3));
    ensure(normals_, cap_normals_, n * sizeof(glm::vec3));
    ensure(colors_, cap_colors_, n * sizeof(Rgb8));
    ensure(indices_, cap_indices_, mesh.indices.size() * sizeof(std::uint32_t));
    // Without tiles, every vertex names tile (0, 0); the shader reads it only with imagery tiles.
    ensure(tiles_, cap_tiles_, n * sizeof(std::uint32_t));
    if (n && mesh.tiles.empty()) {
        const std::uint32_t zero = 0;
        glClearNamedBufferSubData(tiles_.get(), GL_R32UI, 0, GLsizeiptr(n * 4), GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    } else if (n) {
        glNamedBufferSubData(tiles_.get(), 0, GLsizeiptr(n * 4), mesh.tiles.data());
    }
    if (n) {
        glNamedBufferSubData(positions_.get(), 0, GLsizeiptr(n * sizeof(glm::vec3)), mesh.positions.data());
        glNamedBufferSubData(normals_.get(), 0, GLsizeiptr(n * sizeof(glm::vec3)), mesh.normals.data());
        glNamedBufferSubData(colors_.get(), 0, GLsizeiptr(n * sizeof(Rgb8)), mesh.colors.data());
    }
    if (!mesh.indices.empty())
        glNamedBufferSubData(indices_.get(), 0, GLsizeiptr(mesh.indices.size() * 4), mesh.indices.data());
    index_count_ = GLsizei(mesh.indices.size());
    // Buffers may have been reallocated: rebind them (cheap, no allocation).
    glVertexArrayVertexBuffer(vao_.get(), 0, positions_.get(), 0, sizeof(glm::vec3));
    glVertexArrayVertexBuffer(vao_.get(), 1, normals_.get(), 0, sizeof(glm::vec3));
    glVertexArrayVertexBuffer(vao_.get(), 2, colors_.get(), 0, sizeof(Rgb8));
    glVertexArrayVertexBuffer(vao_.get(), 3, tiles_.get(), 0, sizeof(std::uint32_t));
    glVertexArrayElementBuffer(vao_.get(), indices_.get());
}

long long StreamedMesh::draw() const {
    if (index_count_ == 0) return 0;
    glUseProgram(program_.get());
    glBindVertexArray(vao_.get());
    glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
    return index_count_ / 3;
}

LineBatch::LineBatch()
    : points_(make_buffer()), colors_(make_buffer()), vao_(make_vertex_array()),
      program_(make_program("lines", kLineVs, kLineFs)) {
    glEnableVertexArrayAttrib(vao_.get(), 0);
    glVertexArrayAttribFormat(vao_.get(), 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao_.get(), 0, 0);
    glEnableVertexArrayAttrib(vao_.get(), 2);
    glVertexArrayAttribFormat(vao_.get(), 2, 3, GL_UNSIGNED_BYTE, GL_TRUE, 0);
    glVertexArrayAttribBinding(vao_.get(), 2, 1);
}

void LineBatch::upload(const std::vector<glm::vec3>& points, const std::vector<Rgb8>& colors) {
    if (points.size() != colors.size() || points.size() % 2 != 0)
        throw Error("lines", "need an even number of points and one color per point");
    count_ = GLsizei(points.size());
    if (points.empty()) return;
    glNamedBufferData(points_.get(), GLsizeiptr(points.size() * sizeof(glm::vec3)), points.data(), GL_STATIC_DRAW);
    glNamedBufferData(colors_.get(), GLsizeiptr(colors.size() * sizeof(Rgb8)), colors.data(), GL_STATIC_DRAW);
    glVertexArrayVertexBuffer(vao_.get(), 0, points_.get(), 0, sizeof(glm::vec3));
    glVertexArrayVertexBuffer(vao_.get(), 1, colors_.get(), 0, sizeof(Rgb8));
}

void LineBatch::draw() const {
    if (count_ == 0) return;
    glUseProgram(program_.get());
    glBindVertexArray(vao_.get());
    glDrawArrays(GL_LINES, 0, count_);
}

} // namespace overflight::gl
