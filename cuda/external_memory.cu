#include "cuda/external_memory.hpp"

#include <cuda.h>
#include <cudaTypedefs.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "cuda/gl_cuda_semaphores.hpp"
#include "cuda/post_kernels.cuh"
#include "engine/core/error.hpp"
#include "engine/gl/handles.hpp"

namespace lp::cuda {

namespace {

// The driver API calls of the virtual memory management, looked up through the runtime (the
// executable links no libcuda, so it still starts where no NVIDIA driver is installed).
struct DriverApi {
    PFN_cuMemCreate_v10020 memCreate = nullptr;
    PFN_cuMemRelease_v10020 memRelease = nullptr;
    PFN_cuMemExportToShareableHandle_v10020 exportHandle = nullptr;
    PFN_cuMemGetAllocationGranularity_v10020 granularity = nullptr;
    PFN_cuDeviceGetAttribute_v2000 deviceAttribute = nullptr;
    std::string problem;  // why not, when a call is missing
};

template <typename Fn>
void lookUp(DriverApi& api, const char* symbol, Fn& fn) {
    void* p = nullptr;
    cudaDriverEntryPointQueryResult found{};
    if (cudaGetDriverEntryPointByVersion(symbol, &p, 12000, cudaEnableDefault, &found) != cudaSuccess ||
        found != cudaDriverEntryPointSuccess || !p) {
        cudaGetLastError();
        if (api.problem.empty()) api.problem = std::string("the CUDA driver has no ") + symbol;
        return;
    }
    fn = reinterpret_cast<Fn>(p);
}

const DriverApi& driverApi() {
    static const DriverApi api = [] {
        DriverApi a;
        lookUp(a, "cuMemCreate", a.memCreate);
        lookUp(a, "cuMemRelease", a.memRelease);
        lookUp(a, "cuMemExportToShareableHandle", a.exportHandle);
        lookUp(a, "cuMemGetAllocationGranularity", a.granularity);
        lookUp(a, "cuDeviceGetAttribute", a.deviceAttribute);
        return a;
    }();
    return api;
}

void checkDriver(CUresult r, const char* call) {
    if (r == CUDA_SUCCESS) return;
    throw Error(std::string("CUDA ") + call + ": error " + std::to_string(int(r)));
}

void checkGl(const char* call) {
    const GLenum err = glGetError();
    if (err != GL_NO_ERROR) throw Error(std::string("GL ") + call + ": error 0x" + [&] {
        char hex[16];
        std::snprintf(hex, sizeof hex, "%04x", unsigned(err));
        return std::string(hex);
    }());
}

int currentDevice() {
    int device = 0;
    check(cudaGetDevice(&device), "cudaGetDevice");
    return device;
}

CUmemAllocationProp allocationProp() {
    CUmemAllocationProp prop{};
    prop.type = CU_MEM_ALLOCATION_TYPE_PINNED;
    prop.location.type = CU_MEM_LOCATION_TYPE_DEVICE;
    prop.location.id = currentDevice();
    prop.requestedHandleTypes = CU_MEM_HANDLE_TYPE_POSIX_FILE_DESCRIPTOR;
    return prop;
}

size_t roundUp(size_t v, size_t to) { return (v + to - 1) / to * to; }

// Enough for the texture in any tiled layout: GL does not say how much its layout needs (Vulkan's
// vkGetImageMemoryRequirements has no GL counterpart), so rows are padded to 512 bytes and the height
// to 256 rows, beyond the block-linear tiles' padding, and GL checks the size it was given.
size_t allocationBytes(GLenum format, int width, int height) {
    const size_t bpp = format == GL_RGBA32F ? 16 : 8;
    return roundUp(size_t(width) * bpp, 512) * roundUp(size_t(height), 256) + (size_t(1) << 16);
}

int exportFd(unsigned long long allocation) {
    int fd = -1;
    checkDriver(driverApi().exportHandle(&fd, CUmemGenericAllocationHandle(allocation),
                                         CU_MEM_HANDLE_TYPE_POSIX_FILE_DESCRIPTOR, 0),
                "cuMemExportToShareableHandle");
    return fd;
}

// ---- the start-up round trip ------------------------------------------------------------------

template <typename Surface>
__global__ void readSurfaceKernel(Surface s, float4* out, int width, int height) {
    const int x = int(blockIdx.x * blockDim.x + threadIdx.x), y = int(blockIdx.y * blockDim.y + threadIdx.y);
    if (x < width && y < height) out[size_t(y) * size_t(width) + size_t(x)] = s.load(x, y);
}

template <typename Surface>
__global__ void writeSurfaceKernel(Surface s, int width, int height) {
    const int x = int(blockIdx.x * blockDim.x + threadIdx.x), y = int(blockIdx.y * blockDim.y + threadIdx.y);
    if (x < width && y < height) s.store(x, y, make_float4(float(y), float(x), float((x * 7 + y * 3) % 1024), 1.0f));
}

// GL writes a pattern CUDA must read back, then CUDA writes one GL must read back, on a texture of
// kW x kH. Values are integers below 2048: exact in fp16. Without `sync` the host orders the two
// (glFinish, then cudaDeviceSynchronize); with it only the semaphores do, as in a frame: nothing
// waits on the host between GL's upload and GL's read-back but the read-backs themselves.
std::string roundTrip(GLenum format, const SharedTexture::Layout& layout, int kW, int kH, GlCudaSemaphores* sync,
                      cudaStream_t stream) {
    std::unique_ptr<SharedTexture> t = SharedTexture::make(format, kW, kH, "shared_texture_check", layout);
    std::vector<float> pattern(size_t(kW) * kH * 4), back(pattern.size());
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            float* p = &pattern[(size_t(y) * kW + size_t(x)) * 4];
            p[0] = float((x + kW * y) % 1024);
            p[1] = float(x);
            p[2] = float(y);
            p[3] = 1.0f;
        }
    glTextureSubImage2D(t->texture(), 0, 0, 0, kW, kH, GL_RGBA, GL_FLOAT, pattern.data());
    checkGl("glTextureSubImage2D");
    const GLuint texture = t->texture();
    if (sync) sync->glThenCuda(&texture, 1, stream);
    else glFinish();
    float4* device = nullptr;
    check(cudaMalloc(&device, back.size() * sizeof(float)), "cudaMalloc");
    const dim3 block(16, 16), grid((kW + 15) / 16, (kH + 15) / 16);
    if (format == GL_RGBA32F) readSurfaceKernel<<<grid, block, 0, stream>>>(Float4Surface{t->surface()}, device, kW, kH);
    else readSurfaceKernel<<<grid, block, 0, stream>>>(Half4Surface{t->surface()}, device, kW, kH);
    cudaError_t err = cudaMemcpyAsync(back.data(), device, back.size() * sizeof(float), cudaMemcpyDeviceToHost, stream);
    if (err == cudaSuccess) err = cudaStreamSynchronize(stream);
    if (err != cudaSuccess) {
        cudaFree(device);
        check(err, "cudaMemcpy (round trip)");
    }
    if (back != pattern) {
        if (sync) sync->cudaThenGl(&texture, 1, stream);  // keeps the semaphores paired
        cudaStreamSynchronize(stream);
        cudaFree(device);
        return std::string("CUDA does not read what GL wrote (") + (format == GL_RGBA32F ? "RGBA32F " : "RGBA16F ") +
               std::to_string(kW) + "x" + std::to_string(kH) + ")";
    }
    if (format == GL_RGBA32F) writeSurfaceKernel<<<grid, block, 0, stream>>>(Float4Surface{t->surface()}, kW, kH);
    else writeSurfaceKernel<<<grid, block, 0, stream>>>(Half4Surface{t->surface()}, kW, kH);
    if (sync) sync->cudaThenGl(&texture, 1, stream);
    else check(cudaStreamSynchronize(stream), "cudaStreamSynchronize (round trip)");
    glGetTextureImage(t->texture(), 0, GL_RGBA, GL_FLOAT, GLsizei(back.size() * sizeof(float)), back.data());
    checkGl("glGetTextureImage");
    cudaStreamSynchronize(stream);
    cudaFree(device);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const float* b = &back[(size_t(y) * kW + size_t(x)) * 4];
            if (b[0] != float(y) || b[1] != float(x) || b[2] != float((x * 7 + y * 3) % 1024) || b[3] != 1.0f)
                return std::string("GL does not read what CUDA wrote (") + (format == GL_RGBA32F ? "RGBA32F " : "RGBA16F ") +
                       std::to_string(kW) + "x" + std::to_string(kH) + ")";
        }
    return {};
}

