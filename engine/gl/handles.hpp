#pragma once
// Move-only RAII owners for GL objects. Every constructor labels the object (glObjectLabel) so
// RenderDoc and apitrace show names; a live-object count lets tests prove nothing leaks.
#include <string>
#include <utility>

#include "engine/gl/gl.hpp"

namespace lp::gl {

enum class ObjectKind { Texture, Buffer, Framebuffer, Program, Shader, VertexArray, Query, Sampler };

// Number of GL objects created through these types and not yet deleted.
long liveObjectCount();

namespace detail {
void countCreated();
void countDeleted();
void deleteObject(ObjectKind kind, GLuint id);
}  // namespace detail

template <ObjectKind Kind>
class Object {
public:
    Object() = default;
    explicit Object(GLuint id) : id_(id) {
        if (id_) detail::countCreated();
    }
    ~Object() { reset(); }
    Object(Object&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
    Object& operator=(Object&& other) noexcept {
        if (this != &other) {
            reset();
            id_ = std::exchange(other.id_, 0);
        }
        return *this;
    }
    Object(const Object&) = delete;
    Object& operator=(const Object&) = delete;

    GLuint id() const { return id_; }
    explicit operator bool() const { return id_ != 0; }
    void reset() {
        if (id_) {
            detail::deleteObject(Kind, id_);
            detail::countDeleted();
            id_ = 0;
        }
    }

private:
    GLuint id_ = 0;
};

using Buffer = Object<ObjectKind::Buffer>;
using Framebuffer = Object<ObjectKind::Framebuffer>;
using Program = Object<ObjectKind::Program>;
using Shader = Object<ObjectKind::Shader>;
using VertexArray = Object<ObjectKind::VertexArray>;
using Query = Object<ObjectKind::Query>;
using Sampler = Object<ObjectKind::Sampler>;

// A texture remembers its shape, so passes and readback need no extra bookkeeping.
struct Texture {
    Object<ObjectKind::Texture> handle;
    GLenum target = GL_TEXTURE_2D;
    GLenum format = GL_RGBA8;
    int width = 0;
    int height = 0;
    int levels = 1;
    GLuint id() const { return handle.id(); }
    explicit operator bool() const { return bool(handle); }
};

void label(GLenum identifier, GLuint id, const std::string& name);

Texture makeTexture2D(GLenum internalFormat, int width, int height, int levels, const std::string& name);
Texture makeTextureCube(GLenum internalFormat, int size, int levels, const std::string& name);
// One level of `layers` width x height layers (GL_TEXTURE_2D_ARRAY), linear filtering, clamped.
Texture makeTexture2DArray(GLenum internalFormat, int width, int height, int layers, const std::string& name);
// A view of every level of 2D texture `source` (made by makeTexture2D: immutable storage) as
// `internalFormat`, of the same size class: the same texels read or written as another format.
Texture makeTextureView(const Texture& source, GLenum internalFormat, const std::string& name);
// The format image load/store reaches a texture of `internalFormat` through: itself, or for an sRGB
// format (image units take none) its linear twin, GL_RGBA8, whose shader stores the encoding itself.
GLenum imageFormatOf(GLenum internalFormat);
Buffer makeBuffer(GLsizeiptr size, const void* data, GLbitfield flags, const std::string& name);
Framebuffer makeFramebuffer(const std::string& name);
VertexArray makeVertexArray(const std::string& name);
Sampler makeSampler(const std::string& name);
Query makeQuery(GLenum target);

// A fence after the commands issued so far (glFenceSync), deleted with its owner. signaled() never
// waits: results read only once their fence has signaled cost the CPU no stall and leave no idle gap
// inside the GPU timer of the pass that reads them.
class Fence {
public:
    Fence() = default;
    static Fence insert();
    ~Fence();
    Fence(Fence&& other) noexcept : sync_(other.sync_) { other.sync_ = nullptr; }
    Fence& operator=(Fence&& other) noexcept;
    Fence(const Fence&) = delete;
    Fence& operator=(const Fence&) = delete;
    bool signaled() const;
    explicit operator bool() const { return sync_ != nullptr; }

private:
    GLsync sync_ = nullptr;
};

// Number of mip levels of a full chain for a width x height image.
int fullMipCount(int width, int height);
// Bytes per texel of the internal formats lightpass uses (for memory accounting and floors).
int bytesPerTexel(GLenum internalFormat);
// The pixel format and type that clear a texture of `internalFormat` with glClearTexImage
// (integer formats need *_INTEGER, depth formats GL_DEPTH_COMPONENT).
struct ClearFormat {
    GLenum format, type;
};
ClearFormat clearFormatFor(GLenum internalFormat);
const char* formatName(GLenum internalFormat);

// Throws lp::Error naming `where` when glGetError reports anything (LIGHTPASS_GL_CHECKS builds);
// GL_OUT_OF_MEMORY is reported as such so the CLI can say so in one line.
void checkErrors(const std::string& where);

// RAII debug group: passes show up by name in RenderDoc/apitrace captures.
class DebugGroup {
public:
    explicit DebugGroup(const std::string& name);
    ~DebugGroup();
    DebugGroup(const DebugGroup&) = delete;
    DebugGroup& operator=(const DebugGroup&) = delete;
};

}  // namespace lp::gl
