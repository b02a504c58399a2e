// Bloom in CUDA: bright pass, separable Gaussian, composite (the Jimenez mip chain is in
// cuda/bloom_mip_chain.cu). The per-texel math is engine/post/post_math.hpp, the same code the CPU
// reference runs. The separable blur is two tiled launches (bright pass fused into the first); the
// weights travel as a kernel parameter, which lives in the constant bank and is broadcast to the
// warp like __constant__ data.
#include <algorithm>
#include <type_traits>
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
    __device__ void store(int x, int y, float4 c) const { storeOver(x, y, c, hdr.load(x, y)); }
    // store() with the HDR texel `h` loaded beforehand.
    __device__ void storeOver(int x, int y, float4 c, float4 h) const {
        bloom.store(x, y, c);
        const Rgb b = rgb(BloomOut::stored(c));
        hdrOut.store(x, y, f4(post::sanitize(add(post::sanitize(rgb(h)), scale(b, strength)))));
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

// ---- The separable blur on the tensor cores, both passes in one kernel ----
// A 1-D convolution of a 16-wide chunk is a product with a banded Toeplitz matrix of the weights:
// out[16 x n] = T[16 x 16M] * in[16M x n], T[i][k] = w[|16m + k - i - r|] (0 off the band), M =
// the 16-wide input chunks the band of 16 outputs touches. A block owns a 64-column stripe of
// segment rows; per step it stages 16 more input rows (bright-passed) of the stripe plus its
// +-r column apron, blurs them horizontally (M x 16 x 16 products per 16 x 8 outputs) into a
// sliding window of M 16-row chunks held in registers, and from that window blurs 16 output rows
// vertically. The horizontal result comes out of mma.sync in the accumulator layout, which is the
// layout of the next product's A operand when the output columns are the rows of the matrix:
// the horizontal pass computes in^T and the vertical pass multiplies it by T^T, so the
// intermediate never leaves the registers. One warp per (16-column chunk, channel).
//
// Precision: fp16 operands with fp32 accumulation, an operand split as x = hi + lo / 2048
// (hi = fp16(x), lo = fp16((x - hi) * 2048): 22 significant bits, lo scaled into fp16's normal
// range). Into fp32 outputs both are split, three products hi*hi + (lo*hi + hi*lo) / 2048 (lo*lo,
// 2^-22 relative, is dropped): within the tests' 1e-5 of the fp32 reference. Into fp16 outputs (the
// GL textures) only the weights are, two products hi*hi + hi*lo / 2048: the texel and the
// intermediate are rounded to fp16 once each, and with the store's own rounding the result is within
// 3 half-ulps (1.5 fp16 ulps) of the reference. Inputs are >= 0 after the bright pass and <=
// kHalfMax, so every sum is of non-negative terms and the error stays relative to the output.
constexpr int kTcColChunks = 4;                  // 16-column chunks of a block's stripe
constexpr int kTcWidth = 16 * kTcColChunks;      // output columns per block
constexpr int kTcWarps = 3 * kTcColChunks;       // one per (chunk, channel)
constexpr int kTcThreads = 32 * kTcWarps;
constexpr float kLoScale = 2048.0f;

// Input chunks of 16 the band of 16 outputs touches (outputs j, inputs j .. j + 2r in apron
// coordinates).
__host__ __device__ constexpr int tensorChunks(int radius) { return (2 * radius + 15) / 16 + 1; }
static_assert(tensorChunks(post::kMaxRadius) <= 8, "the widest instantiation below has 8 chunks");

template <int M>
struct TensorBlurLayout {
    static constexpr int stagedCols = 16 * (kTcColChunks + M - 1);
    // Row stride of a staged plane in halves: stagedCols / 2 words is a multiple of 8, + 4 words
    // makes it an odd multiple of 4, so the 8 rows x 4 column pairs a B fragment reads hit 32 banks.
    static constexpr int rowHalves = stagedCols + 8;
    static constexpr int planeHalves = 16 * rowHalves;  // one channel's hi or lo of 16 rows
    static constexpr int stageHalves = 6 * planeHalves;  // 3 channels x (hi, lo)
    static constexpr int outRow = kTcWidth + 4;          // floats; (2t * 68 + g) % 32 distinct
    static constexpr int outFloats = 3 * 16 * outRow;
    static constexpr int tableUint4 = 2 * M * 32;  // (hi, lo) x M chunks x lanes
    static constexpr int pairs = 16 * stagedCols / 2;  // column pairs staged per step
    static constexpr int loads = (pairs + kTcThreads - 1) / kTcThreads;  // pairs per thread per step
    static constexpr int deferChunks = M / 2;  // ceil(r / 16) for the largest r of M chunks
    static constexpr size_t sharedBytes = size_t(tableUint4) * 16 + 2 * size_t(stageHalves) * 2 +
                                          (2 + size_t(deferChunks)) * size_t(outFloats) * 4;
};

// A texel as loaded, decoded only when staged (so the loads of the next rows stay in flight while
// the current ones are multiplied).
template <typename In>
struct RawTexel {
    using type = float4;
    __device__ static type load(const In& in, int x, int y) { return in.load(x, y); }
    __device__ static float4 decode(type v) { return v; }
};
template <>
struct RawTexel<Half4Surface> {
    using type = ushort4;
    __device__ static type load(const Half4Surface& in, int x, int y) {
        return surf2Dread<ushort4>(in.surface, x * int(sizeof(ushort4)), y);
    }
    __device__ static float4 decode(type v) {
        return make_float4(__half2float(__ushort_as_half(v.x)), __half2float(__ushort_as_half(v.y)),
                           __half2float(__ushort_as_half(v.z)), 1.0f);
    }
};

__device__ inline uint32_t packHalves(__half low, __half high) {
    return uint32_t(__half_as_ushort(low)) | (uint32_t(__half_as_ushort(high)) << 16);
}
__device__ inline __half hiPart(float v) { return __float2half_rn(v); }
__device__ inline __half loPart(float v, __half hi) { return __float2half_rn((v - __half2float(hi)) * kLoScale); }
// (a, b) as packed fp16 hi and scaled lo pairs: a in the low half.
__device__ inline void splitPair(float a, float b, uint32_t& hi, uint32_t& lo) {
    const __half ah = hiPart(a), bh = hiPart(b);
    hi = packHalves(ah, bh);
    lo = packHalves(loPart(a, ah), loPart(b, bh));
}

// d += a * b, m16n8k16, fp16 in, fp32 accumulate. Fragments (g = lane / 4, t = lane % 4):
// a[0] = A[g][2t, 2t+1], a[1] = A[g+8][2t, 2t+1], a[2] = A[g][2t+8, 2t+9], a[3] = A[g+8][2t+8, 2t+9];
// b0 = B[2t, 2t+1][g], b1 = B[2t+8, 2t+9][g]; d = D[g][2t], D[g][2t+1], D[g+8][2t], D[g+8][2t+1].
__device__ inline void mma16816(float (&d)[4], const uint4& a, uint32_t b0, uint32_t b1) {
#if defined(__CUDA_ARCH__) && __CUDA_ARCH__ >= 800
    asm("mma.sync.aligned.m16n8k16.row.col.f32.f16.f16.f32 {%0,%1,%2,%3}, {%4,%5,%6,%7}, {%8,%9}, {%0,%1,%2,%3};\n"
        : "+f"(d[0]), "+f"(d[1]), "+f"(d[2]), "+f"(d[3])
        : "r"(a.x), "r"(a.y), "r"(a.z), "r"(a.w), "r"(b0), "r"(b1));
#else
    (void)d, (void)a, (void)b0, (void)b1;  // never launched: the host checks the binary's arch
#endif
}

__device__ inline float tapWeight(const Weights& w, int radius, int d) {
    d = d < 0 ? -d : d;
    return d <= radius ? w.w[d] : 0.0f;
}

// What a store reads back, loaded ahead: nothing for plain outputs, the HDR texel for the composite.
template <typename Out>
struct OutputPrefetch {
    using type = char;
    __device__ static type load(const Out&, int, int) { return 0; }
    __device__ static void store(const Out& out, int x, int y, float4 c, type) { out.store(x, y, c); }
};
template <typename HdrIn, typename BloomOut, typename HdrOut>
struct OutputPrefetch<CompositeOnStore<HdrIn, BloomOut, HdrOut>> {
    using Out = CompositeOnStore<HdrIn, BloomOut, HdrOut>;
    using type = typename RawTexel<HdrIn>::type;
    __device__ static type load(const Out& out, int x, int y) { return RawTexel<HdrIn>::load(out.hdr, x, y); }
    __device__ static void store(const Out& out, int x, int y, float4 c, type h) {
        out.storeOver(x, y, c, RawTexel<HdrIn>::decode(h));
    }
};

// In place (the composite writes the HDR texture the blur reads, as bloomCompositeSurfaces does):
// a block must not overwrite HDR texels that another block has yet to stage. Blocks publish how
// many input chunks they have staged (`progress`, one counter per block, zeroed before the launch),
// and before a block stores an output chunk it waits until every block that reads those rows (the
// stripes beside it in its own segment and the next) has staged them; all blocks are resident at
// once (cooperative launch), and no block waits for more than it has staged itself, so the waits
// end. The segment above reads this segment's first r rows at its end: those chunks are kept in
// shared memory and stored last. Segments are at least 64 rows (> r), so only adjacent ones meet.
// Whether every texel the kernel stores is rounded to fp16 (the GL textures the passes use).
template <typename Out>
struct StoresHalf : std::false_type {};
template <>
struct StoresHalf<Half4Surface> : std::true_type {};
template <typename HdrIn, typename BloomOut, typename HdrOut>
struct StoresHalf<CompositeOnStore<HdrIn, BloomOut, HdrOut>>
    : std::bool_constant<StoresHalf<BloomOut>::value && StoresHalf<HdrOut>::value> {};

struct InPlaceOrder {
    int* progress = nullptr;  // null: the output does not alias the input, no ordering
    int stripes = 0, segments = 0;
};

// Rows a block reads and the chunks it stages: segment `segment` of segmentRows rows.
struct SegmentReads {
    int first, last, steps;  // reads rows [first, last) (unclamped, apron included), in `steps` chunks
    __device__ SegmentReads(int segment, int segmentRows, int height, int radius, int chunks) {
        const int y0 = segment * segmentRows;
        const int outChunks = (min(y0 + segmentRows, height) - y0 + 15) / 16;
        first = y0 - radius;
        last = y0 + 16 * outChunks + radius;
        steps = outChunks + chunks - 1;
    }
    // Chunks it must have staged before rows [ya, yb) may change; 0 when it never reads them.
    __device__ int chunksReading(int ya, int yb, int height) const {
        if (yb <= max(first, 0) || ya >= min(last, height)) return 0;
        const int upTo = yb >= height ? last : yb;  // the bottom row is read again for rows past it
        return min((upTo - first + 15) / 16, steps);
    }
};

template <int M, typename In, typename Out>
__global__ void __launch_bounds__(kTcThreads, 1)
    tensorBlurKernel(In hdr, Out out, int width, int height, Weights w, int radius, int segmentRows,
                     post::BloomParams p, InPlaceOrder order) {
    using L = TensorBlurLayout<M>;
    using Raw = RawTexel<In>;
    // Into fp16 outputs the texels and the intermediate stay fp16 (see Precision above): two
    // products instead of three, half the staged planes and the window.
    constexpr bool splitTexels = !StoresHalf<Out>::value;
    extern __shared__ uint4 shared[];
    uint4* table = shared;  // [(m * 2 + hi/lo) * 32 + lane]: Toeplitz chunk m as an A fragment
    __half* stage = reinterpret_cast<__half*>(shared + L::tableUint4);
    float* outBuffer = reinterpret_cast<float*>(stage + 2 * L::stageHalves);
    float* deferred = outBuffer + 2 * L::outFloats;  // L::deferChunks output chunks, stored last

    const int thread = int(threadIdx.x), lane = thread & 31, warp = thread >> 5;
    const int g = lane >> 2, t = lane & 3;
    const int chunk = warp % kTcColChunks, channel = warp / kTcColChunks;
    const int stripe = int(blockIdx.x), segment = int(blockIdx.y);
    const int x0 = stripe * kTcWidth, y0 = segment * segmentRows;
    const int outChunks = (min(y0 + segmentRows, height) - y0 + 15) / 16;
    const int steps = outChunks + M - 1;
    // Apron rows and columns this radius needs (the chunks beyond them multiply zero weights and
    // are not read, so that only adjacent blocks read each other's texels).
    const int neededRows = 16 * outChunks + 2 * radius, neededCols = kTcWidth + 2 * radius;
    // Output chunks the segment above reads (its apron), kept until the end when in place.
    const int deferChunks = order.progress && segment > 0 ? min((radius + 15) / 16, outChunks) : 0;

    auto publish = [&](int staged) {  // after a __syncthreads that follows the staging
        if (order.progress && thread == 0) {
            __threadfence();
            atomicExch(&order.progress[segment * order.stripes + stripe], staged);
        }
    };
    // Lane n < 9 of warp 0 watches neighbour (segment - 1 + n / 3, stripe - 1 + n % 3). It reads the
    // counter early in a step (peek) and again only while that is short of what a store needs:
    // neighbours keep pace, so the stores rarely wait for a counter's round trip.
    const int watchedSegment = segment - 1 + lane / 3, watchedStripe = stripe - 1 + lane % 3;
    const bool watches = order.progress && warp == 0 && lane < 9 && lane != 4 && watchedSegment >= 0 &&
                         watchedSegment < order.segments && watchedStripe >= 0 && watchedStripe < order.stripes;
    volatile int* watched = watches ? order.progress + watchedSegment * order.stripes + watchedStripe : nullptr;
    int seen = 0;
    auto peek = [&] {
        if (watches) seen = *watched;
    };
    auto waitForReaders = [&](int ya, int yb) {  // then __syncthreads
        if (!watches) return;
        const int need = SegmentReads(watchedSegment, segmentRows, height, radius, M).chunksReading(ya, yb, height);
        while (seen < need) {
            __nanosleep(128);
            seen = *watched;
        }
        __threadfence();
    };

    // The Toeplitz fragments, once per block: chunk m as the A operand (16 output columns i x 16
    // input columns k), T[i][k] = w(16m + k - i - r). The vertical pass needs B fragments of
    // (16 input rows k x 8 output rows n of half nt) = w(16m + k - 8nt - n - r) = T[8nt + n][k]:
    // in the fragment layouts those are this lane's registers {0, 2} (nt 0) and {1, 3} (nt 1).
    for (int e = thread; e < M * 32; e += kTcThreads) {
        const int m = e / 32, el = e % 32, eg = el >> 2, et = el & 3;
        uint32_t hi[4], lo[4];
        for (int reg = 0; reg < 4; ++reg) {
            const int i = eg + 8 * (reg & 1), k = 2 * et + 8 * (reg >> 1);
            splitPair(tapWeight(w, radius, 16 * m + k - i - radius), tapWeight(w, radius, 16 * m + k + 1 - i - radius),
                      hi[reg], lo[reg]);
        }
        table[(m * 2 + 0) * 32 + el] = make_uint4(hi[0], hi[1], hi[2], hi[3]);
        table[(m * 2 + 1) * 32 + el] = make_uint4(lo[0], lo[1], lo[2], lo[3]);
    }

    // Staging of input chunk s (apron coordinates: row y0 - r + 16s + i, column x0 - r + c), clamped
    // as the reference's texel(); the bright pass is applied as the texels are staged.
    // Loads run kDepth chunks ahead of the staging, so that a load's latency is covered by two
    // steps of products: two where the registers allow it (fp16 texels), else one.
    constexpr int kDepth = sizeof(typename Raw::type) <= 8 ? 2 : 1;
    using Pending = typename Raw::type[L::loads][2];  // column pairs, so that staging stores half2
    Pending pendingA;
    [[maybe_unused]] Pending pendingB;
    auto load = [&](Pending& pending, int s) {
#pragma unroll
        for (int b = 0; b < L::loads; ++b) {
            const int e = thread + b * kTcThreads;
            const int c = 2 * (e % (L::stagedCols / 2)), row = 16 * s + e / (L::stagedCols / 2);
            const int y = clampi(y0 - radius + row, 0, height - 1);
#pragma unroll
            for (int j = 0; j < 2; ++j) {
                pending[b][j] = typename Raw::type{};
                if (e < L::pairs && c + j < neededCols && row < neededRows)
                    pending[b][j] = Raw::load(hdr, clampi(x0 - radius + c + j, 0, width - 1), y);
            }
        }
    };
    auto commit = [&](const Pending& pending, int s) {
        __half* buffer = stage + (s & 1) * L::stageHalves;
#pragma unroll
        for (int b = 0; b < L::loads; ++b) {
            const int e = thread + b * kTcThreads;
            if (e >= L::pairs) continue;
            const Rgb c0 = post::brightPass(rgb(Raw::decode(pending[b][0])), p.threshold, p.knee, p.highlight);
            const Rgb c1 = post::brightPass(rgb(Raw::decode(pending[b][1])), p.threshold, p.knee, p.highlight);
            const int at = (e / (L::stagedCols / 2)) * L::rowHalves + 2 * (e % (L::stagedCols / 2));
            const float v0[3] = {c0.r, c0.g, c0.b}, v1[3] = {c1.r, c1.g, c1.b};
#pragma unroll
            for (int ch = 0; ch < 3; ++ch) {
                uint32_t hi, lo;
                if constexpr (splitTexels) {
                    splitPair(v0[ch], v1[ch], hi, lo);
                    *reinterpret_cast<uint32_t*>(buffer + (2 * ch + 1) * L::planeHalves + at) = lo;
                } else {
                    hi = packHalves(hiPart(v0[ch]), hiPart(v1[ch]));
                }
                *reinterpret_cast<uint32_t*>(buffer + (2 * ch) * L::planeHalves + at) = hi;
            }
        }
    };
    // Stores of an output chunk: 16 rows x 64 columns from three channel planes. What the output
    // reads back (the composite's HDR texel) is loaded at the start of the step, not at the store.
    using Prefetch = OutputPrefetch<Out>;
    constexpr int kStores = (16 * kTcWidth + kTcThreads - 1) / kTcThreads;
    typename Prefetch::type before[kStores];
    auto prefetch = [&](int jc) {
#pragma unroll
        for (int i = 0; i < kStores; ++i) {
            const int e = thread + i * kTcThreads;
            const int x = x0 + e % kTcWidth, y = y0 + 16 * jc + e / kTcWidth;
            if (e < 16 * kTcWidth && x < width && y < height) before[i] = Prefetch::load(out, x, y);
        }
    };
    auto storeChunk = [&](const float* rows, int jc, bool prefetched) {
#pragma unroll
        for (int i = 0; i < kStores; ++i) {
            const int e = thread + i * kTcThreads;
            const int row = e / kTcWidth, col = e % kTcWidth;
            const int x = x0 + col, y = y0 + 16 * jc + row;
            if (e >= 16 * kTcWidth || x >= width || y >= height) continue;
            const int at = row * L::outRow + col;
            const float4 c = make_float4(rows[at], rows[16 * L::outRow + at], rows[32 * L::outRow + at], 1.0f);
            if (prefetched)
                Prefetch::store(out, x, y, c, before[i]);
            else
                out.store(x, y, c);
        }
    };
    load(pendingA, 0);
    commit(pendingA, 0);
    if constexpr (kDepth == 2)
        if (1 < steps) load(pendingB, 1);
    __syncthreads();
    publish(1);

    // The horizontal result as A fragments: before step s appends its chunk, window[m] holds staged
    // chunk s - M + m, the M chunks output chunk s - M needs. Each step multiplies every Toeplitz
    // chunk m once into both passes: the new staged rows (horizontal) and window[m] (vertical).
    uint4 windowHi[M];
    [[maybe_unused]] uint4 windowLo[M];
    // Step s: loads of chunk s + kDepth into `loading`, staging of chunk s + 1 from `staging`.
    auto step = [&](int s, Pending& loading, const Pending& staging) {
        const bool staged = s < steps, more = s + 1 < steps;
        if (s + kDepth < steps) load(loading, s + kDepth);
        const int jc = s - M;  // output chunk of this step's vertical pass
        const bool deferThis = jc >= 0 && jc < deferChunks;
        if (jc >= 0 && !deferThis) {
            prefetch(jc);
            peek();
        }
        float* rows = deferThis ? deferred + jc * L::outFloats : outBuffer + (jc & 1) * L::outFloats;

        const __half* hiPlane = stage + (s & 1) * L::stageHalves + (2 * channel) * L::planeHalves;
        [[maybe_unused]] const __half* loPlane = hiPlane + L::planeHalves;
        float accHi[2][4] = {}, accLo[2][4] = {}, outHi[2][4] = {}, outLo[2][4] = {};
#pragma unroll
        for (int m = 0; m < M; ++m) {
            const uint4 aHi = table[(m * 2 + 0) * 32 + lane];
            const uint4 aLo = table[(m * 2 + 1) * 32 + lane];
            if (staged) {  // horizontal: this warp's 16 columns x the 16 staged rows (n-tiles of 8 rows)
                const int col = 16 * (chunk + m) + 2 * t;
#pragma unroll
                for (int nt = 0; nt < 2; ++nt) {
                    const int at = (8 * nt + g) * L::rowHalves + col;
                    const uint32_t bHi0 = *reinterpret_cast<const uint32_t*>(hiPlane + at);
                    const uint32_t bHi1 = *reinterpret_cast<const uint32_t*>(hiPlane + at + 8);
                    mma16816(accHi[nt], aHi, bHi0, bHi1);
                    mma16816(accLo[nt], aLo, bHi0, bHi1);
                    if constexpr (splitTexels) {
                        const uint32_t bLo0 = *reinterpret_cast<const uint32_t*>(loPlane + at);
                        const uint32_t bLo1 = *reinterpret_cast<const uint32_t*>(loPlane + at + 8);
                        mma16816(accLo[nt], aHi, bLo0, bLo1);
                    }
                }
            }
            if (jc >= 0) {  // vertical: window[m] (16 columns x 16 rows) x T rows of n-tile nt
                mma16816(outHi[0], windowHi[m], aHi.x, aHi.z);
                mma16816(outLo[0], windowHi[m], aLo.x, aLo.z);
                mma16816(outHi[1], windowHi[m], aHi.y, aHi.w);
                mma16816(outLo[1], windowHi[m], aLo.y, aLo.w);
                if constexpr (splitTexels) {
                    mma16816(outLo[0], windowLo[m], aHi.x, aHi.z);
                    mma16816(outLo[1], windowLo[m], aHi.y, aHi.w);
                }
            }
        }
        if (jc >= 0) {  // D of n-tile nt: (column g / g + 8, output rows 8nt + 2t, +1)
            float* plane = rows + channel * 16 * L::outRow;
#pragma unroll
            for (int nt = 0; nt < 2; ++nt)
#pragma unroll
                for (int j = 0; j < 4; ++j) {
                    const int row = 8 * nt + 2 * t + (j & 1), col = 16 * chunk + g + 8 * (j >> 1);
                    plane[row * L::outRow + col] = outHi[nt][j] + outLo[nt][j] * (1.0f / kLoScale);
                }
        }
        if (staged) {  // slide the window and append: the horizontal D of n-tile nt holds (column g /
                       // g + 8, rows 8nt + 2t, +1), the A fragment (columns x 16 rows) wants that order
#pragma unroll
            for (int m = 0; m < M - 1; ++m) {
                windowHi[m] = windowHi[m + 1];
                if constexpr (splitTexels) windowLo[m] = windowLo[m + 1];
            }
            float v[2][4];
#pragma unroll
            for (int nt = 0; nt < 2; ++nt)
#pragma unroll
                for (int j = 0; j < 4; ++j) v[nt][j] = accHi[nt][j] + accLo[nt][j] * (1.0f / kLoScale);
            uint4 hi, lo;
            splitPair(v[0][0], v[0][1], hi.x, lo.x);
            splitPair(v[0][2], v[0][3], hi.y, lo.y);
            splitPair(v[1][0], v[1][1], hi.z, lo.z);
            splitPair(v[1][2], v[1][3], hi.w, lo.w);
            windowHi[M - 1] = hi;
            if constexpr (splitTexels) windowLo[M - 1] = lo;
        }
        if (more) commit(staging, s + 1);
        __syncthreads();
        if (staged) publish(more ? s + 2 : steps);
        if (jc >= 0 && !deferThis) {
            if (order.progress) {
                waitForReaders(y0 + 16 * jc, min(y0 + 16 * jc + 16, height));
                __syncthreads();
            }
            storeChunk(rows, jc, true);
        }
    };
    for (int s = 0; s < steps + 1; s += kDepth) {
        if constexpr (kDepth == 1) {
            step(s, pendingA, pendingA);
        } else {
            step(s, pendingA, pendingB);
            if (s + 1 < steps + 1) step(s + 1, pendingB, pendingA);
        }
    }
    if (deferChunks > 0) {  // the rows the segment above reads, once it has staged them
        peek();
        waitForReaders(y0, min(y0 + 16 * deferChunks, height));
        __syncthreads();
        for (int jc = 0; jc < deferChunks; ++jc) storeChunk(deferred + jc * L::outFloats, jc, false);
    }
}

// Whether this build has the tensor-core kernel for the current device (mma.sync needs sm_80 and
// a binary made for it; a build for older GPUs only runs the direct blur).
template <int M, typename In, typename Out>
bool tensorBlurRunsHere() {
    static const bool runs = [] {
        cudaFuncAttributes attributes{};
        if (cudaFuncGetAttributes(&attributes, tensorBlurKernel<M, In, Out>) != cudaSuccess) {
            cudaGetLastError();
            return false;
        }
        if (attributes.binaryVersion < 80) return false;
        check(cudaFuncSetAttribute(tensorBlurKernel<M, In, Out>, cudaFuncAttributeMaxDynamicSharedMemorySize,
                                   int(TensorBlurLayout<M>::sharedBytes)),
              "cudaFuncSetAttribute (tensor blur shared memory)");
        return true;
    }();
    return runs;
}

int multiprocessorCount() {
    int device = 0, count = 0;
    check(cudaGetDevice(&device), "cudaGetDevice");
    check(cudaDeviceGetAttribute(&count, cudaDevAttrMultiProcessorCount, device), "cudaDeviceGetAttribute");
    return count;
}

// Blocks of the tensor-core blur that can be resident at once.
template <int M, typename In, typename Out>
int tensorBlurSlots() {
    static const int slots = [] {
        int perSm = 0;
        check(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&perSm, tensorBlurKernel<M, In, Out>, kTcThreads,
                                                            TensorBlurLayout<M>::sharedBytes),
              "cudaOccupancyMaxActiveBlocksPerMultiprocessor");
        return perSm * multiprocessorCount();
    }();
    return slots;
}

