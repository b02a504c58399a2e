// The material evaluation both G-buffer paths share: gbuffer.frag (classic raster, derivatives from
// dFdx/dFdy) and visibility_resolve.comp (compute, derivatives from the neighbouring pixel rays).
// Texture maps are on units 0..4; every sample is a textureGrad with the caller's uv derivatives, so
// the two paths pick the same mip level and anisotropy (sampleMap; on a driver whose anisotropic
// filter ignores those derivatives in compute, the resolve's own filter: LP_ANISOTROPY_FROM_GRADIENTS).
#ifndef LP_MATERIAL_GLSL
#define LP_MATERIAL_GLSL

#include "common/brdf.glsl"
#include "common/normal_map.glsl"
#include "common/ibl.glsl"
#include "common/uv_sets.glsl"
#include "common/normal_encoding.glsl"

#define LP_MATERIAL_BIND_DIFFUSE 0
#define LP_MATERIAL_BIND_BUMP 1
#define LP_MATERIAL_BIND_NORMAL 2
#define LP_MATERIAL_BIND_METAL_ROUGH 3
#define LP_MATERIAL_BIND_OCCLUSION 4
// KHR_materials_specular's maps, on units above those the light passes use (lp::kMaterialSpecularUnit);
// their uMapAnisotropy entries are LP_MATERIAL_SLOT_*.
#define LP_MATERIAL_BIND_SPECULAR 16
#define LP_MATERIAL_BIND_SPECULAR_COLOR 17
#define LP_MATERIAL_SLOT_SPECULAR 5
#define LP_MATERIAL_SLOT_SPECULAR_COLOR 6
// KHR_materials_clearcoat's maps (lp::kMaterialClearcoatUnit and the two after it).
#define LP_MATERIAL_BIND_CLEARCOAT 18
#define LP_MATERIAL_BIND_CLEARCOAT_ROUGHNESS 19
#define LP_MATERIAL_BIND_CLEARCOAT_NORMAL 20
#define LP_MATERIAL_SLOT_CLEARCOAT 7
#define LP_MATERIAL_SLOT_CLEARCOAT_ROUGHNESS 8
#define LP_MATERIAL_SLOT_CLEARCOAT_NORMAL 9
#define LP_MATERIAL_SLOTS 10

layout(binding = LP_MATERIAL_BIND_DIFFUSE) uniform sampler2D uDiffuseMap;        // sRGB: sampled as linear; alpha x opacity
layout(binding = LP_MATERIAL_BIND_BUMP) uniform sampler2D uBumpMap;              // height in r
layout(binding = LP_MATERIAL_BIND_NORMAL) uniform sampler2D uNormalMap;          // tangent-space normal, xyz * 0.5 + 0.5
layout(binding = LP_MATERIAL_BIND_METAL_ROUGH) uniform sampler2D uMetalRoughMap; // roughness in g, metallic in b
layout(binding = LP_MATERIAL_BIND_OCCLUSION) uniform sampler2D uOcclusionMap;    // occlusion in r
layout(binding = LP_MATERIAL_BIND_SPECULAR) uniform sampler2D uSpecularMap;       // KHR_materials_specular weight in a
layout(binding = LP_MATERIAL_BIND_SPECULAR_COLOR) uniform sampler2D uSpecularColorMap;  // its F0 colour (sRGB: sampled as linear)
layout(binding = LP_MATERIAL_BIND_CLEARCOAT) uniform sampler2D uClearcoatMap;                   // the coat's factor in r
layout(binding = LP_MATERIAL_BIND_CLEARCOAT_ROUGHNESS) uniform sampler2D uClearcoatRoughnessMap;  // its roughness in g
layout(binding = LP_MATERIAL_BIND_CLEARCOAT_NORMAL) uniform sampler2D uClearcoatNormalMap;        // its tangent-space normal

