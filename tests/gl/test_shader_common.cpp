// The GLSL in shaders/common/ on the real driver, against double-precision C++ references.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "engine/gl/handles.hpp"
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

namespace {
// A w x h RGBA32F texture on unit 9 holding `texels` (row 0 first), for common/upscale.glsl.
struct UpscaleSource {
    int w, h;
    std::vector<glm::vec4> texels;
    lp::gl::Texture texture;
    UpscaleSource(int w_, int h_, const std::function<glm::vec4(int, int)>& f) : w(w_), h(h_) {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) texels.push_back(f(x, y));
        texture = lp::gl::makeTexture2D(GL_RGBA32F, w, h, 1, "upscale.source");
        glTextureSubImage2D(texture.id(), 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, texels.data());
        glBindTextureUnit(9, texture.id());
    }
    ~UpscaleSource() { glBindTextureUnit(9, 0); }
    glm::dvec4 at(int x, int y) const {
        glm::vec4 t = texels[size_t(std::clamp(y, 0, h - 1)) * size_t(w) + size_t(std::clamp(x, 0, w - 1))];
        return glm::dvec4(t);
    }
    // Double-precision bilinear with centres aligned and edges clamped.
    glm::dvec4 bilinear(int px, int py, int ow, int oh) const {
        double cx = std::clamp((px + 0.5) * w / ow - 0.5, 0.0, double(w - 1));
        double cy = std::clamp((py + 0.5) * h / oh - 0.5, 0.0, double(h - 1));
        int x0 = int(std::floor(cx)), y0 = int(std::floor(cy));
        double fx = cx - x0, fy = cy - y0;
        return (1 - fx) * (1 - fy) * at(x0, y0) + fx * (1 - fy) * at(x0 + 1, y0) + (1 - fx) * fy * at(x0, y0 + 1) +
               fx * fy * at(x0 + 1, y0 + 1);
    }
    // One input per output pixel: (x, y, outW, outH).
    static std::vector<glm::vec4> pixels(int ow, int oh) {
        std::vector<glm::vec4> in;
        for (int y = 0; y < oh; ++y)
            for (int x = 0; x < ow; ++x) in.push_back(glm::vec4(x, y, ow, oh));
        return in;
    }
};
const char* kUpscaleGlobals = "layout(binding = 9) uniform sampler2D uSrc;\n";
const char* kBilinear = "return upscaleBilinear(uSrc, ivec2(x.xy), ivec2(x.zw));";
}  // namespace

// Bound: |GLSL - double bilinear| <= 1e-5 relative for 2x, 4x and non-integer ratios (7x5 -> 16x11),
// and a linear ramp is reproduced exactly away from the clamped border (bilinear is exact on linear
// functions), so upsampling adds no bias to smooth lighting.
TEST(ShaderUpscale, BilinearMatchesDoubleReferenceAndKeepsLinearRamps) {
    for (glm::ivec4 sizes : {glm::ivec4(8, 6, 16, 12), glm::ivec4(8, 6, 32, 24), glm::ivec4(7, 5, 16, 11)}) {
        UpscaleSource src(sizes.x, sizes.y, [](int x, int y) { return glm::vec4(2.0f + 1.5f * x + 0.25f * y, x, y, 1.0f); });
        const int ow = sizes.z, oh = sizes.w;
        auto out = runGlsl({"common/upscale.glsl"}, kBilinear, UpscaleSource::pixels(ow, oh), kUpscaleGlobals);
        for (int y = 0; y < oh; ++y)
            for (int x = 0; x < ow; ++x) {
                const glm::dvec4 e = src.bilinear(x, y, ow, oh);
                const glm::vec4 g = out[size_t(y) * ow + x];
                for (int c = 0; c < 4; ++c)
                    ASSERT_NEAR(g[c], e[c], 1e-5 * std::max(1.0, std::abs(e[c]))) << x << "," << y << " of " << ow << "x" << oh;
                const double cx = (x + 0.5) * sizes.x / ow - 0.5, cy = (y + 0.5) * sizes.y / oh - 0.5;
                if (cx >= 0.0 && cy >= 0.0 && cx <= sizes.x - 1 && cy <= sizes.y - 1)  // inside: the ramp itself
                    ASSERT_NEAR(g.x, 2.0 + 1.5 * cx + 0.25 * cy, 1e-5 * (2.0 + 1.5 * cx + 0.25 * cy));
            }
    }
}

