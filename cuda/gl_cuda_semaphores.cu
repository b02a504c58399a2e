#include "cuda/gl_cuda_semaphores.hpp"

#include <unistd.h>

#include <cstring>
#include <vector>

#include "cuda/vulkan_semaphores.hpp"
#include "engine/core/error.hpp"

namespace lp::cuda {

const VulkanSemaphoreDevice* semaphoreDevice(std::string& problem) {
    struct Opened {
        std::unique_ptr<VulkanSemaphoreDevice> device;
        std::string problem;
    };
    // Kept for the process, never destroyed: GL and CUDA may hold imports of its semaphores until
    // their own teardown, which static destruction does not order against.
    static const Opened* opened = [] {
        auto* o = new Opened;
        int device = 0;
        cudaDeviceProp prop{};
        if (cudaGetDevice(&device) != cudaSuccess || cudaGetDeviceProperties(&prop, device) != cudaSuccess) {
            cudaGetLastError();
            o->problem = "cannot query the CUDA device's UUID";
            return o;
        }
        DeviceUuid uuid{};
        std::memcpy(uuid.data(), prop.uuid.bytes, uuid.size());
        o->device = VulkanSemaphoreDevice::open(uuid, o->problem);
        return o;
    }();
    problem = opened->problem;
    return opened->device.get();
}

bool GlCudaSemaphores::import(Semaphore& s, const VulkanSemaphoreDevice& device, std::string& problem) {
    s.vulkan = device.createSemaphore(problem);
    if (!s.vulkan) return false;
    int fd = device.exportFd(s.vulkan, problem);
    if (fd < 0) return false;
    while (glGetError() != GL_NO_ERROR) {  // earlier errors are not this import's
    }
    glGenSemaphoresEXT(1, &s.gl);
    glImportSemaphoreFdEXT(s.gl, GL_HANDLE_TYPE_OPAQUE_FD_EXT, fd);  // GL owns fd on success
    if (glGetError() != GL_NO_ERROR || !glIsSemaphoreEXT(s.gl)) {
        close(fd);
        problem = "GL glImportSemaphoreFdEXT refused the Vulkan semaphore";
        return false;
    }
    fd = device.exportFd(s.vulkan, problem);
    if (fd < 0) return false;
    cudaExternalSemaphoreHandleDesc desc{};
    desc.type = cudaExternalSemaphoreHandleTypeOpaqueFd;
    desc.handle.fd = fd;
    const cudaError_t err = cudaImportExternalSemaphore(&s.cuda, &desc);  // CUDA owns fd on success
    if (err != cudaSuccess) {
        close(fd);
        cudaGetLastError();
        s.cuda = nullptr;
        problem = std::string("cudaImportExternalSemaphore: ") + cudaGetErrorString(err);
        return false;
    }
    return true;
}

void GlCudaSemaphores::release(Semaphore& s) {
    if (s.cuda) {
        cudaDestroyExternalSemaphore(s.cuda);
        cudaGetLastError();
    }
    if (s.gl) glDeleteSemaphoresEXT(1, &s.gl);
    if (s.vulkan && device_) device_->destroySemaphore(s.vulkan);
    s = Semaphore{};
}

std::unique_ptr<GlCudaSemaphores> GlCudaSemaphores::make(std::string& problem) {
    if (!GLAD_GL_EXT_semaphore || !GLAD_GL_EXT_semaphore_fd) {
        problem = "the GL context has no GL_EXT_semaphore_fd";
        return nullptr;
    }
    const VulkanSemaphoreDevice* device = semaphoreDevice(problem);
    if (!device) return nullptr;
    std::unique_ptr<GlCudaSemaphores> s(new GlCudaSemaphores);
    s->device_ = device;
    if (!import(s->glToCuda_, *device, problem) || !import(s->cudaToGl_, *device, problem)) return nullptr;
    return s;
}

GlCudaSemaphores::~GlCudaSemaphores() {
    // A wait still pending on either queue must not outlive its semaphore.
    if (glToCuda_.gl || cudaToGl_.gl) glFinish();
    cudaDeviceSynchronize();
    cudaGetLastError();
    release(glToCuda_);
    release(cudaToGl_);
}

const std::string& GlCudaSemaphores::deviceName() const { return device_->deviceName(); }

void GlCudaSemaphores::glThenCuda(const GLuint* textures, int count, cudaStream_t stream) {
    const std::vector<GLenum> layouts(size_t(count), GL_LAYOUT_GENERAL_EXT);
    glSignalSemaphoreEXT(glToCuda_.gl, 0, nullptr, GLuint(count), textures, layouts.data());
    // Submitted now: a binary semaphore's signal must reach the GPU before its wait can be met.
    glFlush();
    cudaExternalSemaphoreWaitParams wait{};
    check(cudaWaitExternalSemaphoresAsync(&glToCuda_.cuda, &wait, 1, stream), "cudaWaitExternalSemaphoresAsync");
}

void GlCudaSemaphores::cudaThenGl(const GLuint* textures, int count, cudaStream_t stream) {
    cudaExternalSemaphoreSignalParams signal{};
    check(cudaSignalExternalSemaphoresAsync(&cudaToGl_.cuda, &signal, 1, stream), "cudaSignalExternalSemaphoresAsync");
    // Pushes the stream's work to the GPU now (a query flushes; NotReady is the usual answer), so
    // GL's wait below is not left waiting on commands CUDA still batches on the host.
    const cudaError_t q = cudaStreamQuery(stream);
    if (q == cudaErrorNotReady) cudaGetLastError();  // not an error: still running
    else check(q, "cudaStreamQuery");
    const std::vector<GLenum> layouts(size_t(count), GL_LAYOUT_GENERAL_EXT);
    glWaitSemaphoreEXT(cudaToGl_.gl, 0, nullptr, GLuint(count), textures, layouts.data());
}

}  // namespace lp::cuda
