#version 450
// Clustered method in one compute pass: one work group per tile of the froxel grid
// (LP_CLUSTER_TILE = uClusterTileSize pixels square), the froxels tightened to the depth of the
// pixels they hold (Olsson et al. 2012's compact clusters, Harada's 2.5D culling), their lists kept in
// shared memory (no consumer reads a grid this pass would write: the lights-per-cluster view builds
// its own with light_clusters_tight.comp, the forward passes whole froxels with light_clusters.comp).
//  1. the tile's nearest and farthest pixel (the tiled method's depth bounds);
//  2. per tile, a uniform choice (uCullMode; auto: LP_SLICED_MIN_LIGHTS lights or more and a tile
//     spanning more than LP_SLICED_MIN_SPAN in depth): the tile path shades every pixel from the
//     tile's list exactly as the tiled method does; the slice path also finds each pixel's depth
//     slice, each occupied slice's tight range and box, and reorders the tile's pixels by slice so
//     that a warp's pixels share a slice (a near fence and the far wall behind it go to different
//     warps, which then skip each other's lights as a whole);
//  3. per batch of lights (one per invocation): each light is tested against the tile's frustum
//     between its depth bounds and, on the slice path, against the occupied slices its sphere's depth
//     extent overlaps (their tight range and box), giving a 64-bit slice mask; the survivors' shading
//     data is staged in shared memory with that mask;
//  4. each pixel adds the staged lights whose mask holds its slice.
// Unbounded specular reaches every pixel: then every light is added (the tile path).
// Each work group counts which path it took (dispatch counters 0: slices, 1: the tile's list).
#include "common/local_light.glsl"
#include "common/clusters.glsl"
#include "common/dispatch_counters.glsl"
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
const int LP_THREADS = LP_SIDE * LP_SIDE;
const int LP_BATCH = LP_THREADS;  // lights per batch: one per invocation
const int LP_SLICES = 64;         // kMaxClusterSlices
// The slice path reorders the tile's pixels only while their slots fit a small shared array (tiles up
// to 32 px); larger tiles keep each pixel on its invocation.
const int LP_SLOTS = LP_THREADS * LP_PIXELS;
const bool LP_REORDER = LP_SLOTS <= 1024;
const int LP_ORDER_SIZE = LP_REORDER ? LP_SLOTS : 1;
// Auto's choice (uCullMode 0): below this many lights the slice bookkeeping costs more than it
// saves; a tile whose farthest pixel is at most this many times its nearest gains little from slices.
const int LP_SLICED_MIN_LIGHTS = 32;
const float LP_SLICED_MIN_SPAN = 2.0;
const int LP_CULL_AUTO = 0, LP_CULL_TILES = 1, LP_CULL_SLICES = 2;  // ClusterCull

layout(local_size_x = LP_SIDE, local_size_y = LP_SIDE) in;
layout(std430, binding = 0) readonly buffer LocalLights { LpLocalLight uLights[]; };
layout(rgba16f, binding = 0) uniform image2D uHdr;
uniform int uLightCount;
uniform mat4 uProjection;
uniform ivec2 uImageSize;
uniform bool uUnbounded;     // specular outside the range: every light reaches every pixel
uniform bool uLightingOnly;
uniform int uSpecularMode;
uniform int uCullMode;       // LP_CULL_*

shared uint sTileMin, sTileMax;  // float bits of eye distances (order-preserving as uint)
shared uint sMinDist[LP_SLICES], sMaxDist[LP_SLICES];  // per slice, its pixels' range
shared uint sSliceCount[LP_SLICES], sSliceStart[LP_SLICES];  // per slice, its pixels and their first sorted slot
shared uint sOccupied[2];  // a bit per slice holding a pixel
shared vec4 sBoxLo[LP_SLICES], sBoxHi[LP_SLICES];  // each occupied slice's tight eye-space box
shared uint sOrder[LP_ORDER_SIZE];  // the slice path's pixel order: tile x | y << 8 | slice << 16
shared uint sCount[2];  // lights staged in this batch (two, so one is reset while the other is read)
// The batch's surviving lights, staged: what lpShadeLocalLight reads, and the slices each touches.
shared vec4 sPositionRange[LP_BATCH], sIntensity[LP_BATCH], sDirectionCos[LP_BATCH];
#ifdef LP_SPOT_SHADOWS
shared float sShadowLayer[LP_BATCH];
#endif
shared uvec2 sSliceMask[LP_BATCH];

// Invocation-local pixel slot k: its offset in the tile before any reordering.
ivec2 naturalOffset(int k) {
    return ivec2(gl_LocalInvocationID.xy) + LP_SIDE * ivec2(k % LP_PIXELS_SIDE, k / LP_PIXELS_SIDE);
}

