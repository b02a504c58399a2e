#version 450
// The deferred clustered method's froxel lists tightened to the G-buffer's depth, built without
// shading (the lights-per-cluster view; local_light_clustered.comp shades from the same tests in
// shared memory and writes no lists). One work group per tile of the froxel grid (LP_CLUSTER_TILE =
// uClusterTileSize pixels square):
//  1. its pixels find their depth slice; per slice, the eye-distance range its pixels occupy and
//     which slices hold any pixel at all (common/cluster_tile.glsl, shared with the clustered pass);
//  2. per batch of lights (one per invocation), each light is tested against the tile's frustum
//     between the nearest and farthest pixel (the tiled method's test), and the survivors against
//     the occupied slices its eye-depth interval can reach: each one's tight range and box; a bit per
//     light and slice in shared memory;
//  3. the bits become the tile's froxel lists in the grid (index order, at most the cap; counts
//     uncapped, overflowing froxels counted in uOverflow). Unoccupied froxels list nothing: these
//     lists are for the depth buffer's surfaces, not for transparent ones (light_clusters.comp
//     builds whole froxels for the forward passes).
#include "common/local_light.glsl"
#include "common/clusters.glsl"
#include "common/cluster_tile.glsl"
#define LP_GBUFFER_READ
#include "common/gbuffer_layout.glsl"

#ifndef LP_CLUSTER_TILE
#define LP_CLUSTER_TILE 16
#endif
const int LP_TILE = LP_CLUSTER_TILE;
// At most 16 x 16 invocations; a larger tile gives each invocation several pixels, 16 apart.
const int LP_SIDE = LP_TILE < 16 ? LP_TILE : 16;
const int LP_PIXELS_SIDE = (LP_TILE + LP_SIDE - 1) / LP_SIDE;
const int LP_PIXELS = LP_PIXELS_SIDE * LP_PIXELS_SIDE;
const int LP_BATCH = LP_SIDE * LP_SIDE;  // lights per batch: one per invocation
const int LP_WORDS = (LP_BATCH + 31) / 32;  // bit-mask words per slice

layout(local_size_x = LP_SIDE, local_size_y = LP_SIDE) in;
layout(std430, binding = 0) readonly buffer LocalLights { LpLocalLight uLights[]; };
layout(std430, binding = 1) writeonly buffer ClusterCounts { uint uCounts[]; };
layout(std430, binding = 2) writeonly buffer ClusterLights { uint uLists[]; };
layout(std430, binding = 3) buffer ClusterOverflow { uint uOverflow; };
uniform int uLightCount;
uniform mat4 uProjection;
uniform ivec2 uImageSize;
uniform bool uLightingOnly;  // every non-background pixel is a surface (else flat-lit ones are not)

shared uint sMask[LP_SLICES * LP_WORDS];  // per slice, a bit per light of the batch touching it
shared uint sWords[LP_SLICES];  // per slice, a bit per word of sMask that is not 0
shared uint sListed[LP_SLICES];  // lights listed so far per slice (uncapped)

