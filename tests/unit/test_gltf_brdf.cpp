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
