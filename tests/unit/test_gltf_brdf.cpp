// The double-precision reference of glTF 2.0's BRDF (engine/render/gltf_brdf.hpp) against values
// worked by hand from the specification's Appendix B, and its properties.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/render/gltf_brdf.hpp"

using namespace lp;

namespace {
constexpr double kPi = 3.14159265358979323846;
glm::dvec3 unit(double x, double y, double z) { return glm::normalize(glm::dvec3(x, y, z)); }
}  // namespace

// Head-on (N = V = L): V.H = 1, so F = F0; D = 1 / (pi alpha^2); V = 0.5 / (1 + 1) = 1 / 4 at
// N.V = N.L = 1 in either masking model. Dielectric: (1 - 0.04) base / pi + 0.04 D / 4; metal: base D / 4.
TEST(GltfBrdfReference, HeadOnMatchesTheSpecificationWorkedByHand) {
    const glm::dvec3 N(0, 0, 1), base(0.8, 0.5, 0.2);
    const double roughness = 0.5, alpha = roughness * roughness, d = 1.0 / (kPi * alpha * alpha);
    EXPECT_NEAR(gltfDielectricF0(1.5), 0.04, 1e-15);
    EXPECT_NEAR(gltfIorOfF0(0.04), 1.5, 1e-12);
    const glm::dvec3 dielectric = gltfBrdf({base, 0.0, roughness}, N, N, N);
    const glm::dvec3 metal = gltfBrdf({base, 1.0, roughness}, N, N, N);
    const glm::dvec3 half = gltfBrdf({base, 0.5, roughness}, N, N, N);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(dielectric[c], 0.96 * base[c] / kPi + 0.04 * d / 4.0, 1e-12);
        EXPECT_NEAR(metal[c], base[c] * d / 4.0, 1e-12);
        EXPECT_NEAR(half[c], 0.5 * (dielectric[c] + metal[c]), 1e-12);  // mix(dielectric, metal, metallic)
    }
    EXPECT_NEAR(gltfSmithVisibility(1.0, 1.0, alpha, SpecularMasking::Separable), 0.25, 1e-15);
    EXPECT_NEAR(gltfSmithVisibility(1.0, 1.0, alpha, SpecularMasking::HeightCorrelated), 0.25, 1e-15);
}

// An oblique pair, every term from the specification's formulas: V.H, Schlick with (1 - V.H)^5, GGX D
// at N.H, the height-correlated V = 0.5 / (N.V sqrt(a2 + (1 - a2) N.L^2) + N.L sqrt(a2 + (1 - a2) N.V^2)).
TEST(GltfBrdfReference, ObliqueMatchesTheSpecificationsTerms) {
    const glm::dvec3 N(0, 0, 1), V = unit(0.6, 0.0, 0.8), L = unit(-0.3, 0.4, 0.866);
    const glm::dvec3 H = glm::normalize(V + L);
    const double nv = V.z, nl = L.z, nh = H.z, vh = glm::dot(V, H), alpha = 0.7 * 0.7, a2 = alpha * alpha;
    const double D = a2 / (kPi * std::pow(nh * nh * (a2 - 1.0) + 1.0, 2.0));
    const double vis = 0.5 / (nv * std::sqrt(a2 + (1.0 - a2) * nl * nl) + nl * std::sqrt(a2 + (1.0 - a2) * nv * nv));
    const double w = std::pow(1.0 - vh, 5.0), fd = 0.04 + 0.96 * w;
    const glm::dvec3 base(0.3, 0.6, 0.9);
    const GltfBrdfLobes lobes = gltfBrdfLobes({base, 0.25, 0.7}, N, V, L);
    for (int c = 0; c < 3; ++c) {
        const double fm = base[c] + (1.0 - base[c]) * w;
        EXPECT_NEAR(lobes.diffuse[c], 0.75 * (1.0 - fd) * base[c] / kPi, 1e-12);
        EXPECT_NEAR(lobes.specular[c], D * vis * (0.75 * fd + 0.25 * fm), 1e-12);
    }
}

