#pragma once
// Kernels shared by cuda/bloom.cu, cuda/toon.cu and cuda/post_cuda.cu: texel accessors for
// device buffers and mapped GL surfaces, the device workspace, and the host-side launchers.
#include <cuda_fp16.h>
#include <cuda_runtime.h>

#include <string>
#include <utility>
#include <vector>

#include "cuda/post_cuda.hpp"
#include "engine/post/post_math.hpp"
#include "engine/post/post_params.hpp"

namespace lp::cuda {

// A row-major float4 image in device memory.
struct BufferImage {
    float4* data;
    int width;
    __device__ float4 load(int x, int y) const { return data[size_t(y) * size_t(width) + size_t(x)]; }
    __device__ void store(int x, int y, float4 c) const { data[size_t(y) * size_t(width) + size_t(x)] = c; }
    __device__ static float4 stored(float4 c) { return c; }  // what load() returns after store(c)
};

// RGBA16F texels packed in 8 bytes (one access) and back; packing rounds to nearest even.
__device__ inline float4 unpackHalf4(uint2 v) {
    const float2 rg = __half22float2(*reinterpret_cast<const __half2*>(&v.x));
    const float2 ba = __half22float2(*reinterpret_cast<const __half2*>(&v.y));
    return make_float4(rg.x, rg.y, ba.x, ba.y);
}
__device__ inline uint2 packHalf4(float4 c) {
    const __half2 rg = __floats2half2_rn(c.x, c.y), ba = __floats2half2_rn(c.z, c.w);
    return make_uint2(*reinterpret_cast<const unsigned*>(&rg), *reinterpret_cast<const unsigned*>(&ba));
}

// A row-major RGBA16F image in device memory: scratch where the results land in RGBA16F
// textures anyway (half the bytes of BufferImage).
struct HalfBufferImage {
    uint2* data;
    int width;
    __device__ float4 load(int x, int y) const { return unpackHalf4(data[size_t(y) * size_t(width) + size_t(x)]); }
    __device__ void store(int x, int y, float4 c) const { data[size_t(y) * size_t(width) + size_t(x)] = packHalf4(c); }
};

// A mapped RGBA16F GL texture (the HDR buffer, the bloom buffer).
struct Half4Surface {
    cudaSurfaceObject_t surface;
    __device__ float4 load(int x, int y) const {
        ushort4 v = surf2Dread<ushort4>(surface, x * int(sizeof(ushort4)), y);
        return make_float4(__half2float(__ushort_as_half(v.x)), __half2float(__ushort_as_half(v.y)),
                           __half2float(__ushort_as_half(v.z)), __half2float(__ushort_as_half(v.w)));
    }
    __device__ void store(int x, int y, float4 c) const {
        ushort4 v = make_ushort4(__half_as_ushort(__float2half_rn(c.x)), __half_as_ushort(__float2half_rn(c.y)),
                                 __half_as_ushort(__float2half_rn(c.z)), __half_as_ushort(__float2half_rn(c.w)));
        surf2Dwrite(v, surface, x * int(sizeof(ushort4)), y);
    }
    __device__ static float4 stored(float4 c) {  // what load() returns after store(c)
        return make_float4(__half2float(__float2half_rn(c.x)), __half2float(__float2half_rn(c.y)),
                           __half2float(__float2half_rn(c.z)), __half2float(__float2half_rn(c.w)));
    }
};

// A mapped RGBA32F GL texture (G-buffer position and normal).
struct Float4Surface {
    cudaSurfaceObject_t surface;
    __device__ float4 load(int x, int y) const { return surf2Dread<float4>(surface, x * int(sizeof(float4)), y); }
    __device__ void store(int x, int y, float4 c) const { surf2Dwrite(c, surface, x * int(sizeof(float4)), y); }
};

// CUDA events around each launch of a chain of kernels, for the benchmark's per-kernel times.
class StepRecorder {
public:
    StepRecorder() = default;
    ~StepRecorder() {
        for (auto& e : events_) {
            cudaEventDestroy(e.first);
            cudaEventDestroy(e.second);
        }
    }
    StepRecorder(const StepRecorder&) = delete;
    StepRecorder& operator=(const StepRecorder&) = delete;
    void restart() { next_ = 0; }
    void begin(cudaStream_t stream) {
        if (next_ == events_.size()) {
            std::pair<cudaEvent_t, cudaEvent_t> e{};
            cudaEventCreate(&e.first);
            cudaEventCreate(&e.second);
            events_.push_back(e);
            names_.emplace_back();
            bytes_.push_back(0.0);
        }
        cudaEventRecord(events_[next_].first, stream);
    }
    void end(cudaStream_t stream, const char* name, double bytes) {
        cudaEventRecord(events_[next_].second, stream);
        names_[next_] = name;
        bytes_[next_] = bytes;
        ++next_;
    }
    // After the stream finished: the steps of the last run.
    size_t count() const { return next_; }
    const std::string& name(size_t i) const { return names_[i]; }
    double bytes(size_t i) const { return bytes_[i]; }
    double ms(size_t i) const {
        float t = 0.0f;
        cudaEventElapsedTime(&t, events_[i].first, events_[i].second);
        return double(t);
    }

private:
    std::vector<std::pair<cudaEvent_t, cudaEvent_t>> events_;
    std::vector<std::string> names_;
    std::vector<double> bytes_;
    size_t next_ = 0;
};

// Device scratch of the bloom: the full-resolution horizontal-blur buffer and the mip chain, grown
// on demand; and which separable blur runs (the tensor-core blur needs only per-block counters).
struct BloomWorkspace {
    BloomBlur blur = BloomBlur::Auto;
    MipChainTuning mipChain;
    StepRecorder* recorder = nullptr;  // when set, the mip chain records each launch (and does not overlap them)
    float4* a = nullptr;
    size_t fullTexels = 0;
    float4* mips[post::kMaxMipLevels] = {};
    size_t mipTexels[post::kMaxMipLevels] = {};
    int* progress = nullptr;  // the tensor-core blur's per-block counters when it composites in place
    size_t progressCount = 0;
    BloomWorkspace() = default;
    ~BloomWorkspace();
    BloomWorkspace(const BloomWorkspace&) = delete;
    BloomWorkspace& operator=(const BloomWorkspace&) = delete;
    void ensure(int width, int height, const post::BloomParams& p);
    int* progressCounters(size_t count);  // at least `count`, grown on demand
};

// The mip-chain bloom (cuda/bloom_mip_chain.cu). On device buffers: fp32 levels, the bloom into
// `bloom` and, with hdrOut non-null, the composite into hdrOut (may be hdr). On RGBA16F surfaces:
// fp16 levels (as GLSL's RGBA16F mips), the composite in place into hdr when `composite`.
void mipChainBloomBuffers(const float4* hdr, float4* bloom, float4* hdrOut, int width, int height,
                          const post::BloomParams& p, BloomWorkspace& ws, cudaStream_t stream);
void mipChainBloomSurfaces(cudaSurfaceObject_t hdr, cudaSurfaceObject_t bloom, bool composite, int width, int height,
                           const post::BloomParams& p, BloomWorkspace& ws, cudaStream_t stream);

// An RGBA16F CUDA array with its surface, as the GL textures the passes share (benchmarks, tests).
struct Half4Array {
    cudaArray_t array = nullptr;
    cudaSurfaceObject_t surface = 0;
    Half4Array(int width, int height);
    ~Half4Array();
    Half4Array(const Half4Array&) = delete;
    Half4Array& operator=(const Half4Array&) = delete;
};

// Bloom buffer of `hdr` into `bloom` (fp32 intermediates), by p.method.
void bloomBufferToBuffer(const float4* hdr, float4* bloom, int width, int height, const post::BloomParams& p,
                         BloomWorkspace& ws, cudaStream_t stream);
void bloomSurfaceToSurface(cudaSurfaceObject_t hdr, cudaSurfaceObject_t bloom, int width, int height,
                           const post::BloomParams& p, BloomWorkspace& ws, cudaStream_t stream);
// Both at once: the bloom buffer into `bloom` and, from the last bloom kernel's outputs as stored,
// hdrOut = sanitize(sanitize(hdr) + p.strength * bloom) (hdrOut may be hdr: in place). One launch
// fewer, and through interop one map/unmap fewer, than bloom then composite.
void bloomCompositeBuffers(const float4* hdr, float4* bloom, float4* hdrOut, int width, int height,
                           const post::BloomParams& p, BloomWorkspace& ws, cudaStream_t stream);
void bloomCompositeSurfaces(cudaSurfaceObject_t hdr, cudaSurfaceObject_t bloom, int width, int height,
                            const post::BloomParams& p, BloomWorkspace& ws, cudaStream_t stream);
// out = sanitize(hdr + strength * bloom).
void compositeBuffers(const float4* hdr, const float4* bloom, float4* out, int width, int height, float strength,
                      cudaStream_t stream);
void compositeSurfaces(cudaSurfaceObject_t hdr, cudaSurfaceObject_t bloom, int width, int height, float strength,
                       cudaStream_t stream);
// Toon (ramp + outlines) of hdr into out; the surface version works in place.
void toonBuffers(const float4* hdr, const float4* position, const float4* normal, float4* out, int width, int height,
                 const post::ToonParams& p, cudaStream_t stream);
void toonSurfaces(cudaSurfaceObject_t hdr, cudaSurfaceObject_t position, cudaSurfaceObject_t normal, int width,
                  int height, const post::ToonParams& p, cudaStream_t stream);

inline dim3 gridFor(int width, int height) { return dim3(unsigned(width + 15) / 16, unsigned(height + 15) / 16); }
constexpr unsigned kBlock = 16;

}  // namespace lp::cuda
