#version 450
// Image-based lighting added into the HDR buffer: diffuse kd (1 - Fss) E / pi from the SH (or the
// irradiance cube) and specular prefiltered(R, roughness) * Fss, Fss = F0 A + B from the DFG LUT
// (F0 = the material's specular colour). The (1 - Fss) keeps a white surface in a white
// environment at exactly the environment's radiance (white furnace).
#include "common/ibl.glsl"
#include "common/tonemap.glsl"
#include "common/gbuffer_layout.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = LP_BIND_DEPTH) uniform sampler2D uDepth;
layout(binding = LP_BIND_NORMAL) uniform sampler2D uNormal;
layout(binding = LP_BIND_DIFFUSE) uniform sampler2D uDiffuse;
layout(binding = LP_BIND_POSITION) uniform sampler2D uPosition;
layout(binding = LP_BIND_SPECULAR) uniform sampler2D uSpecular;
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

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uHdr);
    if (p.x >= size.x || p.y >= size.y) return;
    if (texelFetch(uDepth, p, 0).r >= 1.0) return;
    vec3 N = texelFetch(uNormal, p, 0).xyz;
    vec3 P = texelFetch(uPosition, p, 0).xyz;
    vec4 spec = texelFetch(uSpecular, p, 0);
    vec3 kd = uLightingOnly ? vec3(1.0) : texelFetch(uDiffuse, p, 0).rgb;
    float pl = length(P);
    vec3 V = pl > 0.0 ? -P / pl : vec3(0.0, 0.0, 1.0);
    float NdotV = clamp(dot(N, V), 0.0, 1.0);
    vec3 R = 2.0 * dot(N, V) * N - V;
    vec3 Nw = normalize(uEyeToWorld * N), Rw = normalize(uEyeToWorld * R);
    vec3 E = uDiffuseFromCube ? textureLod(uIrradiance, Nw, 0.0).rgb : shIrradiance(uSh, Nw);
    float roughness = roughnessFromShininess(spec.a);
    vec2 ab = textureLod(uDfg, vec2(NdotV, roughness), 0.0).rg;
    vec3 fss = spec.rgb * ab.x + ab.y;
    vec3 prefiltered = textureLod(uPrefiltered, Rw, roughness * uMaxLod).rgb;
    vec3 c = uIntensity * (kd * (1.0 - fss) * E / LP_IBL_PI + prefiltered * fss);
    vec3 hdr = imageLoad(uHdr, p).rgb;
    imageStore(uHdr, p, vec4(sanitizeHdr(hdr + c), 1.0));
}
