// The GLSL in shaders/common/ on the real driver, against double-precision C++ references.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tests/gl/gl_fixture.hpp"

using lp::test::runGlsl;

namespace {
const float kInf = std::numeric_limits<float>::infinity();
const float kNaN = std::numeric_limits<float>::quiet_NaN();

double tonemapRef(double c) {
    if (!(c > 0.0)) return 0.0;  // NaN and negatives
    c = std::min(c, 65504.0);
    return std::pow(c / (c + 1.0), 1.2);
}
double srgbRef(double x) {
    x = std::clamp(x, 0.0, 1.0);
    return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
}
}  // namespace

// Bound: |GLSL - double| <= 2e-6 over [0, 65504]; documented hard cases: 0 -> 0, 1e-30 -> 0 (below
// float pow's range), 1 -> 0.5^1.2 = 0.43528, 1e38 and +Inf -> 65504/65505 ^ 1.2 (about 1), NaN -> 0.
TEST(ShaderToneMap, MatchesReferenceAndHandlesHardCases) {
    std::vector<glm::vec4> in;
    std::vector<double> ref;
    const float hard[] = {0.0f, 1e-30f, 1.0f, 1e38f, kInf, kNaN, -1.0f, -kInf, 65504.0f, 1e5f};
    for (float h : hard) in.push_back(glm::vec4(h));
    for (int i = 0; i <= 2000; ++i) in.push_back(glm::vec4(float(std::pow(10.0, -6.0 + 11.0 * i / 2000.0))));
    auto out = runGlsl({"common/tonemap.glsl"}, "return vec4(tonemapLightpass(x.xyz), 0.0);", in);
    double prev = -1.0;
    for (size_t i = 0; i < in.size(); ++i) {
        float got = out[i].x;
        ASSERT_TRUE(std::isfinite(got)) << "input " << in[i].x;
        EXPECT_GE(got, 0.0f);
        EXPECT_LE(got, 1.0f);
        EXPECT_NEAR(got, tonemapRef(in[i].x), 2e-6) << "input " << in[i].x;
        if (i >= std::size(hard)) {
            EXPECT_GE(got, prev - 1e-7) << "not monotone at " << in[i].x;  // monotone non-decreasing
            prev = got;
        }
    }
    EXPECT_FLOAT_EQ(out[0].x, 0.0f);
    EXPECT_NEAR(out[2].x, std::pow(0.5, 1.2), 1e-6);
    EXPECT_NEAR(out[3].x, 1.0, 3e-5);
    EXPECT_NEAR(out[4].x, 1.0, 3e-5);
    EXPECT_FLOAT_EQ(out[5].x, 0.0f);
}

// Bound: |GLSL - IEC 61966-2-1| <= 1e-6 on [0, 1]; out-of-range inputs clamp.
TEST(ShaderToneMap, SrgbEncodingMatchesStandard) {
    std::vector<glm::vec4> in;
    for (int i = 0; i <= 1000; ++i) in.push_back(glm::vec4(float(i) / 1000.0f));
    in.push_back(glm::vec4(-0.5f));
    in.push_back(glm::vec4(2.0f));
    auto out = runGlsl({"common/tonemap.glsl"}, "return vec4(linearToSrgb(x.xyz), 0.0);", in);
    for (size_t i = 0; i < in.size(); ++i) EXPECT_NEAR(out[i].x, srgbRef(in[i].x), 1e-6) << in[i].x;
}

TEST(ShaderToneMap, SanitizeClampsNanInfAndNegatives) {
    std::vector<glm::vec4> in = {glm::vec4(kNaN, kInf, -kInf, -3.0f), glm::vec4(1e30f, 70000.0f, 1.0f, 0.0f)};
    auto out = runGlsl({"common/tonemap.glsl"}, "return vec4(sanitizeHdr(x.xyz), sanitizeHdr(x.www).x);", in);
    EXPECT_EQ(out[0], glm::vec4(0.0f, 65504.0f, 0.0f, 0.0f));
    EXPECT_EQ(out[1], glm::vec4(65504.0f, 65504.0f, 1.0f, 0.0f));
}

