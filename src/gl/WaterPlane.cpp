// Based on: Tessendorf (2001), Schlick (1994) through core/WaterSurface.h;
// the OpenGL 4.5 core specification (dual-source blending). See WaterPlane.h.
#include "gl/WaterPlane.h"

#include "core/WaterSurface.h"
#include "gl/SkyPass.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace overflight::gl {

namespace {

// WATER_CONSTANTS is replaced by core/WaterSurface.h's constants.
const char* const kWaterFs = R"(
layout(binding = 5) uniform sampler2D water_heights; // world Y, texel (col, row)
layout(binding = 6) uniform sampler2D water_colors;
uniform vec4 water; // level, time (s), highest sample, 1 = baked
uniform float water_texel; // world units between texels of water_heights (the cell, times the decimation)
layout(location = 0, index = 0) out vec4 frag;
layout(location = 0, index = 1) out vec4 weight;

WATER_CONSTANTS

float height_at(vec2 xz) { // Terrain::height_bilinear (of the decimated heights)
    vec2 p = xz / water_texel;
    ivec2 last = textureSize(water_heights, 0) - 1;
    ivec2 i = clamp(ivec2(floor(p)), ivec2(0), last - 1);
    vec2 f = clamp(p - vec2(i), 0.0, 1.0);
    float h00 = texelFetch(water_heights, i, 0).r, h10 = texelFetch(water_heights, i + ivec2(1, 0), 0).r;
    float h01 = texelFetch(water_heights, i + ivec2(0, 1), 0).r, h11 = texelFetch(water_heights, i + ivec2(1, 1), 0).r;
    return mix(mix(h00, h10, f.x), mix(h01, h11, f.x), f.y);
}
vec3 wave_normal(vec2 xz) { // water_normal
    float gx = 0.0, gz = 0.0;
    for (int i = 0; i < 4; ++i) {
        float k = 6.283185307179586 / (kWaves[i].z * grid.x);
        float c = cos(k * dot(kWaves[i].xy, xz) - kWaveSpeed[i] * water.y);
        gx += kWaves[i].w * kWaves[i].x * c;
        gz += kWaves[i].w * kWaves[i].y * c;
    }
    return normalize(vec3(-gx, 1.0, -gz));
}
float fresnel(float c) { // water_fresnel
    float m = 1.0 - clamp(c, 0.0, 1.0);
    return kF0 + (1.0 - kF0) * m * m * m * m * m;
}
vec3 mirrored(vec3 v, vec3 n) { // water_reflect
    vec3 r = v - 2.0 * dot(v, n) * n;
    if (r.y < 0.01) r = normalize(vec3(r.x, 0.01 * length(r.xz), r.z));
    return r;
}
bool inside(vec2 xz) {
    vec2 extent = vec2(grid.w - 1.0, grid.z - 1.0) * grid.x;
    return all(greaterThanEqual(xz, vec2(0.0))) && all(lessThanEqual(xz, extent));
}
vec3 sky(vec3 dir) {
    if (air_haze.a > 0.0) return air_sky(dir);
    return mix(sky_horizon.rgb, sky_zenith.rgb, max(normalize(dir).y, 0.0));
}
void main() {
    float u = gl_FragCoord.x - 0.5 * image.x;
    float v = gl_FragCoord.y - 0.5 * image.y;
    vec3 dir = view_axis.xyz + (u / image.z) * view_right.xyz + ((v + image.w) / image.z) * view_up.xyz;
    float level = water.x;
    bool under = eye.y < level;
    if (under ? !(dir.y > 0.0) : !(dir.y < 0.0)) discard;
    vec3 offset = dir * ((level - eye.y) / dir.y); // eye to the water point
    vec3 p = eye.xyz + offset;
    if (!inside(p.xz)) discard;
    vec4 clip = view_proj * vec4(offset, 1.0);
    float z = clip.z / clip.w * 0.5 + 0.5;
    if (z <= 0.0 || z >= 1.0) discard;
    gl_FragDepth = z;
    vec3 view = normalize(dir);
    vec3 n = wave_normal(p.xz);
    if (under) { // the surface from below, opaque: water_underside, underwater_color
        vec3 up = refract(view, -n, kIndex);
        vec3 c = water_deep.rgb;
        if (up != vec3(0.0)) {
            float f = fresnel(dot(up, n));
            c = sky(up) * (1.0 - f) + water_deep.rgb * f;
        }
        frag = vec4(under_water(c, p), 1.0);
        weight = vec4(1.0);
        return;
    }
    // The mirrored ray through the height field.
    vec3 r = mirrored(view, n);
    float reach = (water.z - level) / r.y + grid.x;
    float t = 0.0, step = 0.5 * grid.x;
    vec3 reflected = sky(r);
    for (int i = 0; i < 192 && t < reach; ++i) {
        t += step;
        vec3 q = p + r * t;
        if (!inside(q.xz)) break;
        if (height_at(q.xz) >= q.y) {
            ivec2 s = ivec2(floor(q.xz / water_texel + 0.5));
            vec3 albedo = texelFetch(water_colors, s, 0).rgb;
            vec3 lit = albedo;
            if (water.w == 0.0) {
                float e = grid.x;
                vec3 tn = normalize(vec3(height_at(q.xz - vec2(e, 0.0)) - height_at(q.xz + vec2(e, 0.0)), 2.0 * e,
                                         height_at(q.xz - vec2(0.0, e)) - height_at(q.xz + vec2(0.0, e))));
                lit = albedo * (ambient.rgb + sun_color.rgb * (sun_dir.y > 0.0 ? max(dot(tn, sun_dir.xyz), 0.0) : 0.0));
            }
            reflected = air_haze.a > 0.0 ? aerial(lit, eye.xyz + (q - p))
                                         : mix(fog.rgb, lit, exp(-fog.a * length(q - p)));
            break;
        }
        step *= 1.04;
    }
    // water_light
    float f = fresnel(-dot(view, n));
    vec3 light = water.w > 0.0 ? vec3(1.0) : ambient.rgb + sun_color.rgb * max(sun_dir.y, 0.0);
    float path = max(level - height_at(p.xz), 0.0) / max(-view.y, 1e-3);
    vec3 tr = exp(-kAbsorption * path);
    vec3 behind = tr * (1.0 - f);
    vec3 own = reflected * f + kDeep * light * (1.0 - tr) * (1.0 - f);
    if (sun_dir.y > 0.0 && water.w == 0.0)
        own += sun_color.rgb * (f * pow(max(dot(mirrored(view, n), sun_dir.xyz), 0.0), 256.0));
    vec3 surface = clamp(own / (1.0 - behind), 0.0, 1.0);
    frag = vec4(fogged(surface, p) * (1.0 - behind), 1.0);
    weight = vec4(1.0 - behind, 1.0);
}
)";

