// Toon in CUDA: luminance ramp and Sobel outlines on depth and normals, per
// engine/post/post_math.hpp (the CPU reference runs the same functions).
#include "cuda/interop.hpp"
#include "cuda/post_kernels.cuh"

namespace lp::cuda {

namespace {

template <typename In, typename Pos, typename Nrm, typename Out>
__global__ void toonKernel(In hdr, Pos position, Nrm normal, Out out, int width, int height, post::ToonParams p) {
    int x = int(blockIdx.x * blockDim.x + threadIdx.x), y = int(blockIdx.y * blockDim.y + threadIdx.y);
    if (x >= width || y >= height) return;
    float z[3][3], n[3][3][3];
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            int sx = min(max(x + i - 1, 0), width - 1), sy = min(max(y + j - 1, 0), height - 1);
            float4 q = position.load(sx, sy);
            float4 nn = normal.load(sx, sy);
            z[j][i] = q.w > 0.0f ? -q.z : p.farDepth;
            n[0][j][i] = nn.x;
            n[1][j][i] = nn.y;
            n[2][j][i] = nn.z;
        }
    const float zc = fmaxf(z[1][1], 1e-6f);
    const bool edge = post::sobelSquared(z) / (zc * zc) > p.depthEdge * p.depthEdge ||
                      post::sobelSquared(n[0]) + post::sobelSquared(n[1]) + post::sobelSquared(n[2]) >
                          p.normalEdge * p.normalEdge;
    float4 h = hdr.load(x, y);
    post::Rgb c = post::sanitize(post::Rgb{h.x, h.y, h.z});
    if (edge) {
        c = post::Rgb{};
    } else if (position.load(x, y).w > 0.0f) {
        float k = post::toonScale(post::luminance(c), p.levels);
        c = post::Rgb{c.r * k, c.g * k, c.b * k};
    }
    c = post::sanitize(c);
    out.store(x, y, make_float4(c.r, c.g, c.b, 1.0f));
}

}  // namespace

void toonBuffers(const float4* hdr, const float4* position, const float4* normal, float4* out, int width, int height,
                 const post::ToonParams& p, cudaStream_t stream) {
    toonKernel<<<gridFor(width, height), dim3(kBlock, kBlock), 0, stream>>>(
        BufferImage{const_cast<float4*>(hdr), width}, BufferImage{const_cast<float4*>(position), width},
        BufferImage{const_cast<float4*>(normal), width}, BufferImage{out, width}, width, height, p);
    check(cudaGetLastError(), "toonKernel");
}

void toonSurfaces(cudaSurfaceObject_t hdr, cudaSurfaceObject_t position, cudaSurfaceObject_t normal, int width,
                  int height, const post::ToonParams& p, cudaStream_t stream) {
    // In place is safe: each thread reads and writes only its own HDR texel.
    toonKernel<<<gridFor(width, height), dim3(kBlock, kBlock), 0, stream>>>(
        Half4Surface{hdr}, Float4Surface{position}, Float4Surface{normal}, Half4Surface{hdr}, width, height, p);
    check(cudaGetLastError(), "toonKernel");
}

}  // namespace lp::cuda
