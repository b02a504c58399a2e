#version 450
#include "common/tonemap.glsl"
// The normal format and position mode come from gbuffer_layout.glsl's #defines.
#include "common/gbuffer_layout.glsl"
#include "common/velocity.glsl"
#include "common/material_uniforms.glsl"

in vec3 vPosition;
in vec3 vNormal;
in vec4 vTangent;
#include "common/vertex_uvs.glsl"
#include "common/vertex_color.glsl"

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
#ifdef LP_GBUFFER_CLEARCOAT
layout(location = 4) out vec4 outClearcoat;  // gbuffer.clearcoat: the coat's weight, alpha, normal (KHR_materials_clearcoat)
#else
layout(location = 4) out vec4 outTexcoord;
#endif
layout(location = 5) out vec4 outTangent;  // the tangent view: eye-space tangent x 0.5 + 0.5, handedness
#ifdef LP_GBUFFER_FRESNEL
layout(location = 7) out vec2 outFresnel;  // gbuffer.fresnel: f90 and the diffuse shape (KHR_materials_specular)
#else
layout(location = 7) out vec4 outMaterialInput;  // the material-input views (uMaterialInput != 0)
#endif
#ifdef LP_GBUFFER_VELOCITY
in vec4 vCurrentClip;
in vec4 vPreviousClip;
layout(location = 6) out vec2 outVelocity;  // uv_current - uv_previous, unjittered (common/velocity.glsl)
#endif

void main() {
    // Derivatives before any discard (they need the whole quad).
    UvSets uvs = fragmentUvSets();
    if (!uDoubleSided && !gl_FrontFacing) discard;
    MaterialInputs m = materialFromUniforms();
    vec4 base = materialBaseColor(m, uvs, vColor);
    if (materialAlphaRejects(m, base)) discard;
#ifdef LP_GBUFFER_DEPTH_ONLY
    // The forward+ depth pre-pass: depth (and motion) only; the forward pass shades the material.
#ifdef LP_GBUFFER_VELOCITY
    outVelocity = velocityFromClip(vCurrentClip, vPreviousClip);
#endif
    return;
#else
    MaterialSample g = materialEvaluate(m, base, SurfaceInputs(vNormal, vTangent, uvs, gl_FrontFacing, vPosition));
    g.shininess = gbufferEncodeShininess(g.shininess);  // the half-float channel's encoding (to the 0.02 floor)
#ifdef LP_GBUFFER_NORMAL_OCT
    outNormal = gbufferEncodeNormalOct(g.normal);
#else
    outNormal = gbufferEncodeNormal(g.normal, g.shininess);
#endif
    // The sRGB targets are attached as RGBA8 views: the encoding is written here, exactly as the compute
    // stores write it (common/gbuffer_images.glsl), not by the rasteriser's approximate blend-unit encode.
    outDiffuse = vec4(linearToSrgb(g.kd), m.flatLit ? 0.0 : gbufferEncodeOcclusion(g.occlusion));
#ifndef LP_GBUFFER_POSITION_FROM_DEPTH
    outPosition = vec4(vPosition, 1.0);
#endif
#ifdef LP_GBUFFER_SHININESS_IN_NORMAL
    outSpecular = vec4(linearToSrgb(g.f0), 0.0);  // the seed formats' sRGB F0
#else
    outSpecular = vec4(g.f0, g.shininess);
#endif
#ifdef LP_GBUFFER_CLEARCOAT
    outClearcoat = materialClearcoatValue(g);
#else
    outTexcoord = vec4(vUv, 0.0, 0.0);
#endif
    outTangent = g.tangentView;
#ifdef LP_GBUFFER_FRESNEL
    outFresnel = materialFresnelValue(g);
#else
    if (uMaterialInput != 0) outMaterialInput = materialInputValue(g);
#endif
#ifdef LP_GBUFFER_VELOCITY
    outVelocity = velocityFromClip(vCurrentClip, vPreviousClip);
#endif
#endif
}