// The constants of core/WaterSurface.h as GLSL.
std::string water_constants() {
    std::string s;
    char line[256];
    std::snprintf(line, sizeof line, "const float kF0 = %.9g;\n", double(kWaterF0));
    s += line;
    std::snprintf(line, sizeof line, "const float kIndex = %.9g;\n", double(kWaterIndex));
    s += line;
    std::snprintf(line, sizeof line, "const vec3 kAbsorption = vec3(%.9g, %.9g, %.9g);\n", double(kWaterAbsorption[0]),
                  double(kWaterAbsorption[1]), double(kWaterAbsorption[2]));
    s += line;
    std::snprintf(line, sizeof line, "const vec3 kDeep = vec3(%.9g, %.9g, %.9g);\n", double(kWaterDeep[0]),
                  double(kWaterDeep[1]), double(kWaterDeep[2]));
    s += line;
    s += "const vec4 kWaves[4] = vec4[4](";
    for (int i = 0; i < 4; ++i) {
        const WaterWave& w = kWaterWaves[i];
        std::snprintf(line, sizeof line, "%svec4(%.9g, %.9g, %.9g, %.9g)", i ? ", " : "", double(w.dx), double(w.dz),
                      double(w.cells), double(w.slope));
        s += line;
    }
    s += ");\nconst float kWaveSpeed[4] = float[4](";
    for (int i = 0; i < 4; ++i) {
        std::snprintf(line, sizeof line, "%s%.9g", i ? ", " : "", double(kWaterWaves[i].speed));
        s += line;
    }
    return s + ");\n";
}

} // namespace

