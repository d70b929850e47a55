// Based on: the OpenGL 4.5 core specification (DSA object creation, program linking).
#include "gl/GlProgram.h"

#include "core/Error.h"
#include "gl/AtmosphereGlsl.h"

#include <iterator>
#include <string>

namespace overflight::gl {

void delete_buffer(GLuint id) { glDeleteBuffers(1, &id); }
void delete_texture(GLuint id) { glDeleteTextures(1, &id); }
void delete_framebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
void delete_vertex_array(GLuint id) { glDeleteVertexArrays(1, &id); }
void delete_program(GLuint id) { glDeleteProgram(id); }

Buffer make_buffer() { GLuint id = 0; glCreateBuffers(1, &id); return Buffer(id); }
Texture make_texture(GLenum target) { GLuint id = 0; glCreateTextures(target, 1, &id); return Texture(id); }
Framebuffer make_framebuffer() { GLuint id = 0; glCreateFramebuffers(1, &id); return Framebuffer(id); }
VertexArray make_vertex_array() { GLuint id = 0; glCreateVertexArrays(1, &id); return VertexArray(id); }

const char* const kLitFragmentGlsl = R"(
in vec3 v_world;
in vec3 v_normal;
in vec3 v_color;
out vec4 frag;
void main() { frag = vec4(shade(v_color, v_normal, v_world), 1.0); }
)";

const char* const kFrameGlsl = R"(
// One uniform block for the frame (binding 0), filled by FrameUniforms.
layout(std140, binding = 0) uniform Frame {
    mat4 view_proj;    // eye-relative: multiplies (world - eye)
    vec4 eye;          // world eye position
    vec4 sun_dir;      // unit, towards the sun
    vec4 sun_color;
    vec4 ambient;
    vec4 fog;          // rgb = fog color, a = GL_EXP density
    vec4 sky_zenith;
    vec4 sky_horizon;
    vec4 view_axis;    // camera F (shear) or F' (tilt)
    vec4 view_right;   // R
    vec4 view_up;      // Y (shear) or U' (tilt)
    vec4 image;        // width, height, focal length px, shear shift fp*tan(pitch)
    vec4 grid;         // h_scale, min terrain height, rows, cols
    // The atmosphere (core/AerialPerspective.h, AerialFrame):
    vec4 air_beta;     // rgb = beta_c rho0 (extinction at the eye's height), a = scale height H
    vec4 air_rayleigh; // rgb = R_c, a = haze asymmetry g
    vec4 air_haze;     // rgb = M_c, a = 1 when the atmosphere replaces the fog and sky gradient
    vec4 shadow;       // x: 1 = the terrain casts shadows; y: texels per world unit
    vec4 look;         // x: 1 = what is drawn now is baked (the terrain's colors with --lighting baked): no sun;
                       // y: 1 = what is drawn now is the terrain
    vec4 imagery;      // 1 / extent x, 1 / extent z, origin x, z of the imagery (ImageryTexture); 0: none
    vec4 underwater;       // x: 1 = the eye is under the water, y: the water's level
    vec4 water_absorption; // rgb: per world unit of water path
    vec4 water_deep;       // rgb: the deep water's light
    vec4 tile_imagery; // imagery tiles (TiledImageryTexture): 1 / tile world size, coarsest level, page
                       // table's first tile column and row; 0: none
    vec4 tile_imagery_size; // 1 / world width, 1 / world depth of a tile's texels, texels across, down
};
// The terrain's shadow ceiling (core/HorizonSweep.h), one texel per sample.
layout(binding = 7) uniform sampler2D shadow_ceiling;
// The objects' shadow map from the sun (gl/ObjectShadowMap.h).
layout(std140, binding = 3) uniform ObjectShadow {
    mat4 object_sun_proj;  // multiplies (world - object_origin)
    vec4 object_origin;
    vec4 object_shadow;    // x: 1 = objects cast shadows; y: depth bias
};
layout(binding = 8) uniform sampler2DShadow object_shadow_map;
// The vehicle's, fitted to it alone (the same layout).
layout(std140, binding = 4) uniform VehicleShadow {
    mat4 vehicle_sun_proj;
    vec4 vehicle_origin;
    vec4 vehicle_shadow;
};
layout(binding = 11) uniform sampler2DShadow vehicle_shadow_map;
// The terrain's imagery, mipmapped (core/ImageryPyramid.h), over its world rectangle.
layout(binding = 10) uniform sampler2D imagery_texture;
// The imagery tiles near the viewer (gl/TiledImageryTexture.h): a layer per
// tile, and per tile of the page table its layer + 1 (0: none) and the world
// x, z of its first texel.
layout(binding = 12) uniform sampler2DArray imagery_tiles;
layout(binding = 13) uniform sampler2D imagery_pages;

