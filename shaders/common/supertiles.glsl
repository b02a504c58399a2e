// A tile's candidate lights from light_cluster_supertiles.comp's lists (bindings 6 and 7): the lights
// that can touch its supertile, in index order; or every light, where no lists were built
// (uSupertile 0) or its supertile's list overflowed (a count above uSupertileCapacity). Read by the
// whole-froxel build (light_clusters.comp) and the tiled and clustered shading passes.
#ifndef LP_SUPERTILES_GLSL
#define LP_SUPERTILES_GLSL

layout(std430, binding = 6) readonly buffer SupertileCounts { uint uSupertileCounts[]; };
layout(std430, binding = 7) readonly buffer SupertileLights { uint uSupertileLists[]; };
uniform int uSupertile;          // froxel tiles per supertile side; 0: no lists
uniform int uSupertileCapacity;  // list entries per supertile

struct SupertileCandidates {
    int count;    // candidates to test
    bool listed;  // from the supertile's list (else candidate k is light k)
    uint base;    // the list's first entry
};

// Tile `tile` (of a grid `tilesX` tiles wide) in a pass over lightCount lights.
SupertileCandidates supertileCandidates(ivec2 tile, int tilesX, int lightCount) {
    SupertileCandidates c = SupertileCandidates(lightCount, false, 0u);
    if (uSupertile <= 0) return c;
    ivec2 st = tile / uSupertile;
    int index = st.y * ((tilesX + uSupertile - 1) / uSupertile) + st.x;
    uint n = uSupertileCounts[index];
    c.listed = n <= uint(uSupertileCapacity);
    if (c.listed) c.count = int(n);
    c.base = uint(index) * uint(uSupertileCapacity);
    return c;
}

// The light index of candidate k < c.count.
int supertileCandidate(SupertileCandidates c, int k) { return c.listed ? int(uSupertileLists[c.base + uint(k)]) : k; }

#endif
