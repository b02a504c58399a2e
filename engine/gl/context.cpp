#include "engine/gl/context.hpp"

#include <cstdlib>
#include <vector>

#include <glad/egl.h>
#include <glad/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"

namespace lp::gl {

bool GpuContext::isNvidia() const { return info_.vendor.find("NVIDIA") != std::string::npos; }
bool GpuContext::isSoftware() const { return isSoftwareRenderer(info_.renderer); }

bool isSoftwareRenderer(const std::string& r) {
    return r.find("llvmpipe") != std::string::npos || r.find("softpipe") != std::string::npos ||
           r.find("SwiftShader") != std::string::npos;
}

bool currentContextIsSoftware() {
    const GLubyte* r = glGetString(GL_RENDERER);
    return !r || isSoftwareRenderer(reinterpret_cast<const char*>(r));
}

namespace {

void GLAD_API_PTR debugCallback(GLenum source, GLenum type, GLuint, GLenum severity, GLsizei, const GLchar* message,
                                const void*) {
    if (source == GL_DEBUG_SOURCE_APPLICATION) return;  // our own push/pop groups
    std::string text = std::string("GL: ") + message;
#ifdef LIGHTPASS_GL_CHECKS
    // checkErrors turns an out-of-memory into the one error line naming what was being allocated;
    // the driver's own wording of it would be a second, raw line.
    if (type == GL_DEBUG_TYPE_ERROR && text.find("GL_OUT_OF_MEMORY") != std::string::npos) {
        logDebug(text);
        return;
    }
#endif
    if (type == GL_DEBUG_TYPE_ERROR) {
        logError(text);
    } else if (severity == GL_DEBUG_SEVERITY_HIGH) {
        logWarn(text);
    } else {
        logDebug(text);
    }
}

void requireGl45(const std::string& platform) {
    if (!GLAD_GL_VERSION_4_5)
        throw Error(platform + ": OpenGL 4.5 core is required, got " +
                    std::string(reinterpret_cast<const char*>(glGetString(GL_VERSION))));
}

class EglContext final : public GpuContext {
public:
    EglContext(EGLDisplay display, EGLContext context, const std::string& deviceName)
        : display_(display), context_(context) {
        info_ = queryContextInfo("EGL device (" + deviceName + ")");
    }
    ~EglContext() override {
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display_, context_);
        eglTerminate(display_);
    }
    bool hasWindow() const override { return false; }
    glm::ivec2 framebufferSize() const override { return {0, 0}; }
    void swapBuffers() override {}

private:
    EGLDisplay display_;
    EGLContext context_;
};

// Tries to make a GL 4.5 core context on one EGL device; returns nullptr with a reason on failure.
std::unique_ptr<GpuContext> tryDevice(EGLDeviceEXT device, const std::string& name, std::string& reason) {
    EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
    if (display == EGL_NO_DISPLAY) {
        reason = name + ": no display";
        return nullptr;
    }
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) {
        reason = name + ": eglInitialize failed";
        return nullptr;
    }
    gladLoaderLoadEGL(display);  // display-level extensions and 1.5 entry points
    if (!eglBindAPI(EGL_OPENGL_API)) {
        eglTerminate(display);
        reason = name + ": no desktop OpenGL";
        return nullptr;
    }
    const EGLint configAttribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    eglChooseConfig(display, configAttribs, &config, 1, &count);
    const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_CONTEXT_OPENGL_DEBUG, EGL_TRUE, EGL_NONE};
    EGLContext context = eglCreateContext(display, count > 0 ? config : EGLConfig(nullptr), EGL_NO_CONTEXT, contextAttribs);
    if (context == EGL_NO_CONTEXT) {
        eglTerminate(display);
        reason = name + ": no OpenGL 4.5 core context (EGL error 0x" + std::to_string(eglGetError()) + ")";
        return nullptr;
    }
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        eglDestroyContext(display, context);
        eglTerminate(display);
        reason = name + ": surfaceless eglMakeCurrent failed";
        return nullptr;
    }
    if (!gladLoadGL(reinterpret_cast<GLADloadfunc>(eglGetProcAddress))) {
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display, context);
        eglTerminate(display);
        reason = name + ": could not load OpenGL entry points";
        return nullptr;
    }
    return std::make_unique<EglContext>(display, context, name);
}

std::string deviceName(EGLDeviceEXT device) {
    const char* ext = eglQueryDeviceStringEXT ? eglQueryDeviceStringEXT(device, EGL_EXTENSIONS) : nullptr;
    std::string extensions = ext ? ext : "";
    if (extensions.find("EGL_NV_device_cuda") != std::string::npos) return "NVIDIA";
    if (extensions.find("EGL_MESA_device_software") != std::string::npos) return "Mesa software";
    const char* drm = (extensions.find("EGL_EXT_device_drm") != std::string::npos)
                          ? eglQueryDeviceStringEXT(device, EGL_DRM_DEVICE_FILE_EXT)
                          : nullptr;
    return drm ? std::string("DRM ") + drm : std::string("unknown");
}

}  // namespace

