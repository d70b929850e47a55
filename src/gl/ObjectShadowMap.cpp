// Based on: Williams 1978 (shadow depth maps); Reeves, Salesin, Cook 1987
// (percentage-closer filtering). See ObjectShadowMap.h.
#include "gl/ObjectShadowMap.h"

#include "core/Error.h"

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace overflight::gl {

ObjectShadowMap::ObjectShadowMap(GLuint unit, GLuint binding, int size)
    : unit_(unit), binding_(binding), size_(size), depth_(make_texture(GL_TEXTURE_2D)), fbo_(make_framebuffer()),
      ubo_(make_buffer()), pass_frame_(make_buffer()), off_ubo_(make_buffer()) {
    glTextureStorage2D(depth_.get(), 1, GL_DEPTH_COMPONENT32F, size_, size_);
    glTextureParameteri(depth_.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(depth_.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(depth_.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(depth_.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(depth_.get(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTextureParameteri(depth_.get(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    glNamedFramebufferTexture(fbo_.get(), GL_DEPTH_ATTACHMENT, depth_.get(), 0);
    glNamedFramebufferDrawBuffer(fbo_.get(), GL_NONE);
    glNamedFramebufferReadBuffer(fbo_.get(), GL_NONE);
    if (glCheckNamedFramebufferStatus(fbo_.get(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw Error("opengl", "the objects' shadow map framebuffer is incomplete");
    glNamedBufferStorage(ubo_.get(), sizeof(ObjectShadowBlock), &block_, GL_DYNAMIC_STORAGE_BIT);
    glNamedBufferStorage(pass_frame_.get(), sizeof(FrameBlock), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glNamedBufferStorage(off_ubo_.get(), sizeof(ObjectShadowBlock), nullptr, GL_DYNAMIC_STORAGE_BIT);
}

std::vector<WorldBox> ObjectShadowMap::reach(const std::vector<WorldBox>& objects, const glm::vec3& sun, float floor) {
    std::vector<WorldBox> out;
    out.reserve(objects.size());
    for (const WorldBox& b : objects) {
        // The top's corners follow the rays away from the sun down to the floor.
        const float drop = std::max(b.hi.y - floor, 0.0f) / std::max(sun.y, 1e-3f);
        const glm::vec3 shift(-sun.x * drop, 0.0f, -sun.z * drop);
        const glm::vec3 l(std::min(b.lo.x, b.lo.x + shift.x), std::min(b.lo.y, floor), std::min(b.lo.z, b.lo.z + shift.z));
        out.push_back({l, glm::max(b.hi, b.hi + shift)});
    }
    return out;
}

float ObjectShadowMap::texel_bound(const std::vector<WorldBox>& boxes, int size) {
    if (boxes.empty()) return 0.0f;
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const WorldBox& b : boxes) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    // begin_pass() maps the boxes' extent across the sun's view, at most
    // their diagonal, plus a margin of a texel and 0.01 on each side, onto
    // `size` texels.
    const float extent = glm::length(hi - lo);
    return (extent * (1.0f + 2.0f / float(size)) + 0.02f) / float(size);
}

bool ObjectShadowMap::begin_pass(bool on, const glm::vec3& sun, const std::vector<WorldBox>& boxes, bool changed,
                                 const FrameBlock& frame) {
    const bool want = on && sun.y > 0 && !boxes.empty();
    if (!want) {
        if (block_.params.x != 0.0f) {
            block_.params.x = 0.0f;
            glNamedBufferSubData(ubo_.get(), 0, sizeof(ObjectShadowBlock), &block_);
        }
        return false;
    }
    if (rendered_ && rendered_for_ == sun && !changed) {
        if (block_.params.x == 0.0f) {
            block_.params.x = 1.0f;
            glNamedBufferSubData(ubo_.get(), 0, sizeof(ObjectShadowBlock), &block_);
        }
        return false;
    }
    // The sun's view: orthographic along -sun, centred on the objects' bounds.
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const WorldBox& b : boxes) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    const glm::vec3 origin = 0.5f * (lo + hi);
    const float radius = 0.5f * glm::length(hi - lo) + 1.0f;
    const glm::vec3 up = std::abs(sun.y) > 0.99f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
    const glm::mat4 view = glm::lookAt(sun * (2.0f * radius), glm::vec3(0.0f), up);
    glm::vec3 vlo(std::numeric_limits<float>::max()), vhi(-std::numeric_limits<float>::max());
    for (const WorldBox& b : boxes)
        for (int c = 0; c < 8; ++c) {
            const glm::vec3 corner(c & 1 ? b.hi.x : b.lo.x, c & 2 ? b.hi.y : b.lo.y, c & 4 ? b.hi.z : b.lo.z);
            const glm::vec3 v = glm::vec3(view * glm::vec4(corner - origin, 1.0f));
            vlo = glm::min(vlo, v);
            vhi = glm::max(vhi, v);
        }
    // A texel's margin on every side, and depth from just before the nearest
    // corner to just past the farthest (the view looks down -z).
    const glm::vec2 margin = (glm::vec2(vhi) - glm::vec2(vlo)) / float(size_) + 0.01f;
    const float near = -vhi.z - 1.0f, far = -vlo.z + 1.0f;
    const glm::mat4 proj = glm::ortho(vlo.x - margin.x, vhi.x + margin.x, vlo.y - margin.y, vhi.y + margin.y, near, far);
    block_.sun_proj = proj * view;
    block_.origin = glm::vec4(origin, 1.0f);
    // A fragment on a lit face lies within about a texel's footprint of the
    // depth stored for it: a bias of one texel's width in depth units.
    const float texel = std::max(margin.x, margin.y);
    block_.params = glm::vec4(1.0f, 2.0f * texel / (far - near), 0.0f, 0.0f);
    glNamedBufferSubData(ubo_.get(), 0, sizeof(ObjectShadowBlock), &block_);

    // The objects' programs project (world - eye) by the frame's view_proj:
    // the sun's, with the shadows of this very map turned off while it is drawn.
    FrameBlock pass = frame;
    pass.view_proj = block_.sun_proj;
    pass.eye = block_.origin;
    pass.shadow = glm::vec4(0.0f);
    glNamedBufferSubData(pass_frame_.get(), 0, sizeof(FrameBlock), &pass);
    ObjectShadowBlock off = block_;
    off.params.x = 0.0f;
    glNamedBufferSubData(off_ubo_.get(), 0, sizeof(ObjectShadowBlock), &off);
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, pass_frame_.get());
    glBindBufferBase(GL_UNIFORM_BUFFER, binding_, off_ubo_.get());
    glBindTextureUnit(unit_, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
    glViewport(0, 0, size_, size_);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(2.0f, 4.0f);
    return true;
}

void ObjectShadowMap::end_pass(const glm::vec3& sun) {
    glDisable(GL_POLYGON_OFFSET_FILL);
    rendered_ = true;
    rendered_for_ = sun;
}

void ObjectShadowMap::bind() const {
    glBindBufferBase(GL_UNIFORM_BUFFER, binding_, ubo_.get());
    glBindTextureUnit(unit_, depth_.get());
}

} // namespace overflight::gl
