// glTF 2.0's BRDF (Appendix B) is what lightpass computes by default: the GLSL against the double
// reference engine/render/gltf_brdf.hpp for every metallic, and the default frame's HDR radiance of
// sun- and point-lit glTF materials against the same reference in every path that shades them
// (classic and visibility G-buffers, forward+, the transparent pass).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/io/gltf_loader.hpp"
#include "engine/io/image_io.hpp"
#include "engine/render/gltf_brdf.hpp"
#include "engine/scene/primitives.hpp"
#include "frame/renderer.hpp"
#include "tests/gl/gl_fixture.hpp"
#include "tests/gl/render_fixture.hpp"

using namespace lp;
using lp::test::runGlsl;

namespace {

constexpr double kPi = 3.14159265358979323846;

// The materials the GLSL is checked with: dielectrics, metals and the mixes between them.
const GltfBrdfMaterial kMaterials[] = {
    {{0.8, 0.5, 0.25}, 0.0, 0.5},  {{1.0, 0.766, 0.336}, 1.0, 1.0}, {{0.9, 0.6, 0.3}, 0.5, 0.3},
    {{0.2, 0.9, 0.4}, 0.25, 0.8},  {{1.0, 1.0, 1.0}, 0.0, 0.2},     {{0.05, 0.05, 0.05}, 0.9, 0.6},
};

std::string glslVec3(glm::dvec3 v) {
    return "vec3(" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) + ")";
}

// const arrays kBase, kMetallic, kRoughness of kMaterials for the harness.
std::string materialTable() {
    const size_t n = std::size(kMaterials);
    std::string base = "const vec3 kBase[" + std::to_string(n) + "] = vec3[](";
    std::string metallic = "const float kMetallic[" + std::to_string(n) + "] = float[](";
    std::string roughness = "const float kRoughness[" + std::to_string(n) + "] = float[](";
    for (size_t i = 0; i < n; ++i) {
        const char* sep = i + 1 < n ? ", " : ");\n";
        base += glslVec3(kMaterials[i].baseColor) + sep;
        metallic += std::to_string(kMaterials[i].metallic) + sep;
        roughness += std::to_string(kMaterials[i].roughness) + sep;
    }
    return base + metallic + roughness;
}

// L in the xz plane at N.L = x.x, V at N.V = x.y and azimuth x.z, N = +Z.
const char* kDirections = R"(
        vec3 N = vec3(0.0, 0.0, 1.0);
        float sl = sqrt(max(1.0 - x.x * x.x, 0.0)), sv = sqrt(max(1.0 - x.y * x.y, 0.0));
        vec3 L = vec3(sl, 0.0, x.x);
        vec3 V = vec3(sv * cos(x.z), sv * sin(x.z), x.y);
)";
void directions(const glm::vec4& x, glm::dvec3& V, glm::dvec3& L) {
    const double sl = std::sqrt(std::max(1.0 - double(x.x) * x.x, 0.0)), sv = std::sqrt(std::max(1.0 - double(x.y) * x.y, 0.0));
    L = glm::dvec3(sl, 0.0, x.x);
    V = glm::dvec3(sv * std::cos(double(x.z)), sv * std::sin(double(x.z)), x.y);
}

}  // namespace

// The GGX path as a G-buffer pixel feeds it: kd = materialDiffuseAlbedo (base (1 - metallic)
// (1 - 0.04)), F0 = mix(0.04, base, metallic), the roughness as its exponent n = 2 / r^4 - 2; and the
// BRDF switch with uBrdf left unset (a program's default: GGX), split into brdfDiffuse + brdfSpecular
// as the local lights use it. Against gltfBrdf (the specification, height-correlated: the default
// masking) for dielectrics, metals and metallic 0.25 / 0.5 / 0.9 (the G-buffer's mixed F0 and
// pre-weighted kd are exact for every metallic), at N.L, N.V in {1, 0.7, 0.3, 0.05} and two azimuths.
// Bound: 2e-4 relative (+1e-6): float rounding.
TEST(GltfBrdf, ShaderMatchesTheSpecificationForEveryMetallic) {
    ASSERT_EQ(RenderSettings{}.brdf, Brdf::Ggx);
    ASSERT_EQ(RenderSettings{}.specularMasking, SpecularMasking::HeightCorrelated);
    std::vector<glm::vec4> in;
    for (size_t k = 0; k < std::size(kMaterials); ++k)
        for (float nl : {1.0f, 0.7f, 0.3f, 0.05f})
            for (float nv : {1.0f, 0.7f, 0.3f, 0.05f})
                for (float phi : {0.4f, 2.8f}) in.push_back(glm::vec4(nl, nv, phi, float(k)));
    const std::string body = std::string(kDirections) + R"(
        int k = int(x.w);
        vec3 base = kBase[k];
        float m = kMetallic[k], r = kRoughness[k];
        vec3 kd = materialDiffuseAlbedo(LP_BRDF_GGX, base, m, vec3(0.04));
        vec3 f0 = mix(vec3(0.04), base, m);
        float n = 2.0 / (r * r * r * r) - 2.0;
        vec3 f = ggxBrdf(N, V, L, kd, f0, n);
        vec3 viaSwitch = brdfRadiance(uBrdf, N, V, L, kd, f0, n, vec3(1.0)) / dot(N, L);
        vec3 parts = brdfDiffuse(uBrdf, N, V, L, kd, f0) + brdfSpecular(uBrdf, N, V, L, f0, n);
        float agree = max(length(viaSwitch - f), length(parts - f)) / max(length(f), 1e-20);
        return vec4(f, agree);)";
    const auto out = runGlsl({"common/brdf.glsl"}, body, in, materialTable());
    double worst = 0.0;
    for (size_t i = 0; i < in.size(); ++i) {
        glm::dvec3 V, L;
        directions(in[i], V, L);
        const GltfBrdfMaterial& m = kMaterials[size_t(in[i].w)];
        const glm::dvec3 want = gltfBrdf(m, glm::dvec3(0, 0, 1), V, L);
        const std::string where = "material " + std::to_string(int(in[i].w)) + " N.L " + std::to_string(in[i].x) +
                                  " N.V " + std::to_string(in[i].y) + " phi " + std::to_string(in[i].z);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(out[i][c], want[c], 2e-4 * want[c] + 1e-6) << where << " channel " << c;
            worst = std::max(worst, std::abs(out[i][c] - want[c]) / std::max(want[c], 1e-6));
        }
        EXPECT_LT(out[i].w, 1e-5f) << where << ": brdfRadiance / brdfDiffuse + brdfSpecular differ from ggxBrdf";
    }
    RecordProperty("worst_relative_error", std::to_string(worst));
}