// Rows per block: blocks of a stripe re-blur M - 1 chunks of apron rows each, so fewer, taller
// segments cost less work, but the grid should fill the GPU: the segment count whose waves x
// (steps per block) is least, segments of at least 4 chunks (64 rows > r: only adjacent segments
// read each other's rows). In place every block must be resident at once: 0 when that cannot be.
int tensorSegmentRows(int width, int height, int chunksPerBand, int slots, bool inPlace) {
    const int stripes = (width + kTcWidth - 1) / kTcWidth, chunks = (height + 15) / 16;
    if (slots < 1) return 0;
    int best = 0, bestCost = 0;
    for (int segments = 1; segments <= chunks; ++segments) {
        const int perSegment = (chunks + segments - 1) / segments;
        if (segments > 1 && perSegment < 4) break;
        const int blocks = stripes * ((chunks + perSegment - 1) / perSegment);
        if (inPlace && blocks > slots) continue;
        const int cost = (blocks + slots - 1) / slots * (perSegment + chunksPerBand - 1);
        if (best == 0 || cost < bestCost) bestCost = cost, best = perSegment;
    }
    return 16 * best;
}

// Whether a block's output stores change the texels the blur reads (the fused composite).
template <typename Out>
struct StoresIntoInput : std::false_type {};
template <typename HdrIn, typename BloomOut, typename HdrOut>
struct StoresIntoInput<CompositeOnStore<HdrIn, BloomOut, HdrOut>> : std::true_type {};

