#include "engine/gl/limits.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>

#include "engine/core/error.hpp"
#include "engine/gl/gl.hpp"

namespace lp::gl {
namespace {

bool hasExtension(const char* name) {
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint i = 0; i < count; ++i) {
        const auto* ext = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)));
        if (ext && std::strcmp(ext, name) == 0) return true;
    }
    return false;
}

// MemAvailable from /proc/meminfo: what a software rasteriser can allocate.
int64_t systemAvailableBytes() {
    std::ifstream in("/proc/meminfo");
    for (std::string key; in >> key;) {
        int64_t kib = 0;
        in >> kib;
        if (key == "MemAvailable:") return kib * 1024;
        in.ignore(256, '\n');
    }
    return -1;
}

std::string gib(double bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f GiB", bytes / (1024.0 * 1024.0 * 1024.0));
    return text;
}

// A pixel format and type the driver accepts beside internalFormat in glTexImage2D (the data
// pointer is null: only their compatibility matters).
std::pair<GLenum, GLenum> uploadFormatFor(GLenum internalFormat) {
    switch (internalFormat) {
        case GL_DEPTH_COMPONENT16:
        case GL_DEPTH_COMPONENT24:
        case GL_DEPTH_COMPONENT32:
        case GL_DEPTH_COMPONENT32F: return {GL_DEPTH_COMPONENT, GL_FLOAT};
        case GL_DEPTH24_STENCIL8: return {GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8};
        case GL_DEPTH32F_STENCIL8: return {GL_DEPTH_STENCIL, GL_FLOAT_32_UNSIGNED_INT_24_8_REV};
        case GL_R8UI: case GL_R16UI: case GL_R32UI: case GL_RG8UI: case GL_RG16UI: case GL_RG32UI:
        case GL_RGBA8UI: case GL_RGBA16UI: case GL_RGBA32UI: case GL_RGB10_A2UI:
            return {GL_RGBA_INTEGER, GL_UNSIGNED_INT};
        case GL_R8I: case GL_R16I: case GL_R32I: case GL_RG8I: case GL_RG16I: case GL_RG32I:
        case GL_RGBA8I: case GL_RGBA16I: case GL_RGBA32I:
            return {GL_RGBA_INTEGER, GL_INT};
        default: return {GL_RGBA, GL_FLOAT};
    }
}

}  // namespace

uint64_t maxShaderStorageBlockBytes() {
    if (!glGetString(GL_RENDERER)) return 0;
    GLint64 bytes = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &bytes);
    return bytes > 0 ? uint64_t(bytes) : 0;
}

bool canAllocateTexture(unsigned internalFormat, int width, int height) {
    // The probe must not reach the log as a GL error, whatever the driver thinks of it.
    const bool debugOutput = glIsEnabled(GL_DEBUG_OUTPUT);
    if (debugOutput) glDisable(GL_DEBUG_OUTPUT);
    while (glGetError() != GL_NO_ERROR) {
    }
    const auto [format, type] = uploadFormatFor(GLenum(internalFormat));
    glTexImage2D(GL_PROXY_TEXTURE_2D, 0, GLint(internalFormat), width, height, 0, format, type, nullptr);
    GLint probedWidth = 0;
    glGetTexLevelParameteriv(GL_PROXY_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, &probedWidth);
    const bool failed = glGetError() != GL_NO_ERROR;
    while (glGetError() != GL_NO_ERROR) {
    }
    if (debugOutput) glEnable(GL_DEBUG_OUTPUT);
    return failed || probedWidth != 0;  // a probe the driver rejects outright decides nothing
}

TextureFit fitTexture(unsigned internalFormat, int width, int height) {
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    TextureFit fit;
    int w = width, h = height;
    auto overSide = [&] { return maxSize > 0 && (w > maxSize || h > maxSize); };
    if (overSide()) fit.reason = "larger than this GPU's " + std::to_string(maxSize) + " texel limit (GL_MAX_TEXTURE_SIZE)";
    while ((w > 1 || h > 1) && (overSide() || !canAllocateTexture(internalFormat, w, h))) {
        if (fit.reason.empty()) fit.reason = "more than this GPU allocates for one texture";
        w = std::max(w / 2, 1);
        h = std::max(h / 2, 1);
        ++fit.halvings;
    }
    return fit;
}

RenderTargetLimits queryRenderTargetLimits(bool softwareRasteriser) {
    RenderTargetLimits l;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &l.maxTextureSize);
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, l.maxViewport);
    glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &l.maxFramebuffer[0]);
    glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &l.maxFramebuffer[1]);
    constexpr GLenum kNvxCurrentAvailableKib = 0x9049;  // GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX
    constexpr GLenum kAtiTextureFreeMemory = 0x87FC;    // GL_TEXTURE_FREE_MEMORY_ATI: 4 ints, [0] in KiB
    if (softwareRasteriser) {
        l.freeBytes = systemAvailableBytes();
    } else if (hasExtension("GL_NVX_gpu_memory_info")) {
        GLint kib = 0;
        glGetIntegerv(kNvxCurrentAvailableKib, &kib);
        if (kib > 0) l.freeBytes = int64_t(kib) * 1024;
    } else if (hasExtension("GL_ATI_meminfo")) {
        GLint info[4] = {0, 0, 0, 0};
        glGetIntegerv(kAtiTextureFreeMemory, info);
        if (info[0] > 0) l.freeBytes = int64_t(info[0]) * 1024;
    }
    while (glGetError() != GL_NO_ERROR) {  // a query this driver lacks must not fail the next check
    }
    // LIGHTPASS_GPU_FREE_BYTES=N: pretend N bytes are free (tests of the check; a GPU shared with others).
    if (const char* free = std::getenv("LIGHTPASS_GPU_FREE_BYTES")) {
        char* end = nullptr;
        const long long n = std::strtoll(free, &end, 10);
        if (end != free && *end == '\0' && n > 0) l.freeBytes = n;
    }
    return l;
}

void requireRenderSizeFits(int width, int height, size_t renderTargetBytes, const RenderTargetLimits& l) {
    const std::string size = "--size " + std::to_string(width) + "x" + std::to_string(height);
    auto over = [&](int limit, const char* name) {
        if (limit > 0 && (width > limit || height > limit))
            throw Error(size + ": larger than this GPU's limit of " + std::to_string(limit) + " (" + name + ")");
    };
    over(l.maxTextureSize, "GL_MAX_TEXTURE_SIZE");
    if (l.maxViewport[0] > 0 && (width > l.maxViewport[0] || height > l.maxViewport[1]))
        throw Error(size + ": larger than this GPU's viewport limit of " + std::to_string(l.maxViewport[0]) + "x" +
                    std::to_string(l.maxViewport[1]) + " (GL_MAX_VIEWPORT_DIMS)");
    if (l.maxFramebuffer[0] > 0 && (width > l.maxFramebuffer[0] || height > l.maxFramebuffer[1]))
        throw Error(size + ": larger than this GPU's framebuffer limit of " + std::to_string(l.maxFramebuffer[0]) + "x" +
                    std::to_string(l.maxFramebuffer[1]) + " (GL_MAX_FRAMEBUFFER_WIDTH/HEIGHT)");
    if (l.freeBytes > 0 && double(renderTargetBytes) > 0.9 * double(l.freeBytes))
        throw Error(size + ": the frame's render targets need " + gib(double(renderTargetBytes)) + ", more than the " +
                    gib(double(l.freeBytes)) + " this GPU has free");
}

}  // namespace lp::gl