// KHR_materials_specular in the GLSL as the G-buffer and the forward passes evaluate it:
// materialDiffuseAlbedo (kd = base (1 - metallic) (1 - max3 F0_dielectric)) and materialFresnelEnds
// (F0 and f90 mixed by metallic, the diffuse shape of the dielectric), through ggxBrdf and the switch's
// brdfDiffuse + brdfSpecular, against gltfBrdf with the extension's fresnel_mix for every material of
// kMaterials at five weights and colours (a weight 0, colours above 1 and clamped, a zero colour).
// Bound: 2e-4 relative (+1e-6), as for the plain material.
TEST(GltfBrdf, ShaderMatchesTheSpecularExtension) {
    struct SpecularCase {
        double s;
        glm::dvec3 colour;
    };
    const SpecularCase cases[] = {{0.5, {1.0, 0.5, 0.2}}, {0.0, {1.0, 1.0, 1.0}}, {0.7, {4.0, 2.0, 1.0}},
                                  {1.0, {30.0, 10.0, 2.0}}, {0.3, {0.0, 0.0, 0.0}}};
    const size_t nc = std::size(cases);
    std::string table = materialTable() + "const float kWeight[" + std::to_string(nc) + "] = float[](";
    std::string colours = "const vec3 kColour[" + std::to_string(nc) + "] = vec3[](";
    for (size_t j = 0; j < nc; ++j) {
        table += std::to_string(cases[j].s) + (j + 1 < nc ? ", " : ");\n");
        colours += glslVec3(cases[j].colour) + (j + 1 < nc ? ", " : ");\n");
    }
    std::vector<glm::vec4> in;
    for (size_t k = 0; k < std::size(kMaterials); ++k)
        for (size_t j = 0; j < nc; ++j)
            for (float nl : {1.0f, 0.6f, 0.1f})
                for (float nv : {1.0f, 0.5f, 0.08f}) in.push_back(glm::vec4(nl, nv, 1.3f, float(k * nc + j)));
    const std::string body = std::string(kDirections) + R"(
        int k = int(x.w) / )" + std::to_string(nc) + R"(, j = int(x.w) % )" + std::to_string(nc) + R"(;
        vec3 base = kBase[k];
        float m = kMetallic[k], r = kRoughness[k];
        vec3 dielectricF0 = min(vec3(0.04) * kColour[j], vec3(1.0)) * kWeight[j];
        vec3 kd = materialDiffuseAlbedo(LP_BRDF_GGX, base, m, dielectricF0, true);
        FresnelEnds e = materialFresnelEnds(base, m, dielectricF0, kWeight[j], true);
        float n = 2.0 / (r * r * r * r) - 2.0;
        vec3 f = ggxBrdf(N, V, L, kd, e, n);
        vec3 parts = brdfDiffuse(uBrdf, N, V, L, kd, e) + brdfSpecular(uBrdf, N, V, L, e, n);
        return vec4(f, length(parts - f) / max(length(f), 1e-20));)";
    const auto out = runGlsl({"common/brdf.glsl"}, body, in, table + colours);
    double worst = 0.0;
    for (size_t i = 0; i < in.size(); ++i) {
        glm::dvec3 V, L;
        directions(in[i], V, L);
        const size_t k = size_t(in[i].w) / nc, j = size_t(in[i].w) % nc;
        GltfBrdfMaterial m = kMaterials[k];
        m.specular = cases[j].s;
        m.specularColor = cases[j].colour;
        const glm::dvec3 want = gltfBrdf(m, glm::dvec3(0, 0, 1), V, L);
        const std::string where = "material " + std::to_string(k) + " specular case " + std::to_string(j) + " N.L " +
                                  std::to_string(in[i].x) + " N.V " + std::to_string(in[i].y);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(out[i][c], want[c], 2e-4 * want[c] + 1e-6) << where << " channel " << c;
            worst = std::max(worst, std::abs(out[i][c] - want[c]) / std::max(want[c], 1e-6));
        }
        EXPECT_LT(out[i].w, 1e-5f) << where << ": brdfDiffuse + brdfSpecular differ from ggxBrdf";
    }
    RecordProperty("worst_relative_error", std::to_string(worst));
}