// lp::GpuMaterial: metallic-roughness, with the dielectric F0 as a colour (MTL Ks).
struct MaterialInputs {
    vec3 diffuse;     // base colour
    float opacity;    // base alpha
    vec3 specular;    // dielectric F0 (KHR_materials_specular: F0_ior x specularColorFactor, unclamped)
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
    float dielectricF90;  // KHR_materials_specular's specular weight: the dielectric's f90 (with givenF90)
    bool givenF90;        // KHR_materials_specular: f90 given, the diffuse weighted by 1 - max3(F) (brdf.glsl)
    bool hasSpecularMap;       // its specularTexture (weight in a)
    bool hasSpecularColorMap;  // its specularColorTexture
    float clearcoat;           // KHR_materials_clearcoat's clearcoatFactor (0: no coat)
    float clearcoatRoughness;  // its clearcoatRoughnessFactor
    float clearcoatNormalScale;  // its clearcoatNormalTexture.scale
    bool hasClearcoatMap;           // clearcoatTexture (r)
    bool hasClearcoatRoughnessMap;  // clearcoatRoughnessTexture (g)
    bool hasClearcoatNormalMap;     // clearcoatNormalTexture
};

// The interpolated vertex attributes at a pixel, eye space, and its uv sets with their footprints.
struct SurfaceInputs {
    vec3 normal;   // interpolated, not normalised
    vec4 tangent;  // xyz interpolated, w handedness (for the normal map's uv set)
    UvSets uvs;
    bool frontFacing;
    vec3 position;  // eye space: the view direction the clearcoat's Fresnel weight needs
};

// Where map `bit` (LP_MAP_*) of material m samples.
TexCoord materialTexCoord(MaterialInputs m, UvSets uvs, uint bit) {
    return (m.secondUvMaps & bit) != 0u ? uvs.set1 : uvs.set0;
}
#ifdef LP_ANISOTROPY_FROM_GRADIENTS
// On a driver whose anisotropic filter takes its footprint from neighbouring invocations rather than
// from textureGrad's gradients (engine/gl/gradient_probe: llvmpipe, in compute), the visibility
// resolve filters anisotropically itself: the pass binds an isotropic sampler over each map whose
// texture is anisotropic and gives that texture's GL_TEXTURE_MAX_ANISOTROPY here (1: none, the map is
// sampled as it is), per material unit (LP_MATERIAL_BIND_*), with how the driver's raster picks the
// level (lp::gl::GradientSampling), so both G-buffer modes read the same levels.
uniform float uMapAnisotropy[LP_MATERIAL_SLOTS];  // units 0..4, then the LP_MATERIAL_SLOT_* maps
uniform bool uAnisotropyClampsRatio;  // level of the longer axis / min(ratio, max anisotropy); else the shorter's
uniform int uAnisotropyLevels;        // lp::gl::AnisotropicLevels: 0 blended, 1 floor, 2 nearest
uniform bool uAnisotropyPerQuad;      // the level from the quad's first pixel (TexCoord.quadDx, quadDy)

// The level of detail the driver's raster takes for footprint axes of lx and ly texels.
float rasterAnisotropicLod(float lx, float ly, float maxAnisotropy) {
    float major = max(lx, ly), minor = min(lx, ly);
    float ratio = minor > 0.0 ? min(major / minor, maxAnisotropy) : maxAnisotropy;
    float lod = log2(max(uAnisotropyClampsRatio ? major / ratio : minor, 1e-30));
    if (uAnisotropyLevels == 1) lod = floor(lod);
    if (uAnisotropyLevels == 2) lod = round(lod);
    return lod;
}

// EXT_texture_filter_anisotropic's filter from explicit gradients: the footprint's axes |dx| and |dy|
// in texels, their ratio clamped to maxAnisotropy, ceil(ratio) probes spread evenly along the longer
// axis and averaged, each at the level of detail the raster would take.
vec4 textureGradAnisotropic(sampler2D map, TexCoord t, float maxAnisotropy) {
    vec2 texels = vec2(textureSize(map, 0));
    float lx = length(t.dx * texels), ly = length(t.dy * texels);
    float ratio = min(max(lx, ly) / max(min(lx, ly), 1e-30), maxAnisotropy);
    float lod = rasterAnisotropicLod(length(t.quadDx * texels), length(t.quadDy * texels), maxAnisotropy);
    vec2 axis = lx >= ly ? t.dx : t.dy;
    int probes = max(1, int(ceil(ratio - 1e-3)));
    vec4 sum = vec4(0.0);
    for (int i = 0; i < probes; ++i) sum += textureLod(map, t.uv + axis * ((float(i) + 0.5) / float(probes) - 0.5), lod);
    return sum / float(probes);
}
#endif

