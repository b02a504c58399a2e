#version 450
// Tiled method in one compute pass: each 16x16 work group finds its tile's eye-depth
// bounds from the G-buffer, bins the lights whose bounding sphere (the range sphere, a spot's cone
// sphere) touches the tile's frustum (four side planes and the depth bounds) into shared memory, 256
// lights at a time, and shades its pixels with
// that list. With LP_TILE_HEATMAP it instead paints the per-tile count over the finished image.
#include "common/local_light.glsl"
#include "common/tonemap.glsl"
#include "common/heatmap.glsl"
#include "common/supertiles.glsl"
#define LP_GBUFFER_READ
#include "common/gbuffer_layout.glsl"

layout(local_size_x = 16, local_size_y = 16) in;
const uint LP_BATCH = 256u;  // = threads per group: each thread tests one light per batch

layout(std430, binding = 0) readonly buffer LocalLights { LpLocalLight uLights[]; };
layout(rgba16f, binding = 0) uniform image2D uHdr;
uniform int uLightCount;
uniform mat4 uProjection;
uniform bool uUnbounded;     // specular outside the range: every light reaches every tile
uniform bool uLightingOnly;
uniform int uSpecularMode;
uniform float uHeatMax;      // heat map: this many lights per tile or more is red
uniform float uExposure;     // heat map: EV the tone map will apply

shared uint sMinDist, sMaxDist;  // float bits of positive eye distances (order-preserving as uint)
shared uint sTotal;
shared uint sPassed[LP_BATCH / 32u];  // a bit per light of the batch that touches the tile
shared uint sList[LP_BATCH];

void main() {
    ivec2 size = imageSize(uHdr);
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    uint lid = gl_LocalInvocationIndex;
    bool inside = p.x < size.x && p.y < size.y;
    if (lid == 0u) {
        sMinDist = floatBitsToUint(3.0e38);
        sMaxDist = 0u;
        sTotal = 0u;
    }
    barrier();
    // Flat-lit pixels are no surface to light (and widen no tile's depth bounds).
    bool surface = inside && !gbufferIsBackground(p) && (uLightingOnly || !gbufferIsFlat(p));
    vec3 P = vec3(0.0);
    if (surface) {
        P = gbufferPosition(p);
        uint bits = floatBitsToUint(max(-P.z, 0.0));
        atomicMin(sMinDist, bits);
        atomicMax(sMaxDist, bits);
    }
    barrier();
    float d0 = uintBitsToFloat(sMinDist), d1 = uintBitsToFloat(sMaxDist);
    bool anySurface = d0 <= d1;  // uniform across the group
    vec2 tileLo = vec2(gl_WorkGroupID.xy * gl_WorkGroupSize.xy) / vec2(size) * 2.0 - 1.0;
    vec2 tileHi = vec2((gl_WorkGroupID.xy + 1u) * gl_WorkGroupSize.xy) / vec2(size) * 2.0 - 1.0;

#ifndef LP_TILE_HEATMAP
    vec3 N = vec3(0.0), kd = vec3(0.0), V = vec3(0.0, 0.0, 1.0);
    vec4 spec = vec4(0.0);
    FresnelEnds fresnel = fresnelEndsOfF0(vec3(0.0));
    ClearcoatLayer coat = noClearcoat();
    if (surface) {
        N = gbufferNormal(p);
        spec = vec4(gbufferSpecular(p), gbufferShininess(p));
        fresnel = gbufferFresnel(p);
        coat = gbufferClearcoat(p);
        kd = uLightingOnly ? vec3(1.0) : gbufferDiffuse(p);
        float pl = length(P);
        V = pl > 0.0 ? -P / pl : vec3(0.0, 0.0, 1.0);
    }
    vec3 sum = vec3(0.0);
#endif
    if (anySurface) {
        uint word = lid >> 5u, bit = 1u << (lid & 31u);
        const SupertileCandidates candidates = supertileCandidates(ivec2(gl_WorkGroupID.xy), int(gl_NumWorkGroups.x), uLightCount);
        for (int base = 0; base < candidates.count; base += int(LP_BATCH)) {
            if (lid < LP_BATCH / 32u) sPassed[lid] = 0u;
            barrier();
            int cand = base + int(lid);  // this invocation's candidate
            int i = cand < candidates.count ? supertileCandidate(candidates, cand) : cand;
            bool touches = false;
            if (cand < candidates.count) {
                vec4 pr = uLights[i].bound;
                // 0.1% + 1 um margin: float rounding must never drop a light that reaches the tile.
                touches = uUnbounded || sphereTouchesTileFrustum(pr.xyz, pr.w * 1.001 + 1e-6, tileLo, tileHi, d0, d1, uProjection);
                if (touches) atomicOr(sPassed[word], bit);
            }
            barrier();
            // The list in light index order (each light's place: the touching lights before it), not
            // in the order the invocations happened to append: the sum over the list, and so the image,
            // is then the same bits on every run by construction (an atomic counter's order depends on
            // scheduling, and float sums on their order).
            uint n = 0u, at = 0u;
            for (uint w = 0u; w < LP_BATCH / 32u; ++w) {
                uint c = uint(bitCount(sPassed[w]));
                at += w < word ? c : 0u;
                n += c;
            }
            if (touches) sList[at + uint(bitCount(sPassed[word] & (bit - 1u)))] = uint(i);
            barrier();
#ifndef LP_TILE_HEATMAP
            if (surface)
                for (uint k = 0u; k < n; ++k) {
                    LpLocalLight l = uLights[sList[k]];
                    sum += lpShadeLocalLight(l, P, N, V, kd, fresnel, spec.a, uSpecularMode, coat);
                }
#endif
            if (lid == 0u) sTotal += n;
            barrier();
        }
    }
    if (!inside) return;
#ifdef LP_TILE_HEATMAP
    vec3 scene = tonemapLightpass(applyExposure(imageLoad(uHdr, p).rgb, uExposure));
    vec3 y = sTotal == 0u ? 0.5 * scene : mix(scene, heatColour(float(sTotal) / uHeatMax), 0.6);
    imageStore(uHdr, p, vec4(sanitizeHdr(heatUntonemap(y, uExposure)), 1.0));
#else
    if (surface) imageStore(uHdr, p, vec4(sanitizeHdr(imageLoad(uHdr, p).rgb + sum), 1.0));
#endif
}
