// Alpha in the shadow maps (docs/shadows.md, "Alpha in shadows"): the caster programs compiled with
// LP_SHADOW_ALPHA_TEST draw the MASK and BLEND casters (engine/render/shadow_casters.hpp's
// CasterAlpha), and drop the fragments whose base colour alpha does not occlude. The base colour is
// the G-buffer's (common/material.glsl's materialBaseColor: factor x texture x vertex colour, the
// texture sampled with the shadow texel's footprint). MASK keeps alpha >= alphaCutoff, as the
// G-buffer does. BLEND keeps alpha >= a hashed threshold (Wyman and McGuire, "Hashed Alpha Testing",
// I3D 2017): uniform in (0, 1] over the surface, so on average a fraction alpha of it occludes; a
// hash of the object-space position on a grid about one shadow texel wide, so it does not change
// when the camera moves (the cascade cache keeps tiles bit for bit) and is the same every frame.
#ifndef LP_SHADOW_ALPHA_GLSL
#define LP_SHADOW_ALPHA_GLSL
#include "common/material.glsl"
#include "common/hashed_alpha.glsl"

uniform float uOpacity;      // the material's base alpha
uniform bool uHasDiffuseMap;
uniform uint uSecondUvMaps;  // LP_MAP_* of the maps sampled with the second uv set
uniform float uAlphaCutoff;  // MASK
uniform bool uAlphaHashed;   // BLEND: the hashed threshold instead of the cutoff

// The hashed threshold at object-space point p from its footprint in object space: dFdx/dFdy here.
float shadowHashedThreshold(vec3 p) { return hashedAlphaThreshold(p, max(length(dFdx(p)), length(dFdy(p)))); }

// Whether this fragment of an alpha-tested caster lets the light through. Call first in main(): the
// derivatives need the whole quad.
bool shadowCasterAlphaDiscards(vec2 uv, vec2 uv1, vec4 vertexColor, vec3 objectPosition) {
    UvSets uvs;
    uvs.set0 = TexCoord(uv, dFdxFine(uv), dFdyFine(uv));
    uvs.set1 = TexCoord(uv1, dFdxFine(uv1), dFdyFine(uv1));
    MaterialInputs m;
    m.diffuse = vec3(1.0);
    m.opacity = uOpacity;
    m.hasDiffuseMap = uHasDiffuseMap;
    m.alphaMask = true;
    m.alphaCutoff = uAlphaCutoff;
    m.secondUvMaps = uSecondUvMaps;
    float alpha = materialBaseColor(m, uvs, vertexColor).a;
    float threshold = shadowHashedThreshold(objectPosition);  // before any branch: it takes derivatives
    return alpha < (uAlphaHashed ? threshold : uAlphaCutoff);
}

#endif