ContextInfo queryContextInfo(const std::string& platform) {
    auto str = [](GLenum e) {
        const GLubyte* s = glGetString(e);
        return s ? std::string(reinterpret_cast<const char*>(s)) : std::string();
    };
    return ContextInfo{str(GL_VENDOR), str(GL_RENDERER), str(GL_VERSION), platform};
}

void installDebugOutput() {
    if (!GLAD_GL_KHR_debug && !GLAD_GL_VERSION_4_3) return;
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(debugCallback, nullptr);
}

std::unique_ptr<GpuContext> createHeadlessContext(const ContextOptions& options) {
    if (!gladLoaderLoadEGL(EGL_NO_DISPLAY))
        throw Error("headless OpenGL: libEGL.so.1 not found (install libegl1 and a driver: Mesa or NVIDIA)");
    if (!eglQueryDevicesEXT || !eglGetPlatformDisplayEXT)
        throw Error("headless OpenGL: EGL has no EGL_EXT_platform_device (device enumeration)");
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (!eglQueryDevicesEXT(16, devices, &count) || count == 0)
        throw Error("headless OpenGL: EGL reports no devices");

    // Order: an explicit choice, else NVIDIA devices first, then the rest (Mesa's llvmpipe last).
    std::vector<int> order;
    if (const char* pick = std::getenv("LIGHTPASS_EGL_DEVICE")) {
        int i = std::atoi(pick);
        if (i < 0 || i >= count)
            throw Error("LIGHTPASS_EGL_DEVICE=" + std::string(pick) + ": only " + std::to_string(count) + " EGL devices");
        order.push_back(i);
    } else {
        for (int i = 0; i < count; ++i)
            if (deviceName(devices[i]) == "NVIDIA") order.push_back(i);
        for (int i = 0; i < count; ++i)
            if (deviceName(devices[i]) != "NVIDIA" && deviceName(devices[i]) != "Mesa software") order.push_back(i);
        for (int i = 0; i < count; ++i)
            if (deviceName(devices[i]) == "Mesa software") order.push_back(i);
    }
    std::string reasons;
    for (int i : order) {
        std::string reason;
        auto ctx = tryDevice(devices[i], deviceName(devices[i]), reason);
        if (ctx) {
            requireGl45(ctx->info().platform);
            if (options.debugOutput) installDebugOutput();
            return ctx;
        }
        reasons += (reasons.empty() ? "" : "; ") + reason;
    }
    throw Error("headless OpenGL: no EGL device gave a GL 4.5 core context (" + reasons + ")");
}

bool displayAvailable() {
    const char* x = std::getenv("DISPLAY");
    const char* w = std::getenv("WAYLAND_DISPLAY");
    return (x && *x) || (w && *w);
}

namespace {
class GlfwContext final : public GpuContext {
public:
    explicit GlfwContext(GLFWwindow* w) : window_(w) { info_ = queryContextInfo("GLFW window"); }
    ~GlfwContext() override {
        glfwDestroyWindow(window_);
        glfwTerminate();
    }
    bool hasWindow() const override { return true; }
    glm::ivec2 framebufferSize() const override {
        int w = 0, h = 0;
        glfwGetFramebufferSize(window_, &w, &h);
        return {w, h};
    }
    void swapBuffers() override { glfwSwapBuffers(window_); }
    GLFWwindow* window() override { return window_; }

private:
    GLFWwindow* window_;
};

void glfwErrorToLog(int code, const char* description) {
    logDebug("GLFW error " + std::to_string(code) + ": " + description);
}
}  // namespace

std::unique_ptr<GpuContext> createWindowContext(const ContextOptions& options) {
    if (!displayAvailable())
        throw Error("no display (DISPLAY and WAYLAND_DISPLAY are unset); render headless with 'lightpass render'");
    glfwSetErrorCallback(glfwErrorToLog);
    if (!glfwInit()) throw Error("GLFW could not initialise the display '" + std::string(std::getenv("DISPLAY") ? std::getenv("DISPLAY") : "") + "'");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, options.visible ? GLFW_TRUE : GLFW_FALSE);
    GLFWwindow* window = glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
    if (!window) {
        glfwTerminate();
        throw Error("GLFW: could not create an OpenGL 4.5 core window on this display");
    }
    glfwMakeContextCurrent(window);
    if (!gladLoadGL(glfwGetProcAddress)) {
        glfwDestroyWindow(window);
        glfwTerminate();
        throw Error("GLFW: could not load OpenGL entry points");
    }
    glfwSwapInterval(options.vsync ? 1 : 0);
    auto ctx = std::make_unique<GlfwContext>(window);
    requireGl45("GLFW window");
    if (options.debugOutput) installDebugOutput();
    return ctx;
}

}  // namespace lp::gl
