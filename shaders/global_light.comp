#version 450
// Directional lights with the chosen analytic BRDF (normalised Blinn-Phong or GGX), cascaded shadow
// maps, plus a constant ambient (times the ambient occlusion, when on), into the HDR buffer.
#include "common/brdf.glsl"
#include "common/shadow.glsl"
#include "common/tonemap.glsl"
#define LP_GBUFFER_READ
#include "common/gbuffer_layout.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba16f, binding = 0) uniform writeonly image2D uHdr;

const int MAX_LIGHTS = 16;
uniform int uLightCount;
uniform vec3 uLightDirEye[MAX_LIGHTS];   // towards the light, eye space, unit
uniform vec3 uLightIrradiance[MAX_LIGHTS];
uniform vec3 uAmbient;
uniform bool uLightingOnly;  // debug: white albedo, so the image shows light alone
uniform int uBrdf;           // LP_BRDF_BLINN_PHONG | LP_BRDF_GGX
// Ambient occlusion (passes/ambient_occlusion_pass): indirect light only, so the ambient term alone.
layout(binding = 14) uniform sampler2D uAo;
uniform bool uAmbientOcclusion;

// Shadows (engine/render/shadows.hpp): up to 4 shadowed lights, each an atlas of up to 4 cascades.
const int MAX_SHADOWED = 4;
const int MAX_CASCADES = 4;
layout(binding = 8) uniform sampler2D uShadowMap[MAX_SHADOWED];  // D32F atlases, units 8..11
uniform int uLightShadowSlot[MAX_LIGHTS];                 // -1: unshadowed
uniform int uShadowCascadeCount[MAX_SHADOWED];
uniform mat4 uShadowEyeToClip[MAX_SHADOWED * MAX_CASCADES];
uniform vec4 uShadowCascade[MAX_SHADOWED * MAX_CASCADES];   // split far (view depth), texel (world), texel / depth range
uniform mat3 uShadowEyeToLight[MAX_SHADOWED];
uniform int uShadowColumns;
uniform int uShadowTileSize;
uniform int uShadowFilter;       // LP_SHADOW_FILTER_*
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
        if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) continue;  // try a wider cascade
        float z = ndc.z * 0.5 + 0.5;
        if (z >= 1.0) return 1.0;  // beyond every caster
        ivec2 tileMin = ivec2(c % uShadowColumns, c / uShadowColumns) * uShadowTileSize;
        ivec2 tileMax = tileMin + ivec2(uShadowTileSize - 1);
        vec2 pos = vec2(tileMin) + uv * float(uShadowTileSize);
        vec2 grad = shadowReceiverGradient(uShadowEyeToLight[slot] * N, info.z);
        return shadowFilter(uShadowMap[slot], uShadowFilter, pos, tileMin, tileMax, z, grad,
                            uShadowDepthBias * info.z, pixel);
    }
    return 1.0;  // outside every cascade: nothing there casts
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uHdr);
    if (p.x >= size.x || p.y >= size.y) return;
    if (gbufferIsBackground(p)) {
        imageStore(uHdr, p, vec4(0.0));  // background: the sky pass fills it
        return;
    }
    if (!uLightingOnly && gbufferIsFlat(p)) {  // flat-lit: its colour, no light
        imageStore(uHdr, p, vec4(gbufferDiffuse(p), 1.0));
        return;
    }
    vec3 N = gbufferNormal(p);
    vec3 P = gbufferPosition(p);
    vec4 spec = vec4(gbufferSpecular(p), gbufferShininess(p));
    vec3 kd = uLightingOnly ? vec3(1.0) : gbufferDiffuse(p);
    vec3 ks = spec.rgb;
    float pl = length(P);
    vec3 V = pl > 0.0 ? -P / pl : vec3(0.0, 0.0, 1.0);
    float ao = uAmbientOcclusion ? texelFetch(uAo, p, 0).r : 1.0;
    vec3 c = uAmbient * kd * ao * (uLightingOnly ? 1.0 : gbufferOcclusion(p));  // occlusion darkens ambient light only
    for (int i = 0; i < uLightCount; ++i) {
        vec3 L = uLightDirEye[i];
        float nl = dot(N, L);
        if (nl <= 0.0) continue;
        float visible = 1.0;
        int slot = uLightShadowSlot[i];
        if (slot >= 0) visible = shadowVisibility(slot, P, N, nl, vec2(p));
        if (visible > 0.0) c += visible * brdfRadiance(uBrdf, N, V, L, kd, ks, spec.a, uLightIrradiance[i]);
    }
    imageStore(uHdr, p, vec4(sanitizeHdr(c), 1.0));
}
