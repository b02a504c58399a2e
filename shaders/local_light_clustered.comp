#version 450
// Clustered method in one compute pass, fused like the tiled method: one work group per tile of the
// froxel grid (LP_CLUSTER_TILE = uClusterTileSize pixels square):
//  1. its pixels read their G-buffer texels at once (the loads are in flight while shared memory is
//     cleared), find their depth slice and, per slice, the eye-distance range its pixels occupy and
//     which slices hold any pixel at all (common/cluster_tile.glsl);
//  2. per batch of lights (one per invocation), each light is tested against the tile's frustum
//     between the nearest and farthest pixel (the tiled method's test), then against the occupied
//     slices its eye-depth interval can reach: each one's tight depth range, then the eye-space box
//     around it (made once per tile); a bit per light and slice in shared memory;
//  3. each pixel adds the lights of its own slice's bits, so a tile holding a near pillar and a far
//     wall shades neither with the lights in the empty depth between them. A pixel no light adds to
//     leaves its HDR texel alone (neither read nor written).
// A tile whose pixels lie in one slice is one froxel: its lights are exactly the tiled method's. The pass writes no froxel lists (nothing
// reads them after it): light_clusters_tight.comp builds the same tight lists for the
// lights-per-cluster view. Unbounded specular reaches every pixel: then every light is added.
// Measured on the H100 and not kept (bench/results/lighting/2026-11-24_clustered-vs-tiled/README.md): sorting a tile's
// pixels by slice so that a warp holds one or two slices (no gain: the shading left is BRDF work),
// fewer values kept in registers, shared arrays sized for the grid's slices, more tiles shaded as one
// froxel.
#include "common/local_light.glsl"
#include "common/clusters.glsl"
#include "common/cluster_tile.glsl"
#include "common/tonemap.glsl"
#define LP_GBUFFER_READ
#include "common/gbuffer_layout.glsl"

#ifndef LP_CLUSTER_TILE
#define LP_CLUSTER_TILE 16
#endif
// Only a tile within one slice shades as one froxel: merging tiles whose depth spans a ratio of 2 or
// 4, or 2 to 3 occupied slices, was slower on the H100 (docs/notes/clustered-kernel-variants.md).
const int LP_TILE = LP_CLUSTER_TILE;
// At most 16 x 16 invocations; a larger tile gives each invocation several pixels, 16 apart.
const int LP_SIDE = LP_TILE < 16 ? LP_TILE : 16;
const int LP_PIXELS_SIDE = (LP_TILE + LP_SIDE - 1) / LP_SIDE;
const int LP_PIXELS = LP_PIXELS_SIDE * LP_PIXELS_SIDE;
const int LP_BATCH = LP_SIDE * LP_SIDE;  // lights per batch: one per invocation
const int LP_WORDS = (LP_BATCH + 31) / 32;  // bit-mask words per slice
const int LP_MASK = LP_SLICES * LP_WORDS;  // one batch's bits

layout(local_size_x = LP_SIDE, local_size_y = LP_SIDE) in;
layout(std430, binding = 0) readonly buffer LocalLights { LpLocalLight uLights[]; };
#ifdef LP_SUPERTILES
// Candidates from light_cluster_supertiles.comp's lists. A variant of its own: without them (up to
// 256 lights) the kernel compiles to what it was before they existed, 2-3% faster there.
#include "common/supertiles.glsl"
#endif
layout(rgba16f, binding = 0) uniform image2D uHdr;
uniform int uLightCount;
uniform mat4 uProjection;
uniform ivec2 uImageSize;
uniform bool uUnbounded;     // specular outside the range: every light reaches every pixel
uniform bool uLightingOnly;
uniform int uSpecularMode;

// Two batches' bits, alternating: a batch's tests write one half while the other is cleared, so a
// batch needs one barrier between its tests and its shading and one before the next batch's tests.
shared uint sMask[2 * LP_MASK];  // per slice, a bit per light of the batch touching it
shared uint sWords[2 * LP_SLICES];  // per slice, a bit per word of its sMask that is not 0
#ifdef LP_SUPERTILES
shared uint sLight[LP_BATCH];  // the batch's light indices where they come from a supertile list
#endif

// Light i (bound b; bit `at` of the batch) against the tile's occupied slices `occ` that its eye-depth
// interval reaches; a bit in the half of sMask / sWords at `mask` / `words` for each slice it touches.
void markSlices(int i, vec4 b, uint at, uvec2 occ, int mask, int words) {
    vec4 apex = uLights[i].positionRange, axis = uLights[i].directionCos;
    float r = b.w * (1.0 + LP_CLUSTER_MARGIN) + 1e-6;
    float dist = -b.z;
    uint word = at >> 5, bit = 1u << (at & 31u);
    uvec2 candidates = clusterCandidateSlices(dist, r, occ);
    for (int h = 0; h < 2; ++h)
        for (uint cand = candidates[h]; cand != 0u; cand &= cand - 1u) {
            int j = 32 * h + findLSB(cand);
            if (!clusterLightTouchesSlice(b, r, dist, apex, axis, j)) continue;
            atomicOr(sMask[mask + j * LP_WORDS + int(word)], bit);
            if ((sWords[words + j] & (1u << word)) == 0u) atomicOr(sWords[words + j], 1u << word);
        }
}

