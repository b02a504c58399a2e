// Render-scale upsampling: the G-buffer and lighting ran at a fraction of the output size; these map
// an output pixel back onto that smaller image. Shared by the upscale pass and the shader tests.
#ifndef LP_UPSCALE_GLSL
#define LP_UPSCALE_GLSL

#include "common/tonemap.glsl"

// Texel centres aligned (as texture() and glBlitFramebuffer(GL_LINEAR) do): output pixel p of
// outSize covers source coordinate (p + 0.5) * inSize / outSize - 0.5, in source texels.
vec2 upscaleSourceCoord(ivec2 p, ivec2 outSize, ivec2 inSize) {
    return (vec2(p) + 0.5) * vec2(inSize) / vec2(outSize) - 0.5;
}

// Bilinear, clamped to the edge, computed by hand so it is exact in fp32 on every driver (no 8-bit
// filter weights) and independent of the texture's filter state. Each tap is sanitised first
// (NaN -> 0, Inf -> 65504): an Inf texel would otherwise turn an aligned neighbour into Inf * 0 = NaN.
vec4 upscaleBilinear(sampler2D src, ivec2 p, ivec2 outSize) {
    ivec2 inSize = textureSize(src, 0);
    vec2 c = clamp(upscaleSourceCoord(p, outSize, inSize), vec2(0.0), vec2(inSize - 1));
    ivec2 i0 = ivec2(floor(c));
    ivec2 i1 = min(i0 + 1, inSize - 1);
    vec2 f = c - vec2(i0);
    vec4 sum = vec4(0.0);
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        vec4 t = texelFetch(src, ivec2(o.x == 1 ? i1.x : i0.x, o.y == 1 ? i1.y : i0.y), 0);
        sum += w * vec4(sanitizeHdr(t.rgb), t.a);
    }
    return sum;
}

// Nearest texel: the debug views show the G-buffer's own texels, not blends of them.
vec4 upscaleNearest(sampler2D src, ivec2 p, ivec2 outSize) {
    ivec2 inSize = textureSize(src, 0);
    ivec2 i = clamp(ivec2(floor((vec2(p) + 0.5) * vec2(inSize) / vec2(outSize))), ivec2(0), inSize - 1);
    return texelFetch(src, i, 0);
}

#endif
