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

#endif
