#pragma once
// Where frames are drawn: a GLFW window (GL 4.5 core) or headless EGL on the device platform.
// Both load the same GL 4.5 core entry points, so every pass runs unchanged on either.
#include <memory>
#include <string>

#include <glm/glm.hpp>

struct GLFWwindow;

namespace lp::gl {

struct ContextOptions {
    int width = 1280;
    int height = 720;
    std::string title = "lightpass";
    bool vsync = true;
    bool visible = true;   // window only
    bool debugOutput = true;  // KHR_debug messages to the log
};

struct ContextInfo {
    std::string vendor;
    std::string renderer;
    std::string version;
    std::string platform;  // "EGL device (NVIDIA)", "GLFW window", ...
};

class GpuContext {
public:
    virtual ~GpuContext() = default;
    virtual bool hasWindow() const = 0;
    virtual glm::ivec2 framebufferSize() const = 0;
    virtual void swapBuffers() = 0;
    virtual GLFWwindow* window() { return nullptr; }
    const ContextInfo& info() const { return info_; }
    bool isNvidia() const;
    bool isSoftware() const;  // llvmpipe & co.: timings mean nothing there

protected:
    ContextInfo info_;
};

// A GL_RENDERER string of a software rasteriser (llvmpipe, softpipe, SwiftShader); the current
// context's (true without one).
bool isSoftwareRenderer(const std::string& renderer);
bool currentContextIsSoftware();

// Headless: EGL_EXT_platform_device, preferring an NVIDIA device, else Mesa's software device.
// LIGHTPASS_EGL_DEVICE=N picks device N. Throws lp::Error with one line when nothing works.
std::unique_ptr<GpuContext> createHeadlessContext(const ContextOptions& options = {});
// A GLFW window with a GL 4.5 core context. Throws lp::Error when there is no display.
std::unique_ptr<GpuContext> createWindowContext(const ContextOptions& options);
bool displayAvailable();

// Installs the KHR_debug callback (errors logged as errors, the rest at debug level).
void installDebugOutput();
ContextInfo queryContextInfo(const std::string& platform);

}  // namespace lp::gl