vec4 clip_of(vec3 world) { return view_proj * vec4(world - eye.xyz, 1.0); }

)";

// After the atmosphere (gl/AtmosphereGlsl.h), which reads the Frame block.
const char* const kFrameFunctionsGlsl = R"(
// `color` seen from the eye under the water through the part of the way to
// `world` below the level (core/WaterSurface.h: underwater_path, underwater_color).
vec3 under_water(vec3 color, vec3 world) {
    float len = length(world - eye.xyz);
    float path = world.y > underwater.y ? len * clamp((underwater.y - eye.y) / (world.y - eye.y), 0.0, 1.0) : len;
    vec3 t = exp(-water_absorption.rgb * path);
    return color * t + water_deep.rgb * (1.0 - t);
}
// GL_EXP fog with the eye distance taken as the length of the eye-space
// position, i.e. the world distance from the eye: f = exp(-density *
// distance); or the aerial perspective when the atmosphere is on; then,
// with the eye under the water, the water's extinction.
vec3 fogged(vec3 color, vec3 world) {
    color = air_haze.a > 0.0 ? aerial(color, world) : mix(fog.rgb, color, exp(-fog.a * length(world - eye.xyz)));
    return underwater.x > 0.0 ? under_water(color, world) : color;
}
// How much of the sun `world` sees past the terrain. Each of the four
// samples around it tests the point's height above the ground against its
// ceiling's (texel: r = ceiling - sample height, g = sample height; a terrain
// fragment is on the ground), and the tests are interpolated bilinearly
// (percentage-closer filtering: Reeves, Salesin, Cook, "Rendering Antialiased
// Shadows with Depth Maps", SIGGRAPH 1987): a terrain fragment's shadow ends
// halfway between a shadowed and a lit sample, where the ray caster's blocks
// end it, and a sample's ceiling is never compared with a point below it.
float sun_visible(vec3 world) {
    if (shadow.x == 0.0) return 1.0;
    vec2 p = world.xz * shadow.y;
    ivec2 i = ivec2(floor(p));
    vec2 f = p - vec2(i);
    ivec2 last = textureSize(shadow_ceiling, 0) - 1;
    ivec2 i0 = clamp(i, ivec2(0), last), i1 = clamp(i + 1, ivec2(0), last);
    vec2 t00 = texelFetch(shadow_ceiling, i0, 0).rg, t10 = texelFetch(shadow_ceiling, ivec2(i1.x, i0.y), 0).rg;
    vec2 t01 = texelFetch(shadow_ceiling, ivec2(i0.x, i1.y), 0).rg, t11 = texelFetch(shadow_ceiling, i1, 0).rg;
    float ground = mix(mix(t00.g, t10.g, f.x), mix(t01.g, t11.g, f.x), f.y);
    float above = look.y > 0.0 ? 0.0 : world.y - ground;
    return mix(mix(step(t00.r, above), step(t10.r, above), f.x), mix(step(t01.r, above), step(t11.r, above), f.x), f.y);
}
// The window coordinates of `world` in a shadow map's sun view; false
// outside the map (where nothing it holds casts a shadow).
bool in_sun_view(mat4 sun_proj, vec3 origin, vec3 world, out vec3 q) {
    vec4 p = sun_proj * vec4(world - origin, 1.0);
    q = p.xyz / p.w * 0.5 + 0.5;
    return !(any(lessThan(q.xy, vec2(0.0))) || any(greaterThan(q.xy, vec2(1.0))) || q.z <= 0.0);
}
// How much of the sun `world` sees past the objects and the vehicle (1
// outside their maps).
float object_sun_visible(vec3 world) {
    float v = 1.0;
    vec3 q;
    if (object_shadow.x != 0.0 && in_sun_view(object_sun_proj, object_origin.xyz, world, q))
        v = texture(object_shadow_map, vec3(q.xy, min(q.z, 1.0) - object_shadow.y));
    if (vehicle_shadow.x != 0.0 && in_sun_view(vehicle_sun_proj, vehicle_origin.xyz, world, q))
        v *= texture(vehicle_shadow_map, vec3(q.xy, min(q.z, 1.0) - vehicle_shadow.y));
    return v;
}
// A terrain fragment's albedo: the imagery at its world (x, z) when the
// terrain has imagery finer than its samples (whose per-vertex colors are
// that imagery averaged), else the vertex color. With imagery tiles, the
// fragment's tile's layer, sampled with the gradients of the world position
// (continuous across tiles, unlike the tiles' texture coordinates), handed
// over to the vertex color over the level after the tile's coarsest.
// The tile (column, row) whose imagery a terrain fragment samples: set by a
// mesh whose triangles each belong to one tile (StreamedMesh); -1: the tile
// under the fragment.
ivec2 albedo_tile = ivec2(-1);
vec3 terrain_albedo(vec3 albedo, vec3 world) {
#ifdef OVERFLIGHT_FRAGMENT_STAGE
    vec2 dx = dFdx(world.xz), dy = dFdy(world.xz);
#endif
    if (imagery.x > 0.0 && look.y > 0.0) return texture(imagery_texture, (world.xz - imagery.zw) * imagery.xy).rgb;
#ifdef OVERFLIGHT_FRAGMENT_STAGE
    if (tile_imagery.x > 0.0 && look.y > 0.0) {
        ivec2 t = (albedo_tile.x >= 0 ? albedo_tile : ivec2(floor(world.xz * tile_imagery.x))) - ivec2(tile_imagery.zw);
        if (all(greaterThanEqual(t, ivec2(0))) && all(lessThan(t, textureSize(imagery_pages, 0)))) {
            vec4 page = texelFetch(imagery_pages, t, 0);
            if (page.x > 0.0) {
                vec2 s = tile_imagery_size.xy;
                vec2 gx = dx * s, gy = dy * s;
                vec2 tx = gx * tile_imagery_size.zw, ty = gy * tile_imagery_size.zw;
                float lod = 0.5 * log2(max(max(dot(tx, tx), dot(ty, ty)), 1e-12));
                vec3 c = textureGrad(imagery_tiles, vec3((world.xz - page.yz) * s, page.x - 1.0), gx, gy).rgb;
                return mix(c, albedo, clamp(lod - tile_imagery.y, 0.0, 1.0));
            }
        }
    }
#endif
    return albedo;
}
// Lambert sun + ambient (hovercraft sun lighting; core/SunLight.h is the same
// per sample: no sun at or below the horizon, none in the terrain's shadow),
// then fogged().
vec3 shade(vec3 albedo, vec3 n, vec3 world) {
    albedo = terrain_albedo(albedo, world);
    if (look.x > 0.0) return fogged(albedo, world);
    float lambert = sun_dir.y > 0.0 ? max(dot(normalize(n), sun_dir.xyz), 0.0) * sun_visible(world) * object_sun_visible(world) : 0.0;
    vec3 lit = albedo * (ambient.rgb + sun_color.rgb * lambert);
    return fogged(lit, world);
}
)";

