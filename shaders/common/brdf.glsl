// BRDFs. Radiance leaving a surface lit by a light of irradiance E (at normal incidence) from L:
//   Lo = f(N, V, L) * E * max(N.L, 0)
#ifndef LP_BRDF_GLSL
#define LP_BRDF_GLSL

const float LP_PI = 3.14159265358979;

// What the lit frame leaves out (lp::hiddenShadingTerms: the term-diffuse, term-specular and emissive
// views); a program that never sets it hides nothing. The diffuse term is hidden by the material
// evaluation (kd = 0: every diffuse and ambient term scales with it); the specular by
// lpSpecularShown() at each specular lobe (the suns', the local lights', the IBL's and its extracted
// sources'), F0 kept, since the diffuse weight 1 - F depends on it; the forward passes and the
// emission pass leave out emission.
#define LP_HIDE_DIFFUSE 1
#define LP_HIDE_SPECULAR 2
#define LP_HIDE_EMISSION 4
#define LP_HIDE_CLEARCOAT 8  // KHR_materials_clearcoat's layer (clearcoatSpecular and its IBL)
uniform int uHiddenTerms;
float lpSpecularShown() { return (uHiddenTerms & LP_HIDE_SPECULAR) != 0 ? 0.0 : 1.0; }
float lpClearcoatShown() { return (uHiddenTerms & LP_HIDE_CLEARCOAT) != 0 ? 0.0 : 1.0; }

// Energy-normalised Blinn-Phong: f = kd/pi + ks * (n + 8) / (8 pi) * (N.H)^n.
// The (n+8)/(8 pi) factor keeps the lobe's reflected energy roughly constant as n changes.
// Safe for n = 0 and n = 10000, for N.L or N.V at or below 0, and for V = -L (H undefined).
vec3 blinnPhongBrdf(vec3 N, vec3 V, vec3 L, vec3 kd, vec3 ks, float shininess) {
    vec3 h = V + L;
    float hl = dot(h, h);
    vec3 H = hl > 1e-12 ? h * inversesqrt(hl) : N;
    float nh = clamp(dot(N, H), 0.0, 1.0);
    float n = clamp(shininess, 0.0, 10000.0);
    // pow(0, 0) is undefined in GLSL: exp2(n * log2(nh)) with nh = 0 and n = 0 must be 1.
    float lobe = (n == 0.0) ? 1.0 : (nh > 0.0 ? exp2(n * log2(nh)) : 0.0);
    return kd / LP_PI + ks * ((n + 8.0) / (8.0 * LP_PI)) * lobe * lpSpecularShown();
}

vec3 blinnPhongRadiance(vec3 N, vec3 V, vec3 L, vec3 kd, vec3 ks, float shininess, vec3 irradiance) {
    float nl = dot(N, L);
    if (nl <= 0.0) return vec3(0.0);
    return blinnPhongBrdf(N, V, L, kd, ks, shininess) * irradiance * nl;
}

// ---- GGX: glTF 2.0's metallic-roughness BRDF (Appendix B) ---------------------------------------
// f = diffuse + D(h) Vis(v, l) F(v.h): GGX (Trowbridge-Reitz) distribution, Smith visibility
// Vis = G2 / (4 N.L N.V) of the model uSpecularMasking selects, Schlick Fresnel towards f90, and the
// dielectric's diffuse base / pi weighted by 1 - F(v.h) (ggxDiffuse). alpha is GGX's width (alpha =
// roughness^2). alpha is clamped to LP_GGX_MIN_ALPHA: D peaks at 1/(pi alpha^2), 3.2e5 there, which
// float holds; alpha = 0 would be a delta. N.V is clamped to LP_GGX_MIN_NV: normal interpolation
// and bump maps make slightly back-facing N.V, which must give a bright rim, not NaN.
const float LP_GGX_MIN_ALPHA = 1e-3;
const float LP_GGX_MIN_NV = 1e-4;

// The BRDF switch (RenderSettings::brdf, --brdf): what the light passes evaluate, and what the material
// evaluation stores as the diffuse colour (materialDiffuseAlbedo). A program that never sets uBrdf gets
// GGX, the default.
#define LP_BRDF_GGX 0
#define LP_BRDF_BLINN_PHONG 1
uniform int uBrdf;

