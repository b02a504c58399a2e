// The material evaluation both G-buffer paths share: gbuffer.frag (classic raster, derivatives from
// dFdx/dFdy) and visibility_resolve.comp (compute, derivatives from the neighbouring pixel rays).
// Texture maps are on units 0..4; every sample is a textureGrad with the caller's uv derivatives, so
// the two paths pick the same mip level and anisotropy.
#ifndef LP_MATERIAL_GLSL
#define LP_MATERIAL_GLSL

#include "common/brdf.glsl"
#include "common/normal_map.glsl"
#include "common/ibl.glsl"
#include "common/uv_sets.glsl"

#define LP_MATERIAL_BIND_DIFFUSE 0
#define LP_MATERIAL_BIND_BUMP 1
#define LP_MATERIAL_BIND_NORMAL 2
#define LP_MATERIAL_BIND_METAL_ROUGH 3
#define LP_MATERIAL_BIND_OCCLUSION 4

layout(binding = LP_MATERIAL_BIND_DIFFUSE) uniform sampler2D uDiffuseMap;        // sRGB: sampled as linear; alpha x opacity
layout(binding = LP_MATERIAL_BIND_BUMP) uniform sampler2D uBumpMap;              // height in r
layout(binding = LP_MATERIAL_BIND_NORMAL) uniform sampler2D uNormalMap;          // tangent-space normal, xyz * 0.5 + 0.5
layout(binding = LP_MATERIAL_BIND_METAL_ROUGH) uniform sampler2D uMetalRoughMap; // roughness in g, metallic in b
layout(binding = LP_MATERIAL_BIND_OCCLUSION) uniform sampler2D uOcclusionMap;    // occlusion in r

// lp::GpuMaterial: metallic-roughness, with the dielectric F0 as a colour (MTL Ks).
struct MaterialInputs {
    vec3 diffuse;     // base colour
    float opacity;    // base alpha
    vec3 specular;    // dielectric F0
    float metallic;
    float shininess;  // Blinn-Phong exponent of the roughness factor (used without a roughness map)
    float roughness;  // perceptual roughness factor (multiplies the map's g)
    float bumpScale;
    float normalScale;
    float occlusionStrength;
    float alphaCutoff;  // MASK: texels with alpha below it are not drawn
    bool hasDiffuseMap;
    bool hasBumpMap;
    bool hasNormalMap;
    bool hasMetalRoughMap;
    bool hasOcclusionMap;
    bool alphaMask;
    bool flatLit;  // flat-lit: diffuse alpha 0 tells the light passes to leave it alone
    uint secondUvMaps;  // LP_MAP_* of the maps sampled with the second uv set (glTF texCoord 1)
};

// The interpolated vertex attributes at a pixel, eye space, and its uv sets with their footprints.
struct SurfaceInputs {
    vec3 normal;   // interpolated, not normalised
    vec4 tangent;  // xyz interpolated, w handedness (for the normal map's uv set)
    UvSets uvs;
    bool frontFacing;
};

// Where map `bit` (LP_MAP_*) of material m samples.
TexCoord materialTexCoord(MaterialInputs m, UvSets uvs, uint bit) {
    return (m.secondUvMaps & bit) != 0u ? uvs.set1 : uvs.set0;
}
vec4 sampleMap(sampler2D map, TexCoord t) { return textureGrad(map, t.uv, t.dx, t.dy); }

// What the G-buffer stores for the pixel.
struct MaterialSample {
    vec3 normal;     // unit shading normal, eye space
    vec3 kd;         // the diffuse layer's albedo: base (1 - metallic) (1 - specular) under GGX (brdf.glsl's
                     // materialDiffuseAlbedo), base (1 - metallic) under Blinn-Phong and for flat-lit materials
    vec3 f0;         // mix(specular, base, metallic)
    float shininess;
    float occlusion;
    vec4 tangentView;  // the tangent view's value: unit tangent orthogonal to normal x 0.5 + 0.5, handedness 0/1
};

// Base colour and alpha (the alpha test reads .a): the factor x the texture x the vertex colour
// (glTF: baseColorFactor x baseColorTexture x COLOR_0).
vec4 materialBaseColor(MaterialInputs m, UvSets uvs, vec4 vertexColor) {
    vec4 base = vec4(m.diffuse, m.opacity) * vertexColor;
    if (m.hasDiffuseMap) base *= sampleMap(uDiffuseMap, materialTexCoord(m, uvs, LP_MAP_DIFFUSE));
    return base;
}

