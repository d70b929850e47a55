// Based on: CMSC 23700 project 2a (skybox) and DESIGN sec. 2 (camera rays).
#include "gl/SkyPass.h"

namespace overflight::gl {

const char* const kFullScreenVs = R"(
void main() {
    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    gl_Position = vec4(p * 2.0 - 1.0, 1.0, 1.0);
}
)";

namespace {

const char* const kSkyFs = R"(
out vec4 frag;
void main() {
    // gl_FragCoord is the pixel centre with y up: v = H/2 - (r + 0.5) = y - H/2.
    float u = gl_FragCoord.x - 0.5 * image.x;
    float v = gl_FragCoord.y - 0.5 * image.y;
    vec3 dir = view_axis.xyz + (u / image.z) * view_right.xyz + ((v + image.w) / image.z) * view_up.xyz;
    // Under the water, unless the ray rises to the surface over the terrain
    // (which the water pass draws there): the depths (core/WaterSurface.h).
    if (underwater.x > 0.0) {
        vec2 p = eye.xz + dir.xz * ((underwater.y - eye.y) / dir.y);
        vec2 extent = vec2(grid.w - 1.0, grid.z - 1.0) * grid.x;
        if (!(dir.y > 0.0) || any(lessThan(p, vec2(0.0))) || any(greaterThan(p, extent))) {
            frag = vec4(water_deep.rgb, 1.0);
            return;
        }
    }
    if (air_haze.a > 0.0) {
        frag = vec4(air_sky(dir), 1.0);
        return;
    }
    float s = max(normalize(dir).y, 0.0);
    frag = vec4(mix(sky_horizon.rgb, sky_zenith.rgb, s), 1.0);
}
)";

} // namespace

SkyPass::SkyPass() : program_(make_program("sky", kFullScreenVs, kSkyFs)), vao_(make_vertex_array()) {}

void SkyPass::draw() const {
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glUseProgram(program_.get());
    glBindVertexArray(vao_.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDepthMask(GL_TRUE);
    glEnable(GL_DEPTH_TEST);
}

} // namespace overflight::gl
