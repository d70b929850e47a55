// Based on: Williams 1978 (shadow depth maps), applied in screen space to a
// ray-cast image with depth. See ShadowScreenPass.h.
#include "gl/ShadowScreenPass.h"

#include "gl/RenderTarget.h"

#include <glm/ext/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <vector>

namespace overflight::gl {

namespace {

// One instance per rectangle: GL window columns x0..x1, rows y0..y1 (whole
// pixels, so that the two triangles cover exactly its pixel centres).
const char* const kPassVs = R"(
layout(location = 0) in ivec4 rect;
void main() {
    const ivec2 corner[6] = ivec2[6](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1), ivec2(0, 0), ivec2(1, 1), ivec2(0, 1));
    ivec2 c = corner[gl_VertexID];
    vec2 p = vec2(c.x == 0 ? rect.x : rect.z, c.y == 0 ? rect.y : rect.w);
    gl_Position = vec4(p / image.xy * 2.0 - 1.0, 0.0, 1.0);
}
)";

const char* const kPassFs = R"(
layout(binding = 9) uniform sampler2D scene_depth; // the target's depth attachment (GL rows)
layout(location = 0) uniform mat4 clip_to_eye;     // inverse of view_proj: clip -> world - eye
layout(location = 0, index = 0) out vec4 add;
layout(location = 0, index = 1) out vec4 factor;
float height_at(ivec2 i, ivec2 last) { return texelFetch(shadow_ceiling, clamp(i, ivec2(0), last), 0).g; }
void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    float d = texelFetch(scene_depth, px, 0).r;
    if (d >= 1.0) discard;
    vec4 ndc = vec4((vec2(px) + 0.5) / image.xy * 2.0 - 1.0, d * 2.0 - 1.0, 1.0);
    vec4 e = clip_to_eye * ndc;
    vec3 world = eye.xyz + e.xyz / e.w;
    // The ray casters' depth is their slice's, up to a slice step off the
    // block they hit: the point is moved along its ray onto that block's top
    // (the height of its nearest sample) when a block top of that height is there, so
    // that a small shadow (the vehicle's) is not shifted by the step.
    ivec2 last0 = textureSize(shadow_ceiling, 0) - 1;
    ivec2 s0 = clamp(ivec2(floor(world.xz * shadow.y + 0.5)), ivec2(0), last0);
    vec3 ray = world - eye.xyz;
    if (ray.y < 0.0) {
        float h = texelFetch(shadow_ceiling, s0, 0).g;
        vec3 top = eye.xyz + ray * ((h - eye.y) / ray.y);
        ivec2 s1 = clamp(ivec2(floor(top.xz * shadow.y + 0.5)), ivec2(0), last0);
        if (texelFetch(shadow_ceiling, s1, 0).g == h) world = top;
    }
    float visible = object_sun_visible(world);
    if (visible >= 1.0) discard;
    // The sample the ray caster painted: its normal (Terrain::sample_normal)
    // and whether the terrain shadows it, from the ceiling texture.
    ivec2 last = textureSize(shadow_ceiling, 0) - 1;
    ivec2 i = clamp(ivec2(floor(world.xz * shadow.y + 0.5)), ivec2(0), last);
    ivec2 x0 = ivec2(max(i.x - 1, 0), i.y), x1 = ivec2(min(i.x + 1, last.x), i.y);
    ivec2 z0 = ivec2(i.x, max(i.y - 1, 0)), z1 = ivec2(i.x, min(i.y + 1, last.y));
    float cell = 1.0 / shadow.y;
    float dhdx = (height_at(x1, last) - height_at(x0, last)) / (cell * float(max(x1.x - x0.x, 1)));
    float dhdz = (height_at(z1, last) - height_at(z0, last)) / (cell * float(max(z1.y - z0.y, 1)));
    vec3 n = normalize(vec3(-dhdx, 1.0, -dhdz));
    float lit = step(texelFetch(shadow_ceiling, i, 0).r, 0.0);
    float sun = max(dot(n, sun_dir.xyz), 0.0) * lit;
    vec3 before = ambient.rgb + sun_color.rgb * sun;
    vec3 f = (ambient.rgb + sun_color.rgb * sun * visible) / max(before, vec3(1e-6));
    add = vec4(fogged(vec3(0.0), world) * (1.0 - f), 0.0);
    factor = vec4(f, 1.0);
}
)";

} // namespace

void ShadowScreenPass::draw(const RenderTarget& target, const Camera& camera, std::span<const PixelRect> rects) {
    std::vector<glm::ivec4> boxes;
    boxes.reserve(rects.size());
    for (const PixelRect& r : rects)
        if (!r.empty()) boxes.emplace_back(r.col0, camera.height - r.row1, r.col1, camera.height - r.row0);
    if (boxes.empty()) return;
    if (!program_) {
        program_ = make_program("object-shadow-pass", kPassVs, kPassFs);
        vao_ = make_vertex_array();
        glEnableVertexArrayAttrib(vao_.get(), 0);
        glVertexArrayAttribIFormat(vao_.get(), 0, 4, GL_INT, 0);
        glVertexArrayAttribBinding(vao_.get(), 0, 0);
        glVertexArrayBindingDivisor(vao_.get(), 0, 1);
    }
    // A buffer large enough for this frame's rectangles (grown by doubling).
    const GLsizeiptr bytes = GLsizeiptr(boxes.size() * sizeof(glm::ivec4));
    if (bytes > capacity_) {
        capacity_ = std::max<GLsizeiptr>(bytes, 2 * capacity_);
        rects_ = make_buffer();
        glNamedBufferData(rects_.get(), capacity_, nullptr, GL_STREAM_DRAW);
        glVertexArrayVertexBuffer(vao_.get(), 0, rects_.get(), 0, sizeof(glm::ivec4));
    }
    glNamedBufferSubData(rects_.get(), 0, bytes, boxes.data());
    // The depth is sampled, so it must not be attached where the pass draws.
    target.bind_color_only();

    // Eye-relative like FrameUniforms' view_proj, inverted in double.
    const glm::mat4 clip_to_eye(glm::inverse(camera.projection_matrix() * camera.view_matrix() *
                                             glm::translate(glm::dmat4(1.0), camera.eye)));
    glUseProgram(program_.get());
    glProgramUniformMatrix4fv(program_.get(), 0, 1, GL_FALSE, glm::value_ptr(clip_to_eye));
    glBindTextureUnit(kUnit, target.depth_texture());
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_SRC1_COLOR);
    glBindVertexArray(vao_.get());
    glDrawArraysInstanced(GL_TRIANGLES, 0, 6, GLsizei(boxes.size()));
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    glEnable(GL_DEPTH_TEST);
}

} // namespace overflight::gl
