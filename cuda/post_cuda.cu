// The CUDA post effects' host side: device checks, GL interop per call, CUDA-event timing,
// and the device-buffer runs the tests use.
#include "cuda/post_cuda.hpp"

#include <algorithm>
#include <chrono>
#include <initializer_list>

#include "cuda/external_memory.hpp"
#include "cuda/gl_cuda_semaphores.hpp"
#include "cuda/interop.hpp"
#include "cuda/post_kernels.cuh"

namespace lp::cuda {

std::string postDeviceProblem() {
    int count = 0;
    cudaError_t err = cudaGetDeviceCount(&count);
    if (err != cudaSuccess) {
        cudaGetLastError();
        return std::string("cudaGetDeviceCount: ") + cudaGetErrorString(err);
    }
    if (count <= 0) return "no CUDA device";
    return {};
}

namespace {

// CUDA events around the kernels of one kind of call on `stream`. The host does not wait for
// them: begin() reports the newest finished call's kernel time among the few still tracked (0
// before any finished), so timing costs no CPU<->GPU round trip per pass. Only when every slot is
// still in flight (the host far ahead of the GPU) does it wait for the oldest.
class LaggedEventTimer {
public:
    LaggedEventTimer() {
        for (Slot& s : slots_) {
            check(cudaEventCreate(&s.begin), "cudaEventCreate");
            check(cudaEventCreate(&s.end), "cudaEventCreate");
        }
    }
    ~LaggedEventTimer() {
        for (Slot& s : slots_) {
            cudaEventDestroy(s.begin);
            cudaEventDestroy(s.end);
        }
    }
    LaggedEventTimer(const LaggedEventTimer&) = delete;
    LaggedEventTimer& operator=(const LaggedEventTimer&) = delete;
    double begin(cudaStream_t stream) {
        for (int i = 0; i < kSlots; ++i) {  // oldest first, so the newest finished one is reported
            Slot& s = slots_[(next_ + i) % kSlots];
            if (!s.pending) continue;
            const cudaError_t q = cudaEventQuery(s.end);
            if (q == cudaErrorNotReady) {
                cudaGetLastError();  // not an error: still running
                continue;
            }
            check(q, "cudaEventQuery");
            read(s);
        }
        Slot& s = slots_[next_];
        if (s.pending) {
            check(cudaEventSynchronize(s.end), "cudaEventSynchronize");
            read(s);
        }
        check(cudaEventRecord(s.begin, stream), "cudaEventRecord");
        current_ = next_;
        next_ = (next_ + 1) % kSlots;
        return lastMs_;
    }
    void end(cudaStream_t stream) {
        check(cudaEventRecord(slots_[current_].end, stream), "cudaEventRecord");
        slots_[current_].pending = true;
    }
    // After the host waited for the stream past end(): this call's kernel time, read now.
    double current() {
        read(slots_[current_]);
        return lastMs_;
    }

private:
    static constexpr int kSlots = 4;
    struct Slot {
        cudaEvent_t begin = nullptr, end = nullptr;
        bool pending = false;
    };
    void read(Slot& s) {
        float ms = 0.0f;
        check(cudaEventElapsedTime(&ms, s.begin, s.end), "cudaEventElapsedTime");
        lastMs_ = double(ms);
        s.pending = false;
    }
    Slot slots_[kSlots];
    int next_ = 0, current_ = 0;
    double lastMs_ = 0.0;
};

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

// Device copies of host images.
struct DeviceImage {
    float4* data = nullptr;
    DeviceImage(const ImageF& img) {
        const size_t bytes = size_t(img.width) * size_t(img.height) * sizeof(float4);
        check(cudaMalloc(&data, bytes), "cudaMalloc");
        check(cudaMemcpy(data, img.rgba.data(), bytes, cudaMemcpyHostToDevice), "cudaMemcpy (to device)");
    }
    DeviceImage(int width, int height) {
        check(cudaMalloc(&data, size_t(width) * size_t(height) * sizeof(float4)), "cudaMalloc");
    }
    ~DeviceImage() { cudaFree(data); }
    DeviceImage(const DeviceImage&) = delete;
    DeviceImage& operator=(const DeviceImage&) = delete;
    ImageF download(int width, int height) const {
        ImageF out;
        out.width = width;
        out.height = height;
        out.rgba.resize(size_t(width) * size_t(height) * 4);
        check(cudaMemcpy(out.rgba.data(), data, out.rgba.size() * sizeof(float), cudaMemcpyDeviceToHost),
              "cudaMemcpy (to host)");
        return out;
    }
};

// The host waits until GL has done every command issued so far (what the kernels read was
// written by them); a fence, not glFinish, so nothing beyond this point is drained.
void waitForGl() {
    GLsync fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    const GLenum r = glClientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, GLuint64(10) * 1000000000ull);
    glDeleteSync(fence);
    if (r == GL_TIMEOUT_EXPIRED || r == GL_WAIT_FAILED)
        throw Error("GL fence before the CUDA post kernels: " + std::string(r == GL_TIMEOUT_EXPIRED ? "timed out" : "failed"));
}

}  // namespace

