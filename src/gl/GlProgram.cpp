// Based on: the OpenGL 4.5 core specification (DSA object creation, program linking).
#include "gl/GlProgram.h"

#include "core/Error.h"

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
};

vec4 clip_of(vec3 world) { return view_proj * vec4(world - eye.xyz, 1.0); }

// Lambert sun + ambient (hovercraft sun lighting), then GL_EXP fog with the
// eye distance taken as the length of the eye-space position, i.e. the world
// distance from the eye: f = exp(-density * distance).
vec3 shade(vec3 albedo, vec3 n, vec3 world) {
    float lambert = max(dot(normalize(n), sun_dir.xyz), 0.0);
    vec3 lit = albedo * (ambient.rgb + sun_color.rgb * lambert);
    float f = exp(-fog.a * length(world - eye.xyz));
    return mix(fog.rgb, lit, f);
}
vec3 fogged(vec3 color, vec3 world) {
    return mix(fog.rgb, color, exp(-fog.a * length(world - eye.xyz)));
}
)";

namespace {

GLuint compile(const char* name, GLenum stage, const char* source) {
    const GLuint s = glCreateShader(stage);
    const char* parts[] = {"#version 450 core\n", kFrameGlsl, source};
    glShaderSource(s, 3, parts, nullptr);
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
