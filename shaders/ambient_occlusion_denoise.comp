#version 450
// The raw GTAO (ambient_occlusion.comp) filtered to the full G-buffer size: a 4x4 box of raw texels
// (one period of the slice-rotation pattern, so it averages the 16 rotations) weighted by how far
// each texel's surface point lies from this pixel's tangent plane, relative to its depth: so
// occlusion does not bleed across depth edges, while on a slanted plane every tap keeps its full
// weight (a plain depth difference would drop the far taps there and leave the rotations unevenly
// averaged). At half size the same taps upsample. Output: AO^uIntensity in the R8 target; sky 1.
#define LP_GBUFFER_READ
#include "common/gbuffer_layout.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 13) uniform sampler2D uRaw;  // (ao, eye depth); depth 0 on the sky
layout(r8, binding = 0) uniform writeonly image2D uAo;

uniform int uScale;        // 1: full size, 2: half size
uniform float uIntensity;  // exponent on the filtered AO

// Distance from the tangent plane, relative to the depth, at which a texel's weight is exp(-1).
const float kPlaneSigma = 0.02;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uAo);
    if (p.x >= size.x || p.y >= size.y) return;
    if (gbufferIsBackground(p)) {
        imageStore(uAo, p, vec4(1.0));
        return;
    }
    vec3 P = gbufferPosition(p);
    vec3 N = gbufferNormal(p);
    float depth = max(-P.z, 1e-6);
    ivec2 rawSize = textureSize(uRaw, 0);
    vec2 fullSize = vec2(textureSize(uGbufferDepth, 0));
    // Raw texel q was computed at pixel q * uScale: the 4x4 taps centred as near p as the grid allows.
    ivec2 base = uScale == 1 ? p - 2 : (p + 1) / 2 - 2;
    float sum = 0.0, weights = 0.0;
    float nearestAo = 1.0, nearestDiff = 1e30;
    for (int j = 0; j < 4; ++j) {
        for (int i = 0; i < 4; ++i) {
            ivec2 q = clamp(base + ivec2(i, j), ivec2(0), rawSize - 1);
            vec2 raw = texelFetch(uRaw, q, 0).rg;
            // The texel's surface point, rebuilt from its eye depth at the pixel it was computed at.
            vec2 uv = (vec2(q * uScale) + 0.5) / fullSize;
            vec3 Q = eyePositionFromZ(uv, -raw.y, uGbufferCamera.z, uGbufferCamera.w);
            float rel = raw.y > 0.0 ? abs(dot(Q - P, N)) / depth : 1e30;  // depth 0: sky
            float w = exp(-(rel * rel) / (kPlaneSigma * kPlaneSigma));
            sum += w * raw.x;
            weights += w;
            if (rel < nearestDiff) {
                nearestDiff = rel;
                nearestAo = raw.x;
            }
        }
    }
    // No tap on this surface (a thin sliver at half size): the closest in depth.
    float ao = weights > 1e-4 ? sum / weights : nearestAo;
    ao = pow(clamp(ao, 0.0, 1.0), uIntensity);
    imageStore(uAo, p, vec4(ao, 0.0, 0.0, 0.0));
}