// The light of bit `at` of the batch starting at candidate `first`.
int lightOfBit(bool listed, int first, int at) {
#ifdef LP_SUPERTILES
    if (listed) return int(sLight[at]);
#endif
    return first + at;
}

// What shading needs of pixel p beyond its eye position P.
void readShadingTexels(ivec2 p, vec3 P, out vec3 N, out vec4 spec, out vec3 kd, out vec3 V) {
    N = gbufferNormal(p);
    spec = vec4(gbufferSpecular(p), gbufferShininess(p));
    kd = uLightingOnly ? vec3(1.0) : gbufferDiffuse(p);
    float pl = length(P);
    V = pl > 0.0 ? -P / pl : vec3(0.0, 0.0, 1.0);
}

void main() {
    uint lid = gl_LocalInvocationIndex;
    ivec2 tile = ivec2(gl_WorkGroupID.xy);
    ivec2 origin = tile * LP_TILE;
    int slices = uClusterGrid.z;

    // 1. Each pixel's G-buffer texels first. Flat-lit pixels are no surface to light (and widen no
    // range).
    bool surface[LP_PIXELS];
    vec3 P[LP_PIXELS], N[LP_PIXELS], kd[LP_PIXELS], V[LP_PIXELS], sum[LP_PIXELS];
    vec4 spec[LP_PIXELS];
#ifdef LP_GBUFFER_FRESNEL
    vec2 fresnel[LP_PIXELS];  // the stored f90 and diffuse shape (gbuffer.fresnel)
#endif
#ifdef LP_GBUFFER_CLEARCOAT
    ClearcoatLayer coat[LP_PIXELS];  // KHR_materials_clearcoat's layer (gbuffer.clearcoat)
#endif
    int slice[LP_PIXELS];
    ivec2 at[LP_PIXELS];  // the pixel within the tile
    for (int k = 0; k < LP_PIXELS; ++k) {
        ivec2 q = ivec2(gl_LocalInvocationID.xy) + LP_SIDE * ivec2(k % LP_PIXELS_SIDE, k / LP_PIXELS_SIDE);
        ivec2 p = origin + q;
        at[k] = q;
        surface[k] = q.x < LP_TILE && q.y < LP_TILE && p.x < uImageSize.x && p.y < uImageSize.y &&
                     !gbufferIsBackground(p) && (uLightingOnly || !gbufferIsFlat(p));
        P[k] = vec3(0.0);
        N[k] = vec3(0.0);
        kd[k] = vec3(0.0);
        V[k] = vec3(0.0, 0.0, 1.0);
        spec[k] = vec4(0.0);
#ifdef LP_GBUFFER_FRESNEL
        fresnel[k] = vec2(0.0);
#endif
#ifdef LP_GBUFFER_CLEARCOAT
        coat[k] = noClearcoat();
#endif
        sum[k] = vec3(0.0);
        slice[k] = 0;
        if (surface[k]) {
            P[k] = gbufferPosition(p);
            readShadingTexels(p, P[k], N[k], spec[k], kd[k], V[k]);
#ifdef LP_GBUFFER_FRESNEL
            fresnel[k] = gbufferFresnelStored(p);
#endif
#ifdef LP_GBUFFER_CLEARCOAT
            coat[k] = gbufferClearcoat(p);
#endif
            slice[k] = clusterSliceOf(max(-P[k].z, 0.0));
        }
    }
    clusterTileClear(lid, uint(LP_BATCH));
    for (int j = int(lid); j < slices; j += LP_BATCH) {
        sWords[j] = 0u;
        sWords[LP_SLICES + j] = 0u;
    }
    for (int w = int(lid); w < slices * LP_WORDS; w += LP_BATCH) {
        sMask[w] = 0u;
        sMask[LP_MASK + w] = 0u;
    }
    barrier();
    for (int k = 0; k < LP_PIXELS; ++k)
        if (surface[k]) clusterTileAddPixel(slice[k], max(-P[k].z, 0.0));
    barrier();
    uvec2 occ = clusterTileOccupied();  // uniform across the group
    if ((occ.x | occ.y) == 0u) return;  // no surface in the tile: nothing to add
    float tileNear = clusterTileNear(occ), tileFar = clusterTileFar(occ);
    // One froxel for the whole tile (uniform): the tiled method's lights, slice 0's bits.
    bool merged = bitCount(occ.x) + bitCount(occ.y) == 1;
    if (merged)
        for (int k = 0; k < LP_PIXELS; ++k) slice[k] = 0;
    vec2 ndcLo, ndcHi;
    clusterTileNdc(tile, uImageSize, ndcLo, ndcHi);
    if (!merged) {
        clusterTileBoxes(lid, uint(LP_BATCH), ndcLo, ndcHi, uProjection);
        barrier();
    }

    uint word = lid >> 5, bit = 1u << (lid & 31u);
    int part = 0;  // which half of sMask / sWords this batch uses
    // The candidates: the supertile's lights, or every light (no supertiles, an overflowing list).
#ifdef LP_SUPERTILES
    const SupertileCandidates tileCandidates = supertileCandidates(tile, int(gl_NumWorkGroups.x), uLightCount);
    const int candidates = tileCandidates.count;
    const bool listed = tileCandidates.listed;
#else
    const int candidates = uLightCount;
    const bool listed = false;
#endif
    for (int first = 0; first < candidates; first += LP_BATCH) {
        int mask = part * LP_MASK, words = part * LP_SLICES;
        // 2. This invocation's light against the tile, then against the occupied slices its
        // eye-depth interval reaches (every light everywhere when unbounded: no bits needed).
        int cand = first + int(lid);  // this invocation's candidate
#ifdef LP_SUPERTILES
        int i = cand < candidates ? supertileCandidate(tileCandidates, cand) : cand;
        if (listed && cand < candidates) sLight[lid] = uint(i);
#else
        int i = cand;
#endif
        if (cand < candidates && !uUnbounded) {
            vec4 b = uLights[i].bound;
            float r = b.w * (1.0 + LP_CLUSTER_MARGIN) + 1e-6;
            if (sphereTouchesTileFrustum(b.xyz, r, ndcLo, ndcHi, tileNear, tileFar, uProjection)) {
                if (merged) {
                    atomicOr(sMask[mask + int(word)], bit);
                    if ((sWords[words] & (1u << word)) == 0u) atomicOr(sWords[words], 1u << word);
                } else {
                    markSlices(i, b, lid, occ, mask, words);
                }
            }
        }
        barrier();
        int batch = min(LP_BATCH, candidates - first);
        // 3. Each pixel: the lights of its slice, in index order (only the words holding any).
        uint batchWords = (1u << uint((batch + 31) / 32)) - 1u;
        for (int k = 0; k < LP_PIXELS; ++k) {
            if (!surface[k]) continue;
            for (uint ws = uUnbounded ? batchWords : sWords[words + slice[k]]; ws != 0u; ws &= ws - 1u) {
                int w = findLSB(ws);
                uint bits = sMask[mask + slice[k] * LP_WORDS + w];
                if (uUnbounded) bits = batch - 32 * w >= 32 ? ~0u : (1u << uint(batch - 32 * w)) - 1u;
#ifdef LP_GBUFFER_FRESNEL
                FresnelEnds ends = gbufferFresnelEnds(spec[k].rgb, fresnel[k]);
#else
                FresnelEnds ends = fresnelEndsOfF0(spec[k].rgb);  // f90 and the shape from F0
#endif
#ifdef LP_GBUFFER_CLEARCOAT
                ClearcoatLayer layer = coat[k];
                ends = clearcoatBaseEnds(ends, layer);
#else
                ClearcoatLayer layer = noClearcoat();
#endif
                for (; bits != 0u; bits &= bits - 1u)
                    sum[k] += lpShadeLocalLight(uLights[lightOfBit(listed, first, 32 * w + findLSB(bits))], P[k], N[k], V[k], kd[k],
                                                ends, spec[k].a, uSpecularMode, layer);
            }
        }
        if (first + LP_BATCH >= candidates) break;  // uniform
        // The other half for the next batch: its last readers finished before this batch's barrier.
        int other = (1 - part) * LP_MASK;
        for (int w = int(lid); w < slices * LP_WORDS; w += LP_BATCH) sMask[other + w] = 0u;
        for (int j = int(lid); j < slices; j += LP_BATCH) sWords[(1 - part) * LP_SLICES + j] = 0u;
        barrier();
        part = 1 - part;
    }
    for (int k = 0; k < LP_PIXELS; ++k) {
        if (!surface[k]) continue;
        if (sum[k] == vec3(0.0)) continue;  // adds nothing: no read, no write
        ivec2 p = origin + at[k];
        imageStore(uHdr, p, vec4(sanitizeHdr(imageLoad(uHdr, p).rgb + sum[k]), 1.0));
    }
}
