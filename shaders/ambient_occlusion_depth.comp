#version 450
// The eye depth the GTAO horizon search reads (ambient_occlusion.comp): at raw texel q, -z of the
// G-buffer's surface at pixel q * uScale, 0 on the sky. Every horizon sample is then one 4-byte read
// from a target a quarter of the G-buffer's size at half resolution, which stays in cache, instead of
// a depth and a position read across the full-size G-buffer; and a linear float depth keeps its
// precision in every G-buffer layout (a standard depth buffer loses it far away).
#define LP_GBUFFER_READ
#include "common/gbuffer_layout.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(r32f, binding = 0) uniform writeonly image2D uAoDepth;

uniform int uScale;  // 1: full size, 2: half size

void main() {
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uAoDepth);
    if (q.x >= size.x || q.y >= size.y) return;
    ivec2 p = min(q * uScale, textureSize(uGbufferDepth, 0) - 1);
    float depth = gbufferIsBackground(p) ? 0.0 : max(-gbufferEyeZ(p), 1e-6);
    imageStore(uAoDepth, q, vec4(depth, 0.0, 0.0, 0.0));
}
