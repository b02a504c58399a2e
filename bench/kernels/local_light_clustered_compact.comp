#version 450
// A variant of the clustered kernel measured on the H100 at stop 31 and not kept (bench/results/stop31/),
// run by bench/lighting_clustered.sh's VARIANTS run: `compact`: `compact2` with one buffer (three barriers a
// batch, 2 KB less shared memory).
// Clustered method in one compute pass, fused like the tiled method: one work group per tile of the
// froxel grid (LP_CLUSTER_TILE = uClusterTileSize pixels square):
//  1. its pixels read their G-buffer texels at once (the loads are in flight while shared memory is
//     cleared), find their depth slice and, per slice, the eye-distance range its pixels occupy and
//     which slices hold any pixel at all (common/cluster_tile.glsl);
//  2. per batch of lights (one per invocation), each light is tested against the tile's frustum
//     between the nearest and farthest pixel (the tiled method's test). In a tile that spans depth
//     (a "deep" tile: pixels in more than one slice, the farthest more than LP_CLUSTER_MERGE_RATIO
//     times as far as the nearest) each survivor is then tested against the occupied slices its
//     eye-depth interval can reach (each one's tight depth range, then the eye-space box around it),
//     giving the light a 32-bit mask of the slices it touches, counted from the tile's nearest
//     occupied slice (a tile spanning more than 32 slices shares the last bit among the farthest); a
//     light touching none is dropped. The survivors form one list in light index order, as tiled's,
//     each with its slice mask;
//  3. every pixel walks that list, the same for the whole work group, and in a deep tile skips the
//     lights whose mask lacks its slice: a tile holding a near pillar and a far wall shades neither
//     with the lights in the empty depth between them, and a warp skips a light none of its pixels'
//     slices hold without reading it. A pixel no light adds to leaves its HDR texel alone (neither
//     read nor written).
// Any other tile is one froxel and runs the tiled method's steps exactly: its lights are tiled's.
// The pass writes no froxel lists (nothing reads them after it): light_clusters_tight.comp builds the
// tight lists for the lights-per-cluster view. Unbounded specular reaches every pixel: then every light
// is added.
// Shared memory is kept small (4.6 KB for 16-pixel tiles, the tiled pass's 2.1 KB plus the slices'
// ranges and the masks): on the H100 every KB of it costs these passes speed (bench/results/stop31/).
// Measured there and not kept (bench/results/lighting/clustered/README.md): a bit mask per slice walked
// by each pixel (bench/kernels/local_light_clustered_stop30.comp), sorting a tile's pixels by slice so
// that a warp holds one or two slices, fewer values kept in registers.
#include "common/local_light.glsl"
#include "common/clusters.glsl"
// common/cluster_tile.glsl with each slice's box made where a light is tested (stop 31's variant), inline:
// One tile of the froxel grid tightened to the G-buffer's depth, in shared memory, for the compute
// passes that cull lights per tile against the depth buffer (local_light_clustered.comp shades with
// it, light_clusters_tight.comp lists from it): per depth slice, the eye-distance range its pixels
// occupy (the froxel tightened to the depth of what it holds: Olsson et al. 2012's compact clusters,
// Harada's 2.5D culling) and which slices hold any pixel; the eye-space box around an occupied slice's
// range is made where a light is tested against it, not kept: shared memory is what these passes' speed
// turns on (on the H100 8 KB more of it made the tiled pass 5-14% slower,
// bench/results/stop31/README.md). Needs common/clusters.glsl and common/local_light.glsl first.
#ifndef LP_CLUSTER_TILE_STOP31_GLSL
#define LP_CLUSTER_TILE_STOP31_GLSL

const int LP_SLICES = 64;  // kMaxClusterSlices

shared uint sMinDist[LP_SLICES], sMaxDist[LP_SLICES];  // float bits of eye distances (order-preserving)
shared uint sOccupied[2];  // a bit per slice holding a pixel

// Empties the grid's slices, invocation `lid` of `invocations`; a barrier before clusterTileAddPixel.
void clusterTileClear(uint lid, uint invocations) {
    for (int j = int(lid); j < uClusterGrid.z; j += int(invocations)) {
        sMinDist[j] = floatBitsToUint(3.0e38);
        sMaxDist[j] = 0u;
    }
    if (lid < 2u) sOccupied[lid] = 0u;
}