// Reciprocal (f(V, L) = f(L, V)), zero below either horizon, and the separable masking never above the
// height-correlated one ((1 + a)(1 + b) >= 1 + a + b).
TEST(GltfBrdfReference, IsReciprocalAndZeroBelowTheHorizon) {
    const glm::dvec3 N(0, 0, 1);
    const GltfBrdfMaterial m{{0.9, 0.4, 0.1}, 0.3, 0.45};
    const glm::dvec3 dirs[] = {unit(0.2, 0.1, 1.0), unit(-0.7, 0.3, 0.4), unit(0.5, -0.8, 0.1), unit(0.0, 0.9, 0.2)};
    for (const glm::dvec3& a : dirs)
        for (const glm::dvec3& b : dirs) {
            const glm::dvec3 ab = gltfBrdf(m, N, a, b), ba = gltfBrdf(m, N, b, a);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(ab[c], ba[c], 1e-12 * std::max(ab[c], 1.0));
            EXPECT_LE(gltfSmithVisibility(a.z, b.z, 0.45 * 0.45, SpecularMasking::Separable),
                      gltfSmithVisibility(a.z, b.z, 0.45 * 0.45, SpecularMasking::HeightCorrelated) * (1.0 + 1e-12));
        }
    EXPECT_EQ(gltfBrdf(m, N, unit(0.3, 0.0, 1.0), unit(1.0, 0.0, -0.1)), glm::dvec3(0.0));
    EXPECT_EQ(gltfBrdf(m, N, unit(1.0, 0.0, -0.1), unit(0.3, 0.0, 1.0)), glm::dvec3(0.0));
}

namespace {
// A material with KHR_materials_specular: weight s, colour c (the GltfBrdfMaterial's last two fields).
GltfBrdfMaterial specularMaterial(glm::dvec3 base, double metallic, double roughness, double s, glm::dvec3 c,
                                  double ior = 1.5) {
    GltfBrdfMaterial m{base, metallic, roughness, ior};
    m.specular = s;
    m.specularColor = c;
    return m;
}

// The directional albedo integral of f N.L over the hemisphere of L at view V (per channel), by a
// 256 x 512 midpoint rule in cosine-weighted coordinates (the integral of f N.L = pi mean of f).
glm::dvec3 directionalAlbedo(const GltfBrdfMaterial& m, glm::dvec3 V) {
    const int n = 256;
    glm::dvec3 sum(0.0);
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < 2 * n; ++b) {
            const double u = (a + 0.5) / n, phi = (b + 0.5) / (2 * n) * 2.0 * kPi;
            const glm::dvec3 L(std::sqrt(u) * std::cos(phi), std::sqrt(u) * std::sin(phi), std::sqrt(1.0 - u));
            sum += gltfBrdf(m, glm::dvec3(0, 0, 1), V, L);
        }
    return sum * kPi / double(2 * n * n);
}
}  // namespace

// KHR_materials_specular, from its fresnel_mix: specular 0 leaves no specular lobe and the full Lambert
// diffuse (1 - metallic) base / pi, at any angle and colour; a metal is untouched by it.
TEST(GltfBrdfReference, SpecularWeightZeroIsExactlyLambertian) {
    const glm::dvec3 N(0, 0, 1), base(0.7, 0.4, 0.2);
    const glm::dvec3 dirs[] = {unit(0.0, 0.0, 1.0), unit(0.6, 0.0, 0.8), unit(-0.3, 0.9, 0.1), unit(0.9, -0.2, 0.05)};
    for (double metallic : {0.0, 0.4})
        for (const glm::dvec3& V : dirs)
            for (const glm::dvec3& L : dirs) {
                const GltfBrdfLobes l = gltfBrdfLobes(specularMaterial(base, metallic, 0.5, 0.0, {3.0, 1.0, 0.2}), N, V, L);
                const GltfBrdfLobes metal = gltfBrdfLobes({base, 1.0, 0.5}, N, V, L);
                for (int c = 0; c < 3; ++c) {
                    EXPECT_NEAR(l.diffuse[c], (1.0 - metallic) * base[c] / kPi, 1e-15);
                    EXPECT_NEAR(l.specular[c], metallic * metal.specular[c], 1e-12 * std::max(metal.specular[c], 1.0));
                }
            }
}

