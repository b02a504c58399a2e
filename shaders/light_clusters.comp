#version 450
// Builds the froxel grid's light lists, one work group per screen tile, in two steps per batch of
// 64 lights: each invocation tests one light against the tile's whole column (the tile's frustum
// from the near to the far plane, as the tiled method culls), the survivors are compacted in index
// order in shared memory, then invocation k < slices tests each survivor against slice k's
// eye-space box (bounding sphere vs box; a spot's cone vs the box's sphere) and appends it to its
// froxel's list. Lights are thus tested once per tile and only the tile's survivors once per slice
// (testing every light against every froxel cost 8x the tiled method's culling on the H100). Lists
// hold the lowest-indexed lights first; counts past the cap are kept (uncapped) for the heat map,
// and clusters that overflow are counted in uOverflow.
#include "common/local_light.glsl"
#include "common/clusters.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer LocalLights { LpLocalLight uLights[]; };
layout(std430, binding = 1) writeonly buffer ClusterCounts { uint uCounts[]; };
layout(std430, binding = 2) writeonly buffer ClusterLights { uint uLists[]; };
layout(std430, binding = 3) buffer ClusterOverflow { uint uOverflow; };
uniform int uLightCount;
uniform mat4 uProjection;
uniform ivec2 uImageSize;

shared uint sScan[64];   // inclusive prefix sum of the batch's survivors
shared uint sSurvivor[64];  // the batch's surviving light indices, in index order
shared vec4 sBound[64];
shared vec4 sApex[64];  // xyz position, w range
shared vec4 sAxis[64];  // xyz spot axis, w cos(outer); < -1 a point light

const float LP_MARGIN = 1e-3;  // 0.1% (+ 1 um): float rounding must never drop a light that reaches a froxel

bool touchesBox(int j, vec3 lo, vec3 hi) {
    vec4 b = sBound[j];
    float r = b.w * (1.0 + LP_MARGIN) + 1e-6;
    vec3 off = b.xyz - clamp(b.xyz, lo, hi);
    if (dot(off, off) > r * r) return false;
    vec4 axis = sAxis[j];
    if (axis.w < -1.0) return true;
    vec3 centre = 0.5 * (lo + hi);
    float radius = 0.5 * length(hi - lo) * (1.0 + LP_MARGIN) + 1e-6;
    vec3 v = centre - sApex[j].xyz;
    float along = dot(v, axis.xyz);
    float sinOuter = sqrt(max(1.0 - axis.w * axis.w, 0.0));
    float toSurface = axis.w * sqrt(max(dot(v, v) - along * along, 0.0)) - along * sinOuter;
    float range = sApex[j].w * (1.0 + LP_MARGIN);
    return !(toSurface > radius || along > radius + range || along < -radius);
}

void main() {
    ivec2 tile = ivec2(gl_WorkGroupID.xy);
    uint lid = gl_LocalInvocationIndex;
    int slice = int(lid);
    bool ownsSlice = slice < uClusterGrid.z;
    // The tile's NDC rectangle (the last tile stops at the image's edge).
    vec2 ndcLo = vec2(tile * uClusterTileSize) / vec2(uImageSize) * 2.0 - 1.0;
    vec2 ndcHi = vec2(min((tile + 1) * uClusterTileSize, uImageSize)) / vec2(uImageSize) * 2.0 - 1.0;
    // This invocation's froxel box: its corners on the rays through the tile's corners at both depths.
    vec3 lo = vec3(3.0e38), hi = vec3(-3.0e38);
    for (int e = 0; e < 2; ++e) {
        float d = clusterSliceStart(slice + e);
        for (int q = 0; q < 4; ++q) {
            vec2 ndc = vec2((q & 1) == 0 ? ndcLo.x : ndcHi.x, (q & 2) == 0 ? ndcLo.y : ndcHi.y);
            vec3 p = vec3((ndc.x + uProjection[2][0]) * d / uProjection[0][0],
                          (ndc.y + uProjection[2][1]) * d / uProjection[1][1], -d);
            lo = min(lo, p);
            hi = max(hi, p);
        }
    }
    int cluster = clusterIndex(ivec3(tile, slice));
    uint base = uint(cluster) * LP_MAX_LIGHTS_PER_CLUSTER;
    uint count = 0u;
    for (int first = 0; first < uLightCount; first += 64) {
        int i = first + int(lid);
        bool survives = false;
        if (i < uLightCount) {
            vec4 b = uLights[i].bound;
            survives = sphereTouchesTileFrustum(b.xyz, b.w * (1.0 + LP_MARGIN) + 1e-6, ndcLo, ndcHi, uClusterNear,
                                                uClusterFar, uProjection);
        }
        sScan[lid] = survives ? 1u : 0u;
        barrier();
        for (uint step = 1u; step < 64u; step <<= 1) {  // Hillis-Steele scan: keeps the index order
            uint add = lid >= step ? sScan[lid - step] : 0u;
            barrier();
            sScan[lid] += add;
            barrier();
        }
        if (survives) {
            uint slot = sScan[lid] - 1u;
            sSurvivor[slot] = uint(i);
            sBound[slot] = uLights[i].bound;
            sApex[slot] = uLights[i].positionRange;
            sAxis[slot] = uLights[i].directionCos;
        }
        barrier();
        int n = int(sScan[63]);
        if (ownsSlice)
            for (int j = 0; j < n; ++j)
                if (touchesBox(j, lo, hi)) {
                    if (count < LP_MAX_LIGHTS_PER_CLUSTER) uLists[base + count] = sSurvivor[j];
                    ++count;
                }
        barrier();
    }
    if (!ownsSlice) return;
    uCounts[cluster] = count;
    if (count > LP_MAX_LIGHTS_PER_CLUSTER) atomicAdd(uOverflow, 1u);
}