// A surface pixel at eye distance `dist` >= 0 in slice j widens its range and occupies it.
void clusterTileAddPixel(int j, float dist) {
    // Most pixels of a slice cannot move its range or its bit: a (possibly stale) read first spares
    // their atomics on the one shared word they all hit.
    uint bits = floatBitsToUint(dist);
    if (bits < sMinDist[j]) atomicMin(sMinDist[j], bits);
    if (bits > sMaxDist[j]) atomicMax(sMaxDist[j], bits);
    uint o = 1u << uint(j & 31);
    if ((sOccupied[j >> 5] & o) == 0u) atomicOr(sOccupied[j >> 5], o);
}

// After a barrier: the occupied slices (uniform across the group) and the tile's depth bounds, the
// nearest occupied slice's nearest pixel to the farthest's farthest (occ must not be empty).
uvec2 clusterTileOccupied() { return uvec2(sOccupied[0], sOccupied[1]); }
float clusterTileNear(uvec2 occ) { return uintBitsToFloat(sMinDist[occ.x != 0u ? findLSB(occ.x) : 32 + findLSB(occ.y)]); }
float clusterTileFar(uvec2 occ) { return uintBitsToFloat(sMaxDist[occ.y != 0u ? 32 + findMSB(occ.y) : findMSB(occ.x)]); }

// The eye-space box around the part of tile [ndcLo, ndcHi] between eye distances d0 <= d1: the box
// clusterTileBox makes, to the bit, from the corners that bound it (each coordinate of a corner,
// (ndc + projection[2]) * d / projection's diagonal, is monotone in the corner's NDC and in d, and so
// is its float rounding).
void clusterSliceBox(vec2 ndcLo, vec2 ndcHi, float d0, float d1, mat4 projection, out vec3 lo, out vec3 hi) {
    vec2 nLo = ndcLo + vec2(projection[2][0], projection[2][1]), nHi = ndcHi + vec2(projection[2][0], projection[2][1]);
    vec2 diag = vec2(projection[0][0], projection[1][1]);
    vec2 lo0 = nLo * d0 / diag, lo1 = nLo * d1 / diag, hi0 = nHi * d0 / diag, hi1 = nHi * d1 / diag;
    lo = vec3(min(lo0, lo1), -d1);
    hi = vec3(max(hi0, hi1), -d0);
}

// Bits lo..hi (0 <= lo <= hi < 64) of a 64-bit mask held as two words.
uvec2 sliceRangeBits(int lo, int hi) {
    uvec2 upTo;  // bits 0..hi
    upTo.x = hi >= 31 ? ~0u : (2u << uint(hi)) - 1u;
    upTo.y = hi < 32 ? 0u : (hi >= 63 ? ~0u : (2u << uint(hi - 32)) - 1u);
    uvec2 below;  // bits 0..lo-1
    below.x = lo >= 32 ? ~0u : (1u << uint(lo)) - 1u;
    below.y = lo <= 32 ? 0u : (1u << uint(lo - 32)) - 1u;
    return upTo & ~below;
}

// The slices of `occ` that eye depths [dist - r, dist + r] can reach. clusterSliceOf is monotone up
// to the float logarithm's rounding: one slice more either side, then each slice's own range decides.
uvec2 clusterCandidateSlices(float dist, float r, uvec2 occ) {
    int lo = max(clusterSliceOf(dist - r) - 1, 0), hi = min(clusterSliceOf(dist + r) + 1, uClusterGrid.z - 1);
    return occ & sliceRangeBits(lo, hi);
}

// Does a light (bound b grown to radius r, at eye distance dist = -b.z; apex and axis as
// clusterLightTouchesBox's) reach occupied slice j of tile [ndcLo, ndcHi]? Its tile's side planes
// passed already, so the slice's frustum test is its depth range; then the box around that range.
bool clusterLightTouchesSlice(vec4 b, float r, float dist, vec4 apex, vec4 axis, int j, vec2 ndcLo, vec2 ndcHi,
                              mat4 projection) {
    float d0 = uintBitsToFloat(sMinDist[j]), d1 = uintBitsToFloat(sMaxDist[j]);
    if (dist + r < d0 || dist - r > d1) return false;
    vec3 lo, hi;
    clusterSliceBox(ndcLo, ndcHi, d0, d1, projection, lo, hi);
    return clusterLightTouchesBox(b, apex, axis, lo, hi);
}

#endif
#include "common/tonemap.glsl"
#define LP_GBUFFER_READ
#include "common/gbuffer_layout.glsl"

