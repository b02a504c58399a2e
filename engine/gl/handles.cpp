#include "engine/gl/handles.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <sstream>

#include "engine/core/error.hpp"

namespace lp::gl {
namespace {
std::atomic<long> gLiveObjects{0};
}

long liveObjectCount() { return gLiveObjects.load(); }

namespace detail {
void countCreated() { ++gLiveObjects; }
void countDeleted() { --gLiveObjects; }

void deleteObject(ObjectKind kind, GLuint id) {
    switch (kind) {
        case ObjectKind::Texture: glDeleteTextures(1, &id); break;
        case ObjectKind::Buffer: glDeleteBuffers(1, &id); break;
        case ObjectKind::Framebuffer: glDeleteFramebuffers(1, &id); break;
        case ObjectKind::Program: glDeleteProgram(id); break;
        case ObjectKind::Shader: glDeleteShader(id); break;
        case ObjectKind::VertexArray: glDeleteVertexArrays(1, &id); break;
        case ObjectKind::Query: glDeleteQueries(1, &id); break;
        case ObjectKind::Sampler: glDeleteSamplers(1, &id); break;
    }
}
}  // namespace detail

void label(GLenum identifier, GLuint id, const std::string& name) {
    if (!id || name.empty() || !glObjectLabel) return;
    // A label must be shorter than GL_MAX_LABEL_LENGTH (256 at least): a long name (a file's path,
    // a model's own text) keeps its end, where the file name is.
    GLint maxLength = 256;
    glGetIntegerv(GL_MAX_LABEL_LENGTH, &maxLength);
    const size_t keep = std::min(name.size(), size_t(std::max(maxLength - 1, 1)));
    glObjectLabel(identifier, id, GLsizei(keep), name.c_str() + (name.size() - keep));
}

int fullMipCount(int width, int height) {
    return 1 + int(std::floor(std::log2(double(std::max({width, height, 1})))));
}

Texture makeTexture2D(GLenum internalFormat, int width, int height, int levels, const std::string& name) {
    if (width <= 0 || height <= 0) throw Error("texture '" + name + "': invalid size");
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &id);
    Texture t{Object<ObjectKind::Texture>(id), GL_TEXTURE_2D, internalFormat, width, height, levels};
    glTextureStorage2D(id, levels, internalFormat, width, height);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, levels > 1 ? GL_LINEAR : GL_NEAREST);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    label(GL_TEXTURE, id, name);
    checkErrors("creating texture '" + name + "' (" + std::to_string(width) + "x" + std::to_string(height) + " " +
                formatName(internalFormat) + ")");
    return t;
}

Texture makeTextureView(const Texture& source, GLenum internalFormat, const std::string& name) {
    GLuint id = 0;
    glGenTextures(1, &id);  // a view needs a name never bound (glCreateTextures binds it)
    glTextureView(id, GL_TEXTURE_2D, source.id(), internalFormat, 0, GLuint(source.levels), 0, 1);
    Texture t{Object<ObjectKind::Texture>(id), GL_TEXTURE_2D, internalFormat, source.width, source.height, source.levels};
    label(GL_TEXTURE, id, name);
    checkErrors("creating texture view '" + name + "' (" + formatName(internalFormat) + " of " +
                formatName(source.format) + ")");
    return t;
}

GLenum imageFormatOf(GLenum internalFormat) { return internalFormat == GL_SRGB8_ALPHA8 ? GL_RGBA8 : internalFormat; }

Texture makeTexture2DArray(GLenum internalFormat, int width, int height, int layers, const std::string& name) {
    if (width <= 0 || height <= 0 || layers <= 0) throw Error("texture array '" + name + "': invalid size");
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &id);
    Texture t{Object<ObjectKind::Texture>(id), GL_TEXTURE_2D_ARRAY, internalFormat, width, height, 1};
    glTextureStorage3D(id, 1, internalFormat, width, height, layers);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    label(GL_TEXTURE, id, name);
    checkErrors("creating texture array '" + name + "' (" + std::to_string(width) + "x" + std::to_string(height) + " x " +
                std::to_string(layers) + " " + formatName(internalFormat) + ")");
    return t;
}

Texture makeTextureCube(GLenum internalFormat, int size, int levels, const std::string& name) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &id);
    Texture t{Object<ObjectKind::Texture>(id), GL_TEXTURE_CUBE_MAP, internalFormat, size, size, levels};
    glTextureStorage2D(id, levels, internalFormat, size, size);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    label(GL_TEXTURE, id, name);
    checkErrors("creating cube texture '" + name + "'");
    return t;
}

Buffer makeBuffer(GLsizeiptr size, const void* data, GLbitfield flags, const std::string& name) {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    Buffer b(id);
    glNamedBufferStorage(id, std::max<GLsizeiptr>(size, 1), data, flags);
    label(GL_BUFFER, id, name);
    checkErrors("creating buffer '" + name + "' (" + std::to_string(size) + " bytes)");
    return b;
}