float ggxAlphaFromRoughness(float roughness) {
    float r = clamp(roughness, 0.0, 1.0);
    return max(r * r, LP_GGX_MIN_ALPHA);
}

// MTL/Blinn-Phong exponent -> GGX alpha by the usual Beckmann equivalence alpha = sqrt(2 / (n + 2)):
// n = 0 gives alpha = 1 (roughest). Not clamped to Blinn-Phong's 10000: a glTF roughness below 0.119
// keeps its own alpha = r^2 (the G-buffer carries n to the 0.02 floor), down to LP_GGX_MIN_ALPHA.
float ggxAlphaFromShininess(float shininess) {
    float n = max(shininess, 0.0);
    return max(sqrt(2.0 / (n + 2.0)), LP_GGX_MIN_ALPHA);
}

// A perceptual roughness r (GGX alpha = r^2) as the Blinn-Phong exponent with the same alpha,
// n = 2 / alpha^2 - 2, clamped to [0, 10000] (r >= 0.119); lp::shininessFromRoughness on the CPU.
float shininessFromRoughness(float roughness) {
    float r = clamp(roughness, 0.0, 1.0);
    float a2 = r * r * r * r;
    return a2 <= 2.0 / 10002.0 ? 10000.0 : clamp(2.0 / a2 - 2.0, 0.0, 10000.0);
}

// D(h) = alpha^2 / (pi ((N.H)^2 (alpha^2 - 1) + 1)^2), written with |N x H|^2 = 1 - (N.H)^2 from
// the cross product: near the peak 1 - nh*nh cancels to rounding noise far above alpha^2.
float ggxDistribution(vec3 N, vec3 H, float alpha) {
    float a = max(alpha, LP_GGX_MIN_ALPHA);
    float a2 = a * a;
    float nh = min(dot(N, H), 1.0);
    if (nh <= 0.0) return 0.0;  // microfacets face up: chi+(N.H)
    vec3 nxh = cross(N, H);
    float sin2 = min(dot(nxh, nxh), 1.0);
    float d = nh * nh * a2 + sin2;  // = nh^2 (a2 - 1) + 1 for unit N, H
    return a2 / (LP_PI * max(d * d, 1e-30));
}

// Smith's masking-shadowing G2 (RenderSettings::specularMasking, --specular-masking): height-correlated
// 1 / (1 + Lambda(V) + Lambda(L)) (Heitz 2014; the glTF specification's V_SmithGGXCorrelated, Filament's
// and Unreal's: the default) or separable G1(V) G1(L) (Mitsuba's built-in rough BSDFs). The passes that
// shade GGX set uSpecularMasking; a program that never sets it gets 0, height-correlated.
#define LP_SPECULAR_MASKING_HEIGHT_CORRELATED 0
#define LP_SPECULAR_MASKING_SEPARABLE 1
uniform int uSpecularMasking;

// Vis = G2 / (4 N.L N.V) from each direction's cosine and its length in the alpha-stretched space,
// lv = |(alpha_x V.x, alpha_y V.y, N.V)| = N.V (1 + 2 Lambda(V)) (likewise ll): separable
// 1 / ((nv + lv) (nl + ll)), height-correlated 0.5 / (nl lv + nv ll). Isotropic and anisotropic alike.
float smithVisibilityFromLengths(int masking, float nv, float nl, float lv, float ll) {
    if (masking == LP_SPECULAR_MASKING_SEPARABLE) return 1.0 / max((nv + lv) * (nl + ll), 1e-30);
    return 0.5 / max(nl * lv + nv * ll, 1e-30);
}

// Isotropic GGX: lv = sqrt(N.V^2 (1 - a2) + a2), ll likewise.
float ggxVisibilityOf(int masking, float nv, float nl, float alpha) {
    float a = max(alpha, LP_GGX_MIN_ALPHA);
    float a2 = a * a;
    nv = max(nv, LP_GGX_MIN_NV);
    nl = max(nl, 0.0);
    return smithVisibilityFromLengths(masking, nv, nl, sqrt(nv * nv * (1.0 - a2) + a2), sqrt(nl * nl * (1.0 - a2) + a2));
}

