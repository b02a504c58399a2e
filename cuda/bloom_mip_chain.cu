// The mip-chain bloom (Jimenez 2014) in CUDA, laid out for memory bandwidth. The per-texel math
// and its operation order are the CPU reference's (engine/post/post_reference.cpp); what differs
// is where the values live and how many launches there are:
// - The first downsample (bright pass, Karis, 13 taps) reads each HDR texel once into shared
//   memory and writes the half-resolution level; the 13 taps are 2x2 boxes that neighbouring
//   outputs share, so a block computes each box once (two grids: boxes on even and on odd source
//   texels) and each output reads 13 of them.
// - Levels are fp16 RGBA (8 bytes, one access a texel) where the bloom lands in RGBA16F textures,
//   as the GLSL path's RGBA16F mips and the reference's Storage::Half; fp32 on device buffers.
// - The levels of at most MipChainTuning::tailTexels texels (latency-bound: a few thousand texels
//   each) run down and back up in one launch of one block.
// - The last upsample is fused with the full-resolution one and the composite: a block computes
//   the half-resolution up_0 = down_0 + U(up_1) it needs into shared memory, upsamples it and
//   writes the bloom and the composited HDR; no half-resolution up_0 is written or re-read.
// - On sm_90 the launches after the first are programmatic dependent launches: each kernel lets
//   the next one be scheduled as soon as all its own blocks run, and waits for the previous one to
//   finish before touching what it wrote, so the small levels' launches overlap instead of
//   queueing one after another.
// - The first downsample's HDR reads are evict-first and its divisions __fdividef; downsample
//   blocks make one output row a thread, upsample blocks two (512 threads).
// This is the fastest layout measured on the H100 (bench/results/post/2026-11-24_cuda-interop/README.md). The
// variants that lost there (wide kernel shapes, exact divisions, plain HDR reads, streamed final
// accesses, up_0 in its own launch or from 4 x 4 taps, level 0 persisting in L2, a CUDA graph of the
// launches) were removed after measurement; they are in this file at commit 99b0145. MipChainTuning
// (cuda/post_cuda.hpp) keeps the two settings that cost the passes nothing: the tail's size and the
// overlapping launches.
#include <algorithm>
#include <type_traits>

#include "cuda/interop.hpp"
#include "cuda/post_kernels.cuh"

