#pragma once
// Owning handles for GL objects and shader program compilation. Every failure
// becomes Error("opengl", ...) with the driver's log, so a broken shader is one
// line, not a crash.
#include <epoxy/gl.h>

#include <utility>

namespace overflight::gl {

// A GL object name with its delete function; movable, not copyable.
template <void (*Delete)(GLuint)>
class Handle {
public:
    Handle() = default;
    explicit Handle(GLuint id) : id_(id) {}
    ~Handle() { reset(); }
    Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
    Handle& operator=(Handle&& o) noexcept { if (this != &o) { reset(); id_ = std::exchange(o.id_, 0); } return *this; }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    GLuint get() const { return id_; }
    explicit operator bool() const { return id_ != 0; }
    void reset() { if (id_) Delete(id_); id_ = 0; }

private:
    GLuint id_ = 0;
};

void delete_buffer(GLuint id);
void delete_texture(GLuint id);
void delete_framebuffer(GLuint id);
void delete_vertex_array(GLuint id);
void delete_program(GLuint id);

using Buffer = Handle<delete_buffer>;
using Texture = Handle<delete_texture>;
using Framebuffer = Handle<delete_framebuffer>;
using VertexArray = Handle<delete_vertex_array>;
using Program = Handle<delete_program>;

Buffer make_buffer();
Texture make_texture(GLenum target);
Framebuffer make_framebuffer();
VertexArray make_vertex_array();

// Compiles and links a program from GLSL 450 sources (geometry stage optional).
// Throws Error("opengl", "shader NAME: <log>") on a compile or link error.
Program make_program(const char* name, const char* vertex, const char* fragment);

// GLSL shared by every lit program: the Frame uniform block, Lambert sun +
// ambient and GL_EXP fog. Prepended to each shader after "#version 450 core".
extern const char* const kFrameGlsl;

// The fragment shader of every lit terrain program: shade() of the
// interpolated world position, normal and color (v_world, v_normal, v_color).
extern const char* const kLitFragmentGlsl;

} // namespace overflight::gl
