#pragma once
// Transient textures for the frame graph, keyed by description and reused across passes whose
// lifetimes don't overlap and across frames. Textures unused for a few frames are freed, so a
// resize or a settings change doesn't keep stale memory.
#include <vector>

#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"

namespace lp::fg {

class TexturePool {
public:
    void beginFrame();  // everything becomes free for this frame's passes
    GLuint acquire(const TextureDesc& desc, const std::string& label);
    void release(GLuint texture);
    void endFrame(int keepUnusedFrames = 3);
    void clear();

    size_t textureCount() const { return entries_.size(); }
    size_t totalBytes() const;
    // Number of textures created since the pool was made (tests: reuse means this stays flat).
    size_t created() const { return created_; }

private:
    struct Entry {
        TextureDesc desc;
        gl::Texture texture;
        bool inUse = false;
        int idleFrames = 0;
        bool usedThisFrame = false;
    };
    std::vector<Entry> entries_;
    size_t created_ = 0;
};

}  // namespace lp::fg
