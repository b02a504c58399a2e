// Bloom in CUDA: bright pass, separable Gaussian, Jimenez mip chain, composite. The per-texel
// math is engine/post/post_math.hpp, the same code the CPU reference runs. The separable blur is
// two tiled launches (bright pass fused into the first); the weights travel as a kernel parameter,
// which lives in the constant bank and is broadcast to the warp like __constant__ data.
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
__global__ void downKernel(In src, int sw, int sh, BufferImage dst, int dw, int dh, bool first, post::BloomParams p) {
    // The block's 6x6 windows overlap: stage the source texels 2 * x0 - 2 .. 2 * (x0 + 15) + 3 once
    // (bright-passed once each on the first level) and read the windows from shared memory.
    constexpr int kSpan = 2 * int(kBlock) + 4;
    __shared__ float4 staged[kSpan][kSpan];
    const int sx0 = 2 * int(blockIdx.x * kBlock) - 2, sy0 = 2 * int(blockIdx.y * kBlock) - 2;
    constexpr int kThreads = int(kBlock * kBlock), kBatch = (kSpan * kSpan + kThreads - 1) / kThreads;
    const int thread = int(threadIdx.y * kBlock + threadIdx.x);
    float4 v[kBatch];  // every load in flight before the first is used
#pragma unroll
    for (int b = 0; b < kBatch; ++b) {
        const int e = thread + b * kThreads;
        if (e < kSpan * kSpan) v[b] = src.load(clampi(sx0 + e % kSpan, 0, sw - 1), clampi(sy0 + e / kSpan, 0, sh - 1));
    }
#pragma unroll
    for (int b = 0; b < kBatch; ++b) {
        const int e = thread + b * kThreads;
        if (e >= kSpan * kSpan) continue;
        const Rgb c = rgb(v[b]);
        staged[e / kSpan][e % kSpan] = f4(first ? post::brightPass(c, p.threshold, p.knee, p.highlight) : c);
    }
    __syncthreads();
    const int tx = int(threadIdx.x), ty = int(threadIdx.y);
    const int x = int(blockIdx.x * kBlock) + tx, y = int(blockIdx.y * kBlock) + ty;
    if (x >= dw || y >= dh) return;
    Rgb t[6][6];
    for (int j = 0; j < 6; ++j)
        for (int i = 0; i < 6; ++i) t[j][i] = rgb(staged[2 * ty + j][2 * tx + i]);
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
    // The block's 4x4 coarse windows span coarse texels x0 / 2 - 2 .. x0 / 2 + 9: staged once.
    constexpr int kSpan = int(kBlock) / 2 + 4;
    __shared__ float4 staged[kSpan][kSpan];
    const int x0 = int(blockIdx.x * kBlock), y0 = int(blockIdx.y * kBlock);
    const int cx0 = x0 / 2 - 2, cy0 = y0 / 2 - 2;
    for (int e = int(threadIdx.y * kBlock + threadIdx.x); e < kSpan * kSpan; e += int(kBlock * kBlock)) {
        const int sx = clampi(cx0 + e % kSpan, 0, cw - 1), sy = clampi(cy0 + e / kSpan, 0, ch - 1);
        staged[e / kSpan][e % kSpan] = coarse[size_t(sy) * size_t(cw) + size_t(sx)];
    }
    __syncthreads();
    const int x = x0 + int(threadIdx.x), y = y0 + int(threadIdx.y);
    if (x >= fw || y >= fh) return;
    const bool ox = x & 1, oy = y & 1;
    const int bx = (x >> 1) - (ox ? 1 : 2) - cx0, by = (y >> 1) - (oy ? 1 : 2) - cy0;
    Rgb sum;
    for (int j = 0; j < 4; ++j) {
        Rgb row;
        for (int i = 0; i < 4; ++i) row = add(row, scale(rgb(staged[by + j][bx + i]), post::upsampleWeight(i, ox)));
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

// The composite fused into the last bloom kernel's store: the bloom texel as its target keeps it
// (fp16 on a GL texture), then hdr = sanitize(sanitize(hdr) + strength * bloom) on the same texel.
template <typename HdrIn, typename BloomOut, typename HdrOut>
struct CompositeOnStore {
    HdrIn hdr;
    BloomOut bloom;
    HdrOut hdrOut;
    float strength;
    __device__ void store(int x, int y, float4 c) const {
        bloom.store(x, y, c);
        const Rgb b = rgb(BloomOut::stored(c)), h = rgb(hdr.load(x, y));
        hdrOut.store(x, y, f4(post::sanitize(add(post::sanitize(h), scale(b, strength)))));
    }
};

void checkLaunch(const char* kernel) { check(cudaGetLastError(), kernel); }

// The separable blur, tiled: a block stages a 32 x kTileAlong tile plus its +-radius apron in shared
// memory once (clamped coordinates, as the reference's texel()), then every tap reads shared memory.
// Lanes of a warp run across the blur direction and each thread makes kOutputsPerThread
// consecutive outputs along it, sliding its left/right taps through registers, so a tap step costs
// two shared loads for kOutputsPerThread outputs. The tap order and pairing are the reference's:
// sum = c(0) * w0, then sum += (c(-i) + c(i)) * w[i] for i = 1..radius.
constexpr int kLanes = 32;                                   // across the blur direction
constexpr int kWarpsAlong = 8;                               // warps per block, along it
constexpr int kOutputsPerThread = 8;
constexpr int kTileAlong = kWarpsAlong * kOutputsPerThread;  // outputs per block along the blur

// Shared-memory row length (float4s) of the tile along the blur, odd so that lanes on different
// rows (horizontal pass) fall in different banks.
__host__ __device__ inline int spanAlong(int radius) { return (kTileAlong + 2 * radius) | 1; }
inline size_t blurSharedBytes(int radius) { return size_t(kLanes) * size_t(spanAlong(radius)) * sizeof(float4); }

// Where tile element (along a, across c) lives: horizontal tiles keep each image row contiguous.
template <bool Horizontal>
__device__ inline int tileIndex(int a, int c, int span) { return Horizontal ? c * span + a : a * kLanes + c; }

template <typename In>
struct BrightSource {  // the bright pass applied while staging, so it never round-trips memory
    In in;
    post::BloomParams p;
    __device__ float4 load(int x, int y) const {
        return f4(post::brightPass(rgb(in.load(x, y)), p.threshold, p.knee, p.highlight));
    }
};

template <bool Horizontal, typename Source, typename Out>
__global__ void __launch_bounds__(kLanes * kWarpsAlong)
    blurTileKernel(Source src, Out out, int width, int height, Weights w, int radius) {
    extern __shared__ float4 tile[];
    const int span = spanAlong(radius), stagedAlong = kTileAlong + 2 * radius;
    // Tile origin in the image: `along0` is the first output along the blur, `across0` the first lane's.
    const int along0 = int(Horizontal ? blockIdx.x : blockIdx.y) * kTileAlong;
    const int across0 = int(Horizontal ? blockIdx.y : blockIdx.x) * kLanes;
    const int alongSize = Horizontal ? width : height, acrossSize = Horizontal ? height : width;
    const int thread = int(threadIdx.y) * kLanes + int(threadIdx.x), threads = kLanes * kWarpsAlong;
    // Stage: consecutive threads take consecutive x (coalesced reads in both directions), kStageBatch
    // loads in flight per thread before any is stored (latency, not bandwidth, bounds one by one).
    constexpr int kStageBatch = 4;
    const int staged = stagedAlong * kLanes;
    for (int base = thread; base < staged; base += threads * kStageBatch) {
        float4 v[kStageBatch];
#pragma unroll
        for (int b = 0; b < kStageBatch; ++b) {
            const int e = base + b * threads;
            const int a = Horizontal ? e % stagedAlong : e / kLanes, c = Horizontal ? e / stagedAlong : e % kLanes;
            const int along = clampi(along0 - radius + a, 0, alongSize - 1);
            const int across = min(across0 + c, acrossSize - 1);
            if (e < staged) v[b] = Horizontal ? src.load(along, across) : src.load(across, along);
        }
#pragma unroll
        for (int b = 0; b < kStageBatch; ++b) {
            const int e = base + b * threads;
            const int a = Horizontal ? e % stagedAlong : e / kLanes, c = Horizontal ? e / stagedAlong : e % kLanes;
            if (e < staged) tile[tileIndex<Horizontal>(a, c, span)] = v[b];
        }
    }
    __syncthreads();

    const int across = across0 + int(threadIdx.x);
    const int lane = int(threadIdx.x), first = radius + int(threadIdx.y) * kOutputsPerThread;
    auto at = [&](int a) { return rgb(tile[tileIndex<Horizontal>(a, lane, span)]); };
    Rgb sum[kOutputsPerThread], left[kOutputsPerThread], right[kOutputsPerThread];
#pragma unroll
    for (int k = 0; k < kOutputsPerThread; ++k) {
        sum[k] = scale(at(first + k), w.w[0]);
        if (radius > 0) {
            left[k] = at(first + k - 1);
            right[k] = at(first + k + 1);
        }
    }
    for (int i = 1; i <= radius; ++i) {
#pragma unroll
        for (int k = 0; k < kOutputsPerThread; ++k) sum[k] = add(sum[k], scale(add(left[k], right[k]), w.w[i]));
        if (i == radius) break;
        // Step to tap i + 1: output k's left tap is output k - 1's current one, and so on.
#pragma unroll
        for (int k = kOutputsPerThread - 1; k > 0; --k) left[k] = left[k - 1];
#pragma unroll
        for (int k = 0; k < kOutputsPerThread - 1; ++k) right[k] = right[k + 1];
        left[0] = at(first - i - 1);
        right[kOutputsPerThread - 1] = at(first + kOutputsPerThread - 1 + i + 1);
    }

    if (!Horizontal) {  // lanes already run along x: store directly
#pragma unroll
        for (int k = 0; k < kOutputsPerThread; ++k) {
            const int y = along0 + int(threadIdx.y) * kOutputsPerThread + k;
            if (across < width && y < height) out.store(across, y, f4(sum[k]));
        }
        return;
    }
    // Horizontal: lanes run down the rows, so go through shared memory to store whole rows at once.
    __syncthreads();
#pragma unroll
    for (int k = 0; k < kOutputsPerThread; ++k)
        tile[tileIndex<true>(int(threadIdx.y) * kOutputsPerThread + k, lane, span)] = f4(sum[k]);
    __syncthreads();
    for (int e = thread; e < kTileAlong * kLanes; e += threads) {
        const int a = e % kTileAlong, c = e / kTileAlong;
        const int x = along0 + a, y = across0 + c;
        if (x < width && y < height) out.store(x, y, tile[tileIndex<true>(a, c, span)]);
    }
}

// One launch per direction; the dynamic shared memory of radius 50 (84 KB) needs the opt-in.
template <bool Horizontal, typename Source, typename Out>
void launchBlur(Source src, Out out, int width, int height, const Weights& w, int radius, cudaStream_t stream) {
    static const bool sharedOptIn = (check(cudaFuncSetAttribute(blurTileKernel<Horizontal, Source, Out>,
                                                                 cudaFuncAttributeMaxDynamicSharedMemorySize,
                                                                 int(blurSharedBytes(post::kMaxRadius))),
                                           "cudaFuncSetAttribute (blur shared memory)"),
                                     true);
    (void)sharedOptIn;
    const unsigned tilesAlong = unsigned(((Horizontal ? width : height) + kTileAlong - 1) / kTileAlong);
    const unsigned tilesAcross = unsigned(((Horizontal ? height : width) + kLanes - 1) / kLanes);
    const dim3 grid = Horizontal ? dim3(tilesAlong, tilesAcross) : dim3(tilesAcross, tilesAlong);
    blurTileKernel<Horizontal>
        <<<grid, dim3(kLanes, kWarpsAlong), blurSharedBytes(radius), stream>>>(src, out, width, height, w, radius);
    checkLaunch(Horizontal ? "blurTileKernel (horizontal)" : "blurTileKernel (vertical)");
}

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
        // Bright pass fused into the horizontal blur's staging; fp32 intermediate in ws.a.
        launchBlur<true>(BrightSource<In>{hdr, p}, BufferImage{ws.a, width}, width, height, w, radius, stream);
        launchBlur<false>(BufferImage{ws.a, width}, bloom, width, height, w, radius, stream);
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
    for (float4* m : mips) cudaFree(m);
}

void BloomWorkspace::ensure(int width, int height, const post::BloomParams& p) {
    const size_t full = size_t(width) * size_t(height);
    if (p.method == post::BloomMethod::Separable && fullTexels < full) {
        check(cudaFree(a), "cudaFree");
        a = nullptr;
        check(cudaMalloc(&a, full * sizeof(float4)), "cudaMalloc (bloom scratch)");
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

void bloomCompositeBuffers(const float4* hdr, float4* bloom, float4* hdrOut, int width, int height,
                           const post::BloomParams& p, BloomWorkspace& ws, cudaStream_t stream) {
    const BufferImage in{const_cast<float4*>(hdr), width};
    const CompositeOnStore<BufferImage, BufferImage, BufferImage> out{in, {bloom, width}, {hdrOut, width}, p.strength};
    bloomWork(in, out, width, height, p, ws, stream);
}

void bloomCompositeSurfaces(cudaSurfaceObject_t hdr, cudaSurfaceObject_t bloom, int width, int height,
                            const post::BloomParams& p, BloomWorkspace& ws, cudaStream_t stream) {
    bloomWork(Half4Surface{hdr},
              CompositeOnStore<Half4Surface, Half4Surface, Half4Surface>{{hdr}, {bloom}, {hdr}, p.strength}, width,
              height, p, ws, stream);
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
