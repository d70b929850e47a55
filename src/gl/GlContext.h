#pragma once
// OpenGL 4.5 core contexts: headless through EGL (Mesa's surfaceless platform,
// the EGL device platform on NVIDIA, then the default display) and a GLFW
// window. Both load GL through libepoxy, so the renderer code above them is one
// path for files, benchmarks and the interactive `fly` window.
//
// Based on: DESIGN sec. 7 (headless GL 4.5 through EGL surfaceless Mesa) and
// Szenberg et al. 1997 sec. 5 (objects drawn by OpenGL's Z-buffer).
#include <string>

struct GLFWwindow;

namespace overflight::gl {

class Context {
public:
    virtual ~Context() = default;
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    // Makes this context current on the calling thread.
    virtual void make_current() = 0;
    // GL_RENDERER / GL_VERSION of the current context ("llvmpipe (LLVM 15.0.6, 256 bits)").
    static std::string renderer();
    static std::string version();

protected:
    Context() = default;
};

// A context with no window, for rendering into framebuffer objects. Throws
// Error("opengl", ...) when no EGL display offers an OpenGL 4.5 core context.
class HeadlessContext final : public Context {
public:
    HeadlessContext();
    ~HeadlessContext() override;
    void make_current() override;
    // Which EGL platform gave the display: "surfaceless", "device" or "default".
    const std::string& platform() const { return platform_; }

private:
    void* display_ = nullptr; // EGLDisplay
    void* context_ = nullptr; // EGLContext
    std::string platform_;
};

// A GLFW window with an OpenGL 4.5 core context, current after construction.
// Throws Error("window", ...) when GLFW cannot open one (no display, no GL 4.5).
class WindowContext final : public Context {
public:
    WindowContext(const std::string& title, int width, int height, bool visible = true);
    ~WindowContext() override;
    void make_current() override;
    GLFWwindow* window() const { return window_; }
    // Size of the default framebuffer in pixels (differs from the window size on HiDPI).
    void framebuffer_size(int& width, int& height) const;
    void swap_buffers();
    bool should_close() const;

private:
    GLFWwindow* window_ = nullptr;
};

} // namespace overflight::gl
