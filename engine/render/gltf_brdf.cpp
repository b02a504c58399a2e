#include "engine/render/gltf_brdf.hpp"

#include <algorithm>
#include <cmath>

namespace lp {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

double gltfDielectricF0(double ior) {
    const double r = (ior - 1.0) / (ior + 1.0);
    return r * r;
}

double gltfIorOfF0(double f0) {
    const double r = std::sqrt(f0);
    return (1.0 + r) / (1.0 - r);
}

double gltfGgxDistribution(double nh, double alpha) {
    if (nh <= 0.0) return 0.0;
    const double a2 = alpha * alpha, d = nh * nh * (a2 - 1.0) + 1.0;
    return a2 / (kPi * d * d);
}

double gltfSmithVisibility(double nv, double nl, double alpha, SpecularMasking masking) {
    const double a2 = alpha * alpha;
    const double lv = std::sqrt(a2 + (1.0 - a2) * nv * nv), ll = std::sqrt(a2 + (1.0 - a2) * nl * nl);
    if (masking == SpecularMasking::Separable) return 1.0 / ((nl + ll) * (nv + lv));
    return 0.5 / (nv * ll + nl * lv);
}

GltfBrdfLobes gltfBrdfLobes(const GltfBrdfMaterial& m, glm::dvec3 N, glm::dvec3 V, glm::dvec3 L, SpecularMasking masking) {
    const double nl = glm::dot(N, L), nv = glm::dot(N, V);
    if (nl <= 0.0 || nv <= 0.0) return {};
    const glm::dvec3 H = glm::normalize(V + L);
    const double vh = std::abs(glm::dot(V, H));
    const double alpha = m.roughness * m.roughness;
    const double specular = gltfGgxDistribution(glm::dot(N, H), alpha) * gltfSmithVisibility(nv, nl, alpha, masking);
    const double w = std::pow(1.0 - vh, 5.0);
    const glm::dvec3 metalFresnel = m.baseColor + (glm::dvec3(1.0) - m.baseColor) * w;
    // KHR_materials_specular's fresnel_mix: f0 = min(F0_ior specularColor, 1), fr = f0 + (1 - f0)(1 - V.H)^5,
    // the layer weighted by specular fr and the base by 1 - specular max_value(fr) (without the
    // extension specular = 1 and specularColor = 1: Appendix B's mix(base, layer, F)).
    const glm::dvec3 f0 = glm::min(gltfDielectricF0(m.ior) * m.specularColor, glm::dvec3(1.0));
    const glm::dvec3 fr = f0 + (glm::dvec3(1.0) - f0) * w;
    const double frMax = std::max(fr.x, std::max(fr.y, fr.z));
    // material = mix(dielectric, metal, metallic), dielectric = fresnel_mix(base / pi, specular),
    // metal = F_metal specular.
    GltfBrdfLobes out;
    out.diffuse = (1.0 - m.metallic) * (1.0 - m.specular * frMax) * m.baseColor / kPi;
    out.specular = specular * ((1.0 - m.metallic) * m.specular * fr + m.metallic * metalFresnel);
    return out;
}

glm::dvec3 gltfBrdf(const GltfBrdfMaterial& m, glm::dvec3 N, glm::dvec3 V, glm::dvec3 L, SpecularMasking masking) {
    const GltfBrdfLobes lobes = gltfBrdfLobes(m, N, V, L, masking);
    return lobes.diffuse + lobes.specular;
}

double gltfClearcoatWeight(double clearcoat, glm::dvec3 Nc, glm::dvec3 V) {
    const double f0 = gltfDielectricF0(1.5);
    return clearcoat * (f0 + (1.0 - f0) * std::pow(1.0 - std::abs(glm::dot(V, Nc)), 5.0));
}

double gltfClearcoatLobe(const GltfBrdfMaterial& m, glm::dvec3 Nc, glm::dvec3 V, glm::dvec3 L, SpecularMasking masking) {
    const double nl = glm::dot(Nc, L), nv = glm::dot(Nc, V);
    if (nl <= 0.0 || nv <= 0.0) return 0.0;
    const double alpha = m.clearcoatRoughness * m.clearcoatRoughness;
    return gltfGgxDistribution(glm::dot(Nc, glm::normalize(V + L)), alpha) * gltfSmithVisibility(nv, nl, alpha, masking);
}

glm::dvec3 gltfCoatedBrdfCosine(const GltfBrdfMaterial& m, glm::dvec3 N, glm::dvec3 Nc, glm::dvec3 V, glm::dvec3 L,
                                SpecularMasking masking) {
    const glm::dvec3 base = gltfBrdf(m, N, V, L, masking) * std::max(glm::dot(N, L), 0.0);
    if (m.clearcoat <= 0.0) return base;
    const double w = gltfClearcoatWeight(m.clearcoat, Nc, V);
    return base * (1.0 - w) + glm::dvec3(w * gltfClearcoatLobe(m, Nc, V, L, masking) * std::max(glm::dot(Nc, L), 0.0));
}

}  // namespace lp
