#pragma once
// The resolved parameters of bloom and toon as every implementation sees them (CPU reference,
// GLSL compute, CUDA). Plain structs without dependencies, so CUDA sources can include them.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "engine/core/error.hpp"

namespace lp::post {

enum class BloomMethod { Separable, MipChain };

constexpr int kMaxKernel = 101;                // pixels; the separable blur's widest kernel
constexpr int kMaxRadius = kMaxKernel / 2;     // taps on each side of the centre
constexpr int kMaxMipLevels = 8;               // the mip chain's deepest level count
constexpr float kHalfMax = 65504.0f;           // largest finite half float (RGBA16F)

struct BloomParams {
    BloomMethod method = BloomMethod::Separable;
    int kernel = 25;            // 1..101 px: taps -kernel/2..kernel/2, sigma = kernel / 6
    float threshold = 1.0f;     // brightness (max of r, g, b) where bloom starts
    float knee = 0.5f;          // half-width of the quadratic soft knee around the threshold
    float strength = 0.1f;      // hdr += strength * bloom
    float highlight = 1000.0f;  // per-channel ceiling of what enters the blur (fireflies, +Inf)
    bool karis = true;          // mip chain: Karis average on the first downsample
    bool fragmentBlur = false;  // GLSL separable: blur in fragment passes (bloom_blur.frag), to compare
};

struct ToonParams {
    int levels = 4;             // bands of the ramp
    float depthEdge = 0.1f;     // outline where depthEdge (post_math.hpp), the relative depth step, exceeds this
    float normalEdge = 0.5f;    // outline where |Sobel(n)| / 8 exceeds this (= sin of half the crease angle)
    float farDepth = 100.0f;    // eye depth given to pixels no geometry covers
};

// Taps w[0..r] of the normalised Gaussian (w[0] + 2 * sum w[i>0] = 1, computed in double):
// r = kernel / 2, sigma = kernel / 6 (the kernel spans +-3 sigma). kernel 1 gives {1}.
// Inline (as the two below) because the CUDA library uses them too.
inline std::vector<float> gaussianWeights(int kernel) {
    if (kernel < 1 || kernel > kMaxKernel)
        throw Error("bloom kernel " + std::to_string(kernel) + ": expected 1.." + std::to_string(kMaxKernel));
    const int r = kernel / 2;
    const double sigma = double(kernel) / 6.0;
    std::vector<double> w(size_t(r) + 1);
    double sum = 0.0;
    for (int i = 0; i <= r; ++i) {
        w[size_t(i)] = std::exp(-double(i) * double(i) / (2.0 * sigma * sigma));
        sum += i == 0 ? w[0] : 2.0 * w[size_t(i)];
    }
    std::vector<float> out(w.size());
    for (size_t i = 0; i < w.size(); ++i) out[i] = float(w[i] / sum);
    return out;
}

// Size of mip level `level` (level 0 = half of the full-resolution image, at least 1 texel).
inline int mipSize(int fullSize, int level) { return std::max(1, (fullSize / 2) >> level); }

// Levels of the mip chain for a width x height image: the first level is half resolution, and
// each level doubles the reach, so ceil(log2(kernel)) levels reach about `kernel` pixels; clamped
// to what the image size allows and to kMaxMipLevels.
inline int mipLevelCount(int kernel, int width, int height) {
    int wanted = 1;
    while ((1 << wanted) < kernel) ++wanted;  // ceil(log2(kernel)), at least 1
    int possible = 1;
    while (possible < kMaxMipLevels && ((width / 2) >> possible) >= 1 && ((height / 2) >> possible) >= 1) ++possible;
    return std::max(1, std::min({wanted, possible, kMaxMipLevels}));
}

}  // namespace lp::post
