#version 450
// The lights-per-cluster view over the finished image: per tile, the light count of the froxel in
// slice uSlice (or, with uSlice < 0, the most over all slices) as a heat map, blue (1) to red
// (uHeatMax or more); no light: the image at half brightness; a cluster past the cap: magenta.
// A legend along the bottom-left: the colour ramp from 0 to uHeatMax with a dark notch every 8 lights.
#include "common/clusters.glsl"
#include "common/heatmap.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 1) readonly buffer ClusterCounts { uint uCounts[]; };
layout(rgba16f, binding = 0) uniform image2D uHdr;
uniform int uSlice;
uniform float uHeatMax;
uniform float uExposure;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uHdr);
    if (p.x >= size.x || p.y >= size.y) return;
    vec3 scene = tonemapLightpass(applyExposure(imageLoad(uHdr, p).rgb, uExposure));
    // Legend: 4 px from the bottom-left corner, 8 px tall, up to 256 px (or half the image) wide.
    int legendWidth = min(256, size.x / 2);
    ivec2 q = p - ivec2(4);
    if (q.x >= 0 && q.x < legendWidth && q.y >= 0 && q.y < 8) {
        float lights = (float(q.x) + 0.5) / float(legendWidth) * uHeatMax;
        bool notch = int(lights / 8.0) != int((float(q.x) - 0.5) / float(legendWidth) * uHeatMax / 8.0);
        vec3 y = notch ? vec3(0.0) : heatColour(lights / uHeatMax);
        imageStore(uHdr, p, vec4(sanitizeHdr(heatUntonemap(y, uExposure)), 1.0));
        return;
    }
    ivec2 tile = p / uClusterTileSize;
    uint count = 0u;
    if (uSlice >= 0) {
        count = uCounts[clusterIndex(ivec3(tile, min(uSlice, uClusterGrid.z - 1)))];
    } else {
        for (int k = 0; k < uClusterGrid.z; ++k) count = max(count, uCounts[clusterIndex(ivec3(tile, k))]);
    }
    vec3 y;
    if (count == 0u) y = 0.5 * scene;
    else if (count > LP_MAX_LIGHTS_PER_CLUSTER) y = mix(scene, vec3(1.0, 0.0, 1.0), 0.8);
    else y = mix(scene, heatColour(float(count) / uHeatMax), 0.6);
    imageStore(uHdr, p, vec4(sanitizeHdr(heatUntonemap(y, uExposure)), 1.0));
}
