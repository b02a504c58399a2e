// Bloom in CUDA: bright pass, separable Gaussian, Jimenez mip chain, composite. The per-texel
// math is engine/post/post_math.hpp, the same code the CPU reference runs.
#include <vector>

#include "cuda/interop.hpp"
#include "cuda/post_kernels.cuh"

namespace lp::cuda {

using post::Rgb;

namespace {

__device__ inline Rgb rgb(float4 c) { return {c.x, c.y, c.z}; }
__device__ inline float4 f4(Rgb c) { return make_float4(c.r, c.g, c.b, 1.0f); }
__device__ inline int clampi(int v, int lo, int hi) { return v < lo ? lo : (v > hi ? hi : v); }
__device__ inline Rgb add(Rgb a, Rgb b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }
__device__ inline Rgb scale(Rgb a, float k) { return {a.r * k, a.g * k, a.b * k}; }

struct Weights {
    float w[post::kMaxRadius + 1];
};

template <typename In>
__global__ void brightKernel(In in, BufferImage out, int width, int height, post::BloomParams p) {
    int x = int(blockIdx.x * blockDim.x + threadIdx.x), y = int(blockIdx.y * blockDim.y + threadIdx.y);
    if (x >= width || y >= height) return;
    out.store(x, y, f4(post::brightPass(rgb(in.load(x, y)), p.threshold, p.knee, p.highlight)));
}

template <typename Out>
__global__ void blurKernel(const float4* in, Out out, int width, int height, Weights w, int radius, int dx, int dy) {
    int x = int(blockIdx.x * blockDim.x + threadIdx.x), y = int(blockIdx.y * blockDim.y + threadIdx.y);
    if (x >= width || y >= height) return;
    auto at = [&](int i) {
        int sx = clampi(x + i * dx, 0, width - 1), sy = clampi(y + i * dy, 0, height - 1);
        return rgb(in[size_t(sy) * size_t(width) + size_t(sx)]);
    };
    Rgb sum = scale(at(0), w.w[0]);
    for (int i = 1; i <= radius; ++i) sum = add(sum, scale(add(at(-i), at(i)), w.w[i]));
    out.store(x, y, f4(sum));
}

template <typename In>
__global__ void downKernel(In src, int sw, int sh, BufferImage dst, int dw, int dh, bool first, post::BloomParams p) {
    int x = int(blockIdx.x * blockDim.x + threadIdx.x), y = int(blockIdx.y * blockDim.y + threadIdx.y);
    if (x >= dw || y >= dh) return;
    Rgb t[6][6];
    for (int j = 0; j < 6; ++j)
        for (int i = 0; i < 6; ++i) {
            Rgb c = rgb(src.load(clampi(2 * x - 2 + i, 0, sw - 1), clampi(2 * y - 2 + j, 0, sh - 1)));
            t[j][i] = first ? post::brightPass(c, p.threshold, p.knee, p.highlight) : c;
        }
    auto corner = [&](int ox, int oy) {
        int i = ox + 2, j = oy + 2;
        return scale(add(add(t[j][i], t[j][i + 1]), add(t[j + 1][i], t[j + 1][i + 1])), 0.25f);
    };
    auto group = [](Rgb a, Rgb b, Rgb c, Rgb d) { return scale(add(add(a, b), add(c, d)), 0.25f); };
    const Rgb g[5] = {
        group(corner(-1, -1), corner(1, -1), corner(-1, 1), corner(1, 1)),
        group(corner(-2, -2), corner(0, -2), corner(-2, 0), corner(0, 0)),
        group(corner(0, -2), corner(2, -2), corner(0, 0), corner(2, 0)),
        group(corner(-2, 0), corner(0, 0), corner(-2, 2), corner(0, 2)),
        group(corner(0, 0), corner(2, 0), corner(0, 2), corner(2, 2)),
    };
    const float base[5] = {0.5f, 0.125f, 0.125f, 0.125f, 0.125f};
    const bool karis = first && p.karis;
    Rgb sum;
    float wsum = 0.0f;
    for (int k = 0; k < 5; ++k) {
        float w = karis ? base[k] * post::karisWeight(g[k]) : base[k];
        sum = add(sum, scale(g[k], w));
        wsum += w;
    }
    dst.store(x, y, f4(scale(sum, 1.0f / wsum)));
}

// up: fine = (addFine ? fine : 0) + U(coarse) * scale  (scale applies when not adding).
template <typename Out>
__global__ void upKernel(const float4* coarse, int cw, int ch, Out fine, const float4* fineIn, int fw, int fh,
                         bool addFine, float scaleBy) {
    int x = int(blockIdx.x * blockDim.x + threadIdx.x), y = int(blockIdx.y * blockDim.y + threadIdx.y);
    if (x >= fw || y >= fh) return;
    const bool ox = x & 1, oy = y & 1;
    const int bx = (x >> 1) - (ox ? 1 : 2), by = (y >> 1) - (oy ? 1 : 2);
    Rgb sum;
    for (int j = 0; j < 4; ++j) {
        Rgb row;
        int sy = clampi(by + j, 0, ch - 1);
        for (int i = 0; i < 4; ++i) {
            int sx = clampi(bx + i, 0, cw - 1);
            row = add(row, scale(rgb(coarse[size_t(sy) * size_t(cw) + size_t(sx)]), post::upsampleWeight(i, ox)));
        }
        sum = add(sum, scale(row, post::upsampleWeight(j, oy)));
    }
    Rgb result = addFine ? add(rgb(fineIn[size_t(y) * size_t(fw) + size_t(x)]), sum) : scale(sum, scaleBy);
    fine.store(x, y, f4(result));
}

template <typename In, typename BloomIn, typename Out>
__global__ void compositeKernel(In hdr, BloomIn bloom, Out out, int width, int height, float strength) {
    int x = int(blockIdx.x * blockDim.x + threadIdx.x), y = int(blockIdx.y * blockDim.y + threadIdx.y);
    if (x >= width || y >= height) return;
    Rgb h = rgb(hdr.load(x, y)), b = rgb(bloom.load(x, y));
    out.store(x, y, f4(post::sanitize(add(post::sanitize(h), scale(b, strength)))));
}

void checkLaunch(const char* kernel) { check(cudaGetLastError(), kernel); }

template <typename In, typename Out>
void bloomWork(In hdr, Out bloom, int width, int height, const post::BloomParams& p, BloomWorkspace& ws,
               cudaStream_t stream) {
    ws.ensure(width, height, p);
    const dim3 block(kBlock, kBlock);
    if (p.method == post::BloomMethod::Separable) {
        const std::vector<float> taps = post::gaussianWeights(p.kernel);
        Weights w{};
        for (size_t i = 0; i < taps.size(); ++i) w.w[i] = taps[i];
        const int radius = int(taps.size()) - 1;
        brightKernel<<<gridFor(width, height), block, 0, stream>>>(hdr, BufferImage{ws.a, width}, width, height, p);
        checkLaunch("brightKernel");
        blurKernel<<<gridFor(width, height), block, 0, stream>>>(ws.a, BufferImage{ws.b, width}, width, height, w,
                                                                  radius, 1, 0);
        checkLaunch("blurKernel (horizontal)");
        blurKernel<<<gridFor(width, height), block, 0, stream>>>(ws.b, bloom, width, height, w, radius, 0, 1);
        checkLaunch("blurKernel (vertical)");
        return;
    }
    const int levels = post::mipLevelCount(p.kernel, width, height);
    for (int l = 0; l < levels; ++l) {
        const int dw = post::mipSize(width, l), dh = post::mipSize(height, l);
        if (l == 0) {
            downKernel<<<gridFor(dw, dh), block, 0, stream>>>(hdr, width, height, BufferImage{ws.mips[0], dw}, dw, dh,
                                                              true, p);
        } else {
            const int sw = post::mipSize(width, l - 1), sh = post::mipSize(height, l - 1);
            downKernel<<<gridFor(dw, dh), block, 0, stream>>>(BufferImage{ws.mips[l - 1], sw}, sw, sh,
                                                              BufferImage{ws.mips[l], dw}, dw, dh, false, p);
        }
        checkLaunch("downKernel");
    }
    for (int l = levels - 2; l >= 0; --l) {
        const int fw = post::mipSize(width, l), fh = post::mipSize(height, l);
        const int cw = post::mipSize(width, l + 1), ch = post::mipSize(height, l + 1);
        upKernel<<<gridFor(fw, fh), block, 0, stream>>>(ws.mips[l + 1], cw, ch, BufferImage{ws.mips[l], fw}, ws.mips[l],
                                                        fw, fh, true, 1.0f);
        checkLaunch("upKernel");
    }
    upKernel<<<gridFor(width, height), block, 0, stream>>>(ws.mips[0], post::mipSize(width, 0), post::mipSize(height, 0),
                                                            bloom, nullptr, width, height, false, 1.0f / float(levels));
    checkLaunch("upKernel (full resolution)");
}

}  // namespace

BloomWorkspace::~BloomWorkspace() {
    cudaFree(a);
    cudaFree(b);
    for (float4* m : mips) cudaFree(m);
}

void BloomWorkspace::ensure(int width, int height, const post::BloomParams& p) {
    const size_t full = size_t(width) * size_t(height);
    if (p.method == post::BloomMethod::Separable && fullTexels < full) {
        check(cudaFree(a), "cudaFree");
        check(cudaFree(b), "cudaFree");
        a = b = nullptr;
        check(cudaMalloc(&a, full * sizeof(float4)), "cudaMalloc (bloom scratch)");
        check(cudaMalloc(&b, full * sizeof(float4)), "cudaMalloc (bloom scratch)");
        fullTexels = full;
    }
    if (p.method == post::BloomMethod::MipChain) {
        const int levels = post::mipLevelCount(p.kernel, width, height);
        for (int l = 0; l < levels; ++l) {
            const size_t n = size_t(post::mipSize(width, l)) * size_t(post::mipSize(height, l));
            if (mipTexels[l] >= n) continue;
            check(cudaFree(mips[l]), "cudaFree");
            mips[l] = nullptr;
            check(cudaMalloc(&mips[l], n * sizeof(float4)), "cudaMalloc (bloom mip chain)");
            mipTexels[l] = n;
        }
    }
}

void bloomBufferToBuffer(const float4* hdr, float4* bloom, int width, int height, const post::BloomParams& p,
                         BloomWorkspace& ws, cudaStream_t stream) {
    bloomWork(BufferImage{const_cast<float4*>(hdr), width}, BufferImage{bloom, width}, width, height, p, ws, stream);
}

void bloomSurfaceToSurface(cudaSurfaceObject_t hdr, cudaSurfaceObject_t bloom, int width, int height,
                           const post::BloomParams& p, BloomWorkspace& ws, cudaStream_t stream) {
    bloomWork(Half4Surface{hdr}, Half4Surface{bloom}, width, height, p, ws, stream);
}

void compositeBuffers(const float4* hdr, const float4* bloom, float4* out, int width, int height, float strength,
                      cudaStream_t stream) {
    compositeKernel<<<gridFor(width, height), dim3(kBlock, kBlock), 0, stream>>>(
        BufferImage{const_cast<float4*>(hdr), width}, BufferImage{const_cast<float4*>(bloom), width},
        BufferImage{out, width}, width, height, strength);
    checkLaunch("compositeKernel");
}

void compositeSurfaces(cudaSurfaceObject_t hdr, cudaSurfaceObject_t bloom, int width, int height, float strength,
                       cudaStream_t stream) {
    compositeKernel<<<gridFor(width, height), dim3(kBlock, kBlock), 0, stream>>>(
        Half4Surface{hdr}, Half4Surface{bloom}, Half4Surface{hdr}, width, height, strength);
    checkLaunch("compositeKernel");
}

}  // namespace lp::cuda
