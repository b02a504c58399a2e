#pragma once
// Bloom and toon in CUDA, the plain-C++ face of cuda/bloom.cu, cuda/toon.cu and
// cuda/interop.cu (only built with a CUDA toolkit: LIGHTPASS_HAVE_CUDA).
//
// Two entry points: PostInterop works on GL textures and is what the passes use. Textures made by
// its shared-texture source (cuda/external_memory.hpp: GL memory objects on CUDA allocations, one
// surface each for their lifetime) are used as they are, ordered on the GPU by semaphores Vulkan
// makes (cuda/gl_cuda_semaphores.hpp), or where those are unavailable by host waits on a GL fence
// and a CUDA event; any other texture is registered once with cudaGraphicsGLRegisterImage and
// mapped per call. The *OnDevice functions take host images, run the same kernels on device buffers
// and copy back, so the kernels can be tested against the CPU reference without a GL context.
#include <memory>
#include <string>
#include <vector>

#include "engine/gl/gl.hpp"
#include "engine/io/image_io.hpp"
#include "engine/post/post_params.hpp"

namespace lp::fg {
struct ExternalTextureSource;
}

namespace lp::cuda {

// Empty when a CUDA device can run the kernels, else why not ("cudaGetDeviceCount: ...").
std::string postDeviceProblem();
// Empty when GL and CUDA can share textures through external memory here (GL_EXT_memory_object_fd,
// CUDA allocations exportable as file descriptors, and a start-up round trip through small textures
// that agrees texel for texel), else why not. Needs the GL context current; runs once per process.
std::string sharedTexturesProblem();
// Which layout the start-up round trip settled on ("CUDA view with surface load/store + color
// attachment, memory objects not dedicated"); empty when shared textures do not work.
std::string sharedTexturesLayoutName();

struct PostTiming {
    double kernelMs = 0.0;   // CUDA events around the kernels of the previous call of the same kind
                             // (read without waiting; 0 on the first call)
    double interopMs = 0.0;  // host time of cudaGraphicsMapResources + UnmapResources, or on shared
                             // textures the host's waits for GL (GL work still in flight included)
                             // and for CUDA beyond the kernels
    bool shared = false;     // ran on shared textures (no map/unmap)
    bool gpuOrdered = false; // shared, and ordered by semaphores on the GPU (no host wait)
};

// How GL and CUDA are ordered around the kernels on shared textures.
enum class SharedSync {
    Semaphores,  // Vulkan-made semaphores imported by both: GL signals, CUDA waits, runs, signals, GL waits
    HostWaits,   // the host waits on a GL fence before the kernels and on a CUDA event after them
};

class PostInterop {
public:
    PostInterop();
    ~PostInterop();
    PostInterop(const PostInterop&) = delete;
    PostInterop& operator=(const PostInterop&) = delete;