namespace {
// Normalised Blinn-Phong in double.
double blinnPhongRef(glm::dvec3 N, glm::dvec3 V, glm::dvec3 L, double kd, double ks, double n) {
    glm::dvec3 h = V + L;
    glm::dvec3 H = glm::dot(h, h) > 1e-12 ? glm::normalize(h) : N;
    double nh = std::clamp(glm::dot(N, H), 0.0, 1.0);
    double lobe = n == 0.0 ? 1.0 : std::pow(nh, n);
    double nl = glm::dot(N, L);
    if (nl <= 0.0) return 0.0;
    return (kd / M_PI + ks * (n + 8.0) / (8.0 * M_PI) * lobe) * nl;
}
}  // namespace

// Bound: relative error <= 1e-4 (plus 1e-6 absolute) at N.L, N.V in {1, 0.5, 1e-8, 0, -1e-3},
// shininess in {0, 1, 32, 10000}; never NaN/Inf, and exactly 0 for N.L <= 0.
TEST(ShaderBrdf, BlinnPhongHardCasesMatchReference) {
    std::vector<glm::vec4> in;  // x = N.L, y = N.V, z = shininess, w = azimuth of V
    const float cosines[] = {1.0f, 0.5f, 1e-8f, 0.0f, -1e-3f};
    const float shininess[] = {0.0f, 1.0f, 32.0f, 10000.0f};
    for (float nl : cosines)
        for (float nv : cosines)
            for (float n : shininess)
                for (float phi : {0.0f, 3.14159265f}) in.push_back(glm::vec4(nl, nv, n, phi));
    const std::string body = R"(
        vec3 N = vec3(0.0, 0.0, 1.0);
        float sl = sqrt(max(1.0 - x.x * x.x, 0.0)), sv = sqrt(max(1.0 - x.y * x.y, 0.0));
        vec3 L = vec3(sl, 0.0, x.x);
        vec3 V = vec3(sv * cos(x.w), sv * sin(x.w), x.y);
        vec3 f = blinnPhongRadiance(N, V, L, vec3(0.5), vec3(0.5), x.z, vec3(1.0));
        return vec4(f, 0.0);)";
    auto out = runGlsl({"common/brdf.glsl"}, body, in);
    for (size_t i = 0; i < in.size(); ++i) {
        const glm::vec4 x = in[i];
        double sl = std::sqrt(std::max(1.0 - double(x.x) * x.x, 0.0)), sv = std::sqrt(std::max(1.0 - double(x.y) * x.y, 0.0));
        glm::dvec3 L(sl, 0, x.x), V(sv * std::cos(double(x.w)), sv * std::sin(double(x.w)), x.y);
        double ref = blinnPhongRef({0, 0, 1}, V, L, 0.5, 0.5, x.z);
        ASSERT_TRUE(std::isfinite(out[i].x)) << "N.L=" << x.x << " N.V=" << x.y << " n=" << x.z;
        EXPECT_NEAR(out[i].x, ref, 1e-4 * std::abs(ref) + 1e-6) << "N.L=" << x.x << " N.V=" << x.y << " n=" << x.z;
        if (x.x <= 0.0f) EXPECT_EQ(out[i].x, 0.0f);
    }
}

TEST(ShaderBrdf, OppositeViewAndLightIsFinite) {
    // V = -L makes the half vector 0/0; the BRDF must fall back, not return NaN.
    auto out = runGlsl({"common/brdf.glsl"},
                       "vec3 L = normalize(vec3(0.3, 0.0, 1.0)); return vec4(blinnPhongBrdf(vec3(0,0,1), -L, L, vec3(0.5), vec3(1.0), x.x), 0.0);",
                       {glm::vec4(0.0f), glm::vec4(64.0f), glm::vec4(10000.0f)});
    for (auto& o : out) EXPECT_TRUE(std::isfinite(o.x));
}