bool cooperativeLaunchHere() {
    static const bool supported = [] {
        int device = 0, value = 0;
        check(cudaGetDevice(&device), "cudaGetDevice");
        check(cudaDeviceGetAttribute(&value, cudaDevAttrCooperativeLaunch, device), "cudaDeviceGetAttribute");
        return value != 0;
    }();
    return supported;
}

template <int M, typename In, typename Out>
bool launchTensorBlurChunks(In hdr, Out out, int width, int height, Weights w, int radius, post::BloomParams p,
                            BloomWorkspace& ws, cudaStream_t stream) {
    if (!tensorBlurRunsHere<M, In, Out>()) return false;
    constexpr bool inPlace = StoresIntoInput<Out>::value;
    if (inPlace && !cooperativeLaunchHere()) return false;
    int segmentRows = tensorSegmentRows(width, height, M, tensorBlurSlots<M, In, Out>(), inPlace);
    if (segmentRows == 0) return false;
    const int stripes = (width + kTcWidth - 1) / kTcWidth, segments = (height + segmentRows - 1) / segmentRows;
    const dim3 grid{unsigned(stripes), unsigned(segments)};
    constexpr size_t shared = TensorBlurLayout<M>::sharedBytes;
    InPlaceOrder order;
    if (!inPlace) {
        tensorBlurKernel<M><<<grid, kTcThreads, shared, stream>>>(hdr, out, width, height, w, radius, segmentRows, p,
                                                                  order);
        checkLaunch("tensorBlurKernel");
        return true;
    }
    order = {ws.progressCounters(size_t(stripes) * size_t(segments)), stripes, segments};
    check(cudaMemsetAsync(order.progress, 0, size_t(stripes) * size_t(segments) * sizeof(int), stream),
          "cudaMemsetAsync (tensor blur progress)");
    void* args[] = {&hdr, &out, &width, &height, &w, &radius, &segmentRows, &p, &order};
    const cudaError_t err = cudaLaunchCooperativeKernel(reinterpret_cast<const void*>(tensorBlurKernel<M, In, Out>),
                                                        grid, dim3(kTcThreads), args, shared, stream);
    if (err == cudaErrorCooperativeLaunchTooLarge) {  // fewer SMs free than measured: the direct blur
        cudaGetLastError();
        return false;
    }
    check(err, "cudaLaunchCooperativeKernel (tensorBlurKernel)");
    return true;
}