struct StartupCheck {
    std::string problem;
    SharedTexture::Layout layout;
};

StartupCheck runStartupCheck() {
    if (!GLAD_GL_EXT_memory_object || !GLAD_GL_EXT_memory_object_fd)
        return {"the GL context has no GL_EXT_memory_object_fd"};
    const DriverApi& api = driverApi();
    if (!api.problem.empty()) return {api.problem};
    int posixFd = 0;
    if (api.deviceAttribute(&posixFd, CU_DEVICE_ATTRIBUTE_HANDLE_TYPE_POSIX_FILE_DESCRIPTOR_SUPPORTED,
                            CUdevice(currentDevice())) != CUDA_SUCCESS ||
        !posixFd)
        return {"the CUDA device cannot export allocations as file descriptors"};
    // The color-attachment flag first (the post textures are render targets in GL too), and a
    // plain memory object before a dedicated one; the first that round-trips both formats is used.
    std::string why;
    for (bool dedicated : {false, true})
        for (unsigned flags : {unsigned(cudaArraySurfaceLoadStore | cudaArrayColorAttachment),
                               unsigned(cudaArraySurfaceLoadStore)}) {
            const SharedTexture::Layout layout{flags, dedicated};
            try {
                why = roundTrip(GL_RGBA16F, layout, 67, 35, nullptr, nullptr);
                if (why.empty()) why = roundTrip(GL_RGBA32F, layout, 67, 35, nullptr, nullptr);
            } catch (const Error& e) {
                why = e.what();
            }
            while (glGetError() != GL_NO_ERROR) {
            }
            if (why.empty()) return {{}, layout};
        }
    return {"start-up round trip: " + why};
}

