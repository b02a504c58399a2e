#pragma once
// What the CUDA post tests share: a random HDR image, the relative error they bound, and the skip
// where no CUDA device exists (CI has the toolkit but no GPU).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "cuda/post_cuda.hpp"
#include "engine/post/post_reference.hpp"

namespace lp::posttest {

// A w x h image of fp16-exact values: most in [0, 2), one in ten a highlight in [2, 40); alpha 1.
inline ImageF randomHdr(int w, int h, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> base(0.0f, 2.0f), bright(2.0f, 40.0f), pick(0.0f, 1.0f);
    ImageF img;
    img.width = w;
    img.height = h;
    img.rgba.assign(size_t(w) * size_t(h) * 4, 1.0f);
    for (size_t i = 0; i < img.rgba.size(); ++i)
        if (i % 4 != 3) img.rgba[i] = post::roundToHalf(pick(rng) < 0.1f ? bright(rng) : base(rng));
    return img;
}

// |d| / (|ref| + floor) over the colour channels.
inline double maxRelError(const ImageF& got, const ImageF& ref, double floor = 1e-3) {
    double worst = 0.0;
    for (size_t i = 0; i < got.rgba.size(); ++i)
        if (i % 4 != 3)
            worst = std::max(worst, std::fabs(double(got.rgba[i]) - double(ref.rgba[i])) / (std::fabs(double(ref.rgba[i])) + floor));
    return worst;
}

inline bool skipWithoutDevice() {
    const std::string problem = cuda::postDeviceProblem();
    if (problem.empty()) return false;
    std::printf("  no CUDA device here (%s): CUDA tests skipped\n", problem.c_str());
    return true;
}

}  // namespace lp::posttest