// Auto: the tensor cores from this radius up. On the H100 (bench/results/post/2026-11-24_cuda-interop/README.md)
// the direct blur was faster at kernel 50 and slower at 100 (fused in place, 1080p and 4K); its
// time grows with the radius and the tensor-core blur's is flat within one instantiation (M = 8:
// radius 41..56), so the two meet near kernel 85.
constexpr int kTensorBlurMinRadius = 43;
bool wantsTensorBlur(BloomBlur blur, int radius) {
    if (blur != BloomBlur::Auto) return blur == BloomBlur::TensorCore;
    return radius >= kTensorBlurMinRadius;
}

// The instantiations: M = 2, 4, 6, 8 chunks (radius <= 8, 24, 40, 56); a radius between runs
// the next one up, the extra chunks multiplying zero weights.
template <typename In, typename Out>
bool launchTensorBlur(In hdr, Out out, int width, int height, const Weights& w, int radius,
                      const post::BloomParams& p, BloomWorkspace& ws, cudaStream_t stream) {
    const int chunks = tensorChunks(radius);
    if (chunks <= 2) return launchTensorBlurChunks<2>(hdr, out, width, height, w, radius, p, ws, stream);
    if (chunks <= 4) return launchTensorBlurChunks<4>(hdr, out, width, height, w, radius, p, ws, stream);
    if (chunks <= 6) return launchTensorBlurChunks<6>(hdr, out, width, height, w, radius, p, ws, stream);
    return launchTensorBlurChunks<8>(hdr, out, width, height, w, radius, p, ws, stream);
}