const StartupCheck& startupCheck() {
    static const StartupCheck result = runStartupCheck();
    return result;
}

}  // namespace

std::string sharedTexturesProblem() { return startupCheck().problem; }

std::vector<float> readSurfaceToHost(cudaSurfaceObject_t surface, bool half, int width, int height, cudaStream_t stream) {
    std::vector<float> out(size_t(width) * size_t(height) * 4);
    float4* device = nullptr;
    check(cudaMalloc(&device, out.size() * sizeof(float)), "cudaMalloc");
    const dim3 block(16, 16), grid((width + 15) / 16, (height + 15) / 16);
    if (half) readSurfaceKernel<<<grid, block, 0, stream>>>(Half4Surface{surface}, device, width, height);
    else readSurfaceKernel<<<grid, block, 0, stream>>>(Float4Surface{surface}, device, width, height);
    cudaError_t err = cudaMemcpyAsync(out.data(), device, out.size() * sizeof(float), cudaMemcpyDeviceToHost, stream);
    if (err == cudaSuccess) err = cudaStreamSynchronize(stream);
    cudaFree(device);
    check(err, "cudaMemcpy (surface to host)");
    return out;
}

std::string semaphoreRoundTrip(GlCudaSemaphores& sync, cudaStream_t stream) {
    const StartupCheck& c = startupCheck();
    if (!c.problem.empty()) return c.problem;
    try {
        for (GLenum format : {GLenum(GL_RGBA16F), GLenum(GL_RGBA32F)})
            for (auto [w, h] : {std::pair{67, 35}, std::pair{64, 48}})
                if (std::string why = roundTrip(format, c.layout, w, h, &sync, stream); !why.empty()) return why;
    } catch (const Error& e) {
        while (glGetError() != GL_NO_ERROR) {
        }
        return e.what();
    }
    return {};
}

std::string sharedTexturesLayoutName() {
    const StartupCheck& c = startupCheck();
    if (!c.problem.empty()) return {};
    return std::string("CUDA view with surface load/store") +
           (c.layout.arrayFlags & cudaArrayColorAttachment ? " + color attachment" : "") +
           (c.layout.dedicated ? ", dedicated memory objects" : ", memory objects not dedicated");
}

