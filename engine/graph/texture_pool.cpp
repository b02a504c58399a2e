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

GLuint TexturePool::acquire(const TextureDesc& desc, const std::string& label, bool external) {
    // An external request prefers an external texture but takes an ordinary one when the source
    // cannot share this description; an ordinary request never takes an external one.
    external = external && externalSource_;
    for (int pass = 0; pass < 2; ++pass) {
        for (auto& e : entries_) {
            const bool fromSource = e.external && e.source == externalSource_;  // never an old source's
            const bool match = pass == 0 ? (external ? fromSource : !e.external) : (external && !e.external);
            if (!e.inUse && e.desc == desc && match) {
                e.inUse = true;
                e.usedThisFrame = true;
                e.idleFrames = 0;
                gl::label(GL_TEXTURE, e.id(), label);
                return e.id();
            }
        }
        if (pass == 0 && external) {
            std::shared_ptr<ExternalTexture> made = externalSource_->make(desc, label);
            if (!made) continue;  // not shareable: an ordinary texture
            Entry e;
            e.desc = desc;
            e.external = std::move(made);
            e.source = externalSource_;
            e.inUse = e.usedThisFrame = true;
            ++created_;
            entries_.push_back(std::move(e));
            return entries_.back().id();
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

void TexturePool::setExternalSource(ExternalTextureSource* source) {
    if (source == externalSource_) return;
    externalSource_ = source;
    entries_.erase(std::remove_if(entries_.begin(), entries_.end(),
                                  [](const Entry& e) { return e.external && !e.inUse; }),
                   entries_.end());
    // One still held is orphaned: never handed out again (a later source may live at the old address).
    for (Entry& e : entries_)
        if (e.external) e.source = nullptr;
}

size_t TexturePool::externalCount() const {
    return size_t(std::count_if(entries_.begin(), entries_.end(), [](const Entry& e) { return bool(e.external); }));
}

void TexturePool::release(GLuint texture) {
    for (auto& e : entries_)
        if (e.id() == texture) e.inUse = false;
}

GLuint TexturePool::imageTexture(GLuint texture) {
    for (auto& e : entries_) {
        if (e.id() != texture) continue;
        const GLenum format = gl::imageFormatOf(e.desc.format);
        if (format == e.desc.format) return texture;
        if (e.external) return 0;  // another API's texture: no view of it
        if (!e.imageView) e.imageView = gl::makeTextureView(e.texture, format, "image view");
        return e.imageView.id();
    }
    return 0;
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
