// Directional lights (suns) with their cascaded shadow maps: the uniforms passes/global_light_pass
// sets (setSunUniforms) and the light they reflect, shared by the deferred global_lights pass and the
// forward passes so both shade a surface the same way. The shadow atlases sit on units
// LP_SUN_SHADOW_UNIT .. + 3 (8 unless the includer defines it first).
#ifndef LP_SUN_LIGHT_GLSL
#define LP_SUN_LIGHT_GLSL
#include "common/brdf.glsl"
#include "common/shadow.glsl"

#ifndef LP_SUN_SHADOW_UNIT
#define LP_SUN_SHADOW_UNIT 8
#endif

const int MAX_LIGHTS = 16;
uniform int uLightCount;
uniform vec3 uLightDirEye[MAX_LIGHTS];   // towards the light, eye space, unit
uniform vec3 uLightIrradiance[MAX_LIGHTS];
uniform vec3 uAmbient;

// Shadows (engine/render/shadows.hpp): up to 4 shadowed lights, each an atlas of up to 4 cascades.
const int MAX_SHADOWED = 4;
const int MAX_CASCADES = 4;
layout(binding = LP_SUN_SHADOW_UNIT) uniform sampler2D uShadowMap[MAX_SHADOWED];  // D32F atlases
uniform int uLightShadowSlot[MAX_LIGHTS];                 // -1: unshadowed
uniform int uShadowCascadeCount[MAX_SHADOWED];
uniform mat4 uShadowEyeToClip[MAX_SHADOWED * MAX_CASCADES];
uniform vec4 uShadowCascade[MAX_SHADOWED * MAX_CASCADES];   // split far (view depth), texel (world), texel / depth range, atlas tile
uniform mat3 uShadowEyeToLight[MAX_SHADOWED];
uniform int uShadowColumns;
uniform int uShadowTileSize;
// The filter (LP_SHADOW_FILTER_*) is compiled in: passes/global_light_pass's sunShadowFilterDefine.
// A program carries that filter's code and registers alone; a filter chosen by a uniform sized every
// pixel's registers for the costliest one.
#ifndef LP_SHADOW_FILTER_MODE
#error "common/sun_light.glsl needs LP_SHADOW_FILTER_MODE (passes/global_light_pass: sunShadowFilterDefine)"
#endif
uniform bool uShadowAtlasMarked; // the atlases' depths are marked (passes/shadow_map_pass: conservative raster)
uniform float uShadowDepthBias;  // shadow texels of depth
uniform float uShadowNormalBias; // shadow texels along N, times (1 - N.L)

// Fraction of light `slot`'s light reaching eye-space point P with normal N (N.L = nl > 0).
float shadowVisibility(int slot, vec3 P, vec3 N, float nl, vec2 pixel) {
    float viewDepth = -P.z;
    for (int c = 0; c < uShadowCascadeCount[slot]; ++c) {
        int k = slot * MAX_CASCADES + c;
        vec4 info = uShadowCascade[k];
        if (viewDepth > info.x) continue;
        // Normal offset: move the lookup off the surface, more where the light grazes it.
        vec3 Po = P + N * (uShadowNormalBias * info.y * (1.0 - nl));
        vec3 ndc = (uShadowEyeToClip[k] * vec4(Po, 1.0)).xyz;  // orthographic: w = 1
        vec2 uv = ndc.xy * 0.5 + 0.5;
        // Outside this cascade's square (past its edge, or a square lagging behind its slice under
        // --shadow-redraw-budget): the next cascade's square serves the pixel.
        if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) continue;
        float z = ndc.z * 0.5 + 0.5;
        if (z >= 1.0) return 1.0;  // beyond every caster
        int tile = int(info.w);
        ivec2 tileMin = ivec2(tile % uShadowColumns, tile / uShadowColumns) * uShadowTileSize;
        ivec2 tileMax = tileMin + ivec2(uShadowTileSize - 1);
        vec2 pos = vec2(tileMin) + uv * float(uShadowTileSize);
        vec2 grad = shadowReceiverGradient(uShadowEyeToLight[slot] * N, info.z);
        float bias = uShadowDepthBias * info.z;
#ifdef LP_SUN_SHADOW_CONSTANT_SLOTS
        // A constant index for each atlas: Mesa's llvmpipe (LLVM 15) crashes compiling a fragment
        // shader that gathers (shadowDepths2x2) through a dynamically indexed sampler array.
        // Compute shaders keep the one call (a quarter of the code to compile).
        switch (slot) {
        case 0: return shadowFilter(uShadowMap[0], LP_SHADOW_FILTER_MODE, pos, tileMin, tileMax, z, grad, bias, uShadowAtlasMarked, pixel);
        case 1: return shadowFilter(uShadowMap[1], LP_SHADOW_FILTER_MODE, pos, tileMin, tileMax, z, grad, bias, uShadowAtlasMarked, pixel);
        case 2: return shadowFilter(uShadowMap[2], LP_SHADOW_FILTER_MODE, pos, tileMin, tileMax, z, grad, bias, uShadowAtlasMarked, pixel);
        default: return shadowFilter(uShadowMap[3], LP_SHADOW_FILTER_MODE, pos, tileMin, tileMax, z, grad, bias, uShadowAtlasMarked, pixel);
        }
#else
        return shadowFilter(uShadowMap[slot], LP_SHADOW_FILTER_MODE, pos, tileMin, tileMax, z, grad, bias, uShadowAtlasMarked, pixel);
#endif
    }
    return 1.0;  // outside every cascade: nothing there casts
}