// Bound: at the same size the upscale is the identity, bit for bit (weights 1, 0, 0, 0), and a tap
// of NaN or Inf never yields NaN: an Inf texel reads 65504
// (sanitizeHdr), a NaN texel 0, and their neighbours are unchanged.
TEST(ShaderUpscale, IdentityIsExactAndNonFiniteTexelsStayFinite) {
    UpscaleSource src(6, 4, [](int x, int y) {
        if (x == 2 && y == 1) return glm::vec4(kInf, kInf, 1.0f, 1.0f);
        if (x == 3 && y == 1) return glm::vec4(kNaN, 1.0f, kNaN, 1.0f);
        return glm::vec4(0.1f * x + 1e-7f, float(y), 1e-30f, 1.0f);
    });
    auto same = runGlsl({"common/upscale.glsl"}, kBilinear, UpscaleSource::pixels(6, 4), kUpscaleGlobals);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 6; ++x) {
            const glm::vec4 g = same[size_t(y) * 6 + x];
            for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(g[c])) << x << "," << y;
            if (x == 2 && y == 1) EXPECT_EQ(g, glm::vec4(65504.0f, 65504.0f, 1.0f, 1.0f));
            else if (x == 3 && y == 1) EXPECT_EQ(g, glm::vec4(0.0f, 1.0f, 0.0f, 1.0f));
            else EXPECT_EQ(g, src.texels[size_t(y) * 6 + x]) << x << "," << y;
        }
    auto up = runGlsl({"common/upscale.glsl"}, kBilinear, UpscaleSource::pixels(24, 16), kUpscaleGlobals);
    for (const glm::vec4& g : up)
        for (int c = 0; c < 4; ++c) {
            ASSERT_TRUE(std::isfinite(g[c]));
            ASSERT_GE(g[c], 0.0f);
            ASSERT_LE(g[c], 65504.0f);
        }
}

// Nearest (the debug views): each output pixel is exactly the source texel its centre falls in.
TEST(ShaderUpscale, NearestPicksTheCoveringTexel) {
    UpscaleSource src(5, 3, [](int x, int y) { return glm::vec4(x, y, x * 10 + y, 1.0f); });
    const int ow = 17, oh = 8;
    auto out = runGlsl({"common/upscale.glsl"}, "return upscaleNearest(uSrc, ivec2(x.xy), ivec2(x.zw));",
                       UpscaleSource::pixels(ow, oh), kUpscaleGlobals);
    for (int y = 0; y < oh; ++y)
        for (int x = 0; x < ow; ++x) {
            const int sx = int((x + 0.5) * 5 / ow), sy = int((y + 0.5) * 3 / oh);
            EXPECT_EQ(out[size_t(y) * ow + x], glm::vec4(sx, sy, sx * 10 + sy, 1.0f)) << x << "," << y;
        }
}

// ---- HDR inspection (common/hdr_inspect.glsl) ----------------------------------------------------

TEST(ShaderHdrInspect, InvalidPixelsAreClassified) {
    std::vector<glm::vec4> in = {glm::vec4(1.0f, 2.0f, 3.0f, 1.0f), glm::vec4(kNaN, 0.0f, 0.0f, 1.0f),
                                 glm::vec4(0.0f, kInf, 0.0f, 1.0f), glm::vec4(0.0f, 0.0f, -kInf, 1.0f),
                                 glm::vec4(kNaN, kInf, 0.0f, 1.0f), glm::vec4(65504.0f, 0.0f, 0.0f, 1.0f)};
    auto out = runGlsl({"common/hdr_inspect.glsl"}, "return vec4(float(invalidPixelKind(x)));", in);
    const float expected[] = {0, 1, 2, 2, 1, 0};  // NaN wins over Inf; the largest half float is valid
    for (size_t i = 0; i < in.size(); ++i) EXPECT_EQ(out[i].x, expected[i]) << i;
}

// A known radiance lands in the expected stop: L = 0.18 x 2^k is band k (after exposure), rounded to
// the nearest stop, clamped to [-6, 6]; black and Inf go to the ends.
TEST(ShaderHdrInspect, EvFalseColourBandOfKnownRadiance) {
    std::vector<glm::vec4> in;
    std::vector<int> expected;
    for (int k = -8; k <= 8; ++k)
        for (float offset : {-0.45f, 0.0f, 0.45f}) {
            const float ev = float(k) + offset;
            in.push_back(glm::vec4(0.18f * std::exp2(ev), 0.0f, 0.0f, 0.0f));  // grey radiance, exposure 0
            expected.push_back(std::clamp(k, -6, 6));
        }
    in.push_back(glm::vec4(0.18f, 2.0f, 0.0f, 0.0f));  // exposure +2 EV moves middle grey to +2
    expected.push_back(2);
    in.push_back(glm::vec4(0.0f));
    expected.push_back(-6);
    in.push_back(glm::vec4(kInf, 0.0f, 0.0f, 0.0f));
    expected.push_back(6);
    auto out = runGlsl({"common/hdr_inspect.glsl"},
                       "float L = hdrLuminance(vec3(x.x)); int b = evBand(L, x.y); return vec4(float(b), evBandColor(b));", in);
    for (size_t i = 0; i < in.size(); ++i) {
        EXPECT_EQ(int(out[i].x), expected[i]) << "L " << in[i].x;
        if (expected[i] == 0) EXPECT_EQ(glm::vec3(out[i].y, out[i].z, out[i].w), glm::vec3(0.0f, 0.85f, 0.0f));  // green
    }
}
