// The material of a draw as uniforms (lp::Material, set per draw by the raster passes: the G-buffer,
// the forward+ pre-pass and shading, the transparent pass) on top of common/material.glsl's shared
// evaluation (the visibility resolve feeds the same functions from an SSBO instead).
#ifndef LP_MATERIAL_UNIFORMS_GLSL
#define LP_MATERIAL_UNIFORMS_GLSL
#include "common/material.glsl"

uniform vec3 uDiffuse;     // base colour
uniform float uOpacity;    // base alpha
uniform vec3 uSpecular;    // dielectric F0
uniform float uMetallic;
uniform float uShininess;  // Blinn-Phong exponent of the roughness factor (used without a roughness map)
uniform float uRoughness;  // perceptual roughness factor (multiplies the map's g)
uniform bool uHasDiffuseMap;
uniform bool uHasMetalRoughMap;
uniform bool uHasNormalMap;
uniform float uNormalScale;
uniform bool uHasOcclusionMap;
uniform float uOcclusionStrength;
uniform bool uAlphaMask;     // MASK: texels with alpha below uAlphaCutoff are not drawn
uniform float uAlphaCutoff;
uniform bool uDoubleSided;   // single-sided: back faces are not drawn
uniform bool uFlat;          // flat-lit material: shown as its diffuse colour, untouched by light
uniform bool uHasBumpMap;
uniform float uBumpScale;
uniform uint uSecondUvMaps;  // LP_MAP_* of the maps sampled with the second uv set
uniform float uSpecularF90;  // KHR_materials_specular's weight: the dielectric's f90 (with uSpecularF90Given)
uniform bool uSpecularF90Given;
uniform bool uHasSpecularMap;
uniform bool uHasSpecularColorMap;
uniform float uClearcoat;  // KHR_materials_clearcoat's factor (0: no coat), roughness and normal map scale
uniform float uClearcoatRoughness;
uniform float uClearcoatNormalScale;
uniform bool uHasClearcoatMap;
uniform bool uHasClearcoatRoughnessMap;
uniform bool uHasClearcoatNormalMap;

MaterialInputs materialFromUniforms() {
    return MaterialInputs(uDiffuse, uOpacity, uSpecular, uMetallic, uShininess, uRoughness, uBumpScale, uNormalScale,
                          uOcclusionStrength, uAlphaCutoff, uHasDiffuseMap, uHasBumpMap, uHasNormalMap,
                          uHasMetalRoughMap, uHasOcclusionMap, uAlphaMask, uFlat, uSecondUvMaps, uSpecularF90, uSpecularF90Given, uHasSpecularMap,
                          uHasSpecularColorMap, uClearcoat, uClearcoatRoughness, uClearcoatNormalScale, uHasClearcoatMap,
                          uHasClearcoatRoughnessMap, uHasClearcoatNormalMap);
}

// The surface the forward passes shade.
struct LpSurface {
    vec3 N;           // shading normal, eye space, unit, facing the viewer's side for two-sided
    vec3 kd;          // diffuse colour (MaterialSample::kd)
    vec3 f0;          // specular colour
    FresnelEnds fresnel;  // f0 with Schlick's f90 and the diffuse shape, the base's under the coat
    ClearcoatLayer coat;  // KHR_materials_clearcoat's layer (weight 0: none)
    float shininess;  // Blinn-Phong exponent (up to the IBL's roughness floor)
    float occlusion;  // the material's ambient occlusion (1: none)
    float alpha;      // base alpha (opacity x texture alpha)
    vec3 baseColor;   // the base colour and metallic at the texel (KHR_materials_transmission's BTDF tint)
    float metallic;
};

// Whether the fragment is dropped: a back face of a single-sided material, or MASK below the cutoff.
// uvs: with their derivatives, taken before any discard (they need the whole quad).
bool lpMaterialDiscards(UvSets uvs, vec4 vertexColor, bool frontFacing) {
    if (!uDoubleSided && !frontFacing) return true;
    MaterialInputs m = materialFromUniforms();
    return materialAlphaRejects(m, materialBaseColor(m, uvs, vertexColor));
}

LpSurface lpEvaluateSurface(vec3 position, vec3 normal, vec4 tangent, UvSets uvs, vec4 vertexColor, bool frontFacing) {
    MaterialInputs m = materialFromUniforms();
    vec4 base = materialBaseColor(m, uvs, vertexColor);
    MaterialSample g = materialEvaluate(m, base, SurfaceInputs(normal, tangent, uvs, frontFacing, position));
    LpSurface s;
    s.N = g.normal;
    s.kd = g.kd;
    s.f0 = g.f0;
    s.fresnel = clearcoatBaseEnds(g.fresnel, g.coat);
    s.coat = g.coat;
    s.shininess = g.shininess;
    s.occlusion = g.occlusion;
    s.alpha = clamp(base.a, 0.0, 1.0);
    s.baseColor = g.baseColor;
    s.metallic = g.metallic;
    return s;
}

#endif
