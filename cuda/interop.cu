#include "cuda/interop.hpp"

#include <algorithm>
#include <string>

#include "engine/core/error.hpp"
#include <cstdio>

namespace lp::cuda {

void check(cudaError_t err, const char* call) {
    if (err == cudaSuccess) return;
    cudaGetLastError();  // clear the sticky-free error state
    throw Error(std::string("CUDA ") + call + ": " + cudaGetErrorString(err));
}

GlImageRegistry::~GlImageRegistry() {
    for (Entry& e : entries_) {
        cudaError_t err = cudaGraphicsUnregisterResource(e.resource);
        if (err != cudaSuccess)  // no throwing from a destructor, and no engine logger in this library
            std::fprintf(stderr, "warning: CUDA cudaGraphicsUnregisterResource: %s\n", cudaGetErrorString(err));
    }
}

void GlImageRegistry::beginFrame(unsigned long frame) {
    frame_ = frame;
    for (auto it = entries_.begin(); it != entries_.end();) {
        if (frame_ - it->lastUse <= kMaxIdleFrames) {
            ++it;
            continue;
        }
        // Its texture may be gone already (the post passes did not run for a while): warn, go on.
        cudaError_t err = cudaGraphicsUnregisterResource(it->resource);
        if (err != cudaSuccess) {
            std::fprintf(stderr, "warning: CUDA cudaGraphicsUnregisterResource: %s\n", cudaGetErrorString(err));
            cudaGetLastError();
        }
        it = entries_.erase(it);
    }
}

void GlImageRegistry::forget(GLuint texture) {
    auto it = std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.texture == texture; });
    if (it == entries_.end()) return;
    cudaError_t err = cudaGraphicsUnregisterResource(it->resource);  // callers may be destructors: no throw
    if (err != cudaSuccess) {
        std::fprintf(stderr, "warning: CUDA cudaGraphicsUnregisterResource: %s\n", cudaGetErrorString(err));
        cudaGetLastError();
    }
    entries_.erase(it);
}

cudaGraphicsResource_t GlImageRegistry::resource(GLuint texture, int width, int height) {
    auto it = std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.texture == texture; });
    if (it != entries_.end()) {
        if (it->width == width && it->height == height) {
            it->lastUse = frame_;
            return it->resource;
        }
        check(cudaGraphicsUnregisterResource(it->resource), "cudaGraphicsUnregisterResource");
        entries_.erase(it);
    }
    constexpr size_t kMaxEntries = 16;  // pool textures come and go: drop the least recently used
    if (entries_.size() >= kMaxEntries) {
        auto oldest = std::min_element(entries_.begin(), entries_.end(),
                                       [](const Entry& a, const Entry& b) { return a.lastUse < b.lastUse; });
        check(cudaGraphicsUnregisterResource(oldest->resource), "cudaGraphicsUnregisterResource");
        entries_.erase(oldest);
    }
    Entry e{texture, width, height, nullptr, frame_};
    check(cudaGraphicsGLRegisterImage(&e.resource, texture, GL_TEXTURE_2D, cudaGraphicsRegisterFlagsSurfaceLoadStore),
          "cudaGraphicsGLRegisterImage");
    entries_.push_back(e);
    return e.resource;
}

MappedSurfaces::MappedSurfaces(std::vector<cudaGraphicsResource_t> resources, cudaStream_t stream)
    : resources_(std::move(resources)), stream_(stream) {
    check(cudaGraphicsMapResources(int(resources_.size()), resources_.data(), stream_), "cudaGraphicsMapResources");
    mapped_ = true;
    for (cudaGraphicsResource_t r : resources_) {
        cudaArray_t array = nullptr;
        check(cudaGraphicsSubResourceGetMappedArray(&array, r, 0, 0), "cudaGraphicsSubResourceGetMappedArray");
        cudaResourceDesc desc{};
        desc.resType = cudaResourceTypeArray;
        desc.res.array.array = array;
        cudaSurfaceObject_t surface = 0;
        check(cudaCreateSurfaceObject(&surface, &desc), "cudaCreateSurfaceObject");
        surfaces_.push_back(surface);
    }
}

void MappedSurfaces::unmap() {
    if (!mapped_) return;
    mapped_ = false;
    for (cudaSurfaceObject_t s : surfaces_) check(cudaDestroySurfaceObject(s), "cudaDestroySurfaceObject");
    surfaces_.clear();
    check(cudaGraphicsUnmapResources(int(resources_.size()), resources_.data(), stream_), "cudaGraphicsUnmapResources");
}

MappedSurfaces::~MappedSurfaces() {
    if (!mapped_) return;
    for (cudaSurfaceObject_t s : surfaces_) cudaDestroySurfaceObject(s);
    cudaGraphicsUnmapResources(int(resources_.size()), resources_.data(), stream_);
    cudaGetLastError();
}

}  // namespace lp::cuda