// Head-on (V.H = 1) the layer is s min(F0_ior c, 1) D Vis and the base is weighted by 1 - s max3 of that
// F0: the colour tints F0 channel by channel (clamped at 1 before the weight) and not the diffuse.
TEST(GltfBrdfReference, SpecularColourTintsF0AsTheExtensionSays) {
    const glm::dvec3 N(0, 0, 1), base(0.5, 0.6, 0.7);
    const double roughness = 0.4, alpha = roughness * roughness, dv = 1.0 / (kPi * alpha * alpha) / 4.0;
    struct Case {
        double s, ior;
        glm::dvec3 colour;
    };
    for (const Case& k : {Case{1.0, 1.5, {1.0, 0.5, 0.25}}, Case{0.6, 1.5, {2.0, 1.0, 0.0}}, Case{0.8, 1.5, {40.0, 10.0, 1.0}},
                          Case{0.5, 2.0, {1.0, 1.0, 1.0}}}) {
        const GltfBrdfLobes l = gltfBrdfLobes(specularMaterial(base, 0.0, roughness, k.s, k.colour, k.ior), N, N, N);
        glm::dvec3 f0;
        for (int c = 0; c < 3; ++c) f0[c] = std::min(gltfDielectricF0(k.ior) * k.colour[c], 1.0) * k.s;
        const double maxF0 = std::max(f0.x, std::max(f0.y, f0.z));
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(l.specular[c], f0[c] * dv, 1e-12) << "s " << k.s << " channel " << c;
            EXPECT_NEAR(l.diffuse[c], (1.0 - maxF0) * base[c] / kPi, 1e-14) << "s " << k.s << " channel " << c;
        }
    }
    // Without the extension's fields (s 1, colour white) it is Appendix B's dielectric as before.
    const GltfBrdfLobes plain = gltfBrdfLobes({base, 0.0, roughness}, N, unit(0.6, 0.0, 0.8), unit(-0.3, 0.4, 0.866));
    const GltfBrdfLobes white = gltfBrdfLobes(specularMaterial(base, 0.0, roughness, 1.0, glm::dvec3(1.0)), N,
                                              unit(0.6, 0.0, 0.8), unit(-0.3, 0.4, 0.866));
    EXPECT_EQ(plain.diffuse, white.diffuse);
    EXPECT_EQ(plain.specular, white.specular);
}

// Furnace: a white dielectric's directional albedo (the integral of f N.L over the hemisphere). Head-on
// (N.V 1) it stays at or below 1 in every channel for every weight and colour, a clamped F0 1 and a black
// colour included (max_value keeps the diffuse from taking back what a coloured layer leaves). Away
// from head-on the specification's coupling itself exceeds 1 (the plain material: 1.06 at N.V 0.4 and
// roughness 0.3; docs/brdf.md), and the extension adds nothing to that: the albedo is exactly linear in
// the weight, (1 - s) x Lambert's 1 + s x the weight-1 albedo, at every angle and colour.
TEST(GltfBrdfReference, SpecularExtensionFurnaceAlbedo) {
    const glm::dvec3 colours[] = {{1.0, 1.0, 1.0}, {2.0, 0.5, 0.1}, {25.0, 25.0, 25.0}, {0.0, 0.0, 0.0}};
    double worst = 0.0;
    for (double nv : {1.0, 0.7, 0.4})
        for (double roughness : {0.3, 0.8})
            for (const glm::dvec3& c : colours) {
                const glm::dvec3 V(std::sqrt(1.0 - nv * nv), 0.0, nv);
                const glm::dvec3 full = directionalAlbedo(specularMaterial(glm::dvec3(1.0), 0.0, roughness, 1.0, c), V);
                for (double s : {0.0, 0.5}) {
                    const glm::dvec3 a = directionalAlbedo(specularMaterial(glm::dvec3(1.0), 0.0, roughness, s, c), V);
                    for (int k = 0; k < 3; ++k)
                        EXPECT_NEAR(a[k], (1.0 - s) + s * full[k], 1e-9)
                            << "N.V " << nv << " roughness " << roughness << " s " << s << " colour " << c.x << "," << c.y << ","
                            << c.z << " channel " << k;
                }
                if (nv < 1.0) continue;
                for (int k = 0; k < 3; ++k) {
                    EXPECT_LE(full[k], 1.0 + 1e-3) << "head-on, roughness " << roughness << " colour " << c.x << ","
                                                   << c.y << "," << c.z << " channel " << k;
                    worst = std::max(worst, full[k]);
                }
            }
    RecordProperty("largest_head_on_albedo", std::to_string(worst));
}
