// Dithering before an 8-bit quantisation. Shared by the tone map, FXAA and the shader tests.
#ifndef LP_DITHER_GLSL
#define LP_DITHER_GLSL

// Integer hash (Wellons' lowbias32): the same bits on every driver, no texture needed.
uint ditherHash(uint x) {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

// A uniform number in [0, 1) for pixel p and stream `salt` (24 bits of the hash).
float ditherUniform(ivec2 p, uint salt) {
    uint h = ditherHash(uint(p.x) + ditherHash(uint(p.y) + ditherHash(salt)));
    return float(h >> 8) * (1.0 / 16777216.0);
}

// Triangular-PDF noise in (-1, 1) LSB: the sum of two uniforms minus 1. Added before rounding it
// makes the quantisation error's mean and variance independent of the signal (no bands, no bias).
float ditherTpdf(ivec2 p) { return ditherUniform(p, 0u) + ditherUniform(p, 1u) - 1.0; }

// c in [0, 1] -> k / 255 with k a whole number: rounded after TPDF noise of +-1 LSB (the same
// noise for the three channels, so it is grey, not coloured), or rounded plainly when !dither.
// 0 and 1 stay exact (black stays black, full white stays white); within 1 LSB of them the clamp
// biases the mean slightly.
vec3 quantize8(vec3 c, ivec2 p, bool dither) {
    c = clamp(c, 0.0, 1.0);
    float n = dither ? ditherTpdf(p) : 0.0;
    vec3 k = clamp(floor(c * 255.0 + 0.5 + n), 0.0, 255.0);
    k = mix(k, vec3(0.0), lessThanEqual(c, vec3(0.0)));
    k = mix(k, vec3(255.0), greaterThanEqual(c, vec3(1.0)));
    return k / 255.0;
}

#endif
