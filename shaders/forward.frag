#version 450
// Forward shading of one surface fragment (passes/forward_pass: forward+'s opaque pass; and, with
// LP_FORWARD_TRANSPARENT, passes/transparent_pass): the material as the G-buffer pass evaluates it
// (common/material.glsl), lit by the suns and their shadows (common/sun_light.glsl), the ambient and
// IBL with ambient occlusion (common/ibl_shading.glsl), the local lights of the fragment's froxel
// (common/local_light.glsl, common/clusters.glsl) and its emission: the same functions the deferred
// light passes call, so both paths shade a surface alike. Transparent fragments write premultiplied
// radiance and coverage for "over" blending (ONE, ONE_MINUS_SRC_ALPHA).
#define LP_SUN_SHADOW_UNIT 10
#define LP_SUN_SHADOW_CONSTANT_SLOTS  // common/sun_light.glsl: no gather through a dynamic sampler index
#include "common/material_uniforms.glsl"
#include "common/sun_light.glsl"
#include "common/ibl_shading.glsl"
#include "common/local_light.glsl"
#include "common/clusters.glsl"
#include "common/tonemap.glsl"

in vec3 vPosition;
in vec3 vNormal;
in vec4 vTangent;
#include "common/vertex_uvs.glsl"
#include "common/vertex_color.glsl"

uniform vec3 uEmission;  // linear radiance (emissiveFactor x strength, or Ke)
uniform bool uHasEmissiveMap;
layout(binding = 6) uniform sampler2D uEmissiveMap;  // sRGB: sampled as linear
uniform bool uIbl;
layout(binding = 7) uniform samplerCube uIrradiance;
layout(binding = 8) uniform samplerCube uPrefiltered;
layout(binding = 9) uniform sampler2D uDfg;
uniform bool uAmbientOcclusion;
layout(binding = 14) uniform sampler2D uAo;  // passes/ambient_occlusion_pass, at the pixel
uniform bool uLightingOnly;  // the lighting view: white albedo, no emission
layout(std430, binding = 0) readonly buffer LocalLights { LpLocalLight uLights[]; };
layout(std430, binding = 1) readonly buffer ClusterCounts { uint uCounts[]; };
layout(std430, binding = 2) readonly buffer ClusterLights { uint uLists[]; };
uniform int uLocalLightCount;  // 0: none this frame
uniform bool uUnbounded;       // unranged specular reaches every pixel: every light is added
uniform int uSpecularMode;

layout(location = 0) out vec4 outHdr;

void main() {
    // Derivatives before any discard (they need the whole quad).
    UvSets uvs = fragmentUvSets();
    if (lpMaterialDiscards(uvs, vColor, gl_FrontFacing)) discard;
    LpSurface s = lpEvaluateSurface(vPosition, vNormal, vTangent, uvs, vColor, gl_FrontFacing);
#ifdef LP_FORWARD_TRANSPARENT
    float alpha = s.alpha;
    if (alpha <= 0.0) discard;
#else
    float alpha = 1.0;
#endif
    if (!uLightingOnly && uFlat) {  // flat-lit: its colour, no light
        outHdr = vec4(sanitizeHdr(s.kd) * alpha, alpha);
        return;
    }
    vec3 P = vPosition;
    vec3 N = s.N;
    float pl = length(P);
    vec3 V = pl > 0.0 ? -P / pl : vec3(0.0, 0.0, 1.0);
    vec3 kd = uLightingOnly ? vec3(1.0) : s.kd;
    float occlusion = uLightingOnly ? 1.0 : s.occlusion;
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    float screenAo = uAmbientOcclusion ? texelFetch(uAo, pixel, 0).r : 1.0;
    vec3 c = uAmbient * kd * screenAo * occlusion;  // occlusion darkens ambient light only
    c += lpSunRadiance(P, N, V, kd, s.fresnel, s.shininess, vec2(pixel), s.coat);
    if (uIbl)
        c += lpIblRadiance(uIrradiance, uPrefiltered, uDfg, N, V, kd, s.fresnel, s.shininess, occlusion, screenAo,
                           uAmbientOcclusion, s.coat);
    if (uLocalLightCount > 0) {
        if (uUnbounded) {
            for (int i = 0; i < uLocalLightCount; ++i)
                c += lpShadeLocalLight(uLights[i], P, N, V, kd, s.fresnel, s.shininess, uSpecularMode, s.coat);
        } else {
            int cluster = clusterIndex(ivec3(pixel / uClusterTileSize, clusterSliceOf(-P.z)));
            uint n = min(uCounts[cluster], LP_MAX_LIGHTS_PER_CLUSTER);
            uint base = uint(cluster) * LP_MAX_LIGHTS_PER_CLUSTER;
            for (uint k = 0u; k < n; ++k)
                c += lpShadeLocalLight(uLights[uLists[base + k]], P, N, V, kd, s.fresnel, s.shininess, uSpecularMode, s.coat);
        }
    }
    if (!uLightingOnly && (uHiddenTerms & LP_HIDE_EMISSION) == 0) {
        vec3 e = max(uEmission, vec3(0.0));
        if (uHasEmissiveMap) e *= texture(uEmissiveMap, fragmentUv((uSecondUvMaps & LP_MAP_EMISSIVE) != 0u)).rgb;
        c += e * (1.0 - s.coat.weight);  // KHR_materials_clearcoat: the coat lies over the emission too
    }
    outHdr = vec4(sanitizeHdr(c) * alpha, alpha);
}
