#pragma once
// glTF 2.0's metallic-roughness BRDF (the specification's Appendix B), evaluated exactly in double
// precision: the reference lightpass's light passes are tested against (shaders/common/brdf.glsl
// implements it). No clamps and none of the shaders' heuristics: alpha = roughness^2 as it is,
// Schlick's Fresnel towards 1, the dielectric's diffuse weighted by 1 - F(V.H):
//   metal_brdf      = specular_brdf(alpha) * (base + (1 - base) (1 - |V.H|)^5)
//   dielectric_brdf = fresnel_mix(base / pi, specular_brdf(alpha)): the layer weighted by s F, the base
//                     by 1 - s max3(F), F = f0 + (1 - f0) (1 - |V.H|)^5, f0 = min(F0_ior c, 1)
//                     (KHR_materials_specular's s = specular, c = specularColor; without it 1 and 1,
//                     Appendix B's mix(base / pi, specular_brdf, F))
//   material        = mix(dielectric_brdf, metal_brdf, metallic)
//   specular_brdf   = D_GGX(alpha) * V_Smith(alpha)  (height-correlated: the specification's; or separable)
// KHR_materials_clearcoat layers a coat over that material (gltfCoatedBrdf):
//   coated          = material (1 - w) + specular_brdf(Nc, alpha_c) w,
//   w               = clearcoat (0.04 + 0.96 (1 - |V.Nc|)^5)   (fresnel_coat with ior 1.5)
#include <glm/glm.hpp>

#include "engine/render/settings.hpp"

namespace lp {

struct GltfBrdfMaterial {
    glm::dvec3 baseColor{1.0};
    double metallic = 1.0;
    double roughness = 1.0;  // perceptual: alpha = roughness^2
    double ior = 1.5;        // the dielectric's F0 = ((ior - 1) / (ior + 1))^2 (KHR_materials_ior): 0.04
    double specular = 1.0;   // KHR_materials_specular's specularFactor (x specularTexture.a): the weight
    glm::dvec3 specularColor{1.0};  // its specularColorFactor (x specularColorTexture.rgb)
    double clearcoat = 0.0;           // KHR_materials_clearcoat's clearcoatFactor (x clearcoatTexture.r); 0: none
    double clearcoatRoughness = 0.0;  // its clearcoatRoughnessFactor (x clearcoatRoughnessTexture.g): alpha_c = r^2
};

double gltfDielectricF0(double ior);
// Its inverse: the index of a dielectric of F0 `f0` in [0, 1) (MTL's Ks as glTF's dielectric).
double gltfIorOfF0(double f0);

// GGX's D at N.H for alpha (0 where N.H <= 0).
double gltfGgxDistribution(double nh, double alpha);

// The visibility V = G2 / (4 |N.L| |N.V|) of `masking` at |N.V| = nv, |N.L| = nl.
double gltfSmithVisibility(double nv, double nl, double alpha, SpecularMasking masking);

// f(N, V, L) for unit vectors (no N.L factor) as its two lobes, the diffuse (1 - metallic) (1 - F(V.H))
// base / pi and the specular mix(F_dielectric, F_metal, metallic) D V; zero where N.L <= 0 or N.V <= 0
// (the specification's chi+(H.L) chi+(H.V) follow for a reflection).
struct GltfBrdfLobes {
    glm::dvec3 diffuse{0.0}, specular{0.0};
};
GltfBrdfLobes gltfBrdfLobes(const GltfBrdfMaterial& m, glm::dvec3 N, glm::dvec3 V, glm::dvec3 L,
                            SpecularMasking masking = SpecularMasking::HeightCorrelated);
// Their sum: the material's BRDF.
glm::dvec3 gltfBrdf(const GltfBrdfMaterial& m, glm::dvec3 N, glm::dvec3 V, glm::dvec3 L,
                    SpecularMasking masking = SpecularMasking::HeightCorrelated);

// KHR_materials_clearcoat's weight w = clearcoat (0.04 + 0.96 (1 - |V.Nc|)^5) for unit Nc and V.
double gltfClearcoatWeight(double clearcoat, glm::dvec3 Nc, glm::dvec3 V);
// The coat's lobe alone, specular_brdf(Nc, clearcoatRoughness^2) (no N.L, no weight); zero where
// Nc.L <= 0 or Nc.V <= 0.
double gltfClearcoatLobe(const GltfBrdfMaterial& m, glm::dvec3 Nc, glm::dvec3 V, glm::dvec3 L,
                         SpecularMasking masking = SpecularMasking::HeightCorrelated);
// The coated material's radiance factor f cos from L: gltfBrdf(N) (1 - w) N.L + lobe(Nc) w Nc.L, each
// cosine on its own normal (N the base's shading normal, Nc the coat's); the base's part is zero below
// its horizon and the coat's below the coat's. Without a coat (clearcoat 0) exactly gltfBrdf N.L.
glm::dvec3 gltfCoatedBrdfCosine(const GltfBrdfMaterial& m, glm::dvec3 N, glm::dvec3 Nc, glm::dvec3 V, glm::dvec3 L,
                                SpecularMasking masking = SpecularMasking::HeightCorrelated);

}  // namespace lp
