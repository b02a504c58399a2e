// Image-based lighting of one surface point, shared by the deferred ibl pass and the forward passes:
// diffuse kd w E / pi from the SH (or the irradiance cube) and specular
// prefiltered(R, roughness) * Fss, Fss = F0 A + f90 B from the DFG LUT (splitSumReflectance), the
// prefiltered mip from the perceptual roughness (prefilteredLodFromRoughness); or, with
// uSpecularSamples > 0 (--ibl-specular sampled), F0 A La + f90 B Lb with La, Lb the lobe-weighted
// radiance of that many per-pixel GGX samples (common/ibl_sampled.glsl). The diffuse weight w: under
// GGX (the glTF BRDF), the diffuse layer's 1 - F(V.H) averaged over a uniform light,
// ggxDiffuseFresnelMeanWeight (kd already holds the 1 - F0: common/brdf.glsl), which is what the
// spec's BRDF reflects from a uniform environment (a path tracer of it gives exactly that). Filament
// and the Khronos sample viewer weight the diffuse by 1 - Fss instead (the mixed F0's in Filament, the
// dielectric's in the viewer): an energy balance, not the spec's BRDF integrated, which darkens a
// smooth dielectric's rim against that path tracer (F0 0.04: x0.57 at N.V 0.15 and roughness 0.1, x0.93
// at N.V 0.4; x1.03 at roughness 1 head-on). Under Blinn-Phong w stays 1 - Fss (a white material in a
// white furnace reflects exactly 1). Plus the sources extracted
// from the map at bake time, as distant discs with the GGX BRDF itself (common/ibl_lights.glsl). The samplers are the includer's
// (their units differ between passes); the environment's other inputs are these uniforms.
#ifndef LP_IBL_SHADING_GLSL
#define LP_IBL_SHADING_GLSL
#include "common/ambient_occlusion.glsl"
#include "common/ibl.glsl"
#include "common/ibl_sampled.glsl"
#include "common/ibl_lights.glsl"

uniform vec3 uSh[9];
uniform bool uDiffuseFromCube;
uniform mat3 uEyeToWorld;
uniform float uIntensity;
uniform float uMaxLod;        // prefiltered levels - 1
uniform int uSpecularSamples;  // 0: split sum; n: the sampled specular with n samples a pixel
// Sources taken out of the map at bake time (--ibl-extract-lights), lit by common/ibl_lights.glsl.
#define LP_MAX_IBL_LIGHTS 4
uniform int uIblLightCount;
uniform vec3 uIblLightDirection[LP_MAX_IBL_LIGHTS];   // towards the source, world space, unit
uniform vec3 uIblLightIrradiance[LP_MAX_IBL_LIGHTS];  // E at normal incidence, without uIntensity
uniform float uIblLightSinRadius[LP_MAX_IBL_LIGHTS];  // sin of the source's angular radius

// Radiance the environment reflects at a point with eye-space normal N and view direction V.
// `occlusion`: the material's; `screenAo`: the ambient-occlusion pass's (1 without it), and whether
// that pass ran (then the specular term is darkened by the specular occlusion derived from both).
// `coat`: KHR_materials_clearcoat's layer (kd and f0 already the base under it): its own split sum,
// w prefiltered(Rc, coat roughness) (A + B)(Nc.V) (the lobe has no Fresnel inside: F0 = f90 = 1), and
// the extracted sources through its lobe.
vec3 lpIblClearcoatRadiance(samplerCube prefilteredMap, sampler2D dfg, ClearcoatLayer coat, vec3 V, float ao,
                            float occlusion, bool aoOn) {
    if (coat.weight <= 0.0) return vec3(0.0);
    vec3 Nc = coat.normal;
    float ncv = clamp(dot(Nc, V), 0.0, 1.0);
    float roughness = sqrt(coat.alpha);
    vec3 R = specularDominantDirection(Nc, 2.0 * dot(Nc, V) * Nc - V, coat.alpha);
    vec2 ab = textureLod(dfg, dfgLutCoordinate(ncv, roughness, textureSize(dfg, 0).x), 0.0).rg;
    vec3 specular = textureLod(prefilteredMap, normalize(uEyeToWorld * R), prefilteredLodFromRoughness(roughness, uMaxLod)).rgb *
                    (ab.x + ab.y);
    float specularAo = aoOn ? specularOcclusion(ncv, ao, coat.alpha) : occlusion;
    vec3 lights = vec3(0.0);
    for (int i = 0; i < min(uIblLightCount, LP_MAX_IBL_LIGHTS); ++i) {
        vec3 D = uIblLightDirection[i] * uEyeToWorld;
        float vh;
        lights += environmentLightLobe(Nc, V, D, uIblLightSinRadius[i], coat.alpha, vh) * max(dot(Nc, D), 0.0) *
                  uIblLightIrradiance[i];
    }
    return coat.weight * specularAo * (specular + lights) * lpClearcoatShown();
}

