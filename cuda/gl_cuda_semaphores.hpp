#pragma once
// GPU-side ordering between GL and CUDA on shared textures (CUDA sources only): two binary
// semaphores made by Vulkan (cuda/vulkan_semaphores.hpp), each imported into GL
// (GL_EXT_semaphore_fd: glImportSemaphoreFdEXT) and into CUDA (cudaImportExternalSemaphore).
// A hand-over is: GL signals (glSignalSemaphoreEXT, the textures in the general layout) and CUDA's
// stream waits for it (cudaWaitExternalSemaphoresAsync); after the kernels CUDA signals
// (cudaSignalExternalSemaphoresAsync) and GL waits (glWaitSemaphoreEXT, the same layouts) before
// its next command. The host never waits.
//
// The layouts are part of the hand-over, not decoration: GL_EXT_memory_object leaves the contents
// of memory another API wrote undefined to GL unless it came back through glWaitSemaphoreEXT with the
// textures' layouts (and likewise GL's writes reach the other API through glSignalSemaphoreEXT), so
// GL can decompress, flush or invalidate what it keeps of those textures at the hand-over.
#include <memory>
#include <string>

#include "cuda/interop.hpp"

namespace lp::cuda {

class VulkanSemaphoreDevice;

// The Vulkan device on the current CUDA device's GPU, opened once per process; null with `problem`.
const VulkanSemaphoreDevice* semaphoreDevice(std::string& problem);

class GlCudaSemaphores {
public:
    // Needs the GL context current (GL semaphore objects belong to it). Null with `problem` set
    // where GL lacks GL_EXT_semaphore_fd, no Vulkan device matches, or an import is refused.
    static std::unique_ptr<GlCudaSemaphores> make(std::string& problem);
    ~GlCudaSemaphores();
    GlCudaSemaphores(const GlCudaSemaphores&) = delete;
    GlCudaSemaphores& operator=(const GlCudaSemaphores&) = delete;

    // GL's commands so far, and the textures, handed to what CUDA enqueues on `stream` next.
    void glThenCuda(const GLuint* textures, int count, cudaStream_t stream);
    // What CUDA enqueued on `stream` so far, and the textures, handed back before GL's next command.
    void cudaThenGl(const GLuint* textures, int count, cudaStream_t stream);
    // The Vulkan device that made the semaphores ("NVIDIA H100 80GB HBM3").
    const std::string& deviceName() const;

private:
    GlCudaSemaphores() = default;
    struct Semaphore {
        uint64_t vulkan = 0;
        GLuint gl = 0;
        cudaExternalSemaphore_t cuda = nullptr;
    };
    static bool import(Semaphore& s, const VulkanSemaphoreDevice& device, std::string& problem);
    void release(Semaphore& s);
    Semaphore glToCuda_, cudaToGl_;
    const VulkanSemaphoreDevice* device_ = nullptr;
};

}  // namespace lp::cuda