struct PostInterop::Impl {
    GlImageRegistry registry;
    std::unique_ptr<SharedTextures> shared;  // null: every texture is mapped
    std::unique_ptr<GlCudaSemaphores> semaphores;  // null: shared textures are ordered by host waits
    std::string semaphoreProblem;
    BloomWorkspace workspace;
    LaggedEventTimer bloomTimer, compositeTimer, toonTimer;
    cudaStream_t stream = nullptr;
    cudaEvent_t done = nullptr;
    Impl() {
        check(cudaStreamCreate(&stream), "cudaStreamCreate");
        check(cudaEventCreateWithFlags(&done, cudaEventDisableTiming), "cudaEventCreate");
    }
    ~Impl() {
        semaphores.reset();  // waits for what is in flight on either side
        cudaStreamSynchronize(stream);
        cudaEventDestroy(done);
        cudaStreamDestroy(stream);
    }

    // Runs `kernels(surfaces)` on the textures timed by `timer`: on their shared surfaces when the
    // shared-texture source made them all, else mapped for the call.
    template <class Kernels>
    PostTiming run(std::initializer_list<GLuint> textures, int width, int height, LaggedEventTimer& timer,
                   Kernels&& kernels) {
        std::vector<cudaSurfaceObject_t> surfaces;
        for (GLuint texture : textures)
            if (cudaSurfaceObject_t s = shared ? shared->surfaceOf(texture) : 0) surfaces.push_back(s);
        if (surfaces.size() == textures.size())
            return semaphores ? runOrderedBySemaphores(textures, surfaces, timer, kernels)
                              : runShared(surfaces, timer, kernels);
        std::vector<cudaGraphicsResource_t> resources;
        for (GLuint texture : textures) resources.push_back(registry.resource(texture, width, height));
        PostTiming t;
        auto t0 = Clock::now();
        MappedSurfaces mapped(std::move(resources), stream);
        t.interopMs = msSince(t0);
        for (size_t i = 0; i < textures.size(); ++i) surfaces.push_back(mapped.surface(i));
        t.kernelMs = timer.begin(stream);
        kernels(surfaces.data());
        timer.end(stream);
        auto t1 = Clock::now();
        mapped.unmap();
        t.interopMs += msSince(t1);
        return t;
    }

    // GL hands the textures to CUDA's stream and CUDA hands them back through the semaphores: the
    // queues order themselves and the host goes on at once. The interop time is the host's cost of
    // the two hand-overs (what the GPU pays shows in the pass's GL time); the kernel time is the
    // newest finished call's, as on the map path.
    template <class Kernels>
    PostTiming runOrderedBySemaphores(std::initializer_list<GLuint> textures,
                                      const std::vector<cudaSurfaceObject_t>& surfaces, LaggedEventTimer& timer,
                                      Kernels&& kernels) {
        PostTiming t;
        t.shared = true;
        t.gpuOrdered = true;
        const int n = int(textures.size());
        auto t0 = Clock::now();
        semaphores->glThenCuda(textures.begin(), n, stream);
        t.interopMs = msSince(t0);
        t.kernelMs = timer.begin(stream);
        kernels(surfaces.data());
        timer.end(stream);
        auto t1 = Clock::now();
        semaphores->cudaThenGl(textures.begin(), n, stream);
        t.interopMs += msSince(t1);
        return t;
    }

    // Without semaphores (no Vulkan device or loader) the host orders the two: GL's work done
    // before the kernels, the kernels done before GL goes on. The interop time is both waits less
    // the kernels' own time.
    template <class Kernels>
    PostTiming runShared(const std::vector<cudaSurfaceObject_t>& surfaces, LaggedEventTimer& timer, Kernels&& kernels) {
        PostTiming t;
        t.shared = true;
        auto t0 = Clock::now();
        waitForGl();
        t.interopMs = msSince(t0);
        timer.begin(stream);  // nothing pending: the previous call was read at its end
        kernels(surfaces.data());
        timer.end(stream);
        auto t1 = Clock::now();
        check(cudaEventRecord(done, stream), "cudaEventRecord");
        check(cudaEventSynchronize(done), "cudaEventSynchronize");
        const double waited = msSince(t1);
        t.kernelMs = timer.current();
        t.interopMs += std::max(0.0, waited - t.kernelMs);
        return t;
    }
};

PostInterop::PostInterop() : impl_(std::make_unique<Impl>()) {}
PostInterop::~PostInterop() = default;

int PostInterop::registeredCount() const { return impl_->registry.size(); }
void PostInterop::forgetTexture(GLuint texture) { impl_->registry.forget(texture); }

std::string PostInterop::useSharedTextures(SharedSync preferred) {
    std::string problem = sharedTexturesProblem();
    if (!problem.empty()) return problem;
    if (!impl_->shared) impl_->shared = std::make_unique<SharedTextures>();
    if (preferred == SharedSync::HostWaits) {
        impl_->semaphores.reset();
        impl_->semaphoreProblem.clear();
    } else if (!impl_->semaphores) {
        std::string why;
        impl_->semaphores = GlCudaSemaphores::make(why);
        if (impl_->semaphores) why = semaphoreRoundTrip(*impl_->semaphores, impl_->stream);
        if (!why.empty()) impl_->semaphores.reset();
        impl_->semaphoreProblem = why;
    }
    return {};
}

