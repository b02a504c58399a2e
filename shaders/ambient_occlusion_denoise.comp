#version 450
// ao_denoise: ao_blur's AO averaged along y over one period of the GTAO pattern and brought to the
// full G-buffer size, into the R8 target: for pixel p, the raw rows within 4 of the raw texels around
// it (aoPeriodWeight about each of the two at half size, whose mean again weighs every phase 1), in
// the one column of p's raw texel or the two columns p lies between at half size (1/2 each), every tap
// also weighted by how near its surface point lies to p's tangent plane (aoPlaneWeight). Output:
// AO^uIntensity; sky 1.
#define LP_GBUFFER_READ
#include "common/gbuffer_layout.glsl"
#include "common/ambient_occlusion.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 12) uniform sampler2D uAoDepth;  // eye depth per raw texel, 0 on the sky
layout(binding = 13) uniform sampler2D uBlurred;  // ao_blur's AO per raw texel
layout(r8, binding = 0) uniform writeonly image2D uAo;

uniform int uScale;        // 1: full size, 2: half size
uniform float uIntensity;  // exponent on the filtered AO

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uAo);
    if (p.x >= size.x || p.y >= size.y) return;
    if (gbufferIsBackground(p)) {
        imageStore(uAo, p, vec4(1.0));
        return;
    }
    vec3 P = gbufferPosition(p);
    vec3 N = normalize(gbufferNormal(p));
    float depth = max(-P.z, 1e-6);
    ivec2 rawSize = textureSize(uBlurred, 0);
    vec2 fullSize = vec2(textureSize(uGbufferDepth, 0));
    // Raw texel c stands for pixel c * uScale: p lies between c0 and c1 (the same texel where p is one's own).
    ivec2 c0 = min(p / uScale, rawSize - 1), c1 = min((p + uScale - 1) / uScale, rawSize - 1);
    const int reach = LP_AO_PATTERN_PERIOD / 2;
    float sum = 0.0, weights = 0.0;
    float nearestAo = 1.0, nearestDiff = 1e30;
    for (int column = 0; column < 2; ++column) {
        if (column == 1 && c1.x == c0.x) break;
        int x = column == 0 ? c0.x : c1.x;
        float columnWeight = c1.x == c0.x ? 1.0 : 0.5;
        for (int y = c0.y - reach; y <= c1.y + reach; ++y) {
            if (y < 0 || y >= rawSize.y) continue;
            ivec2 t = ivec2(x, y);
            float z = texelFetch(uAoDepth, t, 0).r;
            if (!(z > 0.0)) continue;  // the sky
            float ao = texelFetch(uBlurred, t, 0).r;
            vec3 Q = aoTexelPosition(t, z, uScale, fullSize, uGbufferCamera);
            float rowWeight = 0.5 * (aoPeriodWeight(y - c0.y) + aoPeriodWeight(y - c1.y));
            float w = columnWeight * rowWeight * aoPlaneWeight(Q, P, N, depth);
            sum += w * ao;
            weights += w;
            float diff = abs(dot(Q - P, N));
            if (diff < nearestDiff) {
                nearestDiff = diff;
                nearestAo = ao;
            }
        }
    }
    // No tap on this surface (a thin sliver at half size): the one nearest its plane.
    float ao = weights > 1e-4 ? sum / weights : nearestAo;
    ao = pow(clamp(ao, 0.0, 1.0), uIntensity);
    imageStore(uAo, p, vec4(ao, 0.0, 0.0, 0.0));
}