float ggxVisibility(float nv, float nl, float alpha) { return ggxVisibilityOf(uSpecularMasking, nv, nl, alpha); }

// G2 / G1(V) from Smith's Lambdas: what f cos / pdf(L) comes to when L is drawn from the distribution of
// visible normals (pdf(L) = G1(V) D(H) / (4 N.V)). Separable: G1(L); height-correlated:
// (1 + Lambda(V)) / (1 + Lambda(V) + Lambda(L)).
float smithShadowingGivenMasking(int masking, float lambdaV, float lambdaL) {
    if (masking == LP_SPECULAR_MASKING_SEPARABLE) return 1.0 / (1.0 + lambdaL);
    return (1.0 + lambdaV) / (1.0 + lambdaV + lambdaL);
}

// Schlick's Fresnel F = F0 + (f90 - F0) (1 - V.H)^5 reaches f90 = clamp(50 * mean(F0), 0, 1) at grazing
// (Filament's specular occlusion): 1, as in the glTF specification, for every F0 of a real material
// (0.02 and up); F0 = 0 (MTL Ks 0, "no specular") stays exactly Lambertian.
float specularF90(vec3 f0) { return clamp(50.0 * dot(f0, vec3(1.0 / 3.0)), 0.0, 1.0); }

float schlickWeight(float vh) {
    float m = clamp(1.0 - vh, 0.0, 1.0);
    float m2 = m * m;
    return m2 * m2 * m;
}

// Schlick's two ends at a surface point, and the diffuse layer's Fresnel shape under them (ggxDiffuse):
// the diffuse weight is 1 - diffuseScale (1 - V.H)^5 on top of the kd the material evaluation stores.
// Most materials derive f90 and the shape from F0 (fresnelEndsOfF0, the clamp above); a material with
// KHR_materials_specular gives them (materialFresnelEnds), and the G-buffer carries them then
// (gbuffer.fresnel: common/gbuffer_layout.glsl's gbufferFresnel).
struct FresnelEnds {
    vec3 f0;
    float f90;
    vec3 diffuseScale;
};

vec3 fresnelSchlick(FresnelEnds e, float vh) { return e.f0 + (vec3(e.f90) - e.f0) * schlickWeight(vh); }

// Unit half vector of V and L (N where they cancel).
vec3 brdfHalfVector(vec3 N, vec3 V, vec3 L) {
    vec3 h = V + L;
    float hl = dot(h, h);
    return hl > 1e-12 ? h * inversesqrt(hl) : N;
}

// Specular lobe alone: D Vis F (no N.L). Zero for N.L <= 0.
vec3 ggxSpecular(vec3 N, vec3 V, vec3 L, FresnelEnds e, float alpha) {
    float nl = dot(N, L);
    if (nl <= 0.0) return vec3(0.0);
    vec3 H = brdfHalfVector(N, V, L);
    float vh = clamp(dot(V, H), 0.0, 1.0);
    return ggxDistribution(N, H, alpha) * ggxVisibility(dot(N, V), nl, alpha) * fresnelSchlick(e, vh) * lpSpecularShown();
}

// ---- The diffuse layer --------------------------------------------------------------------------
// glTF's dielectric is fresnel_mix(diffuse, specular): base / pi weighted by 1 - F(V.H), F of the
// dielectric's own F0 (0.04, or KHR_materials_ior's; MTL: Ks). With f90 = 1 that weight factors as
// (1 - F0) (1 - (1 - V.H)^5): the material evaluation stores kd = base (1 - metallic) (1 - F0_dielectric)
// (materialDiffuseAlbedo) and the light passes apply the shape (1 - (1 - V.H)^5) alone, so the G-buffer's
// mixed F0 = mix(F0_dielectric, base, metallic) (Schlick is linear in F0: the metal's and the
// dielectric's specular mix exactly) needs no second F0 and every metallic is exact. For the rare
// F0 < 0.02 (f90 < 1: MTL Ks 0, ior below 1.33) the shape is 1 - c (1 - V.H)^5 with
// c = (f90 - F0) / (1 - F0) of the stored F0: exact where metallic is 0 or 1 (Ks 0: c = 0, Lambertian).
vec3 ggxDiffuseFresnelScale(vec3 f0) {
    float f90 = specularF90(f0);
    return f90 >= 1.0 ? vec3(1.0) : (vec3(f90) - f0) / max(vec3(1.0) - f0, vec3(1e-6));
}

