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

#ifdef LP_FORWARD_TRANSMISSION
// KHR_materials_transmission + KHR_materials_volume on a rasteriser (the glTF sample viewer's model):
// the opaque frame behind (passes/transparent_pass's transmission_background copy, mip-mapped) seen
// through the surface along the refracted ray.
#define LP_TRANSMISSION_BACKGROUND_UNIT 23
#define LP_TRANSMISSION_MAP_UNIT 24
#define LP_THICKNESS_MAP_UNIT 25
layout(binding = LP_TRANSMISSION_BACKGROUND_UNIT) uniform sampler2D uTransmissionBackground;  // linear HDR
layout(binding = LP_TRANSMISSION_MAP_UNIT) uniform sampler2D uTransmissionMap;  // transmission in r
layout(binding = LP_THICKNESS_MAP_UNIT) uniform sampler2D uThicknessMap;        // thickness in g
uniform float uTransmission;  // transmissionFactor (0: the material does not transmit)
uniform bool uHasTransmissionMap;
uniform float uThickness;     // thicknessFactor, model space (0: thin-walled)
uniform bool uHasThicknessMap;
uniform float uIor;
uniform vec3 uAttenuationColor;
uniform float uAttenuationDistance;  // 0: infinite (no absorption)
uniform mat4 uProjection;            // gbuffer.vert's: the exit point onto the screen
uniform mat3 uNormalMatrix;          // gbuffer.vert's: inverse(model-view) = transpose(uNormalMatrix)

// The radiance the surface passes through from behind (without the transmission weight): the
// refracted ray (Snell, 1 / ior, eye space) crosses the volume as a slab of its thickness under the
// surface (model space along the normal, scaled by the model there: thin-walled at 0, no offset), so
// it travels thickness / cos(theta_t) and a flat slab shifts what is behind by Snell's lateral offset
// t sin(theta - theta_t) / cos(theta_t) (the sample viewer travels the thickness itself, the same at
// normal incidence); its exit point projected to the screen reads the background at a level of detail
// from the roughness widened by the IOR (the sample viewer's applyIorToRoughness); Beer-Lambert
// absorption over the distance; tinted by the base colour and weighted by 1 - the specular
// reflectance the surface takes first (its directional albedo: the DFG LUT's split sum with IBL on,
// Schlick at N.V without).
vec3 lpTransmittedRadiance(vec3 P, vec3 N, vec3 V, LpSurface s, float thickness) {
    float ior = max(uIor, 1.0);
    vec3 ray = refract(-V, N, 1.0 / ior);
    float rl = length(ray);
    ray = rl > 0.0 ? ray / rl : -V;
    // inverse(model-view) N = transpose(uNormalMatrix) N: its length is 1 / the model's scale along N.
    float depth = thickness / max(length(N * uNormalMatrix), 1e-12);
    vec3 travel = ray * (depth / max(dot(ray, -N), 1e-3));
    vec4 clip = uProjection * vec4(P + travel, 1.0);
    vec2 uv = clip.w > 0.0 ? clip.xy / clip.w * 0.5 + 0.5 : gl_FragCoord.xy / vec2(textureSize(uTransmissionBackground, 0));
    float roughness = roughnessFromShininess(s.shininess);
    float lod = log2(float(textureSize(uTransmissionBackground, 0).x)) * roughness * clamp(ior * 2.0 - 2.0, 0.0, 1.0);
    vec3 behind = textureLod(uTransmissionBackground, uv, lod).rgb;
    if (uAttenuationDistance > 0.0)
        behind *= pow(max(uAttenuationColor, vec3(0.0)), vec3(length(travel) / uAttenuationDistance));
    float NdotV = clamp(dot(N, V), 0.0, 1.0);
    vec3 reflected = fresnelSchlick(s.fresnel, NdotV);
    if (uIbl) reflected = splitSumReflectance(s.fresnel, textureLod(uDfg, dfgLutCoordinate(NdotV, roughness, textureSize(uDfg, 0).x), 0.0).rg);
    return (vec3(1.0) - clamp(reflected, 0.0, 1.0)) * s.baseColor * sanitizeHdr(behind);
}
#endif

void main() {
    // Derivatives before any discard (they need the whole quad).
    UvSets uvs = fragmentUvSets();
    vec3 dPdx = dFdx(vPosition), dPdy = dFdy(vPosition);  // the triangle's plane: the IBL's geometric normal
    if (lpMaterialDiscards(uvs, vColor, gl_FrontFacing)) discard;
    LpSurface s = lpEvaluateSurface(vPosition, vNormal, vTangent, uvs, vColor, gl_FrontFacing);
#ifdef LP_FORWARD_TRANSMISSION
    // The dielectric base's share that refracts (metals do not transmit); a volume is drawn by its
    // entry surface alone (the thickness stands for what lies behind it).
    float transmission = uTransmission * (1.0 - s.metallic);
    if (uHasTransmissionMap)
        transmission *= texture(uTransmissionMap, fragmentUv((uSecondUvMaps & LP_MAP_TRANSMISSION) != 0u)).r;
    transmission = clamp(transmission, 0.0, 1.0);
    float thickness = uThickness;
    if (uHasThicknessMap) thickness *= texture(uThicknessMap, fragmentUv((uSecondUvMaps & LP_MAP_THICKNESS) != 0u)).g;
    if (uTransmission > 0.0 && uThickness > 0.0 && !gl_FrontFacing) discard;
#endif
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
#ifdef LP_FORWARD_TRANSMISSION
    // glTF's dielectric base: mix(diffuse BRDF, specular BTDF, transmission) under the same Fresnel layer.
    kd *= 1.0 - transmission;
#endif
    float occlusion = uLightingOnly ? 1.0 : s.occlusion;
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    float screenAo = uAmbientOcclusion ? texelFetch(uAo, pixel, 0).r : 1.0;
    vec3 c = uAmbient * kd * screenAo * occlusion;  // occlusion darkens ambient light only
    c += lpSunRadiance(P, N, V, kd, s.fresnel, s.shininess, vec2(pixel), s.coat);
    if (uIbl)
        c += lpIblRadiance(uIrradiance, uPrefiltered, uDfg, N, lpIblFaceNormal(dPdx, dPdy, N, V), V, kd, s.fresnel, s.shininess, occlusion, screenAo,
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
#ifdef LP_FORWARD_TRANSMISSION
    if (!uLightingOnly && transmission > 0.0 && (uHiddenTerms & LP_HIDE_DIFFUSE) == 0)
        c += transmission * (1.0 - s.coat.weight) * lpTransmittedRadiance(P, N, V, s, thickness);
#endif
    outHdr = vec4(sanitizeHdr(c) * alpha, alpha);
}