template <typename In, typename Out>
void separableBloom(In hdr, Out bloom, int width, int height, const post::BloomParams& p, BloomWorkspace& ws,
                    cudaStream_t stream) {
    const std::vector<float> taps = post::gaussianWeights(p.kernel);
    Weights w{};
    for (size_t i = 0; i < taps.size(); ++i) w.w[i] = taps[i];
    const int radius = int(taps.size()) - 1;
    if (wantsTensorBlur(ws.blur, radius) && launchTensorBlur(hdr, bloom, width, height, w, radius, p, ws, stream))
        return;
    ws.ensure(width, height, p);
    // Bright pass fused into the horizontal blur's staging; the intermediate in ws.a: fp16 where the
    // bloom lands in RGBA16F textures and the radius is small (half the bytes, measured 3-9% faster
    // up to kernel 17 on the H100 and slower from kernel 25, where the staging's conversions cost
    // more than the bytes; its one rounding keeps the result within one fp16 ulp of the fp32
    // reference), else fp32.
    constexpr int kHalfIntermediateMaxRadius = 8;
    if constexpr (std::is_same_v<In, Half4Surface>) {
        if (radius <= kHalfIntermediateMaxRadius) {
            const HalfBufferImage intermediate{reinterpret_cast<uint2*>(ws.a), width};
            launchBlur<true>(BrightSource<In>{hdr, p}, intermediate, width, height, w, radius, stream);
            launchBlur<false>(intermediate, bloom, width, height, w, radius, stream);
            return;
        }
    }
    launchBlur<true>(BrightSource<In>{hdr, p}, BufferImage{ws.a, width}, width, height, w, radius, stream);
    launchBlur<false>(BufferImage{ws.a, width}, bloom, width, height, w, radius, stream);
}

}  // namespace

