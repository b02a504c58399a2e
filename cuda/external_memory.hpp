#pragma once
// GL textures that CUDA reaches without registering and mapping them per use (CUDA sources only).
//
// The memory is CUDA's: cuMemCreate allocates it exportable as a POSIX file descriptor, GL imports
// one descriptor as a memory object (GL_EXT_memory_object_fd) and makes the texture on it
// (glTextureStorageMem2DEXT, optimal tiling), and CUDA imports another descriptor of the same
// allocation as external memory and views it as a CUDA array of the same format and extent, with a
// surface object made once. GL can import memory but never export it, so the allocation cannot be
// GL's. Whether GL and CUDA then agree on the texel layout is not promised by either API for memory
// not made by Vulkan: sharedTexturesProblem() checks it at start-up with a round trip through small
// textures of each format, texel for texel, and the caller falls back to map/unmap when it fails.
//
// Ordering: GL and CUDA can import semaphores but neither can export one, so Vulkan makes them
// (cuda/gl_cuda_semaphores.hpp) and the queues hand the textures over on the GPU. Where that fails
// the post passes order the two with a GL fence the host waits on before the kernels and a CUDA
// event it waits on after them (see PostInterop).
#include <memory>
#include <string>
#include <vector>

#include "cuda/interop.hpp"
#include "cuda/post_cuda.hpp"
#include "engine/graph/texture_pool.hpp"

namespace lp::cuda {

// sharedTexturesProblem() (declared in cuda/post_cuda.hpp) says whether they work here.

class GlCudaSemaphores;
// The start-up round trip again, ordered by `sync` alone, through RGBA16F and RGBA32F textures of
// 67x35 and 64x48 in the layout the start-up check settled on: empty when texel for texel.
std::string semaphoreRoundTrip(GlCudaSemaphores& sync, cudaStream_t stream);
// What CUDA reads from a surface (RGBA16F when `half`, else RGBA32F), row-major RGBA floats, after
// the work already on `stream` (which it synchronises).
std::vector<float> readSurfaceToHost(cudaSurfaceObject_t surface, bool half, int width, int height, cudaStream_t stream);

class SharedTexture final : public fg::ExternalTexture {
public:
    ~SharedTexture() override;
    SharedTexture(const SharedTexture&) = delete;
    SharedTexture& operator=(const SharedTexture&) = delete;
    GLuint texture() const override { return texture_; }
    cudaSurfaceObject_t surface() const { return surface_; }
    // What the start-up check settles: the cudaArray* flags of the CUDA view, and whether GL and CUDA
    // treat the memory as dedicated to the one texture.
    struct Layout {
        unsigned arrayFlags = 0;
        bool dedicated = false;
    };
    // RGBA16F or RGBA32F, one level; throws lp::Error naming the failing call.
    static std::unique_ptr<SharedTexture> make(GLenum format, int width, int height, const std::string& label,
                                               const Layout& layout);

private:
    SharedTexture() = default;
    unsigned long long allocation_ = 0;  // CUmemGenericAllocationHandle
    GLuint memoryObject_ = 0, texture_ = 0;
    cudaExternalMemory_t external_ = nullptr;
    cudaMipmappedArray_t mipmapped_ = nullptr;
    cudaSurfaceObject_t surface_ = 0;
};

// The pool's source of shared textures (RGBA16F and RGBA32F, one level; others get ordinary
// textures) and the surfaces of the ones still alive.
class SharedTextures final : public fg::ExternalTextureSource {
public:
    std::shared_ptr<fg::ExternalTexture> make(const fg::TextureDesc& desc, const std::string& label) override;
    // The surface of a live texture this source made, else 0 (an ordinary texture: map it).
    cudaSurfaceObject_t surfaceOf(GLuint texture) const;

private:
    std::vector<std::weak_ptr<SharedTexture>> made_;
};

}  // namespace lp::cuda