    // hdr: RGBA16F (read); bloom: RGBA16F (written: the bloom buffer alone, before strength).
    PostTiming bloom(GLuint hdr, GLuint bloom, int width, int height, const post::BloomParams& p);
    // bloom() then composite() with p.strength in one mapped section, the composite fused into the
    // last bloom kernel (the passes use it when bloom_composite runs right after bloom).
    PostTiming bloomComposite(GLuint hdr, GLuint bloom, int width, int height, const post::BloomParams& p);
    // hdr = sanitize(sanitize(hdr) + strength * bloom), in place.
    PostTiming composite(GLuint hdr, GLuint bloom, int width, int height, float strength);
    // hdr in place; position and normal: the G-buffer's RGBA32F targets.
    PostTiming toon(GLuint hdr, GLuint position, GLuint normal, int width, int height, const post::ToonParams& p);
    // Call once per frame before the calls of that frame (`frame` grows by one per frame):
    // registrations idle for more than two frames are dropped.
    void beginFrame(unsigned long frame);
    // Textures registered now (tests: registration happens once per texture).
    int registeredCount() const;
    // Before deleting a texture outside the pool: drops its map/unmap registration.
    void forgetTexture(GLuint texture);
    // Makes textures through a shared-texture source from now on when they work here; returns why
    // not otherwise (and stays on map/unmap). Needs the GL context current. The ordering is
    // `preferred` where it works: Semaphores falls back to HostWaits when the semaphores cannot be
    // made or their round trip (cuda/external_memory.hpp) disagrees; semaphoreProblem() says why.
    std::string useSharedTextures(SharedSync preferred = SharedSync::Semaphores);
    // The ordering in use on shared textures (HostWaits also before useSharedTextures).
    SharedSync sharedSync() const;
    // Why the semaphores are not used ("no Vulkan loader (...)"); empty when they are or were not asked for.
    const std::string& semaphoreProblem() const;
    // "Vulkan semaphores (NVIDIA H100 80GB HBM3)", "host waits (GL fence, CUDA event)" or "map/unmap".
    std::string syncName() const;
    // What the CUDA kernels would read from a shared texture (format RGBA16F or RGBA32F) now,
    // handed over from GL as before a kernel: tests compare it with what GL wrote. Throws for a
    // texture the shared source did not make.
    ImageF readShared(GLuint texture, GLenum format, int width, int height);
    // Where the texture pool gets the textures the CUDA passes touch; null on the map/unmap path.
    fg::ExternalTextureSource* sharedTextureSource();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// Which kernels run the separable blur (cuda/bloom.cu): Auto picks the tensor-core blur where the
// device has it (sm_80+) and the radius is at least kTensorBlurMinRadius, else the direct one; the
// others force one (tests, benchmark; TensorCore falls back to Direct where the device lacks it).
enum class BloomBlur { Auto, Direct, TensorCore };
// Whether a separable bloom of `kernel` px with `blur` runs on the tensor cores on this device.
bool bloomBlurUsesTensorCores(int kernel, BloomBlur blur);

// How the mip-chain bloom (cuda/bloom_mip_chain.cu) runs; the defaults are what the passes use. Two
// settings the passes' launches read anyway, so that the benchmark can measure what the one-block
// tail and the overlapping launches buy and the tests cover the paths without them. (The variants
// that lost on the H100 were removed from the kernels: bench/results/post/2026-11-24_cuda-interop/README.md.)
struct MipChainTuning {
    int tailTexels = 4096;          // levels of at most this many texels run down and up in one block (0: none)
    bool programmaticLaunch = true; // sm_90: launches overlap their predecessors' ends (on created streams)
};

// Device-buffer runs (fp32 intermediates) for tests and the benchmark.
ImageF bloomOnDevice(const ImageF& hdr, const post::BloomParams& p,
                     BloomBlur blur = BloomBlur::Auto);  // the bloom buffer
struct BloomAndComposite {
    ImageF bloom, hdr;
};
BloomAndComposite bloomCompositeOnDevice(const ImageF& hdr, const post::BloomParams& p,
                                         BloomBlur blur = BloomBlur::Auto);  // the fused path

// Kernel-only time of the fused bloom + composite (or, with composite false, of the bloom buffer
// alone) on RGBA16F CUDA arrays (the layout of the GL textures the passes share, without GL):
// median of `iterations` CUDA-event timings after a warm-up, and the device's copy bandwidth (bytes
// read + written per second by a device-to-device copy of 512 MiB) for the floor.
struct BloomKernelTime {
    double medianMs = 0.0;
    double copyBytesPerSecond = 0.0;
    bool tensorCores = false;  // the blur ran on the tensor cores
};
// One launch of the mip chain timed alone (no overlap with its neighbours): median ms and the bytes
// it reads and writes at least.
struct MipChainStep {
    std::string name;  // "down0", "down1", ..., "tail", "up3", ..., "final"
    double ms = 0.0, bytes = 0.0;
};
// With `steps`, the mip chain is also run `iterations` more times with each launch timed alone.
BloomKernelTime timeBloomCompositeKernels(int width, int height, const post::BloomParams& p, BloomBlur blur,
                                          int iterations, bool composite = true, const MipChainTuning& tuning = {},
                                          std::vector<MipChainStep>* steps = nullptr);
// The surface path without GL: `hdr` uploaded into an RGBA16F CUDA array (rounded to fp16), the
// bloom + composite in place (or, with composite false, the bloom alone) on a created stream as
// the passes run it, both arrays read back.
BloomAndComposite bloomCompositeOnHalfArrays(const ImageF& hdr, const post::BloomParams& p,
                                             BloomBlur blur = BloomBlur::Auto, bool composite = true,
                                             const MipChainTuning& tuning = {});
// The achievable bandwidth of plain copies of an RGBA16F image, the baseline of the kernels'
// floors: one kernel copying CUDA array to CUDA array through surfaces (the GL textures' layout)
// and one copying linear memory to linear memory (16-byte loads and stores); medians of
// `iterations` CUDA-event timings, and the device-to-device cudaMemcpy bandwidth as above.
struct CopyKernelTimes {
    double arrayMs = 0.0, linearMs = 0.0;
    double copyBytesPerSecond = 0.0;
};
CopyKernelTimes timeHalf4Copies(int width, int height, int iterations);
ImageF compositeOnDevice(const ImageF& hdr, const ImageF& bloom, float strength);
ImageF toonOnDevice(const ImageF& hdr, const ImageF& position, const ImageF& normal, const post::ToonParams& p);

}  // namespace lp::cuda