BloomWorkspace::~BloomWorkspace() {
    cudaFree(a);
    cudaFree(progress);
    for (float4* m : mips) cudaFree(m);
}

int* BloomWorkspace::progressCounters(size_t count) {
    if (progressCount < count) {
        check(cudaFree(progress), "cudaFree");
        progress = nullptr;
        check(cudaMalloc(&progress, count * sizeof(int)), "cudaMalloc (tensor blur progress)");
        progressCount = count;
    }
    return progress;
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
    if (p.method == post::BloomMethod::MipChain) return mipChainBloomBuffers(hdr, bloom, nullptr, width, height, p, ws, stream);
    separableBloom(BufferImage{const_cast<float4*>(hdr), width}, BufferImage{bloom, width}, width, height, p, ws, stream);
}

void bloomSurfaceToSurface(cudaSurfaceObject_t hdr, cudaSurfaceObject_t bloom, int width, int height,
                           const post::BloomParams& p, BloomWorkspace& ws, cudaStream_t stream) {
    if (p.method == post::BloomMethod::MipChain) return mipChainBloomSurfaces(hdr, bloom, false, width, height, p, ws, stream);
    separableBloom(Half4Surface{hdr}, Half4Surface{bloom}, width, height, p, ws, stream);
}

void bloomCompositeBuffers(const float4* hdr, float4* bloom, float4* hdrOut, int width, int height,
                           const post::BloomParams& p, BloomWorkspace& ws, cudaStream_t stream) {
    if (p.method == post::BloomMethod::MipChain) return mipChainBloomBuffers(hdr, bloom, hdrOut, width, height, p, ws, stream);
    const BufferImage in{const_cast<float4*>(hdr), width};
    const CompositeOnStore<BufferImage, BufferImage, BufferImage> out{in, {bloom, width}, {hdrOut, width}, p.strength};
    separableBloom(in, out, width, height, p, ws, stream);
}

