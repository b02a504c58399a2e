#pragma once
// CUDA <-> GL interop for the post effects (CUDA sources only): GL textures are registered
// once and again only when a texture's id or size changes, mapped per use, accessed as surfaces.
#include <vector>

#include "engine/gl/gl.hpp"  // glad before cuda_gl_interop.h, which needs GL types
#include <cuda_gl_interop.h>
#include <cuda_runtime.h>

namespace lp::cuda {

// Throws lp::Error("CUDA <call>: <error string>") when `err` is not cudaSuccess.
void check(cudaError_t err, const char* call);

class GlImageRegistry {
public:
    GlImageRegistry() = default;
    ~GlImageRegistry();
    GlImageRegistry(const GlImageRegistry&) = delete;
    GlImageRegistry& operator=(const GlImageRegistry&) = delete;

    // Starts frame `frame` (a counter that grows by one per built frame graph): registrations not
    // used in the last kMaxIdleFrames frames are dropped. The texture pool deletes a texture only
    // after more idle frames than that, so a GL id deleted and reused never meets a stale entry.
    void beginFrame(unsigned long frame);
    // The registration of `texture` (width x height), made on first use and redone when the size
    // of that id changed.
    cudaGraphicsResource_t resource(GLuint texture, int width, int height);
    // Drops the registration of `texture` now: for a texture about to be deleted outside the pool
    // (its id could come back at the same size before the entry aged out). Warns, never throws.
    void forget(GLuint texture);
    static constexpr unsigned long kMaxIdleFrames = 2;
    int size() const { return int(entries_.size()); }

private:
    struct Entry {
        GLuint texture = 0;
        int width = 0, height = 0;
        cudaGraphicsResource_t resource = nullptr;
        unsigned long lastUse = 0;  // frame
    };
    std::vector<Entry> entries_;
    unsigned long frame_ = 0;
};

// Maps resources for the lifetime of the object and gives each a surface object; unmap() reports
// errors, the destructor unmaps quietly if unmap() was not called (an exception is in flight).
class MappedSurfaces {
public:
    MappedSurfaces(std::vector<cudaGraphicsResource_t> resources, cudaStream_t stream);
    ~MappedSurfaces();
    MappedSurfaces(const MappedSurfaces&) = delete;
    MappedSurfaces& operator=(const MappedSurfaces&) = delete;
    cudaSurfaceObject_t surface(size_t i) const { return surfaces_[i]; }
    void unmap();

private:
    std::vector<cudaGraphicsResource_t> resources_;
    std::vector<cudaSurfaceObject_t> surfaces_;
    cudaStream_t stream_;
    bool mapped_ = false;
};

}  // namespace lp::cuda
