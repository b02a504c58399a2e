#version 450
// Builds the whole froxel grid's light lists (every slice of every tile, whatever the depth buffer
// holds): the lists the forward passes read, transparent surfaces included, which are in no depth
// buffer. One work group per screen tile, in two steps per batch of 64 lights: each invocation tests
// one light against the tile's whole column (the tile's frustum from the near to the far plane, as
// the tiled method culls), the survivors are compacted in index order in shared memory, then
// invocation k < slices tests each survivor against slice k's eye-space box
// (clusterLightTouchesBox) and appends it to its froxel's list. Lights are thus tested once per tile
// and only the tile's survivors once per slice. Lists hold the lowest-indexed lights first; counts
// past the cap are kept (uncapped) for the heat map, and clusters that overflow are counted in
// uOverflow. (The deferred clustered method builds tighter lists from the G-buffer's depth in
// local_light_clustered.comp.)
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

void main() {
    ivec2 tile = ivec2(gl_WorkGroupID.xy);
    uint lid = gl_LocalInvocationIndex;
    int slice = int(lid);
    bool ownsSlice = slice < uClusterGrid.z;
    vec2 ndcLo, ndcHi;
    clusterTileNdc(tile, uImageSize, ndcLo, ndcHi);
    // This invocation's froxel box.
    vec3 lo, hi;
    clusterTileBox(ndcLo, ndcHi, clusterSliceStart(slice), clusterSliceStart(slice + 1), uProjection, lo, hi);
    int cluster = clusterIndex(ivec3(tile, slice));
    uint base = uint(cluster) * LP_MAX_LIGHTS_PER_CLUSTER;
    uint count = 0u;
    for (int first = 0; first < uLightCount; first += 64) {
        int i = first + int(lid);
        bool survives = false;
        if (i < uLightCount) {
            vec4 b = uLights[i].bound;
            survives = sphereTouchesTileFrustum(b.xyz, b.w * (1.0 + LP_CLUSTER_MARGIN) + 1e-6, ndcLo, ndcHi,
                                                uClusterNear, uClusterFar, uProjection);
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
                if (clusterLightTouchesBox(sBound[j], sApex[j], sAxis[j], lo, hi)) {
                    if (count < LP_MAX_LIGHTS_PER_CLUSTER) uLists[base + count] = sSurvivor[j];
                    ++count;
                }
        barrier();
    }
    if (!ownsSlice) return;
    uCounts[cluster] = count;
    if (count > LP_MAX_LIGHTS_PER_CLUSTER) atomicAdd(uOverflow, 1u);
}
