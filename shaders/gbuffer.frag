#version 450
#include "common/tonemap.glsl"
// The normal format and position mode come from gbuffer_layout.glsl's #defines.
#include "common/ibl.glsl"
#include "common/gbuffer_layout.glsl"
#include "common/velocity.glsl"
#include "common/brdf.glsl"
#include "common/normal_map.glsl"

in vec3 vPosition;
in vec3 vNormal;
in vec2 vUv;
in vec4 vTangent;

// The material (lp::Material): metallic-roughness, with the dielectric F0 as a colour (MTL Ks).
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
uniform bool uFlat;  // flat-lit material: diffuse alpha 0 tells the light passes to leave it alone
uniform bool uHasBumpMap;
uniform float uBumpScale;
layout(binding = 0) uniform sampler2D uDiffuseMap;    // sRGB texture: sampled as linear; alpha multiplies uOpacity
layout(binding = 1) uniform sampler2D uBumpMap;       // height map in r
layout(binding = 2) uniform sampler2D uNormalMap;     // tangent-space normal, xyz * 0.5 + 0.5
layout(binding = 3) uniform sampler2D uMetalRoughMap; // roughness in g, metallic in b
layout(binding = 4) uniform sampler2D uOcclusionMap;  // occlusion in r

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
    if (!uDoubleSided && !gl_FrontFacing) discard;
    vec4 base = vec4(uDiffuse, uOpacity);
    if (uHasDiffuseMap) base *= texture(uDiffuseMap, vUv);
    if (uAlphaMask && base.a < uAlphaCutoff) discard;
    vec3 N = vNormal;
    float len = length(N);
    N = len > 1e-20 ? N / len : vec3(0.0, 0.0, 1.0);
    if (!gl_FrontFacing) N = -N;  // two-sided: thin walls are lit from either side
    // The tangent frame: the interpolated tangent made orthogonal to the normal; the bitangent
    // cross(N, T) w points along +v (up the image), the +Y of normal maps and of height steps.
    vec3 T = vTangent.xyz - N * dot(N, vTangent.xyz);
    float tl = length(T);
    bool hasFrame = tl > 1e-20;
    T = hasFrame ? T / tl : vec3(1.0, 0.0, 0.0);
    vec3 B = cross(N, T) * (vTangent.w < 0.0 ? -1.0 : 1.0);
    if (uHasNormalMap && hasFrame) {
        vec3 t = texture(uNormalMap, vUv).xyz * 2.0 - 1.0;
        N = normalMapNormal(N, T, B, t, uNormalScale);
    }
    if (uHasBumpMap && hasFrame) {
        // Height map -> normal: central differences in texture space, bent along the tangent frame.
        vec2 texel = 1.0 / vec2(textureSize(uBumpMap, 0));
        float hl = texture(uBumpMap, vUv - vec2(texel.x, 0)).r, hr = texture(uBumpMap, vUv + vec2(texel.x, 0)).r;
        float hd = texture(uBumpMap, vUv - vec2(0, texel.y)).r, hu = texture(uBumpMap, vUv + vec2(0, texel.y)).r;
        vec3 bent = N - uBumpScale * 4.0 * ((hr - hl) * T + (hu - hd) * B);
        float bl = length(bent);
        if (bl > 1e-20) N = bent / bl;
    }
    float metallic = clamp(uMetallic, 0.0, 1.0);
    // Up to the IBL's roughness floor (0.02); the analytic BRDFs clamp to 10000 themselves.
    float shininess = clamp(uShininess, 0.0, LP_IBL_MAX_SHININESS);
    if (uHasMetalRoughMap) {
        vec4 mr = texture(uMetalRoughMap, vUv);
        metallic = clamp(metallic * mr.b, 0.0, 1.0);
        shininess = shininessFromRoughnessToFloor(uRoughness * mr.g);
    }
    vec3 baseColor = clamp(base.rgb, 0.0, 1.0);
    vec3 kd = baseColor * (1.0 - metallic);
    vec3 f0 = mix(clamp(uSpecular, 0.0, 1.0), baseColor, metallic);
    float occlusion = 1.0;
    if (uHasOcclusionMap) occlusion = mix(1.0, texture(uOcclusionMap, vUv).r, clamp(uOcclusionStrength, 0.0, 1.0));
    shininess = gbufferEncodeShininess(shininess);
#ifdef LP_GBUFFER_NORMAL_OCT
    outNormal = gbufferEncodeNormalOct(N);
#else
    outNormal = gbufferEncodeNormal(N, shininess);
#endif
    outDiffuse = vec4(kd, uFlat ? 0.0 : gbufferEncodeOcclusion(occlusion));
#ifndef LP_GBUFFER_POSITION_FROM_DEPTH
    outPosition = vec4(vPosition, 1.0);
#endif
    outSpecular = vec4(f0, shininess);
    outTexcoord = vec4(vUv, 0.0, 0.0);
    vec3 Tn = vTangent.xyz - N * dot(N, vTangent.xyz);
    float tn = length(Tn);
    outTangent = vec4(tn > 1e-20 ? Tn / tn * 0.5 + 0.5 : vec3(0.5), vTangent.w < 0.0 ? 0.0 : 1.0);
#ifdef LP_GBUFFER_VELOCITY
    outVelocity = velocityFromClip(vCurrentClip, vPreviousClip);
#endif
}
