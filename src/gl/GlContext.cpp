// Based on: DESIGN sec. 7 (EGL surfaceless Mesa / EGL device headless GL 4.5 core).
#include "gl/GlContext.h"

#include "core/Error.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <array>
#include <mutex>

namespace overflight::gl {

std::string Context::renderer() {
    const auto* s = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    return s ? s : "";
}

std::string Context::version() {
    const auto* s = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    return s ? s : "";
}

namespace {

bool has_extension(EGLDisplay dpy, const char* name) {
    return epoxy_has_egl_extension(dpy, name);
}

// Creates a GL 4.5 core context on an initialised display, or returns EGL_NO_CONTEXT.
EGLContext create_gl45(EGLDisplay dpy) {
    if (!eglBindAPI(EGL_OPENGL_API)) return EGL_NO_CONTEXT;
    // The surfaceless platform has no window configs; a context without a
    // config (EGL_KHR_no_config_context) renders into FBOs only, which is all we need.
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!has_extension(dpy, "EGL_KHR_no_config_context")) {
        const EGLint attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        EGLint n = 0;
        if (!eglChooseConfig(dpy, attribs, &config, 1, &n) || n < 1) return EGL_NO_CONTEXT;
    }
    const EGLint ctx_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4,
                                  EGL_CONTEXT_MINOR_VERSION, 5,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                  EGL_NONE};
    return eglCreateContext(dpy, config, EGL_NO_CONTEXT, ctx_attribs);
}

} // namespace

HeadlessContext::HeadlessContext() {
    // Candidate displays in the order of the design notes: surfaceless Mesa,
    // each EGL device, then whatever the default display is.
    std::array<EGLDeviceEXT, 8> devices{};
    EGLint n_devices = 0;
    const bool client_ext = epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_base");
    if (client_ext && epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_enumeration"))
        eglQueryDevicesEXT(EGLint(devices.size()), devices.data(), &n_devices);

    auto try_display = [&](EGLDisplay dpy, const char* platform) {
        if (dpy == EGL_NO_DISPLAY) return false;
        EGLint major = 0, minor = 0;
        if (!eglInitialize(dpy, &major, &minor)) return false;
        EGLContext ctx = create_gl45(dpy);
        if (ctx == EGL_NO_CONTEXT || !eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
            if (ctx != EGL_NO_CONTEXT) eglDestroyContext(dpy, ctx);
            return false; // the display stays initialised; EGL refcounts it per process
        }
        display_ = dpy;
        context_ = ctx;
        platform_ = platform;
        return true;
    };

    bool ok = false;
    if (client_ext && epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless"))
        ok = try_display(eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
                         "surfaceless");
    for (EGLint i = 0; !ok && i < n_devices; ++i)
        ok = try_display(eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[std::size_t(i)], nullptr), "device");
    if (!ok) ok = try_display(eglGetDisplay(EGL_DEFAULT_DISPLAY), "default");
    if (!ok)
        throw Error("opengl", "no EGL display offers an OpenGL 4.5 core context (install Mesa or a GPU driver)");
}

HeadlessContext::~HeadlessContext() {
    auto dpy = static_cast<EGLDisplay>(display_);
    if (eglGetCurrentContext() == static_cast<EGLContext>(context_))
        eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, static_cast<EGLContext>(context_));
}

void HeadlessContext::make_current() {
    if (!eglMakeCurrent(static_cast<EGLDisplay>(display_), EGL_NO_SURFACE, EGL_NO_SURFACE,
                        static_cast<EGLContext>(context_)))
        throw Error("opengl", "cannot make the headless context current");
}

namespace {
std::mutex glfw_mutex;
int glfw_users = 0;
} // namespace

WindowContext::WindowContext(const std::string& title, int width, int height, bool visible) {
    {
        std::lock_guard lock(glfw_mutex);
        if (glfw_users == 0 && !glfwInit()) throw Error("window", "GLFW cannot initialise (no display?)");
        ++glfw_users;
    }
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_DEPTH_BITS, 24);
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window_) {
        std::lock_guard lock(glfw_mutex);
        if (--glfw_users == 0) glfwTerminate();
        throw Error("window", "cannot open a window with an OpenGL 4.5 core context");
    }
    glfwMakeContextCurrent(window_);
}

WindowContext::~WindowContext() {
    glfwDestroyWindow(window_);
    std::lock_guard lock(glfw_mutex);
    if (--glfw_users == 0) glfwTerminate();
}

void WindowContext::make_current() { glfwMakeContextCurrent(window_); }

void WindowContext::framebuffer_size(int& width, int& height) const { glfwGetFramebufferSize(window_, &width, &height); }

void WindowContext::swap_buffers() { glfwSwapBuffers(window_); }

bool WindowContext::should_close() const { return glfwWindowShouldClose(window_); }

} // namespace overflight::gl
