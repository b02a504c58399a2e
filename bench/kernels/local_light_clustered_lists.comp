#version 450
// Main's fused clustered kernel up to 0b4a46a, kept as the baseline of bench/lighting_clustered.sh's
// VARIANTS run (copied over shaders/local_light_clustered.comp in a patched shader folder): it writes
// the tile's froxel lists and counts into the grid every frame (the pass then binds the grid and does
// the overflow bookkeeping) and tests each surviving light against every occupied slice.
// Clustered method in one compute pass, fused like the tiled method: one work group per tile of the
// froxel grid (LP_CLUSTER_TILE = uClusterTileSize pixels square):
//  1. its pixels find their depth slice; per slice, the eye-distance range its pixels occupy (the
//     froxel tightened to the depth of what it holds: Olsson et al. 2012's compact clusters, Harada's
//     2.5D culling) and which slices hold any pixel at all;
//  2. per batch of lights (one per invocation), each light is tested against the tile's frustum
//     between the nearest and farthest pixel (the tiled method's test), and the survivors against
//     each occupied slice's tight range and box; a bit per light and slice in shared memory;
//  3. each pixel adds the lights of its own slice's bits, so a tile holding a near pillar and a far
//     wall shades neither with the lights in the empty depth between them;
//  4. the bits become the tile's froxel lists in the shared grid (index order, at most the cap;
//     counts uncapped, overflowing froxels counted in uOverflow). Unoccupied froxels list nothing:
//     these lists are for the depth buffer's surfaces (the lights-per-cluster view), not for
//     transparent ones (light_clusters.comp builds whole froxels for the forward passes).
// Shading never stops at the cap. Unbounded specular reaches every pixel: then every light is added.
// With LP_CLUSTER_BUILD_ONLY it only builds the lists (steps 1, 2 and 4).
#include "common/local_light.glsl"
#include "common/clusters.glsl"
#include "common/tonemap.glsl"
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
const int LP_SLICES = 64;  // kMaxClusterSlices

layout(local_size_x = LP_SIDE, local_size_y = LP_SIDE) in;
layout(std430, binding = 0) readonly buffer LocalLights { LpLocalLight uLights[]; };
layout(std430, binding = 1) writeonly buffer ClusterCounts { uint uCounts[]; };
layout(std430, binding = 2) writeonly buffer ClusterLights { uint uLists[]; };
layout(std430, binding = 3) buffer ClusterOverflow { uint uOverflow; };
#ifndef LP_CLUSTER_BUILD_ONLY
layout(rgba16f, binding = 0) uniform image2D uHdr;
#endif
uniform int uLightCount;
uniform mat4 uProjection;
uniform ivec2 uImageSize;
uniform bool uUnbounded;     // specular outside the range: every light reaches every pixel
uniform bool uLightingOnly;
uniform int uSpecularMode;

shared uint sMinDist[LP_SLICES], sMaxDist[LP_SLICES];  // float bits of eye distances (order-preserving)
shared uint sOccupied[2];  // a bit per slice holding a pixel
shared vec4 sBoxLo[LP_SLICES], sBoxHi[LP_SLICES];  // each occupied slice's tight eye-space box
shared uint sMask[LP_SLICES * LP_WORDS];  // per slice, a bit per light of the batch touching it
shared uint sWords[LP_SLICES];  // per slice, a bit per word of sMask that is not 0
shared uint sListed[LP_SLICES];  // lights listed so far per slice (uncapped)

void main() {
    uint lid = gl_LocalInvocationIndex;
    ivec2 tile = ivec2(gl_WorkGroupID.xy);
    ivec2 origin = tile * LP_TILE;
    int slices = uClusterGrid.z;
    for (uint j = lid; j < uint(LP_SLICES); j += uint(LP_BATCH)) {
        sMinDist[j] = floatBitsToUint(3.0e38);
        sMaxDist[j] = 0u;
        sListed[j] = 0u;
        sWords[j] = 0u;
    }
    for (uint w = lid; w < uint(slices * LP_WORDS); w += uint(LP_BATCH)) sMask[w] = 0u;
    if (lid < 2u) sOccupied[lid] = 0u;
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
            int j = clusterSliceOf(d);
            slice[k] = j;
            // Most pixels of a slice cannot move its range: a (possibly stale) read first spares
            // their atomics on the one shared word they all hit.
            uint bits = floatBitsToUint(d);
            if (bits < sMinDist[j]) atomicMin(sMinDist[j], bits);
            if (bits > sMaxDist[j]) atomicMax(sMaxDist[j], bits);
        }
    }
    barrier();
    vec2 ndcLo, ndcHi;
    clusterTileNdc(tile, uImageSize, ndcLo, ndcHi);
    if (lid < uint(slices) && sMinDist[lid] <= sMaxDist[lid]) {
        vec3 lo, hi;
        clusterTileBox(ndcLo, ndcHi, uintBitsToFloat(sMinDist[lid]), uintBitsToFloat(sMaxDist[lid]), uProjection, lo, hi);
        sBoxLo[lid] = vec4(lo, 0.0);
        sBoxHi[lid] = vec4(hi, 0.0);
        atomicOr(sOccupied[lid >> 5], 1u << (lid & 31u));
    }
    barrier();
    uvec2 occ = uvec2(sOccupied[0], sOccupied[1]);  // uniform across the group
    bool anySurface = (occ.x | occ.y) != 0u;
    // The tile's depth bounds: the nearest occupied slice's nearest pixel to the farthest's farthest.
    float tileNear = 0.0, tileFar = 0.0;
    if (anySurface) {
        tileNear = uintBitsToFloat(sMinDist[occ.x != 0u ? findLSB(occ.x) : 32 + findLSB(occ.y)]);
        tileFar = uintBitsToFloat(sMaxDist[occ.y != 0u ? 32 + findMSB(occ.y) : findMSB(occ.x)]);
    }