namespace lp::cuda {

using post::Rgb;

namespace {

__device__ inline Rgb rgbOf(float4 c) { return {c.x, c.y, c.z}; }
__device__ inline float4 opaque(Rgb c) { return make_float4(c.r, c.g, c.b, 1.0f); }
__device__ inline int clampTo(int v, int hi) { return v < 0 ? 0 : (v > hi ? hi : v); }
__device__ inline Rgb plus(Rgb a, Rgb b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }
__device__ inline Rgb times(Rgb a, float k) { return {a.r * k, a.g * k, a.b * k}; }
__device__ inline Rgb quarterOf(Rgb a, Rgb b, Rgb c, Rgb d) { return times(plus(plus(a, b), plus(c, d)), 0.25f); }

// Programmatic dependent launch (sm_90): wait until the grids this one depends on have finished
// and their writes are visible; let the next grid be scheduled. No-ops below sm_90 and for grids
// launched without the attribute.
__device__ inline void waitForPriorGrids() {
#if defined(__CUDA_ARCH__) && __CUDA_ARCH__ >= 900
    asm volatile("griddepcontrol.wait;" ::: "memory");
#endif
}
__device__ inline void letNextGridLaunch() {
#if defined(__CUDA_ARCH__) && __CUDA_ARCH__ >= 900
    asm volatile("griddepcontrol.launch_dependents;" :::);
#endif
}

// A mip level in fp16 RGBA, 8 bytes a texel (what RGBA16F storage keeps).
struct HalfLevel {
    uint2* data;
    int width, height;
    __device__ float4 load(int x, int y) const { return unpackHalf4(data[size_t(y) * size_t(width) + size_t(x)]); }
    __device__ void store(int x, int y, float4 c) const { data[size_t(y) * size_t(width) + size_t(x)] = packHalf4(c); }
    __device__ static float4 stored(float4 c) { return Half4Surface::stored(c); }
};

// A mip level in fp32 (device-buffer runs, compared with the fp32 reference).
struct FloatLevel {
    float4* data;
    int width, height;
    __device__ float4 load(int x, int y) const { return data[size_t(y) * size_t(width) + size_t(x)]; }
    __device__ void store(int x, int y, float4 c) const { data[size_t(y) * size_t(width) + size_t(x)] = c; }
    __device__ static float4 stored(float4 c) { return c; }
};

// An RGBA16F surface read once per texel (the first downsample's HDR): loads marked evict-first.
struct StreamedHalf4Surface {
    cudaSurfaceObject_t surface;
    __device__ float4 load(int x, int y) const {
        unsigned short r, g, b, a;
        asm("suld.b.2d.cs.v4.b16.trap {%0, %1, %2, %3}, [%4, {%5, %6}];"
            : "=h"(r), "=h"(g), "=h"(b), "=h"(a)
            : "l"(surface), "r"(x * 8), "r"(y));
        return make_float4(__half2float(__ushort_as_half(r)), __half2float(__ushort_as_half(g)),
                           __half2float(__ushort_as_half(b)), __half2float(__ushort_as_half(a)));
    }
};

// The 13-tap downsample (reference: downsample13) from its 13 2x2 boxes: box[m][k] is the box
// on the even source texels of destination (x - 1 + k, y - 1 + m), odd[m][k] the box on the odd
// ones (source 2i + 1..2i + 2) of (x - 1 + k, y - 1 + m). Corner (ox, oy) of the reference is
// box (ox / 2, oy / 2) for even offsets and odd ((ox - 1) / 2, (oy - 1) / 2) for odd ones.
// FastDivide: the Karis weights' and the normalisation's divisions as __fdividef (2 ulps instead of
// correctly rounded): the first downsample was bound by its divisions.
template <bool FastDivide = false>
__device__ inline Rgb downsampleFromBoxes(const Rgb box[3][3], const Rgb odd[2][2], bool karis) {
    const Rgb g[5] = {
        quarterOf(odd[0][0], odd[0][1], odd[1][0], odd[1][1]),
        quarterOf(box[0][0], box[0][1], box[1][0], box[1][1]),
        quarterOf(box[0][1], box[0][2], box[1][1], box[1][2]),
        quarterOf(box[1][0], box[1][1], box[2][0], box[2][1]),
        quarterOf(box[1][1], box[1][2], box[2][1], box[2][2]),
    };
    const float base[5] = {0.5f, 0.125f, 0.125f, 0.125f, 0.125f};
    Rgb sum;
    float wsum = 0.0f;
#pragma unroll
    for (int k = 0; k < 5; ++k) {
        const float karisWeight =
            FastDivide ? __fdividef(1.0f, 1.0f + post::luminance(g[k])) : post::karisWeight(g[k]);
        const float w = karis ? base[k] * karisWeight : base[k];
        sum = plus(sum, times(g[k], w));
        wsum += w;
    }
    return times(sum, FastDivide ? __fdividef(1.0f, wsum) : 1.0f / wsum);
}

// post::brightPass with its two divisions as __fdividef (see FastDivide above; the first
// downsample's bright pass).
__device__ inline Rgb brightPassFast(Rgb c, float threshold, float knee, float highlight) {
    c = post::sanitize(c);
    const float br = fmaxf(c.r, fmaxf(c.g, c.b));
    float soft = fminf(fmaxf(br - threshold + knee, 0.0f), 2.0f * knee);
    soft = __fdividef(soft * soft, 4.0f * knee + 1e-5f);
    const float contrib = __fdividef(fmaxf(soft, br - threshold), fmaxf(br, 1e-5f));
    return {fminf(c.r * contrib, highlight), fminf(c.g * contrib, highlight), fminf(c.b * contrib, highlight)};
}

// ---- Downsample of a level (or of the HDR image, bright-passed, for level 0), tiled ----
// A block of 32 x 8 threads makes 32 x 8 outputs, one a thread: it stages source texels
// 2 * x0 - 2 .. 2 * x1 + 3 and the even boxes of destinations x0 - 1 .. x1 + 1, the odd ones of
// x0 - 1 .. x1. One output row a thread (not two) needs less shared memory and fewer registers, so
// more blocks share an SM.
struct DownTile {
    static constexpr int W = 32, H = 8, Threads = W * H;
    static constexpr int SrcW = 2 * W + 4, SrcH = 2 * H + 4;
    static constexpr int BoxW = W + 2, BoxH = H + 2, OddW = W + 1, OddH = H + 1;
};

struct Planes3 {  // one float plane per channel: consecutive lanes, consecutive banks
    template <int H, int W>
    struct Of {
        float r[H][W], g[H][W], b[H][W];
        __device__ Rgb at(int j, int i) const { return {r[j][i], g[j][i], b[j][i]}; }
        __device__ void put(int j, int i, Rgb c) {
            r[j][i] = c.r;
            g[j][i] = c.g;
            b[j][i] = c.b;
        }
    };
};

// First: the level-0 downsample of the HDR (bright pass, Karis, fast divisions).
template <bool First, typename Src, typename Dst>
__global__ void __launch_bounds__(DownTile::Threads) downTileKernel(Src src, int sw, int sh, Dst dst, post::BloomParams p) {
    constexpr int kDownW = DownTile::W, kDownH = DownTile::H, kDownThreads = DownTile::Threads;
    constexpr int kSrcW = DownTile::SrcW, kSrcH = DownTile::SrcH, kBoxW = DownTile::BoxW, kBoxH = DownTile::BoxH;
    constexpr int kOddW = DownTile::OddW, kOddH = DownTile::OddH;
    __shared__ Planes3::Of<kSrcH, kSrcW> source;
    __shared__ Planes3::Of<kBoxH, kBoxW> boxes;
    __shared__ Planes3::Of<kOddH, kOddW> odds;
    letNextGridLaunch();
    waitForPriorGrids();
    const int thread = int(threadIdx.y) * kDownW + int(threadIdx.x);
    const int x0 = int(blockIdx.x) * kDownW, y0 = int(blockIdx.y) * kDownH;
    const int sx0 = 2 * x0 - 2, sy0 = 2 * y0 - 2;
    constexpr int kStaged = kSrcW * kSrcH, kBatch = (kStaged + kDownThreads - 1) / kDownThreads;
    float4 v[kBatch];  // every load in flight before the first is used
#pragma unroll
    for (int b = 0; b < kBatch; ++b) {
        const int e = thread + b * kDownThreads;
        if (e < kStaged) v[b] = src.load(clampTo(sx0 + e % kSrcW, sw - 1), clampTo(sy0 + e / kSrcW, sh - 1));
    }
#pragma unroll
    for (int b = 0; b < kBatch; ++b) {
        const int e = thread + b * kDownThreads;
        if (e >= kStaged) continue;
        const Rgb c = rgbOf(v[b]);
        source.put(e / kSrcW, e % kSrcW, First ? brightPassFast(c, p.threshold, p.knee, p.highlight) : c);
    }
    __syncthreads();
    // Box (i, j) of the even grid covers staged texels 2i..2i+1, 2j..2j+1; of the odd grid 2i+1..2i+2.
    auto box = [&](int a, int b) {
        return quarterOf(source.at(b, a), source.at(b, a + 1), source.at(b + 1, a), source.at(b + 1, a + 1));
    };
    for (int e = thread; e < kBoxW * kBoxH; e += kDownThreads) {
        const int i = e % kBoxW, j = e / kBoxW;
        boxes.put(j, i, box(2 * i, 2 * j));
    }
    for (int e = thread; e < kOddW * kOddH; e += kDownThreads) {
        const int i = e % kOddW, j = e / kOddW;
        odds.put(j, i, box(2 * i + 1, 2 * j + 1));
    }
    __syncthreads();
    // Destination (tx, ty): even boxes rows ty .. ty + 2, columns tx .. tx + 2 (grid index =
    // destination - x0 + 1 for destination x - 1); odd boxes rows ty .. ty + 1, columns tx .. tx + 1.
    const int tx = int(threadIdx.x), ty = int(threadIdx.y);
    const int x = x0 + tx, y = y0 + ty;
    Rgb even[3][3], oddBoxes[2][2];
#pragma unroll
    for (int m = 0; m < 3; ++m)
#pragma unroll
        for (int k = 0; k < 3; ++k) even[m][k] = boxes.at(ty + m, tx + k);
#pragma unroll
    for (int m = 0; m < 2; ++m)
#pragma unroll
        for (int k = 0; k < 2; ++k) oddBoxes[m][k] = odds.at(ty + m, tx + k);
    if (x < dst.width && y < dst.height)
        dst.store(x, y, opaque(downsampleFromBoxes<First>(even, oddBoxes, First && p.karis)));
}

// ---- Upsample: fine texels from a staged tile of the coarse level ----
// A block of 64 x 8 threads makes a 64 x 16 tile of fine texels, each thread 2 consecutive rows of
// one column; the coarse tile it reads spans coarse texels x0 / 2 - 2 .. x1 / 2 + 1. Two rows a
// thread (not eight, with 256 threads) need fewer registers, so more blocks share an SM.
struct UpTile {
    static constexpr int Rows = 2, ThreadsY = 8, W = 64, H = Rows * ThreadsY, Threads = W * ThreadsY;
    static constexpr int CoarseW = W / 2 + 4, CoarseH = H / 2 + 4;
    static constexpr int CoarseRows = Rows / 2 + 4;  // coarse rows one thread's outputs read
    // up_0 texels (x0 / 2 - 2 + i, ...) of the last kernel's tile need up_1 texels from (x0 / 2 - 2) / 2 - 2.
    static constexpr int Up1W = CoarseW / 2 + 5, Up1H = CoarseH / 2 + 5;
    using Tile = Planes3::Of<CoarseH, CoarseW>;
};

// The upsample (reference: upsample) of the thread's column x = x0 + tx at rows y0 + Rows * ty + m
// from the coarse tile whose origin is (x0 / 2 - 2, y0 / 2 - 2): per coarse row the 4-tap
// horizontal sum once, then the vertical 4 taps per output (the reference's order: rows, then
// their weighted sum).
__device__ inline void upsampleColumn(const UpTile::Tile& tile, int tx, int ty, Rgb out[UpTile::Rows]) {
    const bool ox = tx & 1;
    const int bx = (tx >> 1) + (ox ? 1 : 0);  // (x >> 1) - (ox ? 1 : 2) - (x0 / 2 - 2), x0 even
    const int row0 = (UpTile::Rows / 2) * ty;  // (y0 + Rows * ty) / 2 - 2 - (y0 / 2 - 2)
    Rgb rows[UpTile::CoarseRows];
#pragma unroll
    for (int k = 0; k < UpTile::CoarseRows; ++k) {
        Rgb row;
#pragma unroll
        for (int i = 0; i < 4; ++i) row = plus(row, times(tile.at(row0 + k, bx + i), post::upsampleWeight(i, ox)));
        rows[k] = row;
    }
#pragma unroll
    for (int m = 0; m < UpTile::Rows; ++m) {
        const bool oy = m & 1;
        const int by = (m >> 1) + (oy ? 1 : 0);  // relative to row0
        Rgb sum;
#pragma unroll
        for (int j = 0; j < 4; ++j) sum = plus(sum, times(rows[by + j], post::upsampleWeight(j, oy)));
        out[m] = sum;
    }
}

// fine += U(coarse), in place (up_l = down_l + U(up_{l+1})).
template <typename Lvl>
__global__ void __launch_bounds__(UpTile::Threads) upTileKernel(Lvl coarse, Lvl fine) {
    __shared__ UpTile::Tile tile;
    letNextGridLaunch();
    waitForPriorGrids();
    const int tx = int(threadIdx.x), ty = int(threadIdx.y), thread = ty * UpTile::W + tx;
    const int x0 = int(blockIdx.x) * UpTile::W, y0 = int(blockIdx.y) * UpTile::H;
    const int cx0 = x0 / 2 - 2, cy0 = y0 / 2 - 2;
    const int x = x0 + tx, yFirst = y0 + UpTile::Rows * ty;
    float4 own[UpTile::Rows];
#pragma unroll
    for (int m = 0; m < UpTile::Rows; ++m)
        if (x < fine.width && yFirst + m < fine.height) own[m] = fine.load(x, yFirst + m);
    for (int e = thread; e < UpTile::CoarseW * UpTile::CoarseH; e += UpTile::Threads) {
        const int i = e % UpTile::CoarseW, j = e / UpTile::CoarseW;
        tile.put(j, i, rgbOf(coarse.load(clampTo(cx0 + i, coarse.width - 1), clampTo(cy0 + j, coarse.height - 1))));
    }
    __syncthreads();
    Rgb up[UpTile::Rows];
    upsampleColumn(tile, tx, ty, up);
#pragma unroll
    for (int m = 0; m < UpTile::Rows; ++m)
        if (x < fine.width && yFirst + m < fine.height) fine.store(x, yFirst + m, opaque(plus(rgbOf(own[m]), up[m])));
}

// ---- The last kernel: up_0 on the fly, the full-resolution upsample and the composite ----
// U(up_1) for the tile's up_0 texels in two passes: each up_1 row's horizontal 4-tap sum per up_0
// column once (shared by the up_0 texels of that column), then the vertical 4 taps: the
// reference's rows and their weighted sum, with a third of the shared-memory reads of 4 x 4 taps.
template <typename Lvl, bool Composite, typename HdrIn, typename BloomOut, typename HdrOut>
__global__ void __launch_bounds__(UpTile::Threads)
    finalTileKernel(Lvl down0, Lvl up1, bool hasUp1, HdrIn hdr, BloomOut bloom, HdrOut hdrOut, int width,
                    int height, float norm, float strength) {
    constexpr int kCoarseW = UpTile::CoarseW, kCoarseH = UpTile::CoarseH, kUp1W = UpTile::Up1W, kUp1H = UpTile::Up1H;
    constexpr int kThreads = UpTile::Threads, kRows = UpTile::Rows;
    __shared__ Planes3::Of<kUp1H, kUp1W> coarser;
    __shared__ Planes3::Of<kUp1H, kCoarseW> rowSums;  // [up_1 row][up_0 column]
    __shared__ UpTile::Tile tile;
    letNextGridLaunch();
    const int tx = int(threadIdx.x), ty = int(threadIdx.y), thread = ty * UpTile::W + tx;
    const int x0 = int(blockIdx.x) * UpTile::W, y0 = int(blockIdx.y) * UpTile::H;
    const int cx0 = x0 / 2 - 2, cy0 = y0 / 2 - 2;  // up_0 tile origin (may be negative: clamped per texel)
    const int ux0 = (cx0 >> 1) - 2, uy0 = (cy0 >> 1) - 2;  // up_1 tile origin (floor halves)
    const int x = x0 + tx, yFirst = y0 + kRows * ty;
    // The HDR texels of the composite, in flight during the rest. Loaded before the wait: nothing
    // this launch waits for writes the HDR (the first downsample only reads it, and it started
    // before this grid could be scheduled, after whatever wrote the HDR), and this kernel writes
    // it only after the wait.
    float4 h[kRows];
    if (Composite) {
#pragma unroll
        for (int m = 0; m < kRows; ++m)
            if (x < width && yFirst + m < height) h[m] = hdr.load(x, yFirst + m);
    }
    waitForPriorGrids();
    if (hasUp1) {
        for (int e = thread; e < kUp1W * kUp1H; e += kThreads) {
            const int i = e % kUp1W, j = e / kUp1W;
            coarser.put(j, i, rgbOf(up1.load(clampTo(ux0 + i, up1.width - 1), clampTo(uy0 + j, up1.height - 1))));
        }
    }
    constexpr int kTile = kCoarseW * kCoarseH, kBatch = (kTile + kThreads - 1) / kThreads;
    float4 own[kBatch];
#pragma unroll
    for (int b = 0; b < kBatch; ++b) {
        const int e = thread + b * kThreads;
        if (e < kTile)
            own[b] = down0.load(clampTo(cx0 + e % kCoarseW, down0.width - 1), clampTo(cy0 + e / kCoarseW, down0.height - 1));
    }
    __syncthreads();
    if (hasUp1) {
        // rowSums[r][i]: up_1 row r's 4 taps for up_0 column cx0 + i (clamped), weights by its parity.
        for (int e = thread; e < kUp1H * kCoarseW; e += kThreads) {
            const int i = e % kCoarseW, r = e / kCoarseW;
            const int cx = clampTo(cx0 + i, down0.width - 1);
            const bool ox = cx & 1;
            const int bx = (cx >> 1) - (ox ? 1 : 2) - ux0;
            Rgb row;
#pragma unroll
            for (int k = 0; k < 4; ++k) row = plus(row, times(coarser.at(r, bx + k), post::upsampleWeight(k, ox)));
            rowSums.put(r, i, row);
        }
        __syncthreads();
    }
#pragma unroll
    for (int b = 0; b < kBatch; ++b) {
        const int e = thread + b * kThreads;
        if (e >= kTile) continue;
        Rgb c = rgbOf(own[b]);
        if (hasUp1) {  // up_0 = down_0 + U(up_1) at the clamped texel, as stored
            const int cy = clampTo(cy0 + e / kCoarseW, down0.height - 1);
            const bool oy = cy & 1;
            const int by = (cy >> 1) - (oy ? 1 : 2) - uy0;
            Rgb sum;
#pragma unroll
            for (int j = 0; j < 4; ++j) sum = plus(sum, times(rowSums.at(by + j, e % kCoarseW), post::upsampleWeight(j, oy)));
            c = rgbOf(Lvl::stored(opaque(plus(c, sum))));
        }
        tile.put(e / kCoarseW, e % kCoarseW, c);
    }
    __syncthreads();
    Rgb up[kRows];
    upsampleColumn(tile, tx, ty, up);
#pragma unroll
    for (int m = 0; m < kRows; ++m) {
        const int y = yFirst + m;
        if (x >= width || y >= height) continue;
        const float4 b = opaque(times(up[m], norm));
        bloom.store(x, y, b);
        if (Composite) {
            const Rgb stored = rgbOf(BloomOut::stored(b));
            hdrOut.store(x, y, opaque(post::sanitize(plus(post::sanitize(rgbOf(h[m])), times(stored, strength)))));
        }
    }
}

// ---- The small levels, down and back up, in one block ----
constexpr int kTailThreads = 512;

template <typename Lvl>
struct Chain {
    Lvl level[post::kMaxMipLevels];
    int count;
};

template <typename Lvl>
__global__ void __launch_bounds__(kTailThreads) chainTailKernel(Chain<Lvl> chain, int first) {
    letNextGridLaunch();
    waitForPriorGrids();
    for (int l = first; l < chain.count; ++l) {
        const Lvl src = chain.level[l - 1], dst = chain.level[l];
        for (int e = int(threadIdx.x); e < dst.width * dst.height; e += kTailThreads) {
            const int x = e % dst.width, y = e / dst.width;
            Rgb t[6][6];
#pragma unroll
            for (int j = 0; j < 6; ++j)
#pragma unroll
                for (int i = 0; i < 6; ++i)
                    t[j][i] = rgbOf(src.load(clampTo(2 * x - 2 + i, src.width - 1), clampTo(2 * y - 2 + j, src.height - 1)));
            Rgb even[3][3], odd[2][2];
#pragma unroll
            for (int m = 0; m < 3; ++m)
#pragma unroll
                for (int k = 0; k < 3; ++k)
                    even[m][k] = quarterOf(t[2 * m][2 * k], t[2 * m][2 * k + 1], t[2 * m + 1][2 * k], t[2 * m + 1][2 * k + 1]);
#pragma unroll
            for (int m = 0; m < 2; ++m)
#pragma unroll
                for (int k = 0; k < 2; ++k)
                    odd[m][k] = quarterOf(t[2 * m + 1][2 * k + 1], t[2 * m + 1][2 * k + 2], t[2 * m + 2][2 * k + 1],
                                          t[2 * m + 2][2 * k + 2]);
            dst.store(x, y, opaque(downsampleFromBoxes(even, odd, false)));
        }
        __syncthreads();  // global writes of the block are visible to it after the barrier
    }
    for (int l = chain.count - 2; l >= first; --l) {
        const Lvl fine = chain.level[l], coarse = chain.level[l + 1];
        for (int e = int(threadIdx.x); e < fine.width * fine.height; e += kTailThreads) {
            const int x = e % fine.width, y = e / fine.width;
            const bool ox = x & 1, oy = y & 1;
            const int bx = (x >> 1) - (ox ? 1 : 2), by = (y >> 1) - (oy ? 1 : 2);
            Rgb sum;
#pragma unroll
            for (int j = 0; j < 4; ++j) {
                Rgb row;
#pragma unroll
                for (int i = 0; i < 4; ++i)
                    row = plus(row, times(rgbOf(coarse.load(clampTo(bx + i, coarse.width - 1), clampTo(by + j, coarse.height - 1))),
                                          post::upsampleWeight(i, ox)));
                sum = plus(sum, times(row, post::upsampleWeight(j, oy)));
            }
            fine.store(x, y, opaque(plus(rgbOf(fine.load(x, y)), sum)));
        }
        __syncthreads();
    }
}

bool programmaticLaunchHere() {
    static const bool supported = [] {
        int device = 0, major = 0;
        check(cudaGetDevice(&device), "cudaGetDevice");
        check(cudaDeviceGetAttribute(&major, cudaDevAttrComputeCapabilityMajor, device), "cudaDeviceGetAttribute");
        return major >= 9;
    }();
    return supported;
}

// Launches `kernel`; `afterPrior`: as a programmatic dependent launch where the device has them
// (on a created stream: the legacy default stream keeps plain launches).
template <typename... Params, typename... Args>
void launch(const char* name, void (*kernel)(Params...), dim3 grid, dim3 block, cudaStream_t stream, bool afterPrior,
            Args... args) {
    cudaLaunchAttribute attribute;
    cudaLaunchConfig_t config{};
    config.gridDim = grid;
    config.blockDim = block;
    config.dynamicSmemBytes = 0;
    config.stream = stream;
    if (afterPrior && stream != nullptr && programmaticLaunchHere()) {
        attribute.id = cudaLaunchAttributeProgrammaticStreamSerialization;
        attribute.val.programmaticStreamSerializationAllowed = 1;
        config.attrs = &attribute;
        config.numAttrs = 1;
    }
    check(cudaLaunchKernelEx(&config, kernel, Params(args)...), name);
}

dim3 tilesOf(int width, int height, int tileW, int tileH) {
    return dim3(unsigned((width + tileW - 1) / tileW), unsigned((height + tileH - 1) / tileH));
}

template <typename Lvl>
double bytesOf(const Lvl& level) {
    return double(level.width) * double(level.height) * double(sizeof(*level.data));
}

// downIn: the HDR as the first downsample reads it; hdr: as the last kernel reads it.
template <typename Lvl, bool Composite, typename DownIn, typename HdrIn, typename BloomOut, typename HdrOut>
void mipChain(Chain<Lvl> chain, DownIn downIn, HdrIn hdr, BloomOut bloom, HdrOut hdrOut, int width, int height,
              const post::BloomParams& p, const MipChainTuning& tuning, StepRecorder* recorder, cudaStream_t stream) {
    const int n = chain.count;
    int first = 1;  // the tail: levels first .. n - 1
    while (first < n && chain.level[first].width * chain.level[first].height > tuning.tailTexels) ++first;
    // Every launch after the first may overlap its predecessor's end (not while each is timed alone).
    const bool overlap = tuning.programmaticLaunch && !recorder;
    // Runs `launchIt`, timed as `name` moving `bytes` when recording.
    auto step = [&](const char* name, double bytes, auto&& launchIt) {
        if (recorder) recorder->begin(stream);
        launchIt();
        if (recorder) recorder->end(stream, name, bytes);
    };
    static const char* const kDown[] = {"down0", "down1", "down2", "down3", "down4", "down5", "down6", "down7"};
    static const char* const kUp[] = {"up0", "up1", "up2", "up3", "up4", "up5", "up6", "up7"};
    const double hdrBytes = double(width) * double(height) * 8.0;
    const dim3 downBlock(DownTile::W, DownTile::H), upBlock(UpTile::W, UpTile::ThreadsY);
    const Lvl& l0 = chain.level[0];
    step(kDown[0], hdrBytes + bytesOf(l0), [&] {
        launch("downTileKernel (level 0)", downTileKernel<true, DownIn, Lvl>,
               tilesOf(l0.width, l0.height, DownTile::W, DownTile::H), downBlock, stream, false, downIn, width, height, l0, p);
    });
    for (int l = 1; l < first; ++l) {
        const Lvl &src = chain.level[l - 1], &dst = chain.level[l];
        step(kDown[l], bytesOf(src) + bytesOf(dst), [&] {
            launch("downTileKernel", downTileKernel<false, Lvl, Lvl>, tilesOf(dst.width, dst.height, DownTile::W, DownTile::H),
                   downBlock, stream, overlap, src, src.width, src.height, dst, p);
        });
    }
    if (first < n) {
        double bytes = 0.0;
        for (int l = first; l < n; ++l) bytes += bytesOf(chain.level[l - 1]) + bytesOf(chain.level[l]);
        for (int l = n - 2; l >= first; --l) bytes += bytesOf(chain.level[l + 1]) + 2.0 * bytesOf(chain.level[l]);
        step("tail", bytes, [&] {
            launch("chainTailKernel", chainTailKernel<Lvl>, dim3(1), dim3(kTailThreads), stream, overlap, chain, first);
        });
    }
    // up_l for l >= 1; up_0 is computed inside the last kernel.
    for (int l = std::min(first, n - 1) - 1; l >= 1; --l) {
        const Lvl& fine = chain.level[l];
        step(kUp[l], bytesOf(chain.level[l + 1]) + 2.0 * bytesOf(fine), [&] {
            launch("upTileKernel", upTileKernel<Lvl>, tilesOf(fine.width, fine.height, UpTile::W, UpTile::H), upBlock,
                   stream, overlap, chain.level[l + 1], fine);
        });
    }
    const bool hasUp1 = n > 1;  // level 0 still holds down_0, level 1 up_1
    const Lvl up1 = hasUp1 ? chain.level[1] : chain.level[0];
    step("final", hdrBytes * (Composite ? 3.0 : 1.0) + bytesOf(l0) + (hasUp1 ? bytesOf(up1) : 0.0), [&] {
        launch("finalTileKernel", finalTileKernel<Lvl, Composite, HdrIn, BloomOut, HdrOut>,
               tilesOf(width, height, UpTile::W, UpTile::H), upBlock, stream, overlap, l0, up1, hasUp1, hdr, bloom, hdrOut,
               width, height, 1.0f / float(n), p.strength);
    });
}

template <typename Lvl>
Chain<Lvl> chainOf(BloomWorkspace& ws, int width, int height, const post::BloomParams& p) {
    ws.ensure(width, height, p);
    Chain<Lvl> chain{};
    chain.count = post::mipLevelCount(p.kernel, width, height);
    for (int l = 0; l < chain.count; ++l) {
        // The workspace holds fp32 texels; the fp16 levels use the first half of each.
        using Texel = std::remove_pointer_t<decltype(Lvl::data)>;
        chain.level[l] = Lvl{reinterpret_cast<Texel*>(ws.mips[l]), post::mipSize(width, l), post::mipSize(height, l)};
    }
    return chain;
}

}  // namespace

void mipChainBloomBuffers(const float4* hdr, float4* bloom, float4* hdrOut, int width, int height,
                          const post::BloomParams& p, BloomWorkspace& ws, cudaStream_t stream) {
    const Chain<FloatLevel> chain = chainOf<FloatLevel>(ws, width, height, p);
    const BufferImage in{const_cast<float4*>(hdr), width}, b{bloom, width};
    const MipChainTuning& t = ws.mipChain;
    if (hdrOut)
        mipChain<FloatLevel, true>(chain, in, in, b, BufferImage{hdrOut, width}, width, height, p, t, ws.recorder, stream);
    else
        mipChain<FloatLevel, false>(chain, in, in, b, b, width, height, p, t, ws.recorder, stream);
}

void mipChainBloomSurfaces(cudaSurfaceObject_t hdr, cudaSurfaceObject_t bloom, bool composite, int width, int height,
                           const post::BloomParams& p, BloomWorkspace& ws, cudaStream_t stream) {
    const Chain<HalfLevel> chain = chainOf<HalfLevel>(ws, width, height, p);
    const StreamedHalf4Surface downIn{hdr};
    const Half4Surface in{hdr}, b{bloom};
    const MipChainTuning& t = ws.mipChain;
    if (composite)
        mipChain<HalfLevel, true>(chain, downIn, in, b, in, width, height, p, t, ws.recorder, stream);
    else
        mipChain<HalfLevel, false>(chain, downIn, in, b, b, width, height, p, t, ws.recorder, stream);
}

}  // namespace lp::cuda
