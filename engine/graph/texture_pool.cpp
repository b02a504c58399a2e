#include "engine/graph/texture_pool.hpp"

#include <algorithm>

namespace lp::fg {

size_t TextureDesc::bytes() const {
    size_t total = 0;
    int w = width, h = height;
    for (int l = 0; l < levels; ++l) {
        total += size_t(w) * size_t(h) * size_t(gl::bytesPerTexel(format));
        w = std::max(1, w / 2);
        h = std::max(1, h / 2);
    }
    return cube ? 6 * total : total;
}

void TexturePool::beginFrame() {
    for (auto& e : entries_) {
        e.inUse = false;
        e.usedThisFrame = false;
    }
}

GLuint TexturePool::acquire(const TextureDesc& desc, const std::string& label) {
    for (auto& e : entries_) {
        if (!e.inUse && e.desc == desc) {
            e.inUse = true;
            e.usedThisFrame = true;
            e.idleFrames = 0;
            gl::label(GL_TEXTURE, e.texture.id(), label);
            return e.texture.id();
        }
    }
    Entry e;
    e.desc = desc;
    e.texture = gl::makeTexture2D(desc.format, desc.width, desc.height, desc.levels, label);
    e.inUse = true;
    e.usedThisFrame = true;
    ++created_;
    entries_.push_back(std::move(e));
    return entries_.back().texture.id();
}

void TexturePool::release(GLuint texture) {
    for (auto& e : entries_)
        if (e.texture.id() == texture) e.inUse = false;
}

void TexturePool::endFrame(int keepUnusedFrames) {
    for (auto& e : entries_) e.idleFrames = e.usedThisFrame ? 0 : e.idleFrames + 1;
    entries_.erase(std::remove_if(entries_.begin(), entries_.end(),
                                  [&](const Entry& e) { return e.idleFrames > keepUnusedFrames; }),
                   entries_.end());
}

void TexturePool::clear() { entries_.clear(); }

size_t TexturePool::totalBytes() const {
    size_t total = 0;
    for (const auto& e : entries_) total += e.desc.bytes();
    return total;
}

}  // namespace lp::fg