// `t` moved by `offset` in uv, its footprint kept.
TexCoord offsetTexCoord(TexCoord t, vec2 offset) {
    t.uv += offset;
    return t;
}

// A map's texel with the footprint the pixel's uv derivatives give; `unit` is its LP_MATERIAL_BIND_*
// (0..4) or LP_MATERIAL_SLOT_* (the specular maps): its uMapAnisotropy entry.
vec4 sampleMap(sampler2D map, int unit, TexCoord t) {
#ifdef LP_ANISOTROPY_FROM_GRADIENTS
    if (uMapAnisotropy[unit] > 1.0) return textureGradAnisotropic(map, t, uMapAnisotropy[unit]);
#endif
    return textureGrad(map, t.uv, t.dx, t.dy);
}

// What the G-buffer stores for the pixel.
struct MaterialSample {
    vec3 normal;     // unit shading normal, eye space
    vec3 kd;         // the diffuse layer's albedo: base (1 - metallic) (1 - specular) under GGX (brdf.glsl's
                     // materialDiffuseAlbedo), base (1 - metallic) under Blinn-Phong and for flat-lit materials
    vec3 f0;         // mix(specular, base, metallic)
    FresnelEnds fresnel;  // f0 with Schlick's f90 and the diffuse shape (brdf.glsl's materialFresnelEnds)
    float shininess;
    float occlusion;
    vec4 tangentView;  // the tangent view's value: unit tangent orthogonal to normal x 0.5 + 0.5, handedness 0/1
    vec3 baseColor;    // the material's inputs at the texel, for the material-input views
    float metallic;
    float roughness;   // perceptual: the factor x the map's g
    // KHR_materials_clearcoat's layer at the texel (weight 0: none); kd above already holds its 1 - w,
    // `fresnel` does not (clearcoatBaseEnds: the G-buffer keeps the material's F0 and f90).
    ClearcoatLayer coat;
};

// The material-input views (lp::materialInputShown): which input gbuffer.material_input holds; 0 (a
// program that never sets it) writes none.
#define LP_MATERIAL_INPUT_BASE_COLOR 1
#define LP_MATERIAL_INPUT_METALLIC 2
#define LP_MATERIAL_INPUT_ROUGHNESS 3
#define LP_MATERIAL_INPUT_OCCLUSION 4
uniform int uMaterialInput;

// Base colour and alpha (the alpha test reads .a): the factor x the texture x the vertex colour
// (glTF: baseColorFactor x baseColorTexture x COLOR_0).
vec4 materialBaseColor(MaterialInputs m, UvSets uvs, vec4 vertexColor) {
    vec4 base = vec4(m.diffuse, m.opacity) * vertexColor;
    if (m.hasDiffuseMap) base *= sampleMap(uDiffuseMap, LP_MATERIAL_BIND_DIFFUSE, materialTexCoord(m, uvs, LP_MAP_DIFFUSE));
    return base;
}

// MASK: whether the texel is cut away (the caller discards it).
bool materialAlphaRejects(MaterialInputs m, vec4 base) { return m.alphaMask && base.a < m.alphaCutoff; }

