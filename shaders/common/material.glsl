// The surface a material gives one fragment (lp::Material on the GPU: metallic-roughness, with the
// dielectric F0 as a colour), shared by the G-buffer pass and the forward passes so deferred and
// forward shading start from the same numbers. The includer declares nothing of this: the uniforms
// and the material textures (units 0..4, 6) are here.
#ifndef LP_MATERIAL_GLSL
#define LP_MATERIAL_GLSL
#include "common/brdf.glsl"
#include "common/ibl.glsl"
#include "common/normal_map.glsl"

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
uniform bool uFlat;  // flat-lit material: shown as its diffuse colour, untouched by light
uniform bool uHasBumpMap;
uniform float uBumpScale;
layout(binding = 0) uniform sampler2D uDiffuseMap;    // sRGB texture: sampled as linear; alpha multiplies uOpacity
layout(binding = 1) uniform sampler2D uBumpMap;       // height map in r
layout(binding = 2) uniform sampler2D uNormalMap;     // tangent-space normal, xyz * 0.5 + 0.5
layout(binding = 3) uniform sampler2D uMetalRoughMap; // roughness in g, metallic in b
layout(binding = 4) uniform sampler2D uOcclusionMap;  // occlusion in r

struct LpSurface {
    vec3 N;           // shading normal, eye space, unit, facing the viewer's side for two-sided
    vec3 kd;          // diffuse colour (base x (1 - metallic))
    vec3 f0;          // specular colour
    float shininess;  // Blinn-Phong exponent (up to the IBL's roughness floor; the G-buffer encodes it)
    float occlusion;  // the material's ambient occlusion (1: none)
    float alpha;      // base alpha (opacity x texture alpha)
};

// Whether the fragment is dropped: a back face of a single-sided material, or MASK below the cutoff.
bool lpMaterialDiscards(vec2 uv, bool frontFacing) {
    if (!uDoubleSided && !frontFacing) return true;
    if (!uAlphaMask) return false;
    float a = uOpacity;
    if (uHasDiffuseMap) a *= texture(uDiffuseMap, uv).a;
    return a < uAlphaCutoff;
}

// The surface at a fragment: vNormal and vTangent interpolated (eye space), vUv.
LpSurface lpEvaluateSurface(vec3 vNormal, vec4 vTangent, vec2 vUv, bool frontFacing) {
    LpSurface s;
    vec4 base = vec4(uDiffuse, uOpacity);
    if (uHasDiffuseMap) base *= texture(uDiffuseMap, vUv);
    vec3 N = vNormal;
    float len = length(N);
    N = len > 1e-20 ? N / len : vec3(0.0, 0.0, 1.0);
    if (!frontFacing) N = -N;  // two-sided: thin walls are lit from either side
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
    s.N = N;
    s.kd = baseColor * (1.0 - metallic);
    s.f0 = mix(clamp(uSpecular, 0.0, 1.0), baseColor, metallic);
    s.shininess = shininess;
    s.occlusion = 1.0;
    if (uHasOcclusionMap) s.occlusion = mix(1.0, texture(uOcclusionMap, vUv).r, clamp(uOcclusionStrength, 0.0, 1.0));
    s.alpha = clamp(base.a, 0.0, 1.0);
    return s;
}

#endif
