// The froxel grid of the clustered method (engine/render/light_clusters.hpp is its CPU twin):
// tiles of uClusterTileSize pixels x uClusterSlices exponential depth slices between uClusterNear
// and uClusterFar; per cluster a count (uncapped) and up to LP_MAX_LIGHTS_PER_CLUSTER light indices.
#ifndef LP_CLUSTERS_GLSL
#define LP_CLUSTERS_GLSL

const uint LP_MAX_LIGHTS_PER_CLUSTER = 256u;  // kMaxLightsPerCluster

uniform ivec3 uClusterGrid;       // tiles x, tiles y, slices
uniform int uClusterTileSize;     // pixels
uniform float uClusterNear, uClusterFar;

// The slice holding eye distance d, clamped to the grid.
int clusterSliceOf(float d) {
    float s = log(max(d, 1e-30) / uClusterNear) / log(uClusterFar / uClusterNear) * float(uClusterGrid.z);
    return clamp(int(floor(s)), 0, uClusterGrid.z - 1);
}

// Eye distance where slice k begins.
float clusterSliceStart(int k) {
    return uClusterNear * pow(uClusterFar / uClusterNear, float(k) / float(uClusterGrid.z));
}

int clusterIndex(ivec3 c) { return (c.z * uClusterGrid.y + c.y) * uClusterGrid.x + c.x; }

// Growth of every light bound in a froxel test: 0.1% (+ 1 um), so float rounding never drops a light
// that reaches a froxel.
const float LP_CLUSTER_MARGIN = 1e-3;

// Does a light reach into the eye-space box [lo, hi] (a froxel, or the part of one its pixels
// occupy)? Its bounding sphere `bound` (xyz centre, w radius) against the box and, for a spot
// (axis.w = cos(outer) >= -1; apex xyz position, w range), its cone against the sphere around the
// box (Wronski, "Cull that cone", 2017). Conservative; lp::lightTouchesFroxel is its double twin.
bool clusterLightTouchesBox(vec4 bound, vec4 apex, vec4 axis, vec3 lo, vec3 hi) {
    float r = bound.w * (1.0 + LP_CLUSTER_MARGIN) + 1e-6;
    vec3 off = bound.xyz - clamp(bound.xyz, lo, hi);
    if (dot(off, off) > r * r) return false;
    if (axis.w < -1.0) return true;
    vec3 centre = 0.5 * (lo + hi);
    float radius = 0.5 * length(hi - lo) * (1.0 + LP_CLUSTER_MARGIN) + 1e-6;
    vec3 v = centre - apex.xyz;
    float along = dot(v, axis.xyz);
    float sinOuter = sqrt(max(1.0 - axis.w * axis.w, 0.0));
    float toSurface = axis.w * sqrt(max(dot(v, v) - along * along, 0.0)) - along * sinOuter;
    float range = apex.w * (1.0 + LP_CLUSTER_MARGIN);
    return !(toSurface > radius || along > radius + range || along < -radius);
}

// Eye-space box around the part of tile [ndcLo, ndcHi] between eye distances d0 and d1: its 8
// corners on the rays through the tile's corners at both distances. `projection` as the camera's.
void clusterTileBox(vec2 ndcLo, vec2 ndcHi, float d0, float d1, mat4 projection, out vec3 lo, out vec3 hi) {
    lo = vec3(3.0e38);
    hi = vec3(-3.0e38);
    for (int e = 0; e < 2; ++e) {
        float d = e == 0 ? d0 : d1;
        for (int q = 0; q < 4; ++q) {
            vec2 ndc = vec2((q & 1) == 0 ? ndcLo.x : ndcHi.x, (q & 2) == 0 ? ndcLo.y : ndcHi.y);
            vec3 p = vec3((ndc.x + projection[2][0]) * d / projection[0][0],
                          (ndc.y + projection[2][1]) * d / projection[1][1], -d);
            lo = min(lo, p);
            hi = max(hi, p);
        }
    }
}

// Tile t's NDC rectangle (the last tile stops at the image's edge).
void clusterTileNdc(ivec2 t, ivec2 imageSize, out vec2 ndcLo, out vec2 ndcHi) {
    ndcLo = vec2(t * uClusterTileSize) / vec2(imageSize) * 2.0 - 1.0;
    ndcHi = vec2(min((t + 1) * uClusterTileSize, imageSize)) / vec2(imageSize) * 2.0 - 1.0;
}

#endif
