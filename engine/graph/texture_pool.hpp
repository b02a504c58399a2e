#pragma once
// Transient textures for the frame graph, keyed by description and reused across passes whose
// lifetimes don't overlap and across frames. Textures unused for a few frames are freed, so a
// resize or a settings change doesn't keep stale memory.
#include <memory>
#include <vector>

#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"

namespace lp::fg {

// A GL texture whose memory another API reaches without mapping it per use (CUDA external
// memory): it and that API's view of it live as long as this object.
struct ExternalTexture {
    virtual ~ExternalTexture() = default;
    virtual GLuint texture() const = 0;
};

// Makes the textures that passes touch with Usage::Cuda; null from make() when it cannot share
// this description (the pool then makes an ordinary texture).
struct ExternalTextureSource {
    virtual ~ExternalTextureSource() = default;
    virtual std::shared_ptr<ExternalTexture> make(const TextureDesc& desc, const std::string& label) = 0;
};

class TexturePool {
public:
    void beginFrame();  // everything becomes free for this frame's passes
    // `external`: a pass touches it from CUDA; made by the external source when there is one.
    GLuint acquire(const TextureDesc& desc, const std::string& label, bool external = false);
    // Where external textures come from (not owned; null: none). A different source drops the free
    // textures the previous one made; one still held (the last frame's output) goes once idle.
    void setExternalSource(ExternalTextureSource* source);
    size_t externalCount() const;  // textures made by the external source
    void release(GLuint texture);
    // What a shader image-stores texture `texture` of this pool through: the texture itself, or for an
    // sRGB one (image units take no sRGB format) a view of its storage as gl::imageFormatOf(format),
    // made the first time and kept as long as the texture. 0 for a texture the pool did not make.
    GLuint imageTexture(GLuint texture);
    void endFrame(int keepUnusedFrames = 3);
    void clear();

    size_t textureCount() const { return entries_.size(); }
    size_t totalBytes() const;
    // Number of textures created since the pool was made (tests: reuse means this stays flat).
    size_t created() const { return created_; }

private:
    struct Entry {
        TextureDesc desc;
        gl::Texture texture;                        // ordinary
        gl::Texture imageView;                      // imageTexture's view of an sRGB `texture`
        std::shared_ptr<ExternalTexture> external;  // or from the external source
        const ExternalTextureSource* source = nullptr;  // which one made it
        GLuint id() const { return external ? external->texture() : texture.id(); }
        bool inUse = false;
        int idleFrames = 0;
        bool usedThisFrame = false;
    };
    std::vector<Entry> entries_;
    size_t created_ = 0;
    ExternalTextureSource* externalSource_ = nullptr;
};

}  // namespace lp::fg