// The ends every material without KHR_materials_specular has: f90 and the diffuse shape from F0.
FresnelEnds fresnelEndsOfF0(vec3 f0) { return FresnelEnds(f0, specularF90(f0), ggxDiffuseFresnelScale(f0)); }

// The diffuse term, kd as the material evaluation stores it (without N.L).
vec3 ggxDiffuse(vec3 kd, FresnelEnds e, float vh) {
    return kd / LP_PI * (vec3(1.0) - e.diffuseScale * schlickWeight(vh));
}

// The same weight averaged over a uniform (white-furnace) light: 1 - c X(N.V), X(N.V) = (1 / pi)
// integral of (1 - V.H)^5 N.L over the hemisphere of L, which depends on N.V alone; fitted by a cubic in
// 1 - N.V (X(1) = 8e-5, X(0.5) = 0.0050, X(0) = 0.0282; fit error below 1e-4). The IBL's diffuse: what a
// path tracer of this BRDF reflects from a uniform environment, exactly.
vec3 ggxDiffuseFresnelMeanWeight(FresnelEnds e, float nv) {
    float t = 1.0 - clamp(nv, 0.0, 1.0);
    float mean = max(((0.0256872 * t - 0.00200696) * t + 0.00439877) * t - 1.04356e-5, 0.0);
    return vec3(1.0) - e.diffuseScale * mean;
}

// Full GGX BRDF (without N.L); F0 and f90 from `e`, alpha from the shininess (the roughness's exponent).
vec3 ggxBrdf(vec3 N, vec3 V, vec3 L, vec3 kd, FresnelEnds e, float shininess) {
    vec3 H = brdfHalfVector(N, V, L);
    return ggxDiffuse(kd, e, clamp(dot(V, H), 0.0, 1.0)) + ggxSpecular(N, V, L, e, ggxAlphaFromShininess(shininess));
}

vec3 ggxRadiance(vec3 N, vec3 V, vec3 L, vec3 kd, FresnelEnds e, float shininess, vec3 irradiance) {
    float nl = dot(N, L);
    if (nl <= 0.0) return vec3(0.0);
    return ggxBrdf(N, V, L, kd, e, shininess) * irradiance * nl;
}

// ---- The switch ---------------------------------------------------------------------------------
// The diffuse and the specular part of BRDF `brdf` (without N.L; zero for N.L <= 0 is the caller's):
// the local lights window them apart (LP_LOCAL_SPECULAR_*). Blinn-Phong takes e.f0 as its ks.
vec3 brdfDiffuse(int brdf, vec3 N, vec3 V, vec3 L, vec3 kd, FresnelEnds e) {
    if (brdf == LP_BRDF_BLINN_PHONG) return kd / LP_PI;
    return ggxDiffuse(kd, e, clamp(dot(V, brdfHalfVector(N, V, L)), 0.0, 1.0));
}
vec3 brdfSpecular(int brdf, vec3 N, vec3 V, vec3 L, FresnelEnds e, float shininess) {
    if (brdf == LP_BRDF_BLINN_PHONG) return blinnPhongBrdf(N, V, L, vec3(0.0), e.f0, shininess);
    return ggxSpecular(N, V, L, e, ggxAlphaFromShininess(shininess));
}

vec3 brdfRadiance(int brdf, vec3 N, vec3 V, vec3 L, vec3 kd, FresnelEnds e, float shininess, vec3 irradiance) {
    return brdf == LP_BRDF_BLINN_PHONG ? blinnPhongRadiance(N, V, L, kd, e.f0, shininess, irradiance)
                                       : ggxRadiance(N, V, L, kd, e, shininess, irradiance);
}