void bloomCompositeSurfaces(cudaSurfaceObject_t hdr, cudaSurfaceObject_t bloom, int width, int height,
                            const post::BloomParams& p, BloomWorkspace& ws, cudaStream_t stream) {
    if (p.method == post::BloomMethod::MipChain) return mipChainBloomSurfaces(hdr, bloom, true, width, height, p, ws, stream);
    separableBloom(Half4Surface{hdr},
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

Half4Array::Half4Array(int width, int height) {
    const cudaChannelFormatDesc desc = cudaCreateChannelDescHalf4();
    check(cudaMallocArray(&array, &desc, size_t(width), size_t(height), cudaArraySurfaceLoadStore), "cudaMallocArray");
    cudaResourceDesc resource{};
    resource.resType = cudaResourceTypeArray;
    resource.res.array.array = array;
    check(cudaCreateSurfaceObject(&surface, &resource), "cudaCreateSurfaceObject");
}

Half4Array::~Half4Array() {
    cudaDestroySurfaceObject(surface);
    cudaFreeArray(array);
}

bool bloomBlurUsesTensorCores(int kernel, BloomBlur blur) {
    const int radius = int(post::gaussianWeights(kernel).size()) - 1;
    if (!wantsTensorBlur(blur, radius)) return false;
    using Surfaces = CompositeOnStore<Half4Surface, Half4Surface, Half4Surface>;  // what the passes run
    const int chunks = tensorChunks(radius);
    if (chunks <= 2) return tensorBlurRunsHere<2, Half4Surface, Surfaces>();
    if (chunks <= 4) return tensorBlurRunsHere<4, Half4Surface, Surfaces>();
    if (chunks <= 6) return tensorBlurRunsHere<6, Half4Surface, Surfaces>();
    return tensorBlurRunsHere<8, Half4Surface, Surfaces>();
}

namespace {


// A scene-like HDR image: mostly below the threshold, one texel in 64 bright (up to 50).
__global__ void fillBenchHdr(Half4Surface hdr, int width, int height) {
    const int x = int(blockIdx.x * blockDim.x + threadIdx.x), y = int(blockIdx.y * blockDim.y + threadIdx.y);
    if (x >= width || y >= height) return;
    const unsigned h = (unsigned(x) * 73856093u) ^ (unsigned(y) * 19349663u);
    const float base = float(h % 1000u) * 0.0009f, bright = (h >> 10) % 64u == 0 ? float((h >> 16) % 50u) : 0.0f;
    hdr.store(x, y, make_float4(base + bright, base * 0.8f + bright, base * 0.6f + bright, 1.0f));
}

double copyBytesPerSecond(cudaStream_t stream) {
    const size_t bytes = size_t(512) << 20;
    void *a = nullptr, *b = nullptr;
    check(cudaMalloc(&a, bytes), "cudaMalloc (copy bandwidth)");
    check(cudaMalloc(&b, bytes), "cudaMalloc (copy bandwidth)");
    cudaEvent_t start, stop;
    check(cudaEventCreate(&start), "cudaEventCreate");
    check(cudaEventCreate(&stop), "cudaEventCreate");
    std::vector<float> ms;
    for (int i = 0; i < 12; ++i) {
        check(cudaEventRecord(start, stream), "cudaEventRecord");
        check(cudaMemcpyAsync(b, a, bytes, cudaMemcpyDeviceToDevice, stream), "cudaMemcpyAsync");
        check(cudaEventRecord(stop, stream), "cudaEventRecord");
        check(cudaEventSynchronize(stop), "cudaEventSynchronize");
        float t = 0.0f;
        check(cudaEventElapsedTime(&t, start, stop), "cudaEventElapsedTime");
        if (i >= 2) ms.push_back(t);
    }
    std::sort(ms.begin(), ms.end());
    cudaEventDestroy(start);
    cudaEventDestroy(stop);
    cudaFree(a);
    cudaFree(b);
    return 2.0 * double(bytes) / (double(ms[ms.size() / 2]) * 1e-3);
}

// The copy baselines: one RGBA16F texel a thread through surfaces; two a thread (16 bytes) in
// linear memory.
__global__ void copyArrayKernel(cudaSurfaceObject_t src, cudaSurfaceObject_t dst, int width, int height) {
    const int x = int(blockIdx.x * blockDim.x + threadIdx.x), y = int(blockIdx.y * blockDim.y + threadIdx.y);
    if (x >= width || y >= height) return;
    surf2Dwrite(surf2Dread<ushort4>(src, x * int(sizeof(ushort4)), y), dst, x * int(sizeof(ushort4)), y);
}

__global__ void copyLinearKernel(const uint4* src, uint4* dst, size_t count) {
    const size_t i = size_t(blockIdx.x) * blockDim.x + threadIdx.x;
    if (i < count) dst[i] = src[i];
}

// Median ms of `iterations` CUDA-event timings of launch() on `stream`, after 5 warm-up runs.
template <typename Launch>
double medianEventMs(cudaStream_t stream, int iterations, Launch&& launch) {
    cudaEvent_t start, stop;
    check(cudaEventCreate(&start), "cudaEventCreate");
    check(cudaEventCreate(&stop), "cudaEventCreate");
    std::vector<float> ms;
    for (int i = -5; i < iterations; ++i) {
        check(cudaEventRecord(start, stream), "cudaEventRecord");
        launch();
        check(cudaEventRecord(stop, stream), "cudaEventRecord");
        check(cudaEventSynchronize(stop), "cudaEventSynchronize");
        float t = 0.0f;
        check(cudaEventElapsedTime(&t, start, stop), "cudaEventElapsedTime");
        if (i >= 0) ms.push_back(t);
    }
    cudaEventDestroy(start);
    cudaEventDestroy(stop);
    std::sort(ms.begin(), ms.end());
    return ms.empty() ? 0.0 : double(ms[ms.size() / 2]);
}

// RGBA16F texels of `img` (fp16-rounded) and back.
std::vector<__half> halfTexels(const ImageF& img) {
    std::vector<__half> out(img.rgba.size());
    for (size_t i = 0; i < out.size(); ++i) out[i] = __float2half_rn(img.rgba[i]);
    return out;
}

ImageF readHalfArray(const Half4Array& a, int width, int height) {
    std::vector<__half> texels(size_t(width) * size_t(height) * 4);
    check(cudaMemcpy2DFromArray(texels.data(), size_t(width) * 8, a.array, 0, 0, size_t(width) * 8, size_t(height),
                                cudaMemcpyDeviceToHost),
          "cudaMemcpy2DFromArray");
    ImageF out;
    out.width = width;
    out.height = height;
    out.rgba.resize(texels.size());
    for (size_t i = 0; i < texels.size(); ++i) out.rgba[i] = __half2float(texels[i]);
    return out;
}

}  // namespace

BloomAndComposite bloomCompositeOnHalfArrays(const ImageF& hdr, const post::BloomParams& p, BloomBlur blur,
                                             bool composite, const MipChainTuning& tuning) {
    const int width = hdr.width, height = hdr.height;
    Half4Array hdrArray(width, height), bloomArray(width, height);
    const std::vector<__half> texels = halfTexels(hdr);
    cudaStream_t stream = nullptr;
    check(cudaStreamCreate(&stream), "cudaStreamCreate");
    {
        BloomWorkspace ws;
        ws.blur = blur;
        ws.mipChain = tuning;
        check(cudaMemcpy2DToArray(hdrArray.array, 0, 0, texels.data(), size_t(width) * 8, size_t(width) * 8,
                                  size_t(height), cudaMemcpyHostToDevice),
              "cudaMemcpy2DToArray");
        if (composite)
            bloomCompositeSurfaces(hdrArray.surface, bloomArray.surface, width, height, p, ws, stream);
        else
            bloomSurfaceToSurface(hdrArray.surface, bloomArray.surface, width, height, p, ws, stream);
        check(cudaStreamSynchronize(stream), "cudaStreamSynchronize");
    }
    cudaStreamDestroy(stream);
    return {readHalfArray(bloomArray, width, height), readHalfArray(hdrArray, width, height)};
}

CopyKernelTimes timeHalf4Copies(int width, int height, int iterations) {
    CopyKernelTimes result;
    cudaStream_t stream = nullptr;
    check(cudaStreamCreate(&stream), "cudaStreamCreate");
    result.copyBytesPerSecond = copyBytesPerSecond(stream);
    {
        Half4Array src(width, height), dst(width, height);
        fillBenchHdr<<<gridFor(width, height), dim3(kBlock, kBlock), 0, stream>>>(Half4Surface{src.surface}, width, height);
        checkLaunch("fillBenchHdr");
        const dim3 block(32, 8), grid(unsigned(width + 31) / 32, unsigned(height + 7) / 8);
        result.arrayMs = medianEventMs(stream, iterations, [&] {
            copyArrayKernel<<<grid, block, 0, stream>>>(src.surface, dst.surface, width, height);
            checkLaunch("copyArrayKernel");
        });
    }
    const size_t pairs = (size_t(width) * size_t(height) + 1) / 2;  // 16 bytes: two RGBA16F texels
    uint4 *src = nullptr, *dst = nullptr;
    check(cudaMalloc(&src, pairs * sizeof(uint4)), "cudaMalloc");
    check(cudaMalloc(&dst, pairs * sizeof(uint4)), "cudaMalloc");
    check(cudaMemsetAsync(src, 0x3c, pairs * sizeof(uint4), stream), "cudaMemsetAsync");
    result.linearMs = medianEventMs(stream, iterations, [&] {
        copyLinearKernel<<<unsigned((pairs + 255) / 256), 256, 0, stream>>>(src, dst, pairs);
        checkLaunch("copyLinearKernel");
    });
    check(cudaStreamSynchronize(stream), "cudaStreamSynchronize");
    cudaFree(src);
    cudaFree(dst);
    cudaStreamDestroy(stream);
    return result;
}

BloomKernelTime timeBloomCompositeKernels(int width, int height, const post::BloomParams& p, BloomBlur blur,
                                          int iterations, bool composite, const MipChainTuning& tuning,
                                          std::vector<MipChainStep>* steps) {
    Half4Array hdr(width, height), bloom(width, height);
    cudaStream_t stream = nullptr;
    check(cudaStreamCreate(&stream), "cudaStreamCreate");
    BloomWorkspace ws;
    ws.blur = blur;
    ws.mipChain = tuning;
    BloomKernelTime result;
    result.tensorCores = p.method == post::BloomMethod::Separable && bloomBlurUsesTensorCores(p.kernel, blur);
    result.copyBytesPerSecond = copyBytesPerSecond(stream);
    cudaEvent_t start, stop;
    check(cudaEventCreate(&start), "cudaEventCreate");
    check(cudaEventCreate(&stop), "cudaEventCreate");
    std::vector<float> ms;
    for (int i = -5; i < iterations; ++i) {  // 5 warm-up runs; the HDR refilled so every run composites the same
        fillBenchHdr<<<gridFor(width, height), dim3(kBlock, kBlock), 0, stream>>>(Half4Surface{hdr.surface}, width,
                                                                                  height);
        checkLaunch("fillBenchHdr");
        check(cudaEventRecord(start, stream), "cudaEventRecord");
        if (composite)
            bloomCompositeSurfaces(hdr.surface, bloom.surface, width, height, p, ws, stream);
        else
            bloomSurfaceToSurface(hdr.surface, bloom.surface, width, height, p, ws, stream);
        check(cudaEventRecord(stop, stream), "cudaEventRecord");
        check(cudaEventSynchronize(stop), "cudaEventSynchronize");
        float t = 0.0f;
        check(cudaEventElapsedTime(&t, start, stop), "cudaEventElapsedTime");
        if (i >= 0) ms.push_back(t);
    }
    if (steps && p.method == post::BloomMethod::MipChain) {  // each launch timed alone
        StepRecorder recorder;
        ws.recorder = &recorder;
        std::vector<std::vector<double>> stepMs;
        for (int i = -2; i < iterations; ++i) {
            fillBenchHdr<<<gridFor(width, height), dim3(kBlock, kBlock), 0, stream>>>(Half4Surface{hdr.surface}, width,
                                                                                      height);
            checkLaunch("fillBenchHdr");
            recorder.restart();
            if (composite)
                bloomCompositeSurfaces(hdr.surface, bloom.surface, width, height, p, ws, stream);
            else
                bloomSurfaceToSurface(hdr.surface, bloom.surface, width, height, p, ws, stream);
            check(cudaStreamSynchronize(stream), "cudaStreamSynchronize");
            if (i < 0) continue;
            stepMs.resize(recorder.count());
            for (size_t k = 0; k < recorder.count(); ++k) stepMs[k].push_back(recorder.ms(k));
        }
        ws.recorder = nullptr;
        steps->clear();
        for (size_t k = 0; k < stepMs.size(); ++k) {
            std::sort(stepMs[k].begin(), stepMs[k].end());
            steps->push_back({recorder.name(k), stepMs[k][stepMs[k].size() / 2], recorder.bytes(k)});
        }
    }
    cudaEventDestroy(start);
    cudaEventDestroy(stop);
    cudaStreamDestroy(stream);
    std::sort(ms.begin(), ms.end());
    result.medianMs = ms.empty() ? 0.0 : double(ms[ms.size() / 2]);
    return result;
}

}  // namespace lp::cuda