void main() {
    uint lid = gl_LocalInvocationIndex;
    ivec2 tile = ivec2(gl_WorkGroupID.xy);
    ivec2 origin = tile * LP_TILE;
    int slices = uClusterGrid.z;
    clusterTileClear(lid, uint(LP_BATCH));
    for (uint j = lid; j < uint(LP_SLICES); j += uint(LP_BATCH)) {
        sListed[j] = 0u;
        sWords[j] = 0u;
    }
    for (uint w = lid; w < uint(slices * LP_WORDS); w += uint(LP_BATCH)) sMask[w] = 0u;
    barrier();

    // 1. Each pixel's slice; each slice's occupied depth range. Flat-lit pixels are no surface to
    // light (and widen no range).
    bool surface[LP_PIXELS];
    vec3 P[LP_PIXELS];
    int slice[LP_PIXELS];
    for (int k = 0; k < LP_PIXELS; ++k) {
        ivec2 q = ivec2(gl_LocalInvocationID.xy) + LP_SIDE * ivec2(k % LP_PIXELS_SIDE, k / LP_PIXELS_SIDE);
        ivec2 p = origin + q;
        surface[k] = q.x < LP_TILE && q.y < LP_TILE && p.x < uImageSize.x && p.y < uImageSize.y &&
                     !gbufferIsBackground(p) && (uLightingOnly || !gbufferIsFlat(p));
        P[k] = vec3(0.0);
        slice[k] = 0;
        if (surface[k]) {
            P[k] = gbufferPosition(p);
            float d = max(-P[k].z, 0.0);
            slice[k] = clusterSliceOf(d);
            clusterTileAddPixel(slice[k], d);
        }
    }
    barrier();
    vec2 ndcLo, ndcHi;
    clusterTileNdc(tile, uImageSize, ndcLo, ndcHi);
    uvec2 occ = clusterTileOccupied();  // uniform across the group
    bool anySurface = (occ.x | occ.y) != 0u;
    float tileNear = 0.0, tileFar = 0.0;
    if (anySurface) {
        tileNear = clusterTileNear(occ);
        tileFar = clusterTileFar(occ);
    }
    clusterTileBoxes(lid, uint(LP_BATCH), ndcLo, ndcHi, uProjection);
    barrier();

    if (anySurface) {
        uint word = lid >> 5, bit = 1u << (lid & 31u);
        for (int first = 0; first < uLightCount; first += LP_BATCH) {
            // 2. This invocation's light against the tile, then against the occupied slices its
            // eye-depth interval reaches.
            int i = first + int(lid);
            bool touches = false;  // some occupied slice
            if (i < uLightCount) {
                vec4 b = uLights[i].bound;
                float r = b.w * (1.0 + LP_CLUSTER_MARGIN) + 1e-6;
                if (sphereTouchesTileFrustum(b.xyz, r, ndcLo, ndcHi, tileNear, tileFar, uProjection)) {
                    vec4 apex = uLights[i].positionRange, axis = uLights[i].directionCos;
                    float dist = -b.z;
                    uvec2 candidates = clusterCandidateSlices(dist, r, occ);
                    for (int h = 0; h < 2; ++h)
                        for (uint bits = candidates[h]; bits != 0u; bits &= bits - 1u) {
                            int j = 32 * h + findLSB(bits);
                            if (clusterLightTouchesSlice(b, r, dist, apex, axis, j)) {
                                atomicOr(sMask[j * LP_WORDS + int(word)], bit);
                                atomicOr(sWords[j], 1u << word);
                                touches = true;
                            }
                        }
                }
            }
            barrier();
            // 3. This invocation's light into the list of each slice it touches, after the lights
            // listed there before it (earlier batches, lower bits).
            if (touches)
                for (int h = 0; h < 2; ++h)
                    for (uint bits = occ[h]; bits != 0u; bits &= bits - 1u) {
                        int j = 32 * h + findLSB(bits);
                        uint m = sMask[j * LP_WORDS + int(word)];
                        if ((m & bit) == 0u) continue;
                        uint at = sListed[j] + uint(bitCount(m & (bit - 1u)));
                        for (uint w = 0u; w < word; ++w) at += uint(bitCount(sMask[j * LP_WORDS + int(w)]));
                        if (at < LP_MAX_LIGHTS_PER_CLUSTER)
                            uLists[uint(clusterIndex(ivec3(tile, j))) * LP_MAX_LIGHTS_PER_CLUSTER + at] = uint(i);
                    }
            uint added = 0u;
            if (lid < uint(slices))
                for (uint words = sWords[lid]; words != 0u; words &= words - 1u)
                    added += uint(bitCount(sMask[int(lid) * LP_WORDS + findLSB(words)]));
            barrier();
            if (lid < uint(slices)) {
                sListed[lid] += added;
                sWords[lid] = 0u;
            }
            for (uint w = lid; w < uint(slices * LP_WORDS); w += uint(LP_BATCH)) sMask[w] = 0u;
            barrier();
        }
    }
    if (lid < uint(slices)) {
        uint count = sListed[lid];
        uCounts[clusterIndex(ivec3(tile, int(lid)))] = count;
        if (count > LP_MAX_LIGHTS_PER_CLUSTER) atomicAdd(uOverflow, 1u);
    }
}