MaterialSample materialEvaluate(MaterialInputs m, vec4 base, SurfaceInputs s) {
    vec3 N = s.normal;
    float len = length(N);
    N = len > 1e-20 ? N / len : vec3(0.0, 0.0, 1.0);
    if (!s.frontFacing) N = -N;  // two-sided: thin walls are lit from either side
    vec3 interpolatedNormal = N;  // the clearcoat's, unless its own map bends it (not the base's maps)
    // The tangent frame: the interpolated tangent made orthogonal to the normal; the bitangent
    // cross(N, T) w points along +v (up the image), the +Y of normal maps and of height steps.
    vec3 T = s.tangent.xyz - N * dot(N, s.tangent.xyz);
    float tl = length(T);
    bool hasFrame = tl > 1e-20;
    T = hasFrame ? T / tl : vec3(1.0, 0.0, 0.0);
    vec3 B = cross(N, T) * (s.tangent.w < 0.0 ? -1.0 : 1.0);
    if (m.hasNormalMap && hasFrame) {
        vec3 t = sampleMap(uNormalMap, LP_MATERIAL_BIND_NORMAL, materialTexCoord(m, s.uvs, LP_MAP_NORMAL)).xyz * 2.0 - 1.0;
        N = normalMapNormal(N, T, B, t, m.normalScale);
    }
    if (m.hasBumpMap && hasFrame) {
        // Height map -> normal: central differences in texture space, bent along the tangent frame.
        vec2 texel = 1.0 / vec2(textureSize(uBumpMap, 0));
        TexCoord c = materialTexCoord(m, s.uvs, LP_MAP_BUMP);
        float hl = sampleMap(uBumpMap, LP_MATERIAL_BIND_BUMP, offsetTexCoord(c, vec2(-texel.x, 0))).r;
        float hr = sampleMap(uBumpMap, LP_MATERIAL_BIND_BUMP, offsetTexCoord(c, vec2(texel.x, 0))).r;
        float hd = sampleMap(uBumpMap, LP_MATERIAL_BIND_BUMP, offsetTexCoord(c, vec2(0, -texel.y))).r;
        float hu = sampleMap(uBumpMap, LP_MATERIAL_BIND_BUMP, offsetTexCoord(c, vec2(0, texel.y))).r;
        vec3 bent = N - m.bumpScale * 4.0 * ((hr - hl) * T + (hu - hd) * B);
        float bl = length(bent);
        if (bl > 1e-20) N = bent / bl;
    }
    float metallic = clamp(m.metallic, 0.0, 1.0);
    // Up to the IBL's roughness floor (0.02); the analytic BRDFs clamp to 10000 themselves.
    float shininess = clamp(m.shininess, 0.0, LP_IBL_MAX_SHININESS);
    float roughness = m.roughness;
    if (m.hasMetalRoughMap) {
        vec4 mr = sampleMap(uMetalRoughMap, LP_MATERIAL_BIND_METAL_ROUGH, materialTexCoord(m, s.uvs, LP_MAP_METAL_ROUGH));
        metallic = clamp(metallic * mr.b, 0.0, 1.0);
        roughness = m.roughness * mr.g;
        shininess = shininessFromRoughnessToFloor(roughness);
    }
    MaterialSample o;
    vec3 baseColor = clamp(base.rgb, 0.0, 1.0);
    vec3 dielectricF0 = clamp(m.specular, 0.0, 1.0);
    float dielectricF90 = clamp(m.dielectricF90, 0.0, 1.0);
    if (m.givenF90) {
        // KHR_materials_specular: F0 = min(F0_ior x colour x colour map, 1) x weight x weight map's a.
        vec3 colour = max(m.specular, vec3(0.0));
        if (m.hasSpecularColorMap)
            colour *= sampleMap(uSpecularColorMap, LP_MATERIAL_SLOT_SPECULAR_COLOR,
                                materialTexCoord(m, s.uvs, LP_MAP_SPECULAR_COLOR)).rgb;
        if (m.hasSpecularMap)
            dielectricF90 *= sampleMap(uSpecularMap, LP_MATERIAL_SLOT_SPECULAR, materialTexCoord(m, s.uvs, LP_MAP_SPECULAR)).a;
        dielectricF0 = min(colour, vec3(1.0)) * dielectricF90;
    }
    o.normal = N;
    o.coat = noClearcoat();
    if (m.clearcoat > 0.0 && !m.flatLit) {
        // KHR_materials_clearcoat: clearcoat = factor x map.r, roughness = factor x map.g, the normal the
        // interpolated one or the coat's own map's (the base's normal and bump maps leave it alone).
        float clearcoat = m.clearcoat;
        if (m.hasClearcoatMap)
            clearcoat *= sampleMap(uClearcoatMap, LP_MATERIAL_SLOT_CLEARCOAT, materialTexCoord(m, s.uvs, LP_MAP_CLEARCOAT)).r;
        float coatRoughness = m.clearcoatRoughness;
        if (m.hasClearcoatRoughnessMap)
            coatRoughness *= sampleMap(uClearcoatRoughnessMap, LP_MATERIAL_SLOT_CLEARCOAT_ROUGHNESS,
                                       materialTexCoord(m, s.uvs, LP_MAP_CLEARCOAT_ROUGHNESS)).g;
        vec3 Nc = interpolatedNormal;
        if (m.hasClearcoatNormalMap && hasFrame) {
            vec3 t = sampleMap(uClearcoatNormalMap, LP_MATERIAL_SLOT_CLEARCOAT_NORMAL,
                               materialTexCoord(m, s.uvs, LP_MAP_CLEARCOAT_NORMAL)).xyz * 2.0 - 1.0;
            Nc = normalMapNormal(interpolatedNormal, T, B, t, m.clearcoatNormalScale);
        }
        float pl = length(s.position);
        vec3 V = pl > 0.0 ? -s.position / pl : vec3(0.0, 0.0, 1.0);
        o.coat = clearcoatLayer(clearcoat, coatRoughness, Nc, V);
    }
    // Flat-lit: the colour shown as it is, no BRDF applies.
    o.kd = m.flatLit ? baseColor * (1.0 - metallic)
                     : materialDiffuseAlbedo(uBrdf, baseColor, metallic, dielectricF0, m.givenF90);
    o.fresnel = materialFresnelEnds(baseColor, metallic, dielectricF0, dielectricF90, m.givenF90);
    o.f0 = o.fresnel.f0;
    o.kd *= 1.0 - o.coat.weight;  // the base under the coat (exact: 1 without one)
    if ((uHiddenTerms & LP_HIDE_DIFFUSE) != 0) o.kd = vec3(0.0);
    o.baseColor = baseColor;
    o.metallic = metallic;
    o.roughness = clamp(roughness, 0.0, 1.0);
    o.shininess = shininess;
    o.occlusion = 1.0;
    if (m.hasOcclusionMap)
        o.occlusion = mix(1.0, sampleMap(uOcclusionMap, LP_MATERIAL_BIND_OCCLUSION, materialTexCoord(m, s.uvs, LP_MAP_OCCLUSION)).r,
                          clamp(m.occlusionStrength, 0.0, 1.0));
    vec3 Tn = s.tangent.xyz - N * dot(N, s.tangent.xyz);
    float tn = length(Tn);
    o.tangentView = vec4(tn > 1e-20 ? Tn / tn * 0.5 + 0.5 : vec3(0.5), s.tangent.w < 0.0 ? 0.0 : 1.0);
    return o;
}

