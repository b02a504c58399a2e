#pragma once
// Per-texel math of bloom and toon shared by the CPU reference and the CUDA kernels (the GLSL
// twins are in shaders/common/post.glsl and follow the same operation order).
#include <cmath>

#include "engine/post/post_params.hpp"

#ifdef __CUDACC__
#define LP_POST_HD __host__ __device__
#else
#define LP_POST_HD
#endif

namespace lp::post {

struct Rgb {
    float r = 0.0f, g = 0.0f, b = 0.0f;
};

// NaN and negatives -> 0, +Inf and overflow -> the largest half (as sanitizeHdr in GLSL).
LP_POST_HD inline float sanitize(float v) {
    if (!(v > 0.0f)) return 0.0f;  // NaN compares false
    return v < kHalfMax ? v : kHalfMax;
}
LP_POST_HD inline Rgb sanitize(Rgb c) { return {sanitize(c.r), sanitize(c.g), sanitize(c.b)}; }

LP_POST_HD inline float luminance(Rgb c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

// Bright pass with a quadratic soft knee (as in Unity's and Filament's bloom): the weight of a texel
// of brightness b = max(r, g, b) is max(q(b), b - T) / b with q the knee
// q(b) = clamp(b - T + K, 0, 2K)^2 / (4K + 1e-5). Sanitised first, clamped to `highlight` last.
LP_POST_HD inline Rgb brightPass(Rgb c, float threshold, float knee, float highlight) {
    c = sanitize(c);
    float br = fmaxf(c.r, fmaxf(c.g, c.b));
    float soft = fminf(fmaxf(br - threshold + knee, 0.0f), 2.0f * knee);
    soft = soft * soft / (4.0f * knee + 1e-5f);
    float contrib = fmaxf(soft, br - threshold) / fmaxf(br, 1e-5f);
    return {fminf(c.r * contrib, highlight), fminf(c.g * contrib, highlight), fminf(c.b * contrib, highlight)};
}

// Karis average weight of a 2x2 box: 1 / (1 + luma), so one very bright texel cannot dominate.
LP_POST_HD inline float karisWeight(Rgb box) { return 1.0f / (1.0f + luminance(box)); }

// The toon ramp. t = L / (1 + L) of the linear luminance L (Rec. 709) of the sanitised colour is
// quantised to the centre of its band, tq = (min(floor(t * levels), levels - 1) + 0.5) / levels,
// mapped back through the inverse, Lq = tq / (1 - tq), and the colour is scaled by Lq / L (hue kept).
LP_POST_HD inline float toonScale(float lum, int levels) {
    if (!(lum > 0.0f)) return 0.0f;
    float t = lum / (1.0f + lum);
    float band = fminf(floorf(t * float(levels)), float(levels - 1));
    float tq = (band + 0.5f) / float(levels);
    return tq / (1.0f - tq) / lum;
}

// Sobel gradient magnitude / 8 of a 3x3 neighbourhood v[row][col] (row 0 = y - 1): a unit step
// between two columns reads 0.5 on the pixels either side of it.
LP_POST_HD inline float sobelSquared(const float v[3][3]) {
    float gx = (v[0][2] + 2.0f * v[1][2] + v[2][2]) - (v[0][0] + 2.0f * v[1][0] + v[2][0]);
    float gy = (v[2][0] + 2.0f * v[2][1] + v[2][2]) - (v[0][0] + 2.0f * v[0][1] + v[0][2]);
    return (gx * gx + gy * gy) * (1.0f / 64.0f);
}

// The toon's depth edge of a 3x3 neighbourhood of eye depths z[row][col] (> 0): the largest second
// difference of inverse depth w = 1 / z through the centre (across, down, both diagonals) over the
// largest w (the nearest depth). A plane's w is affine in screen space, so any plane, at any angle,
// reads 0; a step from depth z1 to z2 > z1 reads (z2 - z1) / z2 on the pixels either side of it,
// whatever its distance (the gap over the farther depth, below 1; against the sky almost 1).
// Directions through a tap past the image's border are left out (clamped to the border, their
// difference would be a first one: a sloped plane's slope): hasX, the pixel has a neighbour on
// either side in x; hasY, in y.
LP_POST_HD inline float depthEdge(const float z[3][3], bool hasX, bool hasY) {
    float w[3][3];
    float nearest = 0.0f;
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            w[j][i] = 1.0f / fmaxf(z[j][i], 1e-6f);
            nearest = fmaxf(nearest, w[j][i]);
        }
    const float c = 2.0f * w[1][1];
    const float across = hasX ? fabsf(w[1][0] - c + w[1][2]) : 0.0f;
    const float down = hasY ? fabsf(w[0][1] - c + w[2][1]) : 0.0f;
    const float diagonal = hasX && hasY ? fabsf(w[0][0] - c + w[2][2]) : 0.0f;
    const float antidiagonal = hasX && hasY ? fabsf(w[0][2] - c + w[2][0]) : 0.0f;
    return fmaxf(fmaxf(across, down), fmaxf(diagonal, antidiagonal)) / nearest;
}

// Separable 4-tap weights (1, 5, 7, 3) / 16 of the mip chain's upsample: a 3x3 tent (Jimenez 2014)
// on the coarse level, then bilinear to the fine texel. Even fine x uses coarse x/2 - 2 .. x/2 + 1.
LP_POST_HD inline float upsampleWeight(int tap, bool odd) {
    const float even[4] = {1.0f / 16.0f, 5.0f / 16.0f, 7.0f / 16.0f, 3.0f / 16.0f};
    return odd ? even[3 - tap] : even[tap];
}

}  // namespace lp::post