// How much of sun i reaches eye-space P (normal N; `coat`'s normal may face a sun the base's does
// not): 0 behind both, else its shadow visibility. `pixel` seeds the filters' per-pixel rotation.
float lpSunVisibility(int i, vec3 P, vec3 N, vec2 pixel, ClearcoatLayer coat) {
    vec3 L = uLightDirEye[i];
    float nl = dot(N, L);
    float coatNl = coat.weight > 0.0 ? dot(coat.normal, L) : 0.0;
    if (nl <= 0.0 && coatNl <= 0.0) return 0.0;
    int slot = uLightShadowSlot[i];
    return slot >= 0 ? shadowVisibility(slot, P, N, nl > 0.0 ? nl : coatNl, pixel) : 1.0;
}

// Radiance the suns reflect at eye-space P (normal N, view direction V), shadows included. Ambient
// not included. `coat`: KHR_materials_clearcoat's layer (kd and ks already the base under it), its
// lobe added per sun.
vec3 lpSunRadiance(vec3 P, vec3 N, vec3 V, vec3 kd, FresnelEnds ks, float shininess, vec2 pixel, ClearcoatLayer coat) {
    vec3 c = vec3(0.0);
    for (int i = 0; i < uLightCount; ++i) {
        float visible = lpSunVisibility(i, P, N, pixel, coat);
        if (visible > 0.0)
            c += visible * (brdfRadiance(uBrdf, N, V, uLightDirEye[i], kd, ks, shininess, uLightIrradiance[i]) +
                            clearcoatRadiance(coat, V, uLightDirEye[i], uLightIrradiance[i]));
    }
    return c;
}
vec3 lpSunRadiance(vec3 P, vec3 N, vec3 V, vec3 kd, FresnelEnds ks, float shininess, vec2 pixel) {
    return lpSunRadiance(P, N, V, kd, ks, shininess, pixel, noClearcoat());
}

// The same for a material whose Fresnel ends follow from F0 (no KHR_materials_specular): F0 alone is
// carried through the loop and the ends are made after each sun's shadow filter. Carried across the
// filter, the ends (seven floats) made global_lights 1.43-1.52x slower on an H100 (cornell and gallery,
// 1080p and 4K; bench/results/frame/2026-12-08_sun-loop-fresnel-ends).
vec3 lpSunRadiance(vec3 P, vec3 N, vec3 V, vec3 kd, vec3 f0, float shininess, vec2 pixel, ClearcoatLayer coat) {
    vec3 c = vec3(0.0);
    for (int i = 0; i < uLightCount; ++i) {
        float visible = lpSunVisibility(i, P, N, pixel, coat);
        if (visible > 0.0)
            c += visible * (brdfRadiance(uBrdf, N, V, uLightDirEye[i], kd, f0, shininess, uLightIrradiance[i]) +
                            clearcoatRadiance(coat, V, uLightDirEye[i], uLightIrradiance[i]));
    }
    return c;
}

#endif