// The same with f90 and the diffuse shape derived from F0 = ks (a material without KHR_materials_specular).
vec3 fresnelSchlick(vec3 f0, float vh) { return fresnelSchlick(fresnelEndsOfF0(f0), vh); }
vec3 ggxSpecular(vec3 N, vec3 V, vec3 L, vec3 f0, float alpha) { return ggxSpecular(N, V, L, fresnelEndsOfF0(f0), alpha); }
vec3 ggxDiffuse(vec3 kd, vec3 f0, float vh) { return ggxDiffuse(kd, fresnelEndsOfF0(f0), vh); }
vec3 ggxDiffuseFresnelMeanWeight(vec3 f0, float nv) { return ggxDiffuseFresnelMeanWeight(fresnelEndsOfF0(f0), nv); }
vec3 ggxBrdf(vec3 N, vec3 V, vec3 L, vec3 kd, vec3 ks, float shininess) { return ggxBrdf(N, V, L, kd, fresnelEndsOfF0(ks), shininess); }
vec3 brdfDiffuse(int brdf, vec3 N, vec3 V, vec3 L, vec3 kd, vec3 ks) { return brdfDiffuse(brdf, N, V, L, kd, fresnelEndsOfF0(ks)); }
vec3 brdfSpecular(int brdf, vec3 N, vec3 V, vec3 L, vec3 ks, float shininess) {
    return brdfSpecular(brdf, N, V, L, fresnelEndsOfF0(ks), shininess);
}
vec3 brdfRadiance(int brdf, vec3 N, vec3 V, vec3 L, vec3 kd, vec3 ks, float shininess, vec3 irradiance) {
    return brdfRadiance(brdf, N, V, L, kd, fresnelEndsOfF0(ks), shininess, irradiance);
}

// What the material evaluation stores as the diffuse colour: the diffuse layer's albedo for the BRDF
// in use. GGX: base (1 - metallic) (1 - F0_dielectric) (see the diffuse layer above); Blinn-Phong:
// base (1 - metallic), as the seeds.
vec3 materialDiffuseAlbedo(int brdf, vec3 baseColor, float metallic, vec3 dielectricF0) {
    vec3 kd = baseColor * (1.0 - metallic);
    return brdf == LP_BRDF_BLINN_PHONG ? kd : kd * (vec3(1.0) - dielectricF0);
}

// ---- KHR_materials_specular ---------------------------------------------------------------------
// A dielectric with a given f90 (the extension's specular weight s) and F0 = min(F0_ior specularColor,
// 1) s. The specification's fresnel_mix weights the layer by F = F0 + (f90 - F0) (1 - V.H)^5 and the
// diffuse by 1 - max3(F) (max_value: a scalar, so a coloured F0 tints no diffuse); max3 of F is
// m + (f90 - m) (1 - V.H)^5 with m = max3(F0), so the weight factors as
// (1 - m) (1 - c (1 - V.H)^5), c = (f90 - m) / (1 - m): kd holds (1 - m), the lights apply the shape c.
// The metal keeps F0 = base, f90 = 1; Schlick is linear in both ends, so mixing them by metallic is
// exact, and kd's (1 - metallic) with c of the dielectric alone keeps every metallic exact.
float specularDiffuseShape(vec3 dielectricF0, float dielectricF90) {
    float m = max(max(dielectricF0.r, dielectricF0.g), dielectricF0.b);
    return m >= 1.0 ? 0.0 : clamp((dielectricF90 - m) / (1.0 - m), 0.0, 1.0);
}