// gbuffer.fresnel's value (common/gbuffer_layout.glsl): f90 and the diffuse shape, one scalar (the
// shape of a material without KHR_materials_specular is grey but for MTL's coloured Ks below 0.02: its
// largest channel stands for it).
vec2 materialFresnelValue(MaterialSample g) {
    return vec2(g.fresnel.f90, max(max(g.fresnel.diffuseScale.r, g.fresnel.diffuseScale.g), g.fresnel.diffuseScale.b));
}

// gbuffer.clearcoat's value (common/gbuffer_layout.glsl, RGBA16 unorm): the coat's weight w, sqrt of its
// GGX alpha (the perceptual roughness: 16 bits keep alpha's floor 1e-3 within 0.1%) and its normal,
// octahedral, mapped to [0, 1].
vec4 materialClearcoatValue(MaterialSample g) {
    return vec4(g.coat.weight, sqrt(g.coat.alpha), octahedralEncode(g.coat.normal) * 0.5 + 0.5);
}

// gbuffer.material_input's value: the input uMaterialInput names, linear (base colour) or grey.
vec4 materialInputValue(MaterialSample g) {
    if (uMaterialInput == LP_MATERIAL_INPUT_BASE_COLOR) return vec4(g.baseColor, 1.0);
    if (uMaterialInput == LP_MATERIAL_INPUT_METALLIC) return vec4(vec3(g.metallic), 1.0);
    if (uMaterialInput == LP_MATERIAL_INPUT_ROUGHNESS) return vec4(vec3(g.roughness), 1.0);
    return vec4(vec3(g.occlusion), 1.0);
}

#endif
