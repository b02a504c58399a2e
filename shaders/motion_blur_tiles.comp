#version 450
// Motion blur, step 1 (McGuire et al. 2012 "TileMax"): one work group per K x K tile writes the
// longest half blur vector of its pixels (pixels, common/motion_blur.glsl).
#include "common/motion_blur.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D uVelocity;  // gbuffer.velocity: uv_current - uv_previous
layout(rg16f, binding = 0) uniform writeonly image2D uTiles;
uniform int uTileSize;   // K
uniform float uShutter;  // fraction of the frame interval the shutter is open

shared vec2 sBest[64];
shared float sLength[64];

void main() {
    ivec2 tile = ivec2(gl_WorkGroupID.xy);
    ivec2 size = textureSize(uVelocity, 0);
    uint me = gl_LocalInvocationIndex;
    vec2 best = vec2(0.0);
    float bestLength = 0.0;
    for (int y = int(gl_LocalInvocationID.y); y < uTileSize; y += 8)
        for (int x = int(gl_LocalInvocationID.x); x < uTileSize; x += 8) {
            ivec2 p = tile * uTileSize + ivec2(x, y);
            if (p.x >= size.x || p.y >= size.y) continue;
            vec2 v = motionBlurHalfVector(texelFetch(uVelocity, p, 0).xy, vec2(size), uShutter, float(uTileSize));
            float l = dot(v, v);
            if (l > bestLength) {
                bestLength = l;
                best = v;
            }
        }
    sBest[me] = best;
    sLength[me] = bestLength;
    barrier();
    for (uint stride = 32u; stride > 0u; stride >>= 1u) {
        if (me < stride && sLength[me + stride] > sLength[me]) {
            sLength[me] = sLength[me + stride];
            sBest[me] = sBest[me + stride];
        }
        barrier();
    }
    if (me == 0u) imageStore(uTiles, tile, vec4(sBest[0], 0.0, 0.0));
}
