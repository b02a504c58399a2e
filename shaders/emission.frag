#version 450
// Emitted radiance added to the HDR buffer (passes/emission_pass): where the G-buffer's depth equals
// this surface's, the material's emission times its emissive texture. The same alpha MASK and
// single-sided tests as gbuffer.frag, so exactly the texels the G-buffer kept emit.
in vec3 vPosition;
in vec3 vNormal;
in vec4 vTangent;
#include "common/vertex_uvs.glsl"
// The vertex colour: its alpha is part of the MASK test.
#include "common/vertex_color.glsl"

uniform vec3 uEmission;  // linear radiance (emissiveFactor x strength, or Ke)
uniform bool uHasEmissiveMap;
uniform float uOpacity;
uniform bool uHasDiffuseMap;
uniform bool uAlphaMask;
uniform float uAlphaCutoff;
uniform bool uDoubleSided;
uniform uint uSecondUvMaps;  // LP_MAP_* of the maps sampled with the second uv set
layout(binding = 0) uniform sampler2D uDiffuseMap;   // sRGB: its alpha decides MASK
layout(binding = 1) uniform sampler2D uEmissiveMap;  // sRGB: sampled as linear
#ifdef LP_GBUFFER_CLEARCOAT
// gbuffer.clearcoat (common/gbuffer_layout.glsl): KHR_materials_clearcoat's weight w in r; the coat lies
// over the emission, which it passes times 1 - w.
layout(binding = 2) uniform sampler2D uClearcoatLayer;
#endif

layout(location = 0) out vec4 outHdr;

void main() {
    if (!uDoubleSided && !gl_FrontFacing) discard;
    float alpha = uOpacity * vColor.a;
    if (uHasDiffuseMap) alpha *= texture(uDiffuseMap, fragmentUv((uSecondUvMaps & LP_MAP_DIFFUSE) != 0u)).a;
    if (uAlphaMask && alpha < uAlphaCutoff) discard;
    vec3 e = max(uEmission, vec3(0.0));
    if (uHasEmissiveMap) e *= texture(uEmissiveMap, fragmentUv((uSecondUvMaps & LP_MAP_EMISSIVE) != 0u)).rgb;
#ifdef LP_GBUFFER_CLEARCOAT
    e *= 1.0 - texelFetch(uClearcoatLayer, ivec2(gl_FragCoord.xy), 0).r;
#endif
    outHdr = vec4(e, 0.0);
}