// KHR_materials_clearcoat in the GLSL as every path shades it: the material's kd times 1 - w (the
// material evaluation) and its Fresnel ends through clearcoatBaseEnds, plus clearcoatSpecular on the
// coat's own normal (tilted 0.35 rad off N, or N itself), each with its own cosine, against the
// reference's gltfCoatedBrdfCosine for every material of kMaterials, clearcoat 1, 0.6 and 0, coat
// roughness 0.15 and 0.7. Bound: 2e-4 relative (+1e-6); clearcoat 0 gives the plain material's bits.
TEST(GltfBrdf, ShaderMatchesTheClearcoatLayering) {
    std::vector<glm::vec4> in;
    for (size_t k = 0; k < std::size(kMaterials); ++k)
        for (int c = 0; c < 12; ++c)  // clearcoat (3) x coat roughness (2) x coat normal (2)
            for (float nl : {1.0f, 0.6f, 0.1f})
                for (float nv : {1.0f, 0.5f, 0.08f}) in.push_back(glm::vec4(nl, nv, 1.3f, float(k * 12 + size_t(c))));
    const std::string body = std::string(kDirections) + R"(
        int k = int(x.w) / 12, c = int(x.w) % 12;
        float clearcoat = c / 4 == 0 ? 1.0 : (c / 4 == 1 ? 0.6 : 0.0);
        float coatRoughness = (c / 2) % 2 == 0 ? 0.15 : 0.7;
        vec3 Nc = c % 2 == 0 ? N : vec3(sin(0.35), 0.0, cos(0.35));
        vec3 base = kBase[k];
        float m = kMetallic[k], r = kRoughness[k];
        vec3 kd = materialDiffuseAlbedo(LP_BRDF_GGX, base, m, vec3(0.04));
        FresnelEnds e = fresnelEndsOfF0(mix(vec3(0.04), base, m));
        float n = 2.0 / (r * r * r * r) - 2.0;
        vec3 plain = ggxBrdf(N, V, L, kd, e, n) * dot(N, L);
        ClearcoatLayer coat = clearcoat > 0.0 ? clearcoatLayer(clearcoat, coatRoughness, Nc, V) : noClearcoat();
        vec3 f = ggxBrdf(N, V, L, kd * (1.0 - coat.weight), clearcoatBaseEnds(e, coat), n) * dot(N, L) +
                 clearcoatRadiance(coat, V, L, vec3(1.0));
        return vec4(f, clearcoat == 0.0 && f != plain ? 1.0 : 0.0);)";
    const auto out = runGlsl({"common/brdf.glsl"}, body, in, materialTable());
    double worst = 0.0;
    for (size_t i = 0; i < in.size(); ++i) {
        glm::dvec3 V, L;
        directions(in[i], V, L);
        const size_t k = size_t(in[i].w) / 12, c = size_t(in[i].w) % 12;
        GltfBrdfMaterial m = kMaterials[k];
        m.clearcoat = c / 4 == 0 ? 1.0 : (c / 4 == 1 ? 0.6 : 0.0);
        m.clearcoatRoughness = (c / 2) % 2 == 0 ? 0.15 : 0.7;
        const glm::dvec3 N(0, 0, 1), Nc = c % 2 == 0 ? N : glm::dvec3(std::sin(0.35), 0.0, std::cos(0.35));
        const glm::dvec3 want = gltfCoatedBrdfCosine(m, N, Nc, V, L);
        const std::string where = "material " + std::to_string(k) + " clearcoat " + std::to_string(m.clearcoat) +
                                  " coat roughness " + std::to_string(m.clearcoatRoughness) + (c % 2 ? " tilted" : "") +
                                  " N.L " + std::to_string(in[i].x) + " N.V " + std::to_string(in[i].y);
        for (int ch = 0; ch < 3; ++ch) {
            EXPECT_NEAR(out[i][ch], want[ch], 2e-4 * want[ch] + 1e-6) << where << " channel " << ch;
            worst = std::max(worst, std::abs(out[i][ch] - want[ch]) / std::max(want[ch], 1e-6));
        }
        EXPECT_EQ(out[i].w, 0.0f) << where << ": clearcoat 0 changed the plain material's bits";
    }
    RecordProperty("worst_relative_error", std::to_string(worst));
}

