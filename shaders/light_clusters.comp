#version 450
// Builds the froxel grid's light lists: one invocation per cluster, 64 clusters a work group; the
// group loads 64 lights at a time into shared memory and each invocation tests its froxel's eye-space
// box against them (bounding sphere vs box; a spot's cone vs the box's sphere), in index order, so
// each list holds the lowest-indexed lights first. Counts past the cap are kept (uncapped) for the
// heat map, and clusters that overflow are counted in uOverflow.
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

shared vec4 sBound[64];
shared vec4 sApex[64];  // xyz position, w range
shared vec4 sAxis[64];  // xyz spot axis, w cos(outer); < -1 a point light

const float LP_MARGIN = 1e-3;  // 0.1% (+ 1 um): float rounding must never drop a light that reaches a froxel

bool touches(int j, vec3 lo, vec3 hi) {
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
    int cluster = int(gl_GlobalInvocationID.x);
    int total = uClusterGrid.x * uClusterGrid.y * uClusterGrid.z;
    bool inGrid = cluster < total;
    ivec3 c = ivec3(cluster % uClusterGrid.x, (cluster / uClusterGrid.x) % uClusterGrid.y,
                    cluster / (uClusterGrid.x * uClusterGrid.y));
    // The froxel's eye-space box: its corners on the rays through the tile's corners at both depths.
    vec2 ndcLo = vec2(c.xy * uClusterTileSize) / vec2(uImageSize) * 2.0 - 1.0;
    vec2 ndcHi = vec2(min((c.xy + 1) * uClusterTileSize, uImageSize)) / vec2(uImageSize) * 2.0 - 1.0;
    vec3 lo = vec3(3.0e38), hi = vec3(-3.0e38);
    for (int e = 0; e < 2; ++e) {
        float d = clusterSliceStart(c.z + e);
        for (int q = 0; q < 4; ++q) {
            vec2 ndc = vec2((q & 1) == 0 ? ndcLo.x : ndcHi.x, (q & 2) == 0 ? ndcLo.y : ndcHi.y);
            vec3 p = vec3((ndc.x + uProjection[2][0]) * d / uProjection[0][0],
                          (ndc.y + uProjection[2][1]) * d / uProjection[1][1], -d);
            lo = min(lo, p);
            hi = max(hi, p);
        }
    }
    uint count = 0u;
    uint base = uint(cluster) * LP_MAX_LIGHTS_PER_CLUSTER;
    for (int first = 0; first < uLightCount; first += 64) {
        int i = first + int(gl_LocalInvocationIndex);
        if (i < uLightCount) {
            sBound[gl_LocalInvocationIndex] = uLights[i].bound;
            sApex[gl_LocalInvocationIndex] = uLights[i].positionRange;
            sAxis[gl_LocalInvocationIndex] = uLights[i].directionCos;
        }
        barrier();
        int n = min(64, uLightCount - first);
        if (inGrid)
            for (int j = 0; j < n; ++j)
                if (touches(j, lo, hi)) {
                    if (count < LP_MAX_LIGHTS_PER_CLUSTER) uLists[base + count] = uint(first + j);
                    ++count;
                }
        barrier();
    }
    if (!inGrid) return;
    uCounts[cluster] = count;
    if (count > LP_MAX_LIGHTS_PER_CLUSTER) atomicAdd(uOverflow, 1u);
}
