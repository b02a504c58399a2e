// One tile of the froxel grid tightened to the G-buffer's depth, in shared memory, for the compute
// passes that cull lights per tile against the depth buffer (local_light_clustered.comp shades with
// it, light_clusters_tight.comp lists from it): per depth slice, the eye-distance range its pixels
// occupy (the froxel tightened to the depth of what it holds: Olsson et al. 2012's compact clusters,
// Harada's 2.5D culling), which slices hold any pixel, and the eye-space box around each occupied
// slice's range. Needs common/clusters.glsl and common/local_light.glsl first.
#ifndef LP_CLUSTER_TILE_GLSL
#define LP_CLUSTER_TILE_GLSL

const int LP_SLICES = 64;  // kMaxClusterSlices

shared uint sMinDist[LP_SLICES], sMaxDist[LP_SLICES];  // float bits of eye distances (order-preserving)
shared uint sOccupied[2];  // a bit per slice holding a pixel
shared vec4 sBoxLo[LP_SLICES], sBoxHi[LP_SLICES];  // each occupied slice's eye-space box

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

// Each occupied slice's eye-space box between its range's ends, invocation `lid` of `invocations`;
// a barrier before clusterLightTouchesSlice.
void clusterTileBoxes(uint lid, uint invocations, vec2 ndcLo, vec2 ndcHi, mat4 projection) {
    for (int j = int(lid); j < uClusterGrid.z; j += int(invocations))
        if (sMinDist[j] <= sMaxDist[j]) {
            vec3 lo, hi;
            clusterTileBox(ndcLo, ndcHi, uintBitsToFloat(sMinDist[j]), uintBitsToFloat(sMaxDist[j]), projection, lo, hi);
            sBoxLo[j] = vec4(lo, 0.0);
            sBoxHi[j] = vec4(hi, 0.0);
        }
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
// clusterLightTouchesBox's) reach occupied slice j? Its tile's side planes passed already, so the
// slice's frustum test is its depth range; then the box around that range.
bool clusterLightTouchesSlice(vec4 b, float r, float dist, vec4 apex, vec4 axis, int j) {
    if (dist + r < uintBitsToFloat(sMinDist[j]) || dist - r > uintBitsToFloat(sMaxDist[j])) return false;
    return clusterLightTouchesBox(b, apex, axis, sBoxLo[j].xyz, sBoxHi[j].xyz);
}

#endif