Framebuffer makeFramebuffer(const std::string& name) {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    Framebuffer f(id);
    label(GL_FRAMEBUFFER, id, name);
    return f;
}

VertexArray makeVertexArray(const std::string& name) {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    VertexArray v(id);
    label(GL_VERTEX_ARRAY, id, name);
    return v;
}

Sampler makeSampler(const std::string& name) {
    GLuint id = 0;
    glCreateSamplers(1, &id);
    Sampler s(id);
    label(GL_SAMPLER, id, name);
    return s;
}

Query makeQuery(GLenum target) {
    GLuint id = 0;
    glCreateQueries(target, 1, &id);
    return Query(id);
}

int bytesPerTexel(GLenum f) {
    switch (f) {
        case GL_R8: return 1;
        case GL_RG8: case GL_R16F: case GL_R16UI: case GL_DEPTH_COMPONENT16: return 2;
        case GL_RGBA8: case GL_SRGB8_ALPHA8: case GL_R32F: case GL_RG16F: case GL_RGB10_A2:
        case GL_R11F_G11F_B10F: case GL_DEPTH_COMPONENT32F: case GL_DEPTH24_STENCIL8: case GL_R32UI:
        case GL_RG16: case GL_RGBA8UI: return 4;
        case GL_RGBA16F: case GL_RG32F: case GL_RGBA16: return 8;
        case GL_RGB32F: return 12;
        case GL_RGBA32F: return 16;
        default: return 4;
    }
}

ClearFormat clearFormatFor(GLenum f) {
    switch (f) {
        case GL_R16UI: case GL_R32UI: case GL_RGBA8UI: return {GL_RED_INTEGER, GL_UNSIGNED_INT};
        case GL_DEPTH_COMPONENT16: case GL_DEPTH_COMPONENT24: case GL_DEPTH_COMPONENT32F:
            return {GL_DEPTH_COMPONENT, GL_FLOAT};
        case GL_DEPTH24_STENCIL8: return {GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8};
        default: return {GL_RGBA, GL_FLOAT};
    }
}

const char* formatName(GLenum f) {
    switch (f) {
        case GL_R8: return "R8";
        case GL_RG8: return "RG8";
        case GL_RGBA8: return "RGBA8";
        case GL_SRGB8_ALPHA8: return "SRGB8_A8";
        case GL_R16F: return "R16F";
        case GL_RG16F: return "RG16F";
        case GL_RGBA16F: return "RGBA16F";
        case GL_R32F: return "R32F";
        case GL_RG32F: return "RG32F";
        case GL_RGB32F: return "RGB32F";
        case GL_RGBA32F: return "RGBA32F";
        case GL_RGB10_A2: return "RGB10_A2";
        case GL_R11F_G11F_B10F: return "R11G11B10F";
        case GL_RG16: return "RG16";
        case GL_RGBA16: return "RGBA16";
        case GL_R32UI: return "R32UI";
        case GL_R16UI: return "R16UI";
        case GL_DEPTH_COMPONENT32F: return "D32F";
        case GL_DEPTH_COMPONENT16: return "D16";
        case GL_DEPTH24_STENCIL8: return "D24S8";
        default: return "?";
    }
}

void checkErrors(const std::string& where) {
#ifdef LIGHTPASS_GL_CHECKS
    GLenum err = glGetError();
    if (err == GL_NO_ERROR) return;
    std::ostringstream msg;
    if (err == GL_OUT_OF_MEMORY) {
        msg << "GL out of memory while " << where;
    } else {
        msg << "GL error 0x" << std::hex << err << " in " << where;
    }
    while (glGetError() != GL_NO_ERROR) {
    }
    throw Error(msg.str());
#else
    (void)where;
#endif
}

DebugGroup::DebugGroup(const std::string& name) {
    glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, GLsizei(name.size()), name.c_str());
}
DebugGroup::~DebugGroup() { glPopDebugGroup(); }

Fence Fence::insert() {
    Fence f;
    f.sync_ = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    return f;
}

Fence::~Fence() {
    if (sync_) glDeleteSync(sync_);
}

Fence& Fence::operator=(Fence&& other) noexcept {
    if (this != &other) {
        if (sync_) glDeleteSync(sync_);
        sync_ = other.sync_;
        other.sync_ = nullptr;
    }
    return *this;
}

bool Fence::signaled() const {
    if (!sync_) return false;
    // A status query, not glClientWaitSync: no flush, so asking costs the GPU's queue nothing.
    GLint status = GL_UNSIGNALED;
    glGetSynciv(sync_, GL_SYNC_STATUS, 1, nullptr, &status);
    return status == GL_SIGNALED;
}

}  // namespace lp::gl