#ifndef LP_CLUSTER_TILE
#define LP_CLUSTER_TILE 16
#endif
// A tile is culled per slice only when its farthest pixel is more than this many times as far as its
// nearest (and its pixels lie in more than one slice); closer tiles shade as one froxel, the tiled
// method's way. bench/lighting_clustered.sh's VARIANTS run sets it for its merge variants.
#ifndef LP_CLUSTER_MERGE_RATIO
#define LP_CLUSTER_MERGE_RATIO 0.0
#endif
const int LP_TILE = LP_CLUSTER_TILE;
// At most 16 x 16 invocations; a larger tile gives each invocation several pixels, 16 apart.
const int LP_SIDE = LP_TILE < 16 ? LP_TILE : 16;
const int LP_PIXELS_SIDE = (LP_TILE + LP_SIDE - 1) / LP_SIDE;
const int LP_PIXELS = LP_PIXELS_SIDE * LP_PIXELS_SIDE;
const int LP_BATCH = LP_SIDE * LP_SIDE;  // lights per batch: one per invocation
const int LP_WORDS = (LP_BATCH + 31) / 32;  // bit-mask words per batch

layout(local_size_x = LP_SIDE, local_size_y = LP_SIDE) in;
layout(std430, binding = 0) readonly buffer LocalLights { LpLocalLight uLights[]; };
#ifdef LP_SUPERTILES
// Candidates from light_cluster_supertiles.comp's lists. A variant of its own: without them (up to
// 256 lights) the candidate index is the light index.
#include "common/supertiles.glsl"
#endif
layout(rgba16f, binding = 0) uniform image2D uHdr;
uniform int uLightCount;
uniform mat4 uProjection;
uniform ivec2 uImageSize;
uniform bool uUnbounded;     // specular outside the range: every light reaches every pixel
uniform bool uLightingOnly;
uniform int uSpecularMode;

// Two batches' state, alternating (a batch writes one half while the previous batch's half is read or
// cleared), so a batch needs two barriers: after its tests, and after its list.
shared uint sPassed[LP_WORDS];  // a bit per light of the batch that touches the tile
shared uint sList[LP_BATCH];    // the batch's survivors, in index order
shared uint sSliceBits[LP_BATCH];  // deep tiles: each survivor's slices (bit k: slice nearest + k)

// Slice j's bit in a mask counted from slice `nearest` (the farthest share the last bit).
uint sliceBit(int j, int nearest) { return 1u << uint(min(j - nearest, 31)); }

// The occupied slices `occ` of tile [ndcLo, ndcHi] that light i (bound b) touches, as bits counted
// from slice `nearest`: those its eye-depth interval reaches, each by its tight depth range and the box
// around it.
uint slicesTouched(int i, vec4 b, uvec2 occ, int nearest, vec2 ndcLo, vec2 ndcHi) {
    vec4 apex = uLights[i].positionRange, axis = uLights[i].directionCos;
    float r = b.w * (1.0 + LP_CLUSTER_MARGIN) + 1e-6;
    float dist = -b.z;
    uint touched = 0u;
    uvec2 candidates = clusterCandidateSlices(dist, r, occ);
    for (int h = 0; h < 2; ++h)
        for (uint cand = candidates[h]; cand != 0u; cand &= cand - 1u) {
            int j = 32 * h + findLSB(cand);
            if (clusterLightTouchesSlice(b, r, dist, apex, axis, j, ndcLo, ndcHi, uProjection)) touched |= sliceBit(j, nearest);
        }
    return touched;
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

    // 1. Each pixel's G-buffer texels first. Flat-lit pixels are no surface to light (and widen no
    // range).
    bool surface[LP_PIXELS];
    vec3 P[LP_PIXELS], N[LP_PIXELS], kd[LP_PIXELS], V[LP_PIXELS], sum[LP_PIXELS];
    vec4 spec[LP_PIXELS];
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
        sum[k] = vec3(0.0);
        slice[k] = 0;
        if (surface[k]) {
            P[k] = gbufferPosition(p);
            readShadingTexels(p, P[k], N[k], spec[k], kd[k], V[k]);
            slice[k] = clusterSliceOf(max(-P[k].z, 0.0));
        }
    }
    clusterTileClear(lid, uint(LP_BATCH));
    if (lid < uint(LP_WORDS)) sPassed[lid] = 0u;
    barrier();
    for (int k = 0; k < LP_PIXELS; ++k)
        if (surface[k]) clusterTileAddPixel(slice[k], max(-P[k].z, 0.0));
    barrier();
    uvec2 occ = clusterTileOccupied();  // uniform across the group
    if ((occ.x | occ.y) == 0u) return;  // no surface in the tile: nothing to add
    float tileNear = clusterTileNear(occ), tileFar = clusterTileFar(occ);
    // Culled per slice (uniform): more than one occupied slice, far enough apart.
    bool deep = !uUnbounded && bitCount(occ.x) + bitCount(occ.y) > 1 && tileFar > float(LP_CLUSTER_MERGE_RATIO) * tileNear;
    vec2 ndcLo, ndcHi;
    clusterTileNdc(tile, uImageSize, ndcLo, ndcHi);
    int nearest = occ.x != 0u ? findLSB(occ.x) : 32 + findLSB(occ.y);  // the nearest occupied slice
    uint pixelSlices[LP_PIXELS];  // deep tiles: each pixel's slice as its bit of a light's mask
    for (int k = 0; k < LP_PIXELS; ++k) pixelSlices[k] = sliceBit(slice[k], nearest);

    uint word = lid >> 5, bit = 1u << (lid & 31u);
    int part = 0;  // which half of the batch state this batch uses
    // The candidates: the supertile's lights, or every light (no supertiles, an overflowing list).
