#version 450
// The first level of the whole-froxel build (light_clusters.comp) and of the tiled and clustered
// passes: per supertile (uSupertile x uSupertile froxel tiles), the lights whose bounding sphere
// touches its column (the tiles' union from the near to the far plane), in index order. Each tile then
// tests only its supertile's lights instead of every light of the frame: with thousands of lights the
// tile-by-light tests were most of the build. A supertile with more than uSupertileCapacity lights
// keeps its count (uncapped) and no list: its tiles test every light.
//
// gl_NumWorkGroups.z work groups per supertile, each testing every gl_NumWorkGroups.z-th chunk of 256
// lights, so that thousands of lights spread over the whole GPU: with one group per supertile looping
// over every light, a 1080p frame's 135 groups each ran 64 chunks one after another at 16384 lights.
// With several, each group leaves a bit per light, and the last group of a supertile to finish (a
// counter per supertile) compacts the bits into the list: each invocation a run of consecutive words,
// placed after the lights of the runs before it (a prefix sum in shared memory). It puts the counter
// back to 0 for the next build.
#include "common/local_light.glsl"
#include "common/clusters.glsl"

const int LP_GROUP = 256;  // lights a group tests, and invocations that compact
layout(local_size_x = LP_GROUP) in;
layout(std430, binding = 0) readonly buffer LocalLights { LpLocalLight uLights[]; };
layout(std430, binding = 6) writeonly buffer SupertileCounts { uint uSupertileCounts[]; };
layout(std430, binding = 7) writeonly buffer SupertileLights { uint uSupertileLists[]; };
layout(std430, binding = 8) coherent buffer SupertileBits { uint uSupertileBits[]; };  // uBitWords per supertile
layout(std430, binding = 9) coherent buffer SupertileDone { uint uSupertileDone[]; };  // groups finished per supertile
uniform int uLightCount;
uniform mat4 uProjection;
uniform ivec2 uImageSize;
uniform int uSupertile;          // froxel tiles per supertile side
uniform int uSupertileCapacity;  // list entries per supertile
uniform int uBitWords;           // (uLightCount + 31) / 32

shared uint sPassed[LP_GROUP / 32];  // a bit per light of the group touching the supertile's column
shared uint sSum[LP_GROUP];
shared bool sLast;

void main() {
    ivec2 st = ivec2(gl_WorkGroupID.xy);
    uint lid = gl_LocalInvocationIndex;
    int index = st.y * int(gl_NumWorkGroups.x) + st.x;
    uint bits = uint(index) * uint(uBitWords);
    ivec2 t0 = st * uSupertile, t1 = min(t0 + uSupertile - 1, uClusterGrid.xy - 1);
    // The outer edges of its first and last tiles: the same numbers the tiles' own tests use.
    vec2 lo, hi, innerLo, innerHi;
    clusterTileNdc(t0, uImageSize, lo, innerHi);
    clusterTileNdc(t1, uImageSize, innerLo, hi);
    // Chunks of 256 lights: this group's, one in every gl_NumWorkGroups.z. A supertile's only group
    // (up to 2048 lights) lists its lights as it tests them, each light's place the touching lights
    // before it: no bits, no counter.
    const bool only = gl_NumWorkGroups.z == 1u;  // uniform
    const uint word = lid >> 5u, bit = 1u << (lid & 31u);
    const uint base = uint(index) * uint(uSupertileCapacity);
    uint count = 0u;  // uniform: every invocation sums the same bits
    for (int chunk = int(gl_WorkGroupID.z); chunk * LP_GROUP < uLightCount; chunk += int(gl_NumWorkGroups.z)) {
        if (lid < uint(LP_GROUP / 32)) sPassed[lid] = 0u;
        barrier();
        int i = chunk * LP_GROUP + int(lid);
        bool touches = false;
        if (i < uLightCount) {
            vec4 b = uLights[i].bound;
            touches = sphereTouchesTileFrustum(b.xyz, b.w * (1.0 + LP_CLUSTER_MARGIN) + 1e-6, lo, hi, uClusterNear,
                                               uClusterFar, uProjection);
            if (touches) atomicOr(sPassed[word], bit);
        }
        barrier();
        if (only) {
            uint before = 0u, n = 0u;
            for (uint w = 0u; w < uint(LP_GROUP / 32); ++w) {
                uint c = uint(bitCount(sPassed[w]));
                before += w < word ? c : 0u;
                n += c;
            }
            uint at = count + before + uint(bitCount(sPassed[word] & (bit - 1u)));
            if (touches && at < uint(uSupertileCapacity)) uSupertileLists[base + at] = uint(i);
            count += n;
        } else {
            int w = chunk * (LP_GROUP / 32) + int(lid);
            if (lid < uint(LP_GROUP / 32) && w < uBitWords) uSupertileBits[bits + uint(w)] = sPassed[lid];
        }
        barrier();  // sPassed read before the next chunk clears it
    }
    if (only) {
        if (lid == 0u) uSupertileCounts[index] = count;
        return;
    }
    memoryBarrierBuffer();  // the bits visible before the counter says they are there
    barrier();
    if (lid == 0u) sLast = atomicAdd(uSupertileDone[index], 1u) == gl_NumWorkGroups.z - 1u;
    barrier();
    if (!sLast) return;  // uniform

    // The supertile's last group: its bits, compacted in index order.
    memoryBarrierBuffer();
    int run = (uBitWords + LP_GROUP - 1) / LP_GROUP;  // words per invocation
    int first = int(lid) * run, last = min(first + run, uBitWords);
    uint n = 0u;
    for (int w = first; w < last; ++w) n += uint(bitCount(uSupertileBits[bits + uint(w)]));
    sSum[lid] = n;  // then its inclusive prefix sum (Hillis-Steele)
    barrier();
    for (uint step = 1u; step < uint(LP_GROUP); step <<= 1u) {
        uint add = lid >= step ? sSum[lid - step] : 0u;
        barrier();
        sSum[lid] += add;
        barrier();
    }
    uint at = sSum[lid] - n;  // lights before this invocation's run
    for (int w = first; w < last && at < uint(uSupertileCapacity); ++w)
        for (uint m = uSupertileBits[bits + uint(w)]; m != 0u && at < uint(uSupertileCapacity); m &= m - 1u)
            uSupertileLists[base + at++] = uint(32 * w + findLSB(m));
    if (lid == uint(LP_GROUP - 1)) uSupertileCounts[index] = sSum[lid];
    if (lid == 0u) uSupertileDone[index] = 0u;
}
