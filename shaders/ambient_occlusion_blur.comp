#version 450
// ao_blur: the raw GTAO (ambient_occlusion.comp) averaged along x over one period of its 8x8 pattern,
// at raw size: the taps q + (k, 0), |k| <= 4, weighted by aoPeriodWeight and by how near each tap's
// surface point lies to q's tangent plane (aoPlaneWeight). ao_denoise then does the same along y, so
// together they average the 64 slice rotations and step offsets of the pattern without letting
// occlusion bleed across depth edges. Sky texels: 1.
#define LP_GBUFFER_READ
#include "common/gbuffer_layout.glsl"
#include "common/ambient_occlusion.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 12) uniform sampler2D uAoDepth;  // eye depth per raw texel, 0 on the sky
layout(binding = 13) uniform sampler2D uRaw;      // GTAO per raw texel
layout(r16f, binding = 0) uniform writeonly image2D uBlurred;

uniform int uScale;  // 1: full size, 2: half size

void main() {
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uBlurred);
    if (q.x >= size.x || q.y >= size.y) return;
    float depth = texelFetch(uAoDepth, q, 0).r;
    if (!(depth > 0.0)) {
        imageStore(uBlurred, q, vec4(1.0));
        return;
    }
    ivec2 full = textureSize(uGbufferDepth, 0);
    vec3 P = aoTexelPosition(q, depth, uScale, vec2(full), uGbufferCamera);
    vec3 N = normalize(gbufferNormal(min(q * uScale, full - 1)));
    float sum = 0.0, weights = 0.0;
    for (int k = -LP_AO_PATTERN_PERIOD / 2; k <= LP_AO_PATTERN_PERIOD / 2; ++k) {
        ivec2 t = ivec2(q.x + k, q.y);
        if (t.x < 0 || t.x >= size.x) continue;
        float z = texelFetch(uAoDepth, t, 0).r;
        if (!(z > 0.0)) continue;  // the sky
        vec3 Q = aoTexelPosition(t, z, uScale, vec2(full), uGbufferCamera);
        float w = aoPeriodWeight(k) * aoPlaneWeight(Q, P, N, depth);
        sum += w * texelFetch(uRaw, t, 0).r;
        weights += w;
    }
    // The centre tap weighs 1, so weights >= 1.
    imageStore(uBlurred, q, vec4(sum / weights, 0.0, 0.0, 0.0));
}
