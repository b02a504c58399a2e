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

uniform float uOpacity;      // the material's base alpha
uniform bool uHasDiffuseMap;
uniform uint uSecondUvMaps;  // LP_MAP_* of the maps sampled with the second uv set
uniform float uAlphaCutoff;  // MASK
uniform bool uAlphaHashed;   // BLEND: the hashed threshold instead of the cutoff

// PCG3D (Jarzynski and Olano, "Hash Functions for GPU Rendering", JCGT 2020): integer arithmetic,
// the same on every driver.
uvec3 shadowPcg3d(uvec3 v) {
    v = v * 1664525u + 1013904223u;
    v.x += v.y * v.z;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v ^= v >> 16u;
    v.x += v.y * v.z;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    return v;
}

// Uniform in [0, 1) per cell of the grid of spacing 1 / scale around object-space point p (the
// cell's index by the bits of floor(): defined for any float, no integer overflow).
float shadowCellHash(vec3 p, float scale) {
    return float(shadowPcg3d(floatBitsToUint(floor(p * scale))).x >> 8u) * (1.0 / 16777216.0);
}

// The hashed alpha threshold at object-space point p (Wyman and McGuire's isotropic version, hash
// scale 1): the grid is the power of two nearest above and below one cell per shadow texel, the two
// hashes blended by where the texel lies between them, and the blend's distribution made uniform
// again. In (0, 1]: alpha 1 never drops a fragment, alpha 0 always does.
float shadowHashedThreshold(vec3 p) {
    float texel = max(length(dFdx(p)), length(dFdy(p)));
    // log2 of cells per object-space unit, clamped so a degenerate footprint stays finite.
    float level = clamp(-log2(max(texel, 1e-30)), -60.0, 60.0);
    float lower = floor(level);
    float x = mix(shadowCellHash(p, exp2(lower)), shadowCellHash(p, exp2(lower + 1.0)), level - lower);
    float a = min(level - lower, 1.0 - (level - lower));
    float t;
    if (a < 1e-6) t = x;  // on a level: one hash, already uniform
    else if (x < a) t = x * x / (2.0 * a * (1.0 - a));
    else if (x < 1.0 - a) t = (x - 0.5 * a) / (1.0 - a);
    else t = 1.0 - (1.0 - x) * (1.0 - x) / (2.0 * a * (1.0 - a));
    return clamp(t, 1e-6, 1.0);
}

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
