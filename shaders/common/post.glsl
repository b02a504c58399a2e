// Bloom and toon math, the GLSL twin of engine/post/post_math.hpp (same operation order, so
// the CPU reference predicts these results to float rounding). Needs common/tonemap.glsl.
#ifndef LP_POST_GLSL
#define LP_POST_GLSL

// Soft-knee bright pass: weight max(q(b), b - T) / b of brightness b = max(r, g, b), with the knee
// q(b) = clamp(b - T + K, 0, 2K)^2 / (4K + 1e-5). Sanitised first (NaN -> 0, +Inf -> 65504) so a bad
// texel cannot spread, then clamped to `highlight` per channel.
vec3 bloomBright(vec3 c, float threshold, float knee, float highlight) {
    c = sanitizeHdr(c);
    float br = max(c.r, max(c.g, c.b));
    float soft = min(max(br - threshold + knee, 0.0), 2.0 * knee);
    soft = soft * soft / (4.0 * knee + 1e-5);
    float contrib = max(soft, br - threshold) / max(br, 1e-5);
    return min(c * contrib, vec3(highlight));
}

float postLuminance(vec3 c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

// Karis average weight of a 2x2 box.
float karisWeight(vec3 box) { return 1.0 / (1.0 + postLuminance(box)); }

// Toon ramp: t = L / (1 + L) quantised to its band centre and mapped back; returns Lq / L.
float toonScale(float lum, int levels) {
    if (!(lum > 0.0)) return 0.0;
    float t = lum / (1.0 + lum);
    float band = min(floor(t * float(levels)), float(levels - 1));
    float tq = (band + 0.5) / float(levels);
    return tq / (1.0 - tq) / lum;
}

// (Sobel gradient / 8)^2 of a 3x3 neighbourhood v[row * 3 + col], row 0 = y - 1.
float sobelSquared(float v[9]) {
    float gx = (v[2] + 2.0 * v[5] + v[8]) - (v[0] + 2.0 * v[3] + v[6]);
    float gy = (v[6] + 2.0 * v[7] + v[8]) - (v[0] + 2.0 * v[1] + v[2]);
    return (gx * gx + gy * gy) * (1.0 / 64.0);
}

// The toon's depth edge of a 3x3 neighbourhood of eye depths z[row * 3 + col] (> 0), as
// engine/post/post_math.hpp's depthEdge: the largest second difference of 1 / z through the centre
// over the largest 1 / z, directions through a tap past the image's border left out (has.x: a
// neighbour on either side in x; has.y: in y). A plane reads 0 at any angle; a step from z1 to
// z2 > z1 reads (z2 - z1) / z2.
float depthEdge(float z[9], bvec2 has) {
    float w[9];
    float nearest = 0.0;
    for (int k = 0; k < 9; ++k) {
        w[k] = 1.0 / max(z[k], 1e-6);
        nearest = max(nearest, w[k]);
    }
    float c = 2.0 * w[4];
    float across = has.x ? abs(w[3] - c + w[5]) : 0.0;
    float down = has.y ? abs(w[1] - c + w[7]) : 0.0;
    float diagonal = all(has) ? abs(w[0] - c + w[8]) : 0.0;
    float antidiagonal = all(has) ? abs(w[2] - c + w[6]) : 0.0;
    return max(max(across, down), max(diagonal, antidiagonal)) / nearest;
}

// Mip-chain upsample taps (1, 5, 7, 3) / 16; reversed for odd fine texels.
float upsampleWeight(int tap, bool odd) {
    const float w[4] = float[4](1.0 / 16.0, 5.0 / 16.0, 7.0 / 16.0, 3.0 / 16.0);
    return odd ? w[3 - tap] : w[tap];
}

#endif
