// Based on: Szenberg et al. 1997 sec. 3 (representations a-e) and Table 2.
#include "gl/BlockTerrain.h"

#include <string>
#include <vector>

namespace overflight::gl {

namespace {

// Vertices per sample for each representation.
constexpr int kVerticesPerSample[5] = {1, 6, 12, 2, 36};

const char* const kBlockVs = R"(
layout(binding = 0) uniform sampler2D heights; // world Y, texel (col, row)
layout(binding = 1) uniform sampler2D colors;
out vec3 v_world;
out vec3 v_normal;
out vec3 v_color;

// Block corner `bits` (1 = +X, 2 = top, 4 = +Z) and the 6 faces as corner
// quadruples, counter-clockwise seen from outside: +Y, -Y, +X, -X, +Z, -Z.
const int face_corners[24] = int[](2, 6, 7, 3,  0, 1, 5, 4,  1, 3, 7, 5,  0, 4, 6, 2,  4, 5, 7, 6,  0, 2, 3, 1);
const vec3 face_normals[6] = vec3[](vec3(0, 1, 0), vec3(0, -1, 0), vec3(1, 0, 0), vec3(-1, 0, 0),
                                     vec3(0, 0, 1), vec3(0, 0, -1));
const int quad_order[6] = int[](0, 1, 2, 0, 2, 3);

void main() {
    int sample_id = gl_VertexID / VERTS;
    int k = gl_VertexID - sample_id * VERTS;
    int cols = int(grid.w);
    ivec2 texel = ivec2(sample_id % cols, sample_id / cols);
    float h = texelFetch(heights, texel, 0).r;
    v_color = texelFetch(colors, texel, 0).rgb;
    vec3 centre = vec3(grid.x * float(texel.x), h, grid.x * float(texel.y));
    float ground = grid.y;
    float half_cell = 0.5 * grid.x;
    v_normal = vec3(0, 1, 0);
#if METHOD == 0
    v_world = centre;
#elif METHOD == 3
    v_world = vec3(centre.x, k == 0 ? ground : h, centre.z);
#else
    int face;
    int corner_in_face = quad_order[k % 6];
#if METHOD == 1
    face = 0;
#elif METHOD == 2
    // Frontal faces: the X face and the Z face on the eye's side of the block.
    face = k < 6 ? (eye.x > centre.x ? 2 : 3) : (eye.z > centre.z ? 4 : 5);
#else
    face = k / 6;
#endif
    int bits = face_corners[face * 4 + corner_in_face];
    v_world = vec3(centre.x + ((bits & 1) != 0 ? half_cell : -half_cell),
                   (bits & 2) != 0 ? h : ground,
                   centre.z + ((bits & 4) != 0 ? half_cell : -half_cell));
    v_normal = face_normals[face];
#endif
    gl_Position = clip_of(v_world);
}
)";

} // namespace

const char* to_string(BlockMethod m) {
    switch (m) {
    case BlockMethod::Points: return "points";
    case BlockMethod::TopFaces: return "top-faces";
    case BlockMethod::FrontFaces: return "front-faces";
    case BlockMethod::Segments: return "segments";
    case BlockMethod::Blocks: return "blocks";
    }
    return "blocks";
}

BlockTerrain::BlockTerrain(const Terrain& t) : rows_(t.rows()), cols_(t.cols()) {
    std::vector<float> h(std::size_t(rows_) * std::size_t(cols_));
    for (int r = 0; r < rows_; ++r)
        for (int c = 0; c < cols_; ++c) h[t.index(r, c)] = t.sample_height(r, c);
    heights_ = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(heights_.get(), 1, GL_R32F, cols_, rows_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    // Texel (col, row) = sample (row, col): the texture's row 0 is the grid's row 0.
    glTextureSubImage2D(heights_.get(), 0, 0, 0, cols_, rows_, GL_RED, GL_FLOAT, h.data());
    colors_ = make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(colors_.get(), 1, GL_RGB8, cols_, rows_);
    glTextureSubImage2D(colors_.get(), 0, 0, 0, cols_, rows_, GL_RGB, GL_UNSIGNED_BYTE, t.colors().data());
    vao_ = make_vertex_array();
    for (int m = 0; m < 5; ++m) {
        const std::string src = "#define METHOD " + std::to_string(m) + "\n#define VERTS " +
                                std::to_string(kVerticesPerSample[m]) + "\n" + kBlockVs;
        programs_[std::size_t(m)] = make_program(to_string(BlockMethod(m)), src.c_str(), kLitFragmentGlsl);
    }
}

long long BlockTerrain::draw(BlockMethod m) const {
    const int mi = int(m);
    const long long samples = (long long)rows_ * cols_;
    glUseProgram(programs_[std::size_t(mi)].get());
    glBindVertexArray(vao_.get());
    glBindTextureUnit(0, heights_.get());
    glBindTextureUnit(1, colors_.get());
    const GLenum mode = m == BlockMethod::Points ? GL_POINTS : m == BlockMethod::Segments ? GL_LINES : GL_TRIANGLES;
    if (m == BlockMethod::Blocks) glEnable(GL_CULL_FACE);
    glDrawArrays(mode, 0, GLsizei(samples * kVerticesPerSample[mi]));
    glDisable(GL_CULL_FACE);
    const long long per_sample[5] = {1, 2, 4, 1, 12};
    return samples * per_sample[mi];
}

} // namespace overflight::gl