// The material's kd and Fresnel ends at a texel. givenF90: KHR_materials_specular (dielectricF90 its
// weight); otherwise f90 and the shape come from the mixed F0 as for every other material.
vec3 materialDiffuseAlbedo(int brdf, vec3 baseColor, float metallic, vec3 dielectricF0, bool givenF90) {
    if (!givenF90 || brdf == LP_BRDF_BLINN_PHONG) return materialDiffuseAlbedo(brdf, baseColor, metallic, dielectricF0);
    return baseColor * (1.0 - metallic) * (1.0 - max(max(dielectricF0.r, dielectricF0.g), dielectricF0.b));
}
FresnelEnds materialFresnelEnds(vec3 baseColor, float metallic, vec3 dielectricF0, float dielectricF90, bool givenF90) {
    vec3 f0 = mix(dielectricF0, baseColor, metallic);
    if (!givenF90) return fresnelEndsOfF0(f0);
    return FresnelEnds(f0, mix(dielectricF90, 1.0, metallic), vec3(specularDiffuseShape(dielectricF0, dielectricF90)));
}

// ---- KHR_materials_clearcoat -------------------------------------------------------------------
// The extension's fresnel_coat layers a GGX specular lobe (its own normal Nc and alpha = clearcoat
// roughness^2, no Fresnel inside) over the whole material, emission included:
//   coated = material (1 - w) + clearcoat_brdf w,   w = clearcoat (0.04 + 0.96 (1 - |V.Nc|)^5)
// w depends on V and Nc alone (the spec's N.V Fresnel, not V.H): one number a pixel. So the base is
// scaled once where the surface is evaluated (kd by the material evaluation, the Fresnel ends by
// clearcoatBaseEnds: the base BRDF is linear in kd, F0 and f90 under GGX and Blinn-Phong alike), and
// each light adds the layer's lobe (clearcoatSpecular). Weight 0 (noClearcoat) is the plain material,
// bit for bit.
struct ClearcoatLayer {
    float weight;  // w = clearcoat x the coat's Fresnel at V: the layer's share of the reflection
    float alpha;   // GGX alpha of the coat (clearcoat roughness^2, floored as ggxAlphaFromRoughness)
    vec3 normal;   // Nc: the coat's unit normal (the interpolated normal, or its own normal map's)
};
const float LP_CLEARCOAT_F0 = 0.04;  // ior 1.5

ClearcoatLayer noClearcoat() { return ClearcoatLayer(0.0, 1.0, vec3(0.0, 0.0, 1.0)); }

// w = clearcoat (F0 + (1 - F0) (1 - |V.Nc|)^5), F0 of ior 1.5.
float clearcoatWeight(float clearcoat, vec3 Nc, vec3 V) {
    return clamp(clearcoat, 0.0, 1.0) * (LP_CLEARCOAT_F0 + (1.0 - LP_CLEARCOAT_F0) * schlickWeight(abs(dot(Nc, V))));
}

ClearcoatLayer clearcoatLayer(float clearcoat, float roughness, vec3 Nc, vec3 V) {
    return ClearcoatLayer(clearcoatWeight(clearcoat, Nc, V), ggxAlphaFromRoughness(roughness), Nc);
}

// The base's Fresnel ends under the coat: f0 and f90 times 1 - w (the diffuse shape is a ratio: kept).
FresnelEnds clearcoatBaseEnds(FresnelEnds e, ClearcoatLayer c) {
    float b = 1.0 - c.weight;
    return FresnelEnds(e.f0 * b, e.f90 * b, e.diffuseScale);
}

// The layer's lobe w D(Nc, H) Vis(Nc.V, Nc.L) (no N.L; zero for Nc.L <= 0 or without a coat): the
// glTF specular_brdf on the coat's normal and alpha, weighted by w.
float clearcoatSpecular(ClearcoatLayer c, vec3 V, vec3 L) {
    float nl = dot(c.normal, L);
    if (c.weight <= 0.0 || nl <= 0.0) return 0.0;
    vec3 H = brdfHalfVector(c.normal, V, L);
    return c.weight * ggxDistribution(c.normal, H, c.alpha) * ggxVisibility(dot(c.normal, V), nl, c.alpha) *
           lpClearcoatShown();
}

// Radiance the layer reflects from a light of irradiance E (at normal incidence) from L: lobe x E x Nc.L.
vec3 clearcoatRadiance(ClearcoatLayer c, vec3 V, vec3 L, vec3 E) {
    return clearcoatSpecular(c, V, L) * E * max(dot(c.normal, L), 0.0);
}

#endif