// Blinn-Phong (--brdf blinn-phong) stays the seeds' BRDF: materialDiffuseAlbedo keeps base (1 - metallic)
// and brdfRadiance is Kd / pi + Ks (n + 8) / (8 pi) (N.H)^n. Bound: 2e-5 relative.
TEST(GltfBrdf, BlinnPhongStaysTheSeedsBrdf) {
    std::vector<glm::vec4> in;
    for (float nl : {1.0f, 0.6f, 0.2f})
        for (float nv : {1.0f, 0.5f})
            for (float n : {0.0f, 32.0f, 500.0f}) in.push_back(glm::vec4(nl, nv, 0.7f, n));
    const std::string body = std::string(kDirections) + R"(
        vec3 kd = materialDiffuseAlbedo(LP_BRDF_BLINN_PHONG, vec3(0.6, 0.4, 0.2), 0.25, vec3(0.04));
        return vec4(brdfRadiance(LP_BRDF_BLINN_PHONG, N, V, L, kd, vec3(0.3), x.w, vec3(1.0)), 0.0);)";
    const auto out = runGlsl({"common/brdf.glsl"}, body, in);
    for (size_t i = 0; i < in.size(); ++i) {
        glm::dvec3 V, L;
        directions(in[i], V, L);
        const glm::dvec3 N(0, 0, 1), H = glm::normalize(V + L);
        const double n = in[i].w, lobe = n == 0.0 ? 1.0 : std::pow(glm::dot(N, H), n);
        const glm::dvec3 kd = glm::dvec3(0.6, 0.4, 0.2) * 0.75;
        for (int c = 0; c < 3; ++c) {
            const double want = (kd[c] / kPi + 0.3 * (n + 8.0) / (8.0 * kPi) * lobe) * L.z;
            EXPECT_NEAR(out[i][c], want, 2e-5 * want) << "N.L " << in[i].x << " N.V " << in[i].y << " n " << n;
        }
    }
}

// The IBL's diffuse weight (ggxDiffuseFresnelMeanWeight) is the specification's diffuse weight
// 1 - F(V.H) averaged over a uniform light, divided by the 1 - F0 kd already holds: (1 / pi) integral
// of (1 - F(V.H)) / (1 - F0) N.L over the hemisphere = 1 - mean of (1 - V.H)^5 for every F0 >= 0.02,
// here by a 384 x 768 midpoint rule in cosine-weighted coordinates, for F0 0.04 and 0.1 at N.V from 1
// to 0. And F0 = 0 (MTL Ks 0): exactly 1, Lambertian. Bound: 2e-4 absolute (the cubic fit's error).
TEST(GltfBrdf, IblDiffuseWeightIsTheUniformLightMeanOfTheSpecificationsWeight) {
    const float cosines[] = {1.0f, 0.9f, 0.7f, 0.5f, 0.3f, 0.15f, 0.05f, 0.0f};
    std::vector<glm::vec4> in;
    for (float f0 : {0.04f, 0.1f, 0.0f})
        for (float nv : cosines) in.push_back(glm::vec4(nv, f0, 0, 0));
    const auto out = runGlsl({"common/brdf.glsl"}, "return vec4(ggxDiffuseFresnelMeanWeight(vec3(x.y), x.x), 0.0);", in);
    std::vector<double> mean;  // per N.V: the cosine-weighted mean of 1 - (1 - V.H)^5
    for (float c : cosines) {
        const double nv = c;
        const glm::dvec3 V(std::sqrt(1.0 - nv * nv), 0.0, nv);
        const int n = 384;
        double sum = 0.0;
        for (int a = 0; a < n; ++a)
            for (int b = 0; b < 2 * n; ++b) {
                const double u = (a + 0.5) / n, phi = (b + 0.5) / (2 * n) * 2.0 * kPi;
                const glm::dvec3 L(std::sqrt(u) * std::cos(phi), std::sqrt(u) * std::sin(phi), std::sqrt(1.0 - u));
                const double vh = std::abs(glm::dot(V, glm::normalize(V + L)));
                sum += 1.0 - std::pow(1.0 - vh, 5.0);
            }
        mean.push_back(sum / (2.0 * n * n));
    }
    double worst = 0.0;
    for (size_t i = 0; i < in.size(); ++i) {
        const double f0 = in[i].y, want = f0 == 0.0 ? 1.0 : mean[i % std::size(cosines)];
        EXPECT_NEAR(out[i].x, want, 2e-4) << "N.V " << in[i].x << " F0 " << f0;
        worst = std::max(worst, std::abs(out[i].x - want));
        if (f0 == 0.0) EXPECT_EQ(out[i].x, 1.0f) << "N.V " << in[i].x;
    }
    RecordProperty("worst_abs_error", std::to_string(worst));
}