// `Ng`: the geometric normal (eye space, unit, on the viewer's side; the caller's lpIblFaceNormal or its
// triangle's): light from below it cannot reach the surface, whatever the normal map says. The sampled
// specular and the extracted sources are cut there, as the path tracer cuts its paths, where a map bends
// N more than 25 degrees from it; within that, N and Ng differ by the tessellation (a coarse sphere's
// facets, whose planes are not the surface, and the deferred pass's Ng from the depth of neighbours
// across them: up to 20 degrees on scenes/ibl-spheres.json at 96 x 64), and nothing is cut (Ng = N
// cuts nothing): a cut there would differ between forward+ and deferred by 3%.
const float LP_IBL_HORIZON_MIN_BEND_COS = 0.906;  // cos 25 degrees
vec3 iblHorizonNormal(vec3 N, vec3 Ng) { return dot(N, Ng) < LP_IBL_HORIZON_MIN_BEND_COS ? Ng : N; }
vec3 lpIblRadiance(samplerCube irradiance, samplerCube prefilteredMap, sampler2D dfg, vec3 N, vec3 Ng, vec3 V, vec3 kd,
                   FresnelEnds f0, float shininess, float occlusion, float screenAo, bool aoOn, ClearcoatLayer coat) {
    float NdotV = clamp(dot(N, V), 0.0, 1.0);
    float roughness = roughnessFromShininess(shininess);
    Ng = iblHorizonNormal(N, Ng);
    // The prefiltered chain assumes N = V = R; for rough lobes the reflected energy leans from R
    // towards N (Frostbite's dominant direction, Lagarde & de Rousiers 2014), which matters at grazing
    // angles where R skims the horizon of the map.
    vec3 R = specularDominantDirection(N, 2.0 * dot(N, V) * N - V, roughness * roughness);
    vec3 Nw = normalize(uEyeToWorld * N), Rw = normalize(uEyeToWorld * R);
    vec3 E = uDiffuseFromCube ? textureLod(irradiance, Nw, 0.0).rgb : shIrradiance(uSh, Nw);
    vec2 ab = textureLod(dfg, dfgLutCoordinate(NdotV, roughness, textureSize(dfg, 0).x), 0.0).rg;
    vec3 fss = splitSumReflectance(f0, ab);
    vec3 la, lb;
    bool sampled = uSpecularSamples > 0 &&
                   sampledSpecularRadiance(prefilteredMap, uMaxLod, Nw, normalize(uEyeToWorld * Ng), normalize(uEyeToWorld * V),
                                           roughness * roughness,
                                           uSpecularSamples, uSpecularMasking, la, lb);
    vec3 specular = sampled ? f0.f0 * ab.x * la + f0.f90 * ab.y * lb
                            : textureLod(prefilteredMap, Rw, prefilteredLodFromRoughness(roughness, uMaxLod)).rgb * fss;
    float ao = screenAo * occlusion;
    float specularAo = aoOn ? specularOcclusion(NdotV, ao, roughness * roughness) : occlusion;
    vec3 lights = vec3(0.0);
    for (int i = 0; i < min(uIblLightCount, LP_MAX_IBL_LIGHTS); ++i) {
        vec3 D = uIblLightDirection[i] * uEyeToWorld;  // world -> eye: uEyeToWorld is a rotation
        if (dot(Ng, D) <= 0.0) continue;  // below the geometric surface
        lights += environmentLightRadiance(N, V, D, uIblLightSinRadius[i], uIblLightIrradiance[i], kd, f0,
                                           roughness * roughness, fss, ao, specularAo);
    }
    vec3 diffuseWeight = uBrdf == LP_BRDF_BLINN_PHONG ? 1.0 - fss : ggxDiffuseFresnelMeanWeight(f0, NdotV);
    return uIntensity * (ao * kd * diffuseWeight * E / LP_IBL_PI + specularAo * specular * lpSpecularShown() + lights +
                         lpIblClearcoatRadiance(prefilteredMap, dfg, coat, V, ao, occlusion, aoOn));
}
vec3 lpIblRadiance(samplerCube irradiance, samplerCube prefilteredMap, sampler2D dfg, vec3 N, vec3 V, vec3 kd,
                   FresnelEnds f0, float shininess, float occlusion, float screenAo, bool aoOn, ClearcoatLayer coat) {
    return lpIblRadiance(irradiance, prefilteredMap, dfg, N, N, V, kd, f0, shininess, occlusion, screenAo, aoOn, coat);
}
vec3 lpIblRadiance(samplerCube irradiance, samplerCube prefilteredMap, sampler2D dfg, vec3 N, vec3 V, vec3 kd,
                   FresnelEnds f0, float shininess, float occlusion, float screenAo, bool aoOn) {
    return lpIblRadiance(irradiance, prefilteredMap, dfg, N, N, V, kd, f0, shininess, occlusion, screenAo, aoOn, noClearcoat());
}

// The geometric normal of a surface point from the eye-space position P at it and its derivatives
// across the screen (a face normal: where they span no plane, N), turned to the viewer's side V: the
// Ng of lpIblRadiance.
vec3 lpIblFaceNormal(vec3 dPdx, vec3 dPdy, vec3 N, vec3 V) {
    vec3 c = cross(dPdx, dPdy);
    float l = length(c);
    if (!(l > 1e-30)) return N;
    c /= l;
    return dot(c, V) < 0.0 ? -c : c;
}

#endif