// MASK: whether the texel is cut away (the caller discards it).
bool materialAlphaRejects(MaterialInputs m, vec4 base) { return m.alphaMask && base.a < m.alphaCutoff; }

MaterialSample materialEvaluate(MaterialInputs m, vec4 base, SurfaceInputs s) {
    vec3 N = s.normal;
    float len = length(N);
    N = len > 1e-20 ? N / len : vec3(0.0, 0.0, 1.0);
    if (!s.frontFacing) N = -N;  // two-sided: thin walls are lit from either side
    // The tangent frame: the interpolated tangent made orthogonal to the normal; the bitangent
    // cross(N, T) w points along +v (up the image), the +Y of normal maps and of height steps.
    vec3 T = s.tangent.xyz - N * dot(N, s.tangent.xyz);
    float tl = length(T);
    bool hasFrame = tl > 1e-20;
    T = hasFrame ? T / tl : vec3(1.0, 0.0, 0.0);
    vec3 B = cross(N, T) * (s.tangent.w < 0.0 ? -1.0 : 1.0);
    if (m.hasNormalMap && hasFrame) {
        vec3 t = sampleMap(uNormalMap, materialTexCoord(m, s.uvs, LP_MAP_NORMAL)).xyz * 2.0 - 1.0;
        N = normalMapNormal(N, T, B, t, m.normalScale);
    }
    if (m.hasBumpMap && hasFrame) {
        // Height map -> normal: central differences in texture space, bent along the tangent frame.
        vec2 texel = 1.0 / vec2(textureSize(uBumpMap, 0));
        TexCoord c = materialTexCoord(m, s.uvs, LP_MAP_BUMP);
        float hl = textureGrad(uBumpMap, c.uv - vec2(texel.x, 0), c.dx, c.dy).r;
        float hr = textureGrad(uBumpMap, c.uv + vec2(texel.x, 0), c.dx, c.dy).r;
        float hd = textureGrad(uBumpMap, c.uv - vec2(0, texel.y), c.dx, c.dy).r;
        float hu = textureGrad(uBumpMap, c.uv + vec2(0, texel.y), c.dx, c.dy).r;
        vec3 bent = N - m.bumpScale * 4.0 * ((hr - hl) * T + (hu - hd) * B);
        float bl = length(bent);
        if (bl > 1e-20) N = bent / bl;
    }
    float metallic = clamp(m.metallic, 0.0, 1.0);
    // Up to the IBL's roughness floor (0.02); the analytic BRDFs clamp to 10000 themselves.
    float shininess = clamp(m.shininess, 0.0, LP_IBL_MAX_SHININESS);
    if (m.hasMetalRoughMap) {
        vec4 mr = sampleMap(uMetalRoughMap, materialTexCoord(m, s.uvs, LP_MAP_METAL_ROUGH));
        metallic = clamp(metallic * mr.b, 0.0, 1.0);
        shininess = shininessFromRoughnessToFloor(m.roughness * mr.g);
    }
    MaterialSample o;
    vec3 baseColor = clamp(base.rgb, 0.0, 1.0);
    vec3 dielectricF0 = clamp(m.specular, 0.0, 1.0);
    o.normal = N;
    // Flat-lit: the colour shown as it is, no BRDF applies.
    o.kd = m.flatLit ? baseColor * (1.0 - metallic) : materialDiffuseAlbedo(uBrdf, baseColor, metallic, dielectricF0);
    o.f0 = mix(dielectricF0, baseColor, metallic);
    o.shininess = shininess;
    o.occlusion = 1.0;
    if (m.hasOcclusionMap)
        o.occlusion = mix(1.0, sampleMap(uOcclusionMap, materialTexCoord(m, s.uvs, LP_MAP_OCCLUSION)).r,
                          clamp(m.occlusionStrength, 0.0, 1.0));
    vec3 Tn = s.tangent.xyz - N * dot(N, s.tangent.xyz);
    float tn = length(Tn);
    o.tangentView = vec4(tn > 1e-20 ? Tn / tn * 0.5 + 0.5 : vec3(0.5), s.tangent.w < 0.0 ? 0.0 : 1.0);
    return o;
}

#endif