namespace {

// Four 1.5 m glTF quads in a row at y = 0 (centres x = -2.4, -0.8, 0.8, 2.4): a dielectric (base
// (0.8, 0.5, 0.25), roughness 0.5), a rough metal (gold, roughness 1), a half metal (metallic 0.5,
// roughness 0.6) and a normal-mapped gold quad (roughness 0.4; tests/data/gltf/normal_plane.glb turned
// half a turn about +Y, so its tangent is -X and its bitangent +Z, with tangent-space normal
// (173, 189, 230) / 255 * 2 - 1: the shading normal leans towards the camera). Lit by one sun and one
// point light, no ambient, no environment, seen from above at an angle.
struct QuadCase {
    GltfBrdfMaterial material;
    double centreX;
    bool normalMapped;
    bool specularExtension = false;  // KHR_materials_specular with the material's specular and specularColor
};
GltfBrdfMaterial withClearcoat(GltfBrdfMaterial m, double clearcoat, double roughness) {
    m.clearcoat = clearcoat;
    m.clearcoatRoughness = roughness;
    return m;
}
// KHR_materials_clearcoat on the same places: a full smooth coat over the dielectric, a half coat over
// the rough metal, a rough coat over the half metal, and a full coat over the normal-mapped gold (whose
// coat keeps the interpolated normal: the base's normal map leaves it alone).
const std::vector<QuadCase> kClearcoatQuads = {
    {withClearcoat({{0.8, 0.5, 0.25}, 0.0, 0.5}, 1.0, 0.15), -2.4, false},
    {withClearcoat({{1.0, 0.766, 0.336}, 1.0, 1.0}, 0.5, 0.3), -0.8, false},
    {withClearcoat({{0.8, 0.5, 0.3}, 0.5, 0.6}, 1.0, 0.8), 0.8, false},
    {withClearcoat({{1.0, 0.766, 0.336}, 1.0, 0.4}, 1.0, 0.2), 2.4, true},
};
const std::vector<QuadCase> kQuads = {
    {{{0.8, 0.5, 0.25}, 0.0, 0.5}, -2.4, false},
    {{{1.0, 0.766, 0.336}, 1.0, 1.0}, -0.8, false},
    {{{0.8, 0.5, 0.3}, 0.5, 0.6}, 0.8, false},
    {{{1.0, 0.766, 0.336}, 1.0, 0.4}, 2.4, true},
};
GltfBrdfMaterial withSpecular(GltfBrdfMaterial m, double s, glm::dvec3 colour) {
    m.specular = s;
    m.specularColor = colour;
    return m;
}
// The same places with KHR_materials_specular: a dielectric at weight 0.5 with a coloured F0 (f90 0.5),
// a dielectric at weight 0 (Lambertian: no specular at all), a half metal at weight 0.7 with a colour
// above 1, and the normal-mapped quad as a dielectric whose colour takes F0 to (0.4, 0.2, 0.08).
const std::vector<QuadCase> kSpecularQuads = {
    {withSpecular({{0.8, 0.5, 0.25}, 0.0, 0.5}, 0.5, {1.0, 0.5, 0.2}), -2.4, false, true},
    {withSpecular({{0.3, 0.6, 0.9}, 0.0, 0.35}, 0.0, {1.0, 1.0, 1.0}), -0.8, false, true},
    {withSpecular({{0.8, 0.5, 0.3}, 0.5, 0.6}, 0.7, {4.0, 2.0, 1.0}), 0.8, false, true},
    {withSpecular({{0.9, 0.9, 0.9}, 0.0, 0.4}, 1.0, {10.0, 5.0, 2.0}), 2.4, true, true},
};
const glm::dvec3 kToSun = glm::normalize(glm::dvec3(0.3, 0.75, -0.5));
constexpr double kSunIrradiance = 3.0;
const glm::dvec3 kPointPosition(0.5, 1.2, 0.4);
constexpr double kPointIntensity = 4.0, kPointRange = 30.0;

// `specularExtension`: the material carries KHR_materials_specular with g.specular and g.specularColor,
// as the glTF loader makes it (specular F0_ior x colour, f90 = s; the shader clamps and weighs).
Material materialOf(const GltfBrdfMaterial& g, bool specularExtension = false) {
    Material m;
    m.diffuse = glm::vec3(g.baseColor);
    m.specular = glm::vec3(float(gltfDielectricF0(g.ior)));
    if (specularExtension) {
        m.specular = glm::vec3(gltfDielectricF0(g.ior) * g.specularColor);
        m.dielectricF90 = float(g.specular);
    }
    m.metallic = float(g.metallic);
    m.roughness = float(g.roughness);
    m.shininess = shininessFromRoughness(m.roughness);
    m.clearcoat = float(g.clearcoat);
    m.clearcoatRoughness = float(g.clearcoatRoughness);
    m.doubleSided = false;
    return m;
}

glm::dvec3 mappedNormal() {
    const glm::dvec3 t = glm::dvec3(173.0, 189.0, 230.0) / 255.0 * 2.0 - 1.0;
    return glm::normalize(t.x * glm::dvec3(-1, 0, 0) + t.z * glm::dvec3(0, 1, 0) + t.y * glm::dvec3(0, 0, 1));
}

Scene quadsScene(AlphaMode mode, const std::vector<QuadCase>& quads = kQuads) {
    Scene s;
    for (const QuadCase& q : quads) {
        ModelInstance m;
        m.name = "quad";
        if (q.normalMapped) {
            m.mesh = loadGltf(test::repoPath("tests/data/gltf/normal_plane.glb")).mesh;  // 2 x 2, tangents +X
            m.transform = glm::translate(glm::mat4(1.0f), glm::vec3(float(q.centreX), 0, 0)) *
                          glm::rotate(glm::mat4(1.0f), float(kPi), glm::vec3(0, 1, 0)) * glm::scale(glm::mat4(1.0f), glm::vec3(0.75f));
        } else {
            m.mesh = makePlane(1.5f);
            m.transform = glm::translate(glm::mat4(1.0f), glm::vec3(float(q.centreX), 0, 0));
        }
        Material mat = materialOf(q.material, q.specularExtension);
        if (q.normalMapped) {
            Image8 normal{8, 8, {}};
            for (int i = 0; i < 64; ++i) normal.rgba.insert(normal.rgba.end(), {173, 189, 230, 255});
            mat.normalMap.encoded = std::make_shared<const std::string>(encodePng(normal));
            mat.normalMap.key = "tilted-normal";
        }
        mat.alphaMode = mode;
        m.mesh.materials.assign(m.mesh.materials.size(), mat);
        s.models.push_back(std::move(m));
    }
    s.ambient = glm::vec3(0.0f);
    s.environment.color = glm::vec3(0.0f);
    s.camera.position = {0.0f, 3.2f, 3.0f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    s.camera.fovYDegrees = 50.0f;
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 20.0f;
    DirectionalLight sun;
    sun.direction = -glm::vec3(kToSun);
    sun.intensity = float(kSunIrradiance);
    sun.castsShadows = false;
    s.directionalLights.push_back(sun);
    PointLight point;
    point.position = glm::vec3(kPointPosition);
    point.intensity = float(kPointIntensity);
    point.range = float(kPointRange);
    s.pointLights.push_back(point);
    return s;
}

// The specification's radiance at world point p on quad q seen from `eye`: f (sun) E N.L + f (point)
// I window(d / R) / d^2 N.L, the window being lightpass's (and KHR_lights_punctual's) range falloff.
// With KHR_materials_clearcoat the coated material's (gltfCoatedBrdfCosine), its coat on the plane's
// own normal +Y.
// `coatMapped`: the coat has the tilted map too (its normal the mapped one).
glm::dvec3 referenceRadiance(const QuadCase& q, glm::dvec3 p, glm::dvec3 eye, bool coatMapped = false) {
    const glm::dvec3 N = q.normalMapped ? mappedNormal() : glm::dvec3(0, 1, 0), V = glm::normalize(eye - p);
    const glm::dvec3 Nc = coatMapped ? mappedNormal() : glm::dvec3(0, 1, 0);
    glm::dvec3 c = gltfCoatedBrdfCosine(q.material, N, Nc, V, kToSun) * kSunIrradiance;
    const glm::dvec3 toPoint = kPointPosition - p;
    const double d = glm::length(toPoint), x = d / kPointRange, window = std::pow(std::max(1.0 - x * x * x * x, 0.0), 2.0);
    const glm::dvec3 L = toPoint / d;
    c += gltfCoatedBrdfCosine(q.material, N, Nc, V, L) * kPointIntensity * window / (d * d);
    return c;
}

}  // namespace

namespace {
struct Path {
    const char* name;
    RenderPath path;
    GBufferMode mode;
    AlphaMode alpha;
    GBufferNormalFormat normal = GBufferNormalFormat::Unpacked;
};
const Path kPaths[] = {{"deferred classic", RenderPath::Deferred, GBufferMode::Classic, AlphaMode::Opaque},
                       {"deferred visibility", RenderPath::Deferred, GBufferMode::Visibility, AlphaMode::Opaque},
                       {"forward+", RenderPath::ForwardPlus, GBufferMode::Auto, AlphaMode::Opaque},
                       {"transparent", RenderPath::Deferred, GBufferMode::Auto, AlphaMode::Blend}};

ImageF renderQuads(const Scene& scene, const Path& path, int w, int h,
                   std::optional<LocalLightMethod> method = std::nullopt) {
    Renderer r(scene);
    RenderSettings s;
    if (method) s.localLights.method = *method;
    s.width = w;
    s.height = h;
    s.keepHdr = true;
    s.renderPath = path.path;
    s.gbuffer.mode = path.mode;
    s.gbuffer.normal = path.normal;
    r.render(s, 0.0f, false);
    return r.readHdr();
}

// Every pixel well inside the quads (5 cm from their edges) against referenceRadiance at the pixel
// centre's ray, within 1% per channel (+1e-3 absolute).
// `edit` changes the scene before it is drawn (maps that stand for the factors the reference uses).
// `method`: the local lights' (the default's otherwise); `coatMappedQuad`: the quad whose coat has the
// tilted normal map (-1: none).
void expectQuadsMatchTheSpecification(const std::vector<QuadCase>& quads, const Path& path,
                                      const std::function<void(Scene&)>& edit = {},
                                      std::optional<LocalLightMethod> method = std::nullopt, int coatMappedQuad = -1) {
    SCOPED_TRACE(path.name);
    const int w = 128, h = 64;
    Scene scene = quadsScene(path.alpha, quads);
    if (edit) edit(scene);
    const ImageF hdr = renderQuads(scene, path, w, h, method);
    const glm::dvec3 eye(scene.camera.position);
    std::vector<int> checked(quads.size(), 0);
    std::vector<double> worst(quads.size(), 0.0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::optional<glm::dvec3> hit = test::planePoint(scene.camera, w, h, x, y);
            if (!hit) continue;
            const glm::dvec3 p = *hit;
            for (size_t k = 0; k < quads.size(); ++k) {
                if (std::abs(p.x - quads[k].centreX) > 0.7 || std::abs(p.z) > 0.7) continue;
                const glm::dvec3 want = referenceRadiance(quads[k], p, eye, int(k) == coatMappedQuad);
                const float* got = &hdr.rgba[(size_t(y) * w + size_t(x)) * 4];
                for (int c = 0; c < 3; ++c) {
                    EXPECT_NEAR(got[c], want[c], 0.01 * want[c] + 1e-3)
                        << "quad " << k << " pixel " << x << "," << y << " channel " << c;
                    worst[k] = std::max(worst[k], std::abs(got[c] - want[c]) / std::max(want[c], 1e-2));
                }
                ++checked[k];
            }
        }
    for (size_t k = 0; k < quads.size(); ++k) {
        EXPECT_GT(checked[k], 60) << "quad " << k;
        ::testing::Test::RecordProperty(std::string(path.name) + " quad " + std::to_string(k) + " worst relative error",
                                        std::to_string(worst[k]));
    }
}
}  // namespace

// The default frame (RenderSettings{}: GGX, height-correlated) shades glTF materials by the
// specification: every pixel well inside the four quads against referenceRadiance, in the deferred path
// with each G-buffer mode, forward+ and the transparent pass (the quads BLEND with alpha 1). Bound: 1%
// per channel (+1e-3 absolute): the G-buffer's 8-bit diffuse colour and half-float F0 and radiance.
// (The seeds' Blinn-Phong default put the rough metal +196% off under a sun; leaving out the spec's
// 1 - F, the dielectric +4%.)
TEST(GltfBrdf, SunAndPointLitGltfMaterialsMatchTheSpecificationInEveryPath) {
    for (const Path& path : kPaths) expectQuadsMatchTheSpecification(kQuads, path);
}

// KHR_materials_specular (kSpecularQuads: weights 0.5, 0, 0.7 and 1, coloured F0s, a half metal, a
// normal map) against the reference's fresnel_mix in every path: the deferred G-buffer carries f90 and
// the diffuse shape in gbuffer.fresnel (classic and visibility, with the unpacked, oct16 and seed-packed
// layouts), forward+ and the transparent pass evaluate them in place. Bound: 1% per channel, as above.
TEST(GltfBrdf, SpecularExtensionMatchesTheSpecificationInEveryPath) {
    for (const Path& path : kPaths) expectQuadsMatchTheSpecification(kSpecularQuads, path);
    expectQuadsMatchTheSpecification(kSpecularQuads, {"classic oct16", RenderPath::Deferred, GBufferMode::Classic,
                                                      AlphaMode::Opaque, GBufferNormalFormat::Oct16});
    expectQuadsMatchTheSpecification(kSpecularQuads, {"visibility seed-packed-signed", RenderPath::Deferred,
                                                      GBufferMode::Visibility, AlphaMode::Opaque,
                                                      GBufferNormalFormat::SeedPackedSigned});
}

// KHR_materials_specular's maps: the first quad's weight 0.6 and colour (1, 0.5 x 0.503, 0.2) given as
// factors 1 and (1, 0.5, 0.2) times a specularTexture of alpha 153 / 255 and a specularColorTexture of
// sRGB (255, 188, 255), in every path (the visibility resolve samples the maps itself). Bound: 1%.
TEST(GltfBrdf, SpecularExtensionMapsMatchTheSpecification) {
    auto srgbDecode = [](double code) {
        const double v = code / 255.0;
        return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
    };
    std::vector<QuadCase> quads = kSpecularQuads;
    quads[0].material.specular = 153.0 / 255.0;
    quads[0].material.specularColor = {1.0, 0.5 * srgbDecode(188.0), 0.2};
    auto map = [](uint8_t r, uint8_t g, uint8_t b, uint8_t a, const char* key) {
        Image8 image{8, 8, {}};
        for (int i = 0; i < 64; ++i) image.rgba.insert(image.rgba.end(), {r, g, b, a});
        TextureRef t;
        t.encoded = std::make_shared<const std::string>(encodePng(image));
        t.key = key;
        return t;
    };
    const auto withMaps = [&](Scene& scene) {
        for (Material& m : scene.models[0].mesh.materials) {
            m.specular = glm::vec3(0.04f) * glm::vec3(1.0f, 0.5f, 0.2f);  // the loader's F0_ior x colour factor
            m.dielectricF90 = 1.0f;
            m.specularMap = map(0, 0, 0, 153, "specular-weight");
            m.specularColorMap = map(255, 188, 255, 255, "specular-colour");
        }
    };
    for (const Path& path : kPaths) expectQuadsMatchTheSpecification(quads, path, withMaps);
}

// A material without the extension renders the same bits whether or not the scene has one with it
// (then gbuffer.fresnel is allocated and read), and the extension at its defaults (weight 1, colour
// white) is the plain material: the four quads with and without KHR_materials_specular on the
// dielectric at its defaults, every HDR value equal, in every path.
TEST(GltfBrdf, SpecularExtensionAtItsDefaultsChangesNoBit) {
    std::vector<QuadCase> defaults = kQuads;
    defaults[0].specularExtension = true;  // weight 1, colour (1, 1, 1)
    for (const Path& path : kPaths) {
        SCOPED_TRACE(path.name);
        const ImageF plain = renderQuads(quadsScene(path.alpha, kQuads), path, 64, 32);
        const ImageF extended = renderQuads(quadsScene(path.alpha, defaults), path, 64, 32);
        EXPECT_TRUE(test::imagesNear(extended, plain, 0.0f, "with the extension vs without"));
    }
    // The deferred frame of the scene with the extension reads gbuffer.fresnel; without it there is none.
    for (const bool withExtension : {false, true}) {
        const Scene scene = quadsScene(AlphaMode::Opaque, withExtension ? defaults : kQuads);
        Renderer r(scene);
        RenderSettings s;
        s.width = 32;
        s.height = 16;
        s.gbuffer.mode = GBufferMode::Classic;
        r.render(s, 0.0f, false);
        bool live = false;
        for (const auto& resource : r.graph().resources()) live = live || (resource.name == "gbuffer.fresnel" && resource.live);
        EXPECT_EQ(live, withExtension) << "gbuffer.fresnel";
    }
}

// KHR_materials_clearcoat (kClearcoatQuads: coats 1, 0.5, 1, 1 of roughness 0.15 to 0.8 over a
// dielectric, a rough metal, a half metal and a normal-mapped gold whose coat keeps the plane's normal)
// against the reference's layering in every path: the deferred G-buffer carries the coat in
// gbuffer.clearcoat (classic and visibility; unpacked, oct32 and seed-packed-signed), forward+ and the transparent pass
// evaluate it in place; sun and point light alike. Bound: 1% per channel, as for the plain material.
TEST(GltfBrdf, ClearcoatMatchesTheSpecificationInEveryPath) {
    for (const Path& path : kPaths) expectQuadsMatchTheSpecification(kClearcoatQuads, path);
    // Other layouts carry it alike (oct16's 8 bits an axis put the normal-mapped gold's own highlight, not
    // the coat, 1.4% off: oct32 here).
    expectQuadsMatchTheSpecification(kClearcoatQuads, {"classic oct32", RenderPath::Deferred, GBufferMode::Classic,
                                                       AlphaMode::Opaque, GBufferNormalFormat::Oct32});
    expectQuadsMatchTheSpecification(kClearcoatQuads, {"visibility seed-packed-signed", RenderPath::Deferred,
                                                       GBufferMode::Visibility, AlphaMode::Opaque,
                                                       GBufferNormalFormat::SeedPackedSigned});
    // The local lights' other methods read the same target.
    for (const LocalLightMethod method : {LocalLightMethod::Fullscreen, LocalLightMethod::Clustered}) {
        SCOPED_TRACE(localLightMethodName(method));
        expectQuadsMatchTheSpecification(kClearcoatQuads, kPaths[0], {}, method);
    }
}

// KHR_materials_clearcoat's maps: the first quad's clearcoat 0.6 and coat roughness 0.2 given as
// factors 1 and 0.5 times a clearcoatTexture of r 153 / 255 and a clearcoatRoughnessTexture of g 102 / 255,
// and the fourth quad's coat normal bent by a clearcoatNormalTexture (the base's tilted map, so the
// reference's coat normal is the mapped one), in every path. Bound: 1%.
TEST(GltfBrdf, ClearcoatMapsMatchTheSpecification) {
    std::vector<QuadCase> quads = kClearcoatQuads;
    quads[0].material.clearcoat = 153.0 / 255.0;
    quads[0].material.clearcoatRoughness = 0.5 * 102.0 / 255.0;
    auto map = [](uint8_t r, uint8_t g, uint8_t b, uint8_t a, const char* key) {
        Image8 image{8, 8, {}};
        for (int i = 0; i < 64; ++i) image.rgba.insert(image.rgba.end(), {r, g, b, a});
        TextureRef t;
        t.encoded = std::make_shared<const std::string>(encodePng(image));
        t.key = key;
        return t;
    };
    const auto withMaps = [&](Scene& scene) {
        for (Material& m : scene.models[0].mesh.materials) {
            m.clearcoat = 1.0f;
            m.clearcoatRoughness = 0.5f;
            m.clearcoatMap = map(153, 0, 0, 255, "clearcoat-factor");
            m.clearcoatRoughnessMap = map(0, 102, 0, 255, "clearcoat-roughness");
        }
        // The fourth quad: the coat bent by the same tilted map as the base (its normalMap).
        for (Material& m : scene.models[3].mesh.materials) m.clearcoatNormalMap = m.normalMap;
    };
    for (const Path& path : kPaths) {
        SCOPED_TRACE(path.name);
        expectQuadsMatchTheSpecification(quads, path, withMaps, std::nullopt, 3);
    }
}

// Clearcoat 0 is the plain material, bit for bit, in every path, and a scene without a coat allocates
// no gbuffer.clearcoat (every pass's programs stay the ones without LP_GBUFFER_CLEARCOAT); with one the
// deferred frame reads it.
TEST(GltfBrdf, ClearcoatZeroChangesNoBitAndAllocatesNothing) {
    std::vector<QuadCase> zero = kQuads;
    zero[0].material.clearcoat = 0.0;
    zero[0].material.clearcoatRoughness = 0.4;  // a roughness without a coat: still nothing
    for (const Path& path : kPaths) {
        SCOPED_TRACE(path.name);
        const ImageF plain = renderQuads(quadsScene(path.alpha, kQuads), path, 64, 32);
        const ImageF coated = renderQuads(quadsScene(path.alpha, zero), path, 64, 32);
        EXPECT_TRUE(test::imagesNear(coated, plain, 0.0f, "clearcoat 0 vs plain"));
    }
    for (const bool withCoat : {false, true}) {
        const Scene scene = quadsScene(AlphaMode::Opaque, withCoat ? kClearcoatQuads : zero);
        for (const GBufferMode mode : {GBufferMode::Classic, GBufferMode::Visibility}) {
            Renderer r(scene);
            RenderSettings s;
            s.width = 32;
            s.height = 16;
            s.gbuffer.mode = mode;
            r.render(s, 0.0f, false);
            bool live = false;
            for (const auto& resource : r.graph().resources())
                live = live || (resource.name == "gbuffer.clearcoat" && resource.live);
            EXPECT_EQ(live, withCoat) << "gbuffer.clearcoat, G-buffer mode " << int(mode);
        }
    }
}
