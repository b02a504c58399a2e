#version 450
// Image-based lighting added into the HDR buffer: diffuse kd (1 - Fss) E / pi from the SH (or the
// irradiance cube) and specular prefiltered(R, roughness) * Fss, Fss = F0 A + f90 B from the DFG LUT
// (F0 = the material's specular colour, f90 as in the analytic GGX: Ks = 0 is exactly Lambertian).
// The (1 - Fss) keeps a white surface in a white environment at exactly the environment's radiance
// (white furnace). With ambient occlusion on, the diffuse term is multiplied by the AO and the
// specular by the specular occlusion derived from it.
#include "common/ambient_occlusion.glsl"
#include "common/ibl.glsl"
#include "common/tonemap.glsl"
#define LP_GBUFFER_READ
#include "common/gbuffer_layout.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 7) uniform samplerCube uIrradiance;
layout(binding = 8) uniform samplerCube uPrefiltered;
layout(binding = 9) uniform sampler2D uDfg;
layout(rgba16f, binding = 0) uniform image2D uHdr;

uniform vec3 uSh[9];
uniform bool uDiffuseFromCube;
uniform mat3 uEyeToWorld;
uniform float uIntensity;
uniform float uMaxLod;        // prefiltered levels - 1
uniform bool uLightingOnly;   // debug: white albedo
layout(binding = 14) uniform sampler2D uAo;  // passes/ambient_occlusion_pass
uniform bool uAmbientOcclusion;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uHdr);
    if (p.x >= size.x || p.y >= size.y) return;
    if (gbufferIsBackground(p)) return;
    if (!uLightingOnly && gbufferIsFlat(p)) return;  // flat-lit: no light adds to it
    vec3 N = gbufferNormal(p);
    vec3 P = gbufferPosition(p);
    vec4 spec = vec4(gbufferSpecular(p), gbufferShininess(p));
    vec3 kd = uLightingOnly ? vec3(1.0) : gbufferDiffuse(p);
    float pl = length(P);
    vec3 V = pl > 0.0 ? -P / pl : vec3(0.0, 0.0, 1.0);
    float NdotV = clamp(dot(N, V), 0.0, 1.0);
    float roughness = roughnessFromShininess(spec.a);
    // The prefiltered chain assumes N = V = R; for rough lobes the reflected energy leans from R
    // towards N (Frostbite's dominant direction, Lagarde & de Rousiers 2014), which matters at grazing
    // angles where R skims the horizon of the map.
    vec3 R = specularDominantDirection(N, 2.0 * dot(N, V) * N - V, roughness * roughness);
    vec3 Nw = normalize(uEyeToWorld * N), Rw = normalize(uEyeToWorld * R);
    vec3 E = uDiffuseFromCube ? textureLod(uIrradiance, Nw, 0.0).rgb : shIrradiance(uSh, Nw);
    vec2 ab = textureLod(uDfg, dfgLutCoordinate(NdotV, roughness, textureSize(uDfg, 0).x), 0.0).rg;
    vec3 fss = splitSumReflectance(spec.rgb, ab);
    vec3 prefiltered = textureLod(uPrefiltered, Rw, prefilteredLodFromRoughness(roughness, uMaxLod)).rgb;
    float occlusion = uLightingOnly ? 1.0 : gbufferOcclusion(p);  // the material's ambient occlusion
    float ao = (uAmbientOcclusion ? texelFetch(uAo, p, 0).r : 1.0) * occlusion;
    float specularAo = uAmbientOcclusion ? specularOcclusion(NdotV, ao, roughness * roughness) : occlusion;
    vec3 c = uIntensity * (ao * kd * (1.0 - fss) * E / LP_IBL_PI + specularAo * prefiltered * fss);
    vec3 hdr = imageLoad(uHdr, p).rgb;
    imageStore(uHdr, p, vec4(sanitizeHdr(hdr + c), 1.0));
}
