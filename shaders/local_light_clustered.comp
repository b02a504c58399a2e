#version 450
// Clustered method, shading: each pixel finds its froxel (its tile, and the slice of its eye
// distance) and adds the lights listed there (at most the cap). The grid is light_clusters.comp's,
// built earlier in the same pass. Unbounded specular reaches every pixel: then every light is added.
#include "common/local_light.glsl"
#include "common/clusters.glsl"
#include "common/tonemap.glsl"
#define LP_GBUFFER_READ
#include "common/gbuffer_layout.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 0) readonly buffer LocalLights { LpLocalLight uLights[]; };
layout(std430, binding = 1) readonly buffer ClusterCounts { uint uCounts[]; };
layout(std430, binding = 2) readonly buffer ClusterLights { uint uLists[]; };
layout(rgba16f, binding = 0) uniform image2D uHdr;
uniform int uLightCount;
uniform bool uUnbounded;
uniform bool uLightingOnly;
uniform int uSpecularMode;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uHdr);
    if (p.x >= size.x || p.y >= size.y) return;
    if (gbufferIsBackground(p) || (!uLightingOnly && gbufferIsFlat(p))) return;
    vec3 P = gbufferPosition(p);
    vec3 N = gbufferNormal(p);
    vec4 spec = vec4(gbufferSpecular(p), gbufferShininess(p));
    vec3 kd = uLightingOnly ? vec3(1.0) : gbufferDiffuse(p);
    float pl = length(P);
    vec3 V = pl > 0.0 ? -P / pl : vec3(0.0, 0.0, 1.0);
    vec3 sum = vec3(0.0);
    if (uUnbounded) {
        for (int i = 0; i < uLightCount; ++i)
            sum += lpShadeLocalLight(uLights[i], P, N, V, kd, spec.rgb, spec.a, uSpecularMode);
    } else {
        int cluster = clusterIndex(ivec3(p / uClusterTileSize, clusterSliceOf(-P.z)));
        uint n = min(uCounts[cluster], LP_MAX_LIGHTS_PER_CLUSTER);
        uint base = uint(cluster) * LP_MAX_LIGHTS_PER_CLUSTER;
        for (uint k = 0u; k < n; ++k)
            sum += lpShadeLocalLight(uLights[uLists[base + k]], P, N, V, kd, spec.rgb, spec.a, uSpecularMode);
    }
    imageStore(uHdr, p, vec4(sanitizeHdr(imageLoad(uHdr, p).rgb + sum), 1.0));
}
