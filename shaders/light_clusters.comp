#version 450
// Builds the whole froxel grid's light lists (every slice of every tile, whatever the depth buffer
// holds): the lists the forward passes read, transparent surfaces included, which are in no depth
// buffer. One work group per screen tile, in two steps per batch of 256 of its supertile's lights
// (light_cluster_supertiles.comp; every light where that list overflowed): each invocation
// tests one light against the tile's whole column (the tile's frustum from the near to the far
// plane, as the tiled method culls) and marks a survivor with a bit in shared memory, then
// invocation k < slices walks the survivors' bits (index order, no scan) and tests each against
// slice k's eye-space box (clusterLightTouchesBox), appending it to its froxel's list. Lights are
// thus tested once per tile and only the tile's survivors once per slice. Lists hold the
// lowest-indexed lights first; counts past the cap are kept (uncapped) for the heat map, and clusters
// that overflow are counted in uOverflow. (The deferred clustered method builds tighter lists from
// the G-buffer's depth in local_light_clustered.comp.)
#include "common/local_light.glsl"
#include "common/clusters.glsl"
#include "common/supertiles.glsl"

const int LP_BATCH = 256;  // lights per batch: one per invocation (and >= kMaxClusterSlices)
layout(local_size_x = LP_BATCH) in;
layout(std430, binding = 0) readonly buffer LocalLights { LpLocalLight uLights[]; };
layout(std430, binding = 1) writeonly buffer ClusterCounts { uint uCounts[]; };
layout(std430, binding = 2) writeonly buffer ClusterLights { uint uLists[]; };
layout(std430, binding = 3) buffer ClusterOverflow { uint uOverflow; };
uniform int uLightCount;
uniform mat4 uProjection;
uniform ivec2 uImageSize;

shared uint sSurvivors[LP_BATCH / 32];  // a bit per light of the batch touching the tile's column
shared vec4 sBound[LP_BATCH];
shared vec4 sApex[LP_BATCH];  // xyz position, w range
shared vec4 sAxis[LP_BATCH];  // xyz spot axis, w cos(outer); < -1 a point light
shared uint sLight[LP_BATCH];  // the light's index

void main() {
    ivec2 tile = ivec2(gl_WorkGroupID.xy);
    uint lid = gl_LocalInvocationIndex;
    int slice = int(lid);
    bool ownsSlice = slice < uClusterGrid.z;
    vec2 ndcLo, ndcHi;
    clusterTileNdc(tile, uImageSize, ndcLo, ndcHi);
    // This invocation's froxel box.
    vec3 lo = vec3(0.0), hi = vec3(0.0);
    if (ownsSlice)
        clusterTileBox(ndcLo, ndcHi, clusterSliceStart(slice), clusterSliceStart(slice + 1), uProjection, lo, hi);
    int cluster = clusterIndex(ivec3(tile, slice));
    uint base = uint(cluster) * LP_MAX_LIGHTS_PER_CLUSTER;
    uint count = 0u;
    const SupertileCandidates candidates = supertileCandidates(tile, uClusterGrid.x, uLightCount);
    for (int first = 0; first < candidates.count; first += LP_BATCH) {
        if (lid < uint(LP_BATCH / 32)) sSurvivors[lid] = 0u;
        barrier();
        int k = first + int(lid);
        if (k < candidates.count) {
            int i = supertileCandidate(candidates, k);
            vec4 b = uLights[i].bound;
            if (sphereTouchesTileFrustum(b.xyz, b.w * (1.0 + LP_CLUSTER_MARGIN) + 1e-6, ndcLo, ndcHi, uClusterNear,
                                         uClusterFar, uProjection)) {
                sBound[lid] = b;
                sApex[lid] = uLights[i].positionRange;
                sAxis[lid] = uLights[i].directionCos;
                sLight[lid] = uint(i);
                atomicOr(sSurvivors[lid >> 5], 1u << (lid & 31u));
            }
        }
        barrier();
        if (ownsSlice)
            for (int w = 0; w < LP_BATCH / 32; ++w)
                for (uint bits = sSurvivors[w]; bits != 0u; bits &= bits - 1u) {
                    int j = 32 * w + findLSB(bits);
                    if (clusterLightTouchesBox(sBound[j], sApex[j], sAxis[j], lo, hi)) {
                        if (count < LP_MAX_LIGHTS_PER_CLUSTER) uLists[base + count] = sLight[j];
                        ++count;
                    }
                }
        barrier();
    }
    if (!ownsSlice) return;
    uCounts[cluster] = count;
    if (count > LP_MAX_LIGHTS_PER_CLUSTER) atomicAdd(uOverflow, 1u);
}