#ifdef LP_SUPERTILES
    const SupertileCandidates tileCandidates = supertileCandidates(tile, int(gl_NumWorkGroups.x), uLightCount);
    const int candidates = tileCandidates.count;
#else
    const int candidates = uLightCount;
#endif
    for (int first = 0; first < candidates; first += LP_BATCH) {
        int words = 0, list = 0;
        // The other half for the next batch: its last readers (this half's previous batch's list step)
        // finished before the previous batch's second barrier.
        // 2. This invocation's light against the tile, then (deep tiles) against the occupied slices.
        int cand = first + int(lid);  // this invocation's candidate
#ifdef LP_SUPERTILES
        int i = cand < candidates ? supertileCandidate(tileCandidates, cand) : cand;
#else
        int i = cand;
#endif
        bool touches = false;
        uint touched = 0u;
        if (cand < candidates) {
            vec4 b = uLights[i].bound;
            float r = b.w * (1.0 + LP_CLUSTER_MARGIN) + 1e-6;
            touches = uUnbounded || sphereTouchesTileFrustum(b.xyz, r, ndcLo, ndcHi, tileNear, tileFar, uProjection);
            if (touches && deep) {
                touched = slicesTouched(i, b, occ, nearest, ndcLo, ndcHi);
                touches = touched != 0u;
            }
            if (touches) atomicOr(sPassed[words + int(word)], bit);
        }
        barrier();
        // The list in light index order (each light's place: the touching lights before it), so the
        // sum, and so the image, is the same bits on every run and equals the tiled method's.
        uint n = 0u, place = 0u;
        for (int w = 0; w < LP_WORDS; ++w) {
            uint c = uint(bitCount(sPassed[words + w]));
            place += uint(w) < word ? c : 0u;
            n += c;
        }
        if (touches) {
            place += uint(bitCount(sPassed[words + int(word)] & (bit - 1u)));
            sList[list + int(place)] = uint(i);
            sSliceBits[list + int(place)] = touched;
        }
        barrier();
        if (lid < uint(LP_WORDS)) sPassed[lid] = 0u;  // for the next batch: read before the barrier above
        // 3. Each pixel: the list's lights (in a deep tile those of its slice).
        for (int k = 0; k < LP_PIXELS; ++k) {
            if (!surface[k]) continue;
            if (deep) {
                for (uint m = 0u; m < n; ++m)
                    if ((sSliceBits[list + int(m)] & pixelSlices[k]) != 0u)
                        sum[k] += lpShadeLocalLight(uLights[sList[list + int(m)]], P[k], N[k], V[k], kd[k], spec[k].rgb,
                                                    spec[k].a, uSpecularMode);
            } else {
                for (uint m = 0u; m < n; ++m)
                    sum[k] += lpShadeLocalLight(uLights[sList[list + int(m)]], P[k], N[k], V[k], kd[k], spec[k].rgb,
                                                spec[k].a, uSpecularMode);
            }
        }
        barrier();
    }
    for (int k = 0; k < LP_PIXELS; ++k) {
        if (!surface[k]) continue;
        if (sum[k] == vec3(0.0)) continue;  // adds nothing: no read, no write
        ivec2 p = origin + at[k];
        imageStore(uHdr, p, vec4(sanitizeHdr(imageLoad(uHdr, p).rgb + sum[k]), 1.0));
    }
}
