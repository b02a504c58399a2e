// Toon in CUDA: luminance ramp and outlines on depth steps and normal creases, per
// engine/post/post_math.hpp (the CPU reference runs the same functions), one launch over
// shared-memory tiles of the G-buffer.
#include "cuda/interop.hpp"
#include "cuda/post_kernels.cuh"

namespace lp::cuda {

namespace {

constexpr int kToonBlockX = 32, kToonBlockY = 8;  // a warp per row: coalesced surface reads

// Eye depth and normal of the block's texels plus a one-texel apron, staged once in shared memory
// (clamped coordinates, as the reference's depthAt/texel), so the 3x3 Sobel taps read shared memory
// instead of nine surface reads per texel per target.
struct ToonTile {
    float depth[kToonBlockY + 2][kToonBlockX + 2];
    float3 normal[kToonBlockY + 2][kToonBlockX + 2];
    bool covered[kToonBlockY + 2][kToonBlockX + 2];  // position.w > 0
};

template <typename In, typename Pos, typename Nrm, typename Out>
__global__ void __launch_bounds__(kToonBlockX * kToonBlockY)
    toonKernel(In hdr, Pos position, Nrm normal, Out out, int width, int height, post::ToonParams p) {
    __shared__ ToonTile tile;
    const int x0 = int(blockIdx.x) * kToonBlockX - 1, y0 = int(blockIdx.y) * kToonBlockY - 1;
    constexpr int kTileW = kToonBlockX + 2, kTileTexels = kTileW * (kToonBlockY + 2);
    for (int e = int(threadIdx.y) * kToonBlockX + int(threadIdx.x); e < kTileTexels; e += kToonBlockX * kToonBlockY) {
        const int i = e % kTileW, j = e / kTileW;
        const int sx = min(max(x0 + i, 0), width - 1), sy = min(max(y0 + j, 0), height - 1);
        const float4 q = position.load(sx, sy);
        const float4 nn = normal.load(sx, sy);
        tile.covered[j][i] = q.w > 0.0f;
        tile.depth[j][i] = q.w > 0.0f ? -q.z : p.farDepth;
        tile.normal[j][i] = make_float3(nn.x, nn.y, nn.z);
    }
    __syncthreads();
    const int tx = int(threadIdx.x), ty = int(threadIdx.y);
    const int x = x0 + 1 + tx, y = y0 + 1 + ty;
    if (x >= width || y >= height) return;
    float z[3][3], n[3][3][3];
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            z[j][i] = tile.depth[ty + j][tx + i];
            const float3 nn = tile.normal[ty + j][tx + i];
            n[0][j][i] = nn.x;
            n[1][j][i] = nn.y;
            n[2][j][i] = nn.z;
        }
    const bool edge = post::depthEdge(z, x > 0 && x < width - 1, y > 0 && y < height - 1) > p.depthEdge ||
                      post::sobelSquared(n[0]) + post::sobelSquared(n[1]) + post::sobelSquared(n[2]) >
                          p.normalEdge * p.normalEdge;
    float4 h = hdr.load(x, y);
    post::Rgb c = post::sanitize(post::Rgb{h.x, h.y, h.z});
    if (edge) {
        c = post::Rgb{};
    } else if (tile.covered[ty + 1][tx + 1]) {
        float k = post::toonScale(post::luminance(c), p.levels);
        c = post::Rgb{c.r * k, c.g * k, c.b * k};
    }
    c = post::sanitize(c);
    out.store(x, y, make_float4(c.r, c.g, c.b, 1.0f));
}

dim3 toonGrid(int width, int height) {
    return dim3(unsigned(width + kToonBlockX - 1) / kToonBlockX, unsigned(height + kToonBlockY - 1) / kToonBlockY);
}

}  // namespace

void toonBuffers(const float4* hdr, const float4* position, const float4* normal, float4* out, int width, int height,
                 const post::ToonParams& p, cudaStream_t stream) {
    toonKernel<<<toonGrid(width, height), dim3(kToonBlockX, kToonBlockY), 0, stream>>>(
        BufferImage{const_cast<float4*>(hdr), width}, BufferImage{const_cast<float4*>(position), width},
        BufferImage{const_cast<float4*>(normal), width}, BufferImage{out, width}, width, height, p);
    check(cudaGetLastError(), "toonKernel");
}

void toonSurfaces(cudaSurfaceObject_t hdr, cudaSurfaceObject_t position, cudaSurfaceObject_t normal, int width,
                  int height, const post::ToonParams& p, cudaStream_t stream) {
    // In place is safe: each thread reads and writes only its own HDR texel.
    toonKernel<<<toonGrid(width, height), dim3(kToonBlockX, kToonBlockY), 0, stream>>>(
        Half4Surface{hdr}, Float4Surface{position}, Float4Surface{normal}, Half4Surface{hdr}, width, height, p);
    check(cudaGetLastError(), "toonKernel");
}

}  // namespace lp::cuda
