// Render-scale upsampling: the G-buffer and lighting ran at a fraction of the output size; these map
// an output pixel back onto that smaller image. Shared by the upscale pass and the shader tests.
#ifndef LP_UPSCALE_GLSL
#define LP_UPSCALE_GLSL

#include "common/tonemap.glsl"

// Texel centres aligned (as texture() and glBlitFramebuffer(GL_LINEAR) do): output pixel p of
// outSize covers source coordinate c = (p + 0.5) * inSize / outSize - 0.5, in source texels. It is
// split here into its texel i0 and fraction f in integers: 2 * outSize * c = (2p + 1) * inSize -
// outSize exactly, so a pixel centre that lands on a texel centre (the identity, every integer
// ratio) gets f = 0 exactly on every driver (NVIDIA divides through a reciprocal: 6.0 / 6.0 need
// not be 1). c is clamped to [0, inSize - 1] (clamp to edge).
void upscaleSourceTexel(ivec2 p, ivec2 outSize, ivec2 inSize, out ivec2 i0, out vec2 f) {
    ivec2 den = 2 * outSize;
    ivec2 num = max((2 * p + 1) * inSize - outSize, ivec2(0));
    i0 = num / den;  // num >= 0: truncation is floor
    f = vec2(num - i0 * den) / vec2(den);
    bvec2 beyond = greaterThanEqual(i0, inSize - 1);
    i0 = mix(i0, inSize - 1, beyond);
    f = mix(f, vec2(0.0), beyond);
}

// Bilinear, computed by hand so it is exact in fp32 on every driver (no 8-bit filter weights) and
// independent of the texture's filter state. Each tap is sanitised first (NaN -> 0, Inf -> 65504):
// an Inf texel would otherwise turn an aligned neighbour into Inf * 0 = NaN.
vec4 upscaleBilinear(sampler2D src, ivec2 p, ivec2 outSize) {
    ivec2 inSize = textureSize(src, 0);
    ivec2 i0;
    vec2 f;
    upscaleSourceTexel(p, outSize, inSize, i0, f);
    ivec2 i1 = min(i0 + 1, inSize - 1);
    vec4 sum = vec4(0.0);
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        vec4 t = texelFetch(src, ivec2(o.x == 1 ? i1.x : i0.x, o.y == 1 ? i1.y : i0.y), 0);
        sum += w * vec4(sanitizeHdr(t.rgb), t.a);
    }
    return sum;
}

// Nearest texel, floor((p + 0.5) * inSize / outSize) in integers: the debug views show the
// G-buffer's own texels, not blends of them.
vec4 upscaleNearest(sampler2D src, ivec2 p, ivec2 outSize) {
    ivec2 inSize = textureSize(src, 0);
    ivec2 i = min((2 * p + 1) * inSize / (2 * outSize), inSize - 1);
    return texelFetch(src, i, 0);
}

#endif
