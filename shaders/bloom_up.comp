#version 450
// Mip-chain bloom upsample: a 3x3 tent (Jimenez 2014) on the coarse level, bilinearly placed
// on the fine texel = separable taps (1, 5, 7, 3) / 16, clamp-to-edge. Either adds into the fine
// level (up_i = down_i + U(up_i+1)) or writes the full-resolution bloom buffer scaled by uScale.
#include "common/tonemap.glsl"
#include "common/post.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0) uniform sampler2D uCoarse;
layout(rgba16f, binding = 0) uniform image2D uFine;
uniform int uCoarseLevel;
uniform bool uAddFine;
uniform float uScale;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uFine);
    if (p.x >= size.x || p.y >= size.y) return;
    ivec2 hi = textureSize(uCoarse, uCoarseLevel) - 1;
    bvec2 odd = bvec2((p.x & 1) == 1, (p.y & 1) == 1);
    ivec2 base = (p >> 1) - ivec2(odd.x ? 1 : 2, odd.y ? 1 : 2);
    vec3 sum = vec3(0.0);
    for (int j = 0; j < 4; ++j) {
        vec3 row = vec3(0.0);
        for (int i = 0; i < 4; ++i)
            row += texelFetch(uCoarse, clamp(base + ivec2(i, j), ivec2(0), hi), uCoarseLevel).rgb * upsampleWeight(i, odd.x);
        sum += row * upsampleWeight(j, odd.y);
    }
    vec3 result = uAddFine ? imageLoad(uFine, p).rgb + sum : sum * uScale;
    imageStore(uFine, p, vec4(result, 1.0));
}
