#version 450
// The first level of the whole-froxel build (light_clusters.comp): per supertile (uSupertile x
// uSupertile froxel tiles), the lights whose bounding sphere touches its column (the tiles' union
// from the near to the far plane), in index order. Each tile then tests only its supertile's lights
// instead of every light of the frame: with thousands of lights the tile-by-light tests were most of
// the build. A supertile with more than uSupertileCapacity lights keeps its count (uncapped) and no
// list: its tiles test every light, as before. One work group per supertile; 256 lights a batch, one
// per invocation; the list in index order (each light's place: the touching lights before it).
#include "common/local_light.glsl"
#include "common/clusters.glsl"

const int LP_BATCH = 256;
layout(local_size_x = LP_BATCH) in;
layout(std430, binding = 0) readonly buffer LocalLights { LpLocalLight uLights[]; };
layout(std430, binding = 6) writeonly buffer SupertileCounts { uint uSupertileCounts[]; };
layout(std430, binding = 7) writeonly buffer SupertileLights { uint uSupertileLists[]; };
uniform int uLightCount;
uniform mat4 uProjection;
uniform ivec2 uImageSize;
uniform int uSupertile;          // froxel tiles per supertile side
uniform int uSupertileCapacity;  // list entries per supertile

shared uint sPassed[LP_BATCH / 32];  // a bit per light of the batch touching the supertile's column

void main() {
    ivec2 st = ivec2(gl_WorkGroupID.xy);
    uint lid = gl_LocalInvocationIndex;
    ivec2 t0 = st * uSupertile, t1 = min(t0 + uSupertile - 1, uClusterGrid.xy - 1);
    // The outer edges of its first and last tiles: the same numbers the tiles' own tests use.
    vec2 lo, hi, innerLo, innerHi;
    clusterTileNdc(t0, uImageSize, lo, innerHi);
    clusterTileNdc(t1, uImageSize, innerLo, hi);
    int index = st.y * int(gl_NumWorkGroups.x) + st.x;
    uint base = uint(index) * uint(uSupertileCapacity);
    uint count = 0u;  // uniform: every invocation sums the same bits
    uint word = lid >> 5u, bit = 1u << (lid & 31u);
    for (int first = 0; first < uLightCount; first += LP_BATCH) {
        if (lid < uint(LP_BATCH / 32)) sPassed[lid] = 0u;
        barrier();
        int i = first + int(lid);
        bool touches = false;
        if (i < uLightCount) {
            vec4 b = uLights[i].bound;
            touches = sphereTouchesTileFrustum(b.xyz, b.w * (1.0 + LP_CLUSTER_MARGIN) + 1e-6, lo, hi, uClusterNear,
                                               uClusterFar, uProjection);
            if (touches) atomicOr(sPassed[word], bit);
        }
        barrier();
        uint before = 0u, n = 0u;
        for (uint w = 0u; w < uint(LP_BATCH / 32); ++w) {
            uint c = uint(bitCount(sPassed[w]));
            before += w < word ? c : 0u;
            n += c;
        }
        uint at = count + before + uint(bitCount(sPassed[word] & (bit - 1u)));
        if (touches && at < uint(uSupertileCapacity)) uSupertileLists[base + at] = uint(i);
        count += n;
        barrier();  // every invocation has read sPassed before the next batch clears it
    }
    if (lid == 0u) uSupertileCounts[index] = count;
}