int water_decimation(int cols, int rows, int max_size) {
    int k = 1;
    while ((std::max(cols, rows) - 2) / k + 2 > max_size) ++k;
    return k;
}

void WaterPlane::draw(const Environment& env, double eye_y) {
    if (!env.water || eye_y == double(env.water_level)) return;
    const Terrain& t = terrain_;
    if (!program_.get()) {
        GLint max_size = max_size_;
        if (max_size <= 0) glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
        // Texel (i, j) holds the highest sample within k samples of (i k, j k)
        // (for k > 1; else that sample):
        // between two texels the bilinear heights then never pass below the
        // terrain's, so a mirrored ray hits no later than through the full
        // heights, at most k - 1 samples early.
        decimation_ = water_decimation(t.cols(), t.rows(), max_size);
        top_ = t.max_height();
        const int k = decimation_;
        const int w = (t.cols() - 2) / k + 2, h = (t.rows() - 2) / k + 2;
        std::string fs = kWaterFs;
        fs.replace(fs.find("WATER_CONSTANTS"), 15, water_constants());
        program_ = make_program("water", kFullScreenVs, fs.c_str());
        vao_ = make_vertex_array();
        std::vector<float> heights(std::size_t(w) * std::size_t(h));
        std::vector<Rgb8> colors(heights.size());
        const int pad = k > 1 ? k : 0;
        tbb::parallel_for(0, h, [&](int r) {
            const int r0 = std::min(std::max(r * k - pad, 0), t.rows() - 1), r1 = std::min(r * k + pad, t.rows() - 1);
            for (int c = 0; c < w; ++c) {
                const int c0 = std::min(std::max(c * k - pad, 0), t.cols() - 1), c1 = std::min(c * k + pad, t.cols() - 1);
                float top = -std::numeric_limits<float>::max();
                for (int i = r0; i <= r1; ++i)
                    for (int j = c0; j <= c1; ++j) top = std::max(top, t.sample_height(i, j));
                const std::size_t at = std::size_t(r) * std::size_t(w) + std::size_t(c);
                heights[at] = top;
                colors[at] = t.colors()[t.index(std::min(r * k, t.rows() - 1), std::min(c * k, t.cols() - 1))];
            }
        });
        auto texture = [&](GLenum format) {
            Texture tex = make_texture(GL_TEXTURE_2D);
            glTextureStorage2D(tex.get(), 1, format, w, h);
            glTextureParameteri(tex.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTextureParameteri(tex.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            glTextureParameteri(tex.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
            glTextureParameteri(tex.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
            return tex;
        };
        heights_ = texture(GL_R32F);
        colors_ = texture(GL_RGB8);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTextureSubImage2D(heights_.get(), 0, 0, 0, w, h, GL_RED, GL_FLOAT, heights.data());
        glTextureSubImage2D(colors_.get(), 0, 0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, colors.data());
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    }
    glUseProgram(program_.get());
    glUniform4f(glGetUniformLocation(program_.get(), "water"), env.water_level, float(env.water_time),
                top_, env.baked ? 1.0f : 0.0f);
    glUniform1f(glGetUniformLocation(program_.get(), "water_texel"), t.h_scale() * float(decimation_));
    glBindTextureUnit(5, heights_.get());
    glBindTextureUnit(6, colors_.get());
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC1_COLOR);
    glBindVertexArray(vao_.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_BLEND);
}

} // namespace overflight::gl