#ifndef LP_CLUSTER_BUILD_ONLY
    vec3 N[LP_PIXELS], kd[LP_PIXELS], V[LP_PIXELS], sum[LP_PIXELS];
    vec4 spec[LP_PIXELS];
    for (int k = 0; k < LP_PIXELS; ++k) {
        sum[k] = vec3(0.0);
        N[k] = vec3(0.0);
        kd[k] = vec3(0.0);
        V[k] = vec3(0.0, 0.0, 1.0);
        spec[k] = vec4(0.0);
        if (!surface[k]) continue;
        ivec2 p = origin + ivec2(gl_LocalInvocationID.xy) + LP_SIDE * ivec2(k % LP_PIXELS_SIDE, k / LP_PIXELS_SIDE);
        N[k] = gbufferNormal(p);
        spec[k] = vec4(gbufferSpecular(p), gbufferShininess(p));
        kd[k] = uLightingOnly ? vec3(1.0) : gbufferDiffuse(p);
        float pl = length(P[k]);
        V[k] = pl > 0.0 ? -P[k] / pl : vec3(0.0, 0.0, 1.0);
    }
#endif

    if (anySurface) {
        uint word = lid >> 5, bit = 1u << (lid & 31u);
        for (int first = 0; first < uLightCount; first += LP_BATCH) {
            // 2. This invocation's light against the tile, then against each occupied slice.
            int i = first + int(lid);
            bool touches = false;  // some occupied slice
            if (i < uLightCount) {
                vec4 b = uLights[i].bound;
                float r = b.w * (1.0 + LP_CLUSTER_MARGIN) + 1e-6;
                if (sphereTouchesTileFrustum(b.xyz, r, ndcLo, ndcHi, tileNear, tileFar, uProjection)) {
                    vec4 apex = uLights[i].positionRange, axis = uLights[i].directionCos;
                    for (int h = 0; h < 2; ++h)
                        for (uint bits = occ[h]; bits != 0u; bits &= bits - 1u) {
                            int j = 32 * h + findLSB(bits);
                            if (sphereTouchesTileFrustum(b.xyz, r, ndcLo, ndcHi, uintBitsToFloat(sMinDist[j]),
                                                         uintBitsToFloat(sMaxDist[j]), uProjection) &&
                                clusterLightTouchesBox(b, apex, axis, sBoxLo[j].xyz, sBoxHi[j].xyz)) {
                                atomicOr(sMask[j * LP_WORDS + int(word)], bit);
                                atomicOr(sWords[j], 1u << word);
                                touches = true;
                            }
                        }
                }
            }
            barrier();
            int batch = min(LP_BATCH, uLightCount - first);
#ifndef LP_CLUSTER_BUILD_ONLY
            // 3. Each pixel: the lights of its slice, in index order (only the words holding any).
            uint batchWords = (1u << uint((batch + 31) / 32)) - 1u;
            for (int k = 0; k < LP_PIXELS; ++k) {
                if (!surface[k]) continue;
                for (uint words = uUnbounded ? batchWords : sWords[slice[k]]; words != 0u; words &= words - 1u) {
                    int w = findLSB(words);
                    uint bits = sMask[slice[k] * LP_WORDS + w];
                    if (uUnbounded) bits = batch - 32 * w >= 32 ? ~0u : (1u << uint(batch - 32 * w)) - 1u;
                    for (; bits != 0u; bits &= bits - 1u)
                        sum[k] += lpShadeLocalLight(uLights[first + 32 * w + findLSB(bits)], P[k], N[k], V[k], kd[k],
                                                    spec[k].rgb, spec[k].a, uSpecularMode);
                }
            }
#endif
            // 4. This invocation's light into the list of each slice it touches, after the lights
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
#ifndef LP_CLUSTER_BUILD_ONLY
    for (int k = 0; k < LP_PIXELS; ++k) {
        if (!surface[k]) continue;
        ivec2 p = origin + ivec2(gl_LocalInvocationID.xy) + LP_SIDE * ivec2(k % LP_PIXELS_SIDE, k / LP_PIXELS_SIDE);
        imageStore(uHdr, p, vec4(sanitizeHdr(imageLoad(uHdr, p).rgb + sum[k]), 1.0));
    }
#endif
}