std::unique_ptr<SharedTexture> SharedTexture::make(GLenum format, int width, int height, const std::string& label,
                                                   const Layout& layout) {
    if (format != GL_RGBA16F && format != GL_RGBA32F) throw Error("shared texture '" + label + "': unsupported format");
    const DriverApi& api = driverApi();
    if (!api.problem.empty()) throw Error(api.problem);
    std::unique_ptr<SharedTexture> t(new SharedTexture);
    const CUmemAllocationProp prop = allocationProp();
    size_t granularity = 0;
    checkDriver(api.granularity(&granularity, &prop, CU_MEM_ALLOC_GRANULARITY_RECOMMENDED),
                "cuMemGetAllocationGranularity");
    const size_t bytes = roundUp(allocationBytes(format, width, height), std::max<size_t>(granularity, 1));
    CUmemGenericAllocationHandle allocation = 0;
    checkDriver(api.memCreate(&allocation, bytes, &prop, 0), "cuMemCreate");
    t->allocation_ = allocation;

    while (glGetError() != GL_NO_ERROR) {  // earlier errors are not this texture's
    }
    glCreateMemoryObjectsEXT(1, &t->memoryObject_);
    if (layout.dedicated) {
        const GLint yes = GL_TRUE;
        glMemoryObjectParameterivEXT(t->memoryObject_, GL_DEDICATED_MEMORY_OBJECT_EXT, &yes);
    }
    int fd = exportFd(allocation);
    glImportMemoryFdEXT(t->memoryObject_, GLuint64(bytes), GL_HANDLE_TYPE_OPAQUE_FD_EXT, fd);  // GL owns fd now
    if (glGetError() != GL_NO_ERROR) {
        close(fd);  // not taken
        throw Error("GL glImportMemoryFdEXT refused the CUDA allocation's descriptor");
    }
    glCreateTextures(GL_TEXTURE_2D, 1, &t->texture_);
    glTextureParameteri(t->texture_, GL_TEXTURE_TILING_EXT, GL_OPTIMAL_TILING_EXT);
    glTextureStorageMem2DEXT(t->texture_, 1, format, width, height, t->memoryObject_, 0);
    checkGl("glTextureStorageMem2DEXT");
    glTextureParameteri(t->texture_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t->texture_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(t->texture_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t->texture_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl::label(GL_TEXTURE, t->texture_, label);

    cudaExternalMemoryHandleDesc memory{};
    memory.type = cudaExternalMemoryHandleTypeOpaqueFd;
    memory.handle.fd = exportFd(allocation);
    memory.size = bytes;
    memory.flags = layout.dedicated ? cudaExternalMemoryDedicated : 0;
    cudaError_t err = cudaImportExternalMemory(&t->external_, &memory);  // CUDA owns the fd on success
    if (err != cudaSuccess) close(memory.handle.fd);
    check(err, "cudaImportExternalMemory");
    cudaExternalMemoryMipmappedArrayDesc view{};
    view.offset = 0;
    const int bits = format == GL_RGBA32F ? 32 : 16;
    view.formatDesc = cudaCreateChannelDesc(bits, bits, bits, bits, cudaChannelFormatKindFloat);
    view.extent = make_cudaExtent(size_t(width), size_t(height), 0);
    view.flags = layout.arrayFlags;
    view.numLevels = 1;
    check(cudaExternalMemoryGetMappedMipmappedArray(&t->mipmapped_, t->external_, &view),
          "cudaExternalMemoryGetMappedMipmappedArray");
    cudaArray_t level = nullptr;
    check(cudaGetMipmappedArrayLevel(&level, t->mipmapped_, 0), "cudaGetMipmappedArrayLevel");
    cudaResourceDesc res{};
    res.resType = cudaResourceTypeArray;
    res.res.array.array = level;
    check(cudaCreateSurfaceObject(&t->surface_, &res), "cudaCreateSurfaceObject");
    return t;
}

SharedTexture::~SharedTexture() {
    // No throwing from a destructor: errors here are reported and the rest is still released.
    auto warn = [](cudaError_t err, const char* call) {
        if (err == cudaSuccess) return;
        std::fprintf(stderr, "warning: CUDA %s: %s\n", call, cudaGetErrorString(err));
        cudaGetLastError();
    };
    if (surface_) warn(cudaDestroySurfaceObject(surface_), "cudaDestroySurfaceObject");
    if (mipmapped_) warn(cudaFreeMipmappedArray(mipmapped_), "cudaFreeMipmappedArray");
    if (external_) warn(cudaDestroyExternalMemory(external_), "cudaDestroyExternalMemory");
    if (texture_) glDeleteTextures(1, &texture_);
    if (memoryObject_) glDeleteMemoryObjectsEXT(1, &memoryObject_);
    if (allocation_ && driverApi().memRelease) driverApi().memRelease(CUmemGenericAllocationHandle(allocation_));
}

std::shared_ptr<fg::ExternalTexture> SharedTextures::make(const fg::TextureDesc& desc, const std::string& label) {
    if ((desc.format != GL_RGBA16F && desc.format != GL_RGBA32F) || desc.levels != 1 || desc.cube) return nullptr;
    const StartupCheck& ok = startupCheck();
    if (!ok.problem.empty()) return nullptr;
    std::shared_ptr<SharedTexture> t = SharedTexture::make(desc.format, desc.width, desc.height, label, ok.layout);
    made_.erase(std::remove_if(made_.begin(), made_.end(), [](const auto& w) { return w.expired(); }), made_.end());
    made_.push_back(t);
    return t;
}

cudaSurfaceObject_t SharedTextures::surfaceOf(GLuint texture) const {
    for (const auto& w : made_)
        if (auto t = w.lock(); t && t->texture() == texture) return t->surface();
    return 0;
}

}  // namespace lp::cuda