namespace {

GLuint compile(const char* name, GLenum stage, const char* source) {
    const GLuint s = glCreateShader(stage);
    // Derivatives (terrain_albedo's imagery tiles) exist in fragment shaders only.
    const char* stage_define = stage == GL_FRAGMENT_SHADER ? "#define OVERFLIGHT_FRAGMENT_STAGE 1\n" : "";
    const char* parts[] = {"#version 450 core\n", stage_define, kFrameGlsl, kAtmosphereGlsl, kFrameFunctionsGlsl,
                           source};
    glShaderSource(s, GLsizei(std::size(parts)), parts, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        std::string log(4096, '\0');
        GLsizei n = 0;
        glGetShaderInfoLog(s, GLsizei(log.size()), &n, log.data());
        log.resize(std::size_t(n));
        glDeleteShader(s);
        for (char& c : log) if (c == '\n') c = ' ';
        throw Error("opengl", std::string("shader ") + name + ": " + log);
    }
    return s;
}

} // namespace

Program make_program(const char* name, const char* vertex, const char* fragment) {
    const GLuint vs = compile(name, GL_VERTEX_SHADER, vertex);
    GLuint fs = 0;
    try {
        fs = compile(name, GL_FRAGMENT_SHADER, fragment);
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    Program p(glCreateProgram());
    glAttachShader(p.get(), vs);
    glAttachShader(p.get(), fs);
    glLinkProgram(p.get());
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(p.get(), GL_LINK_STATUS, &ok);
    if (!ok) {
        std::string log(4096, '\0');
        GLsizei n = 0;
        glGetProgramInfoLog(p.get(), GLsizei(log.size()), &n, log.data());
        log.resize(std::size_t(n));
        for (char& c : log) if (c == '\n') c = ' ';
        throw Error("opengl", std::string("program ") + name + ": " + log);
    }
    return p;
}

} // namespace overflight::gl
