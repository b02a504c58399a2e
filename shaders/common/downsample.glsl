// --aa ssaa's resolve: the supersampled HDR image -> the output size. Shared by the downsample pass
// and the shader tests.
#ifndef LP_DOWNSAMPLE_GLSL
#define LP_DOWNSAMPLE_GLSL

#include "common/tonemap.glsl"

// Box filter over output pixel p's exact footprint in a source `scale` times larger in each axis:
// the mean of its scale x scale texels (clamped at the edges, for a source that is not exactly
// scale x the output). Each tap is sanitised first (NaN -> 0, Inf -> 65504), so one bad sample
// cannot make the pixel NaN.
vec4 downsampleBox(sampler2D src, ivec2 p, int scale) {
    ivec2 inSize = textureSize(src, 0);
    ivec2 origin = p * scale;
    vec4 sum = vec4(0.0);
    for (int j = 0; j < scale; ++j)
        for (int i = 0; i < scale; ++i) {
            vec4 t = texelFetch(src, min(origin + ivec2(i, j), inSize - 1), 0);
            sum += vec4(sanitizeHdr(t.rgb), t.a);
        }
    return sum / float(scale * scale);
}

#endif