SharedSync PostInterop::sharedSync() const { return impl_->semaphores ? SharedSync::Semaphores : SharedSync::HostWaits; }
const std::string& PostInterop::semaphoreProblem() const { return impl_->semaphoreProblem; }

std::string PostInterop::syncName() const {
    if (!impl_->shared) return "map/unmap";
    if (impl_->semaphores) return "Vulkan semaphores (" + impl_->semaphores->deviceName() + ")";
    return "host waits (GL fence, CUDA event)";
}

ImageF PostInterop::readShared(GLuint texture, GLenum format, int width, int height) {
    const cudaSurfaceObject_t surface = impl_->shared ? impl_->shared->surfaceOf(texture) : 0;
    if (!surface) throw Error("readShared: texture " + std::to_string(texture) + " is not a shared texture");
    if (impl_->semaphores) impl_->semaphores->glThenCuda(&texture, 1, impl_->stream);
    else waitForGl();
    ImageF out;
    out.width = width;
    out.height = height;
    out.rgba = readSurfaceToHost(surface, format == GL_RGBA16F, width, height, impl_->stream);
    if (impl_->semaphores) impl_->semaphores->cudaThenGl(&texture, 1, impl_->stream);
    return out;
}

fg::ExternalTextureSource* PostInterop::sharedTextureSource() { return impl_->shared.get(); }
void PostInterop::beginFrame(unsigned long frame) { impl_->registry.beginFrame(frame); }

PostTiming PostInterop::bloom(GLuint hdr, GLuint bloom, int width, int height, const post::BloomParams& p) {
    return impl_->run({hdr, bloom}, width, height, impl_->bloomTimer, [&](const cudaSurfaceObject_t* s) {
        bloomSurfaceToSurface(s[0], s[1], width, height, p, impl_->workspace, impl_->stream);
    });
}

PostTiming PostInterop::bloomComposite(GLuint hdr, GLuint bloom, int width, int height, const post::BloomParams& p) {
    return impl_->run({hdr, bloom}, width, height, impl_->bloomTimer, [&](const cudaSurfaceObject_t* s) {
        bloomCompositeSurfaces(s[0], s[1], width, height, p, impl_->workspace, impl_->stream);
    });
}

PostTiming PostInterop::composite(GLuint hdr, GLuint bloom, int width, int height, float strength) {
    return impl_->run({hdr, bloom}, width, height, impl_->compositeTimer, [&](const cudaSurfaceObject_t* s) {
        compositeSurfaces(s[0], s[1], width, height, strength, impl_->stream);
    });
}

PostTiming PostInterop::toon(GLuint hdr, GLuint position, GLuint normal, int width, int height,
                             const post::ToonParams& p) {
    return impl_->run({hdr, position, normal}, width, height, impl_->toonTimer, [&](const cudaSurfaceObject_t* s) {
        toonSurfaces(s[0], s[1], s[2], width, height, p, impl_->stream);
    });
}

ImageF bloomOnDevice(const ImageF& hdr, const post::BloomParams& p, BloomBlur blur) {
    DeviceImage in(hdr), out(hdr.width, hdr.height);
    BloomWorkspace ws;
    ws.blur = blur;
    bloomBufferToBuffer(in.data, out.data, hdr.width, hdr.height, p, ws, nullptr);
    check(cudaDeviceSynchronize(), "cudaDeviceSynchronize");
    return out.download(hdr.width, hdr.height);
}

BloomAndComposite bloomCompositeOnDevice(const ImageF& hdr, const post::BloomParams& p, BloomBlur blur) {
    DeviceImage in(hdr), bloom(hdr.width, hdr.height);
    BloomWorkspace ws;
    ws.blur = blur;
    bloomCompositeBuffers(in.data, bloom.data, in.data, hdr.width, hdr.height, p, ws, nullptr);  // in place
    check(cudaDeviceSynchronize(), "cudaDeviceSynchronize");
    return {bloom.download(hdr.width, hdr.height), in.download(hdr.width, hdr.height)};
}

ImageF compositeOnDevice(const ImageF& hdr, const ImageF& bloom, float strength) {
    DeviceImage h(hdr), b(bloom), out(hdr.width, hdr.height);
    compositeBuffers(h.data, b.data, out.data, hdr.width, hdr.height, strength, nullptr);
    check(cudaDeviceSynchronize(), "cudaDeviceSynchronize");
    return out.download(hdr.width, hdr.height);
}

ImageF toonOnDevice(const ImageF& hdr, const ImageF& position, const ImageF& normal, const post::ToonParams& p) {
    DeviceImage h(hdr), pos(position), n(normal), out(hdr.width, hdr.height);
    toonBuffers(h.data, pos.data, n.data, out.data, hdr.width, hdr.height, p, nullptr);
    check(cudaDeviceSynchronize(), "cudaDeviceSynchronize");
    return out.download(hdr.width, hdr.height);
}

}  // namespace lp::cuda
