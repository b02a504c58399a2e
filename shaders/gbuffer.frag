#version 450
#include "common/tonemap.glsl"
// The normal format and position mode come from gbuffer_layout.glsl's #defines.
#include "common/ibl.glsl"
#include "common/gbuffer_layout.glsl"
#include "common/velocity.glsl"
#include "common/material.glsl"

in vec3 vPosition;
in vec3 vNormal;
in vec2 vUv;
in vec4 vTangent;

#ifdef LP_GBUFFER_NORMAL_OCT
layout(location = 0) out uint outNormal;
#else
layout(location = 0) out vec4 outNormal;
#endif
layout(location = 1) out vec4 outDiffuse;
#ifndef LP_GBUFFER_POSITION_FROM_DEPTH
layout(location = 2) out vec4 outPosition;
#endif
layout(location = 3) out vec4 outSpecular;
layout(location = 4) out vec4 outTexcoord;
layout(location = 5) out vec4 outTangent;  // the tangent view: eye-space tangent x 0.5 + 0.5, handedness
#ifdef LP_GBUFFER_VELOCITY
in vec4 vCurrentClip;
in vec4 vPreviousClip;
layout(location = 6) out vec2 outVelocity;  // uv_current - uv_previous, unjittered (common/velocity.glsl)
#endif

void main() {
    if (lpMaterialDiscards(vUv, gl_FrontFacing)) discard;
#ifdef LP_GBUFFER_DEPTH_ONLY
    // The forward+ depth pre-pass: depth (and motion) only; the forward pass shades the material.
#ifdef LP_GBUFFER_VELOCITY
    outVelocity = velocityFromClip(vCurrentClip, vPreviousClip);
#endif
    return;
#else
    LpSurface surface = lpEvaluateSurface(vNormal, vTangent, vUv, gl_FrontFacing);
    vec3 N = surface.N;
    float shininess = gbufferEncodeShininess(surface.shininess);
#ifdef LP_GBUFFER_NORMAL_OCT
    outNormal = gbufferEncodeNormalOct(N);
#else
    outNormal = gbufferEncodeNormal(N, shininess);
#endif
    outDiffuse = vec4(surface.kd, uFlat ? 0.0 : gbufferEncodeOcclusion(surface.occlusion));
#ifndef LP_GBUFFER_POSITION_FROM_DEPTH
    outPosition = vec4(vPosition, 1.0);
#endif
    outSpecular = vec4(surface.f0, shininess);
    outTexcoord = vec4(vUv, 0.0, 0.0);
    vec3 Tn = vTangent.xyz - N * dot(N, vTangent.xyz);
    float tn = length(Tn);
    outTangent = vec4(tn > 1e-20 ? Tn / tn * 0.5 + 0.5 : vec3(0.5), vTangent.w < 0.0 ? 0.0 : 1.0);
#ifdef LP_GBUFFER_VELOCITY
    outVelocity = velocityFromClip(vCurrentClip, vPreviousClip);
#endif
#endif
}