void main() {
    uint lid = gl_LocalInvocationIndex;
    ivec2 tile = ivec2(gl_WorkGroupID.xy);
    ivec2 origin = tile * LP_TILE;
    int slices = uClusterGrid.z;
    if (lid == 0u) {
        sTileMin = floatBitsToUint(3.0e38);
        sTileMax = 0u;
        sCount[0] = 0u;
        sCount[1] = 0u;
        sOccupied[0] = 0u;
        sOccupied[1] = 0u;
    }
    for (uint j = lid; j < uint(LP_SLICES); j += uint(LP_THREADS)) {
        sMinDist[j] = floatBitsToUint(3.0e38);
        sMaxDist[j] = 0u;
        sSliceCount[j] = 0u;
    }
    barrier();

    // 1. The tile's depth bounds. Flat-lit pixels are no surface to light (and widen no bounds).
    bool surface[LP_PIXELS];
    vec3 P[LP_PIXELS];
    ivec2 offset[LP_PIXELS];
    int slice[LP_PIXELS];
    for (int k = 0; k < LP_PIXELS; ++k) {
        ivec2 q = naturalOffset(k);
        ivec2 p = origin + q;
        offset[k] = q;
        slice[k] = 0;
        surface[k] = q.x < LP_TILE && q.y < LP_TILE && p.x < uImageSize.x && p.y < uImageSize.y &&
                     !gbufferIsBackground(p) && (uLightingOnly || !gbufferIsFlat(p));
        P[k] = surface[k] ? gbufferPosition(p) : vec3(0.0);
        if (surface[k]) {
            // A (possibly stale) read first spares most pixels their atomic on the one shared word.
            uint bits = floatBitsToUint(max(-P[k].z, 0.0));
            if (bits < sTileMin) atomicMin(sTileMin, bits);
            if (bits > sTileMax) atomicMax(sTileMax, bits);
        }
    }
    barrier();
    float tileNear = uintBitsToFloat(sTileMin), tileFar = uintBitsToFloat(sTileMax);
    bool anySurface = tileNear <= tileFar;  // uniform across the group
    vec2 ndcLo, ndcHi;
    clusterTileNdc(tile, uImageSize, ndcLo, ndcHi);

    // 2. The path (uniform across the group).
    bool sliced = anySurface && !uUnbounded && slices > 1 &&
                  (uCullMode == LP_CULL_SLICES ||
                   (uCullMode == LP_CULL_AUTO && uLightCount >= LP_SLICED_MIN_LIGHTS &&
                    tileFar > LP_SLICED_MIN_SPAN * tileNear));
    int sliceLo = 0, sliceHi = 0;
    uvec2 occupied = uvec2(0u);
    if (sliced) {
        // Each pixel's slice, each slice's range and pixel count (a pixel's rank among them).
        uint rank[LP_PIXELS];
        for (int k = 0; k < LP_PIXELS; ++k) {
            rank[k] = 0u;
            if (!surface[k]) continue;
            float d = max(-P[k].z, 0.0);
            int j = clusterSliceOf(d);
            slice[k] = j;
            uint bits = floatBitsToUint(d);
            if (bits < sMinDist[j]) atomicMin(sMinDist[j], bits);
            if (bits > sMaxDist[j]) atomicMax(sMaxDist[j], bits);
            rank[k] = atomicAdd(sSliceCount[j], 1u);
        }
        sliceLo = clusterSliceOf(tileNear);
        sliceHi = clusterSliceOf(tileFar);
        barrier();
        int j = sliceLo + int(lid);
        if (j <= sliceHi) {
            uint start = 0u;
            for (int i = sliceLo; i < j; ++i) start += sSliceCount[i];
            sSliceStart[j] = start;
            if (sSliceCount[j] > 0u) {
                vec3 lo, hi;
                clusterTileBox(ndcLo, ndcHi, uintBitsToFloat(sMinDist[j]), uintBitsToFloat(sMaxDist[j]), uProjection,
                               lo, hi);
                sBoxLo[j] = vec4(lo, 0.0);
                sBoxHi[j] = vec4(hi, 0.0);
                atomicOr(sOccupied[j >> 5], 1u << uint(j & 31));
            }
        }
        barrier();
        occupied = uvec2(sOccupied[0], sOccupied[1]);
        if (LP_REORDER) {
            // The pixels in slice order: sorted slot s goes to invocation s % LP_THREADS, so a warp's
            // pixels are consecutive slots, mostly of one slice.
            for (int k = 0; k < LP_PIXELS; ++k)
                if (surface[k])
                    sOrder[sSliceStart[slice[k]] + rank[k]] =
                        uint(offset[k].x) | (uint(offset[k].y) << 8) | (uint(slice[k]) << 16);
            barrier();
            uint pixels = sSliceStart[sliceHi] + sSliceCount[sliceHi];
            for (int k = 0; k < LP_PIXELS; ++k) {
                uint s = lid + uint(k * LP_THREADS);
                surface[k] = s < pixels;
                if (!surface[k]) continue;
                uint code = sOrder[s];
                offset[k] = ivec2(int(code & 255u), int((code >> 8) & 255u));
                slice[k] = int(code >> 16);
                P[k] = gbufferPosition(origin + offset[k]);
            }
        }
    }

    vec3 N[LP_PIXELS], kd[LP_PIXELS], V[LP_PIXELS], sum[LP_PIXELS];
    vec4 spec[LP_PIXELS];
    for (int k = 0; k < LP_PIXELS; ++k) {
        sum[k] = vec3(0.0);
        N[k] = vec3(0.0);
        kd[k] = vec3(0.0);
        V[k] = vec3(0.0, 0.0, 1.0);
        spec[k] = vec4(0.0);
        if (!surface[k]) continue;
        ivec2 p = origin + offset[k];
        N[k] = gbufferNormal(p);
        spec[k] = vec4(gbufferSpecular(p), gbufferShininess(p));
        kd[k] = uLightingOnly ? vec3(1.0) : gbufferDiffuse(p);
        float pl = length(P[k]);
        V[k] = pl > 0.0 ? -P[k] / pl : vec3(0.0, 0.0, 1.0);
    }

    if (anySurface) {
        int batchIndex = 0;
        for (int first = 0; first < uLightCount; first += LP_BATCH, ++batchIndex) {
            // 3. This invocation's light against the tile (and on the slice path its slices).
            int current = batchIndex & 1;
            int i = first + int(lid);
            if (i < uLightCount) {
                vec4 b = uLights[i].bound;
                float r = b.w * (1.0 + LP_CLUSTER_MARGIN) + 1e-6;
                bool keep = uUnbounded || sphereTouchesTileFrustum(b.xyz, r, ndcLo, ndcHi, tileNear, tileFar, uProjection);
                uvec2 mask = uvec2(~0u);
                if (keep && sliced) {
                    // Only the occupied slices the sphere's depth extent overlaps.
                    int j0 = max(clusterSliceOf(max(-b.z - r, 0.0)), sliceLo);
                    int j1 = min(clusterSliceOf(-b.z + r), sliceHi);
                    vec4 apex = uLights[i].positionRange, axis = uLights[i].directionCos;
                    mask = uvec2(0u);
                    for (int j = j0; j <= j1; ++j) {
                        uint bit = 1u << uint(j & 31);
                        if ((occupied[j >> 5] & bit) == 0u) continue;
                        if (sphereTouchesTileFrustum(b.xyz, r, ndcLo, ndcHi, uintBitsToFloat(sMinDist[j]),
                                                     uintBitsToFloat(sMaxDist[j]), uProjection) &&
                            clusterLightTouchesBox(b, apex, axis, sBoxLo[j].xyz, sBoxHi[j].xyz)) {
                            if (j < 32) mask.x |= bit;
                            else mask.y |= bit;
                        }
                    }
                    keep = (mask.x | mask.y) != 0u;
                }
                if (keep) {
                    uint at = atomicAdd(sCount[current], 1u);
                    sPositionRange[at] = uLights[i].positionRange;
                    sIntensity[at] = uLights[i].intensity;
                    sDirectionCos[at] = uLights[i].directionCos;
#ifdef LP_SPOT_SHADOWS
                    sShadowLayer[at] = uLights[i].shadow.x;
#endif
                    sSliceMask[at] = mask;
                }
            }
            barrier();
            uint n = sCount[current];
            // The other count is free: every invocation read it before the barrier above, and the
            // next batch adds to it only after the barrier below.
            if (lid == 0u) sCount[current ^ 1] = 0u;
            // 4. Each pixel: the staged lights touching its slice.
            for (int k = 0; k < LP_PIXELS; ++k) {
                if (!surface[k]) continue;
                uint bit = 1u << uint(slice[k] & 31);
                bool high = slice[k] >= 32;
                for (uint e = 0u; e < n; ++e) {
                    if (sliced) {
                        uvec2 m = sSliceMask[e];
                        if (((high ? m.y : m.x) & bit) == 0u) continue;
                    }
                    LpLocalLight l;
                    l.positionRange = sPositionRange[e];
                    l.intensity = sIntensity[e];
                    l.directionCos = sDirectionCos[e];
                    l.bound = vec4(0.0);
#ifdef LP_SPOT_SHADOWS
                    l.shadow = vec4(sShadowLayer[e], 0.0, 0.0, 0.0);
#else
                    l.shadow = vec4(-1.0);
#endif
                    sum[k] += lpShadeLocalLight(l, P[k], N[k], V[k], kd[k], spec[k].rgb, spec[k].a, uSpecularMode);
                }
            }
            barrier();
        }
    }
    // The tiles on each path (LocalLightStats::slicedTiles, tileListTiles).
    if (lid == 0u && anySurface) tallyCounter(sliced ? 0 : 1, 1u);
    finishDispatchCounters();
    for (int k = 0; k < LP_PIXELS; ++k) {
        if (!surface[k]) continue;
        ivec2 p = origin + offset[k];
        imageStore(uHdr, p, vec4(sanitizeHdr(imageLoad(uHdr, p).rgb + sum[k]), 1.0));
    }
}
