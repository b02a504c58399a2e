// The GLSL in shaders/common/ on the real driver, against double-precision C++ references.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <random>
#include <string>

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

namespace {
// One triangle in window space (xy in texels, depth) and a texel centre that it touches.
struct CasterTexelCase {
    glm::dvec3 a, b, c;
    glm::dvec2 centre;
};

glm::dvec2 depthPlaneGradientRef(const CasterTexelCase& t) {
    // dz = g . (p - a) through b and c: two equations in g, solved by Cramer's rule.
    const glm::dvec2 e1 = glm::dvec2(t.b) - glm::dvec2(t.a), e2 = glm::dvec2(t.c) - glm::dvec2(t.a);
    const double det = e1.x * e2.y - e1.y * e2.x, dz1 = t.b.z - t.a.z, dz2 = t.c.z - t.a.z;
    if (det == 0.0) return glm::dvec2(0.0);
    return glm::dvec2((dz1 * e2.y - dz2 * e1.y) / det, (e1.x * dz2 - e2.x * dz1) / det);
}

double planeDepth(const CasterTexelCase& t, glm::dvec2 g, glm::dvec2 p) { return t.a.z + glm::dot(g, p - glm::dvec2(t.a)); }

bool insideTriangle(const CasterTexelCase& t, glm::dvec2 p) {
    auto edge = [](glm::dvec3 u, glm::dvec3 v, glm::dvec2 q) { return (v.x - u.x) * (q.y - u.y) - (v.y - u.y) * (q.x - u.x); };
    const double e0 = edge(t.a, t.b, p), e1 = edge(t.b, t.c, p), e2 = edge(t.c, t.a, p);
    return (e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0);
}
}  // namespace

// shaders/common/shadow_caster_depth.glsl against double precision on random triangles (xy within a
// 64-texel box at up to 256 texels from the origin, depth in [0, 1]) and texel centres within 0.7
// texels of them: the plane's gradient within 1e-4 relative (x 64 / area for thin ones), and the
// depth a caster writes in the texel: faces away from the light the plane's minimum over the
// texel's four corners, faces towards it the centre depth + slope bias x max(|dz/dx|, |dz/dy|),
// both clamped to the triangle's depth range (within the gradient's error over the distance from
// the first vertex). The property that closes a crease, checked on 16 x 16 points of each texel: a
// face away from the light never writes a depth farther than any point of the triangle inside that
// texel. A zero-area triangle has gradient 0.
TEST(ShaderShadowCasterDepth, NearestDepthOverTheTexelMatchesTheDepthPlane) {
    std::mt19937 rng(16);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<CasterTexelCase> cases;
    while (cases.size() < 400) {
        CasterTexelCase t;
        const glm::dvec2 origin(std::floor(unit(rng) * 192.0), std::floor(unit(rng) * 192.0));
        const double extent = cases.size() % 4 == 0 ? 2.0 : 64.0;  // every 4th small (a few texels)
        auto vertex = [&] { return glm::dvec3(glm::dvec2(float(origin.x + unit(rng) * extent), float(origin.y + unit(rng) * extent)),
                                              float(unit(rng))); };
        t.a = vertex();
        t.b = vertex();
        t.c = vertex();
        if (cases.size() % 20 == 0) t.c = glm::dvec3(t.a.x, t.a.y, t.c.z);  // zero area: two vertices at one point
        if (cases.size() % 20 == 10) t.b.y = t.c.y = t.a.y;                 // zero area: on one row
        // A texel centre near the triangle: a point of it, moved by up to 0.7 texels.
        const double u = unit(rng), v = unit(rng) * (1.0 - u);
        const glm::dvec2 p = glm::dvec2(t.a) + u * (glm::dvec2(t.b) - glm::dvec2(t.a)) + v * (glm::dvec2(t.c) - glm::dvec2(t.a));
        t.centre = glm::floor(p + glm::dvec2(unit(rng) - 0.5, unit(rng) - 0.5) * 1.4) + 0.5;
        cases.push_back(t);
    }
    const float slopeBias = 1.5f;
    std::vector<glm::vec4> in;
    for (const CasterTexelCase& t : cases) {
        in.push_back(glm::vec4(float(t.a.x), float(t.a.y), float(t.a.z), float(t.b.x)));
        in.push_back(glm::vec4(float(t.b.y), float(t.b.z), float(t.c.x), float(t.c.y)));
        in.push_back(glm::vec4(float(t.c.z), float(t.centre.x), float(t.centre.y), slopeBias));
    }
    const std::string body = R"(
        uint i = gl_GlobalInvocationID.x;
        if (i % 3u != 0u) return vec4(0.0);
        vec4 p = inData[i], q = inData[i + 1u], r = inData[i + 2u];
        vec3 a = p.xyz, b = vec3(p.w, q.xy), c = vec3(q.zw, r.x);
        vec2 g = depthPlaneGradient(a, b, c);
        float centreDepth = a.z + dot(g, r.yz - a.xy);
        vec2 range = vec2(min(a.z, min(b.z, c.z)), max(a.z, max(b.z, c.z)));
        return vec4(g, conservativeCasterDepth(centreDepth, g, range, true, r.w),
                    conservativeCasterDepth(centreDepth, g, range, false, r.w));)";
    const std::vector<glm::vec4> out = runGlsl({"common/shadow_caster_depth.glsl"}, body, in);
    int zeroArea = 0, checkedPoints = 0;
    for (size_t k = 0; k < cases.size(); ++k) {
        const CasterTexelCase& t = cases[k];
        const glm::vec4 got = out[3 * k];
        // The reference from the float inputs the shader saw.
        const glm::dvec2 g = depthPlaneGradientRef(t);
        const glm::dvec2 e1 = glm::dvec2(t.b) - glm::dvec2(t.a), e2 = glm::dvec2(t.c) - glm::dvec2(t.a);
        const double area = std::abs(e1.x * e2.y - e1.y * e2.x);
        const double lo = std::min({t.a.z, t.b.z, t.c.z}), hi = std::max({t.a.z, t.b.z, t.c.z});
        const std::string what = "case " + std::to_string(k) + ", area " + std::to_string(area);
        ASSERT_TRUE(std::isfinite(got.x) && std::isfinite(got.y) && std::isfinite(got.z) && std::isfinite(got.w)) << what;
        if (area == 0.0) {
            ++zeroArea;
            EXPECT_EQ(got.x, 0.0f) << what;
            EXPECT_EQ(got.y, 0.0f) << what;
            continue;
        }
        // Float's rounding of the edge products grows as the triangle thins: relative to 1 / area.
        const double gradientTolerance = 1e-4 * (std::abs(g.x) + std::abs(g.y)) * std::max(1.0, 64.0 / area);
        EXPECT_NEAR(got.x, g.x, gradientTolerance) << what;
        EXPECT_NEAR(got.y, g.y, gradientTolerance) << what;
        if (area < 1.0) continue;  // a sliver: its plane is too steep to compare within a texel
        double corners = 1e30;
        for (glm::dvec2 corner : {glm::dvec2(-0.5, -0.5), glm::dvec2(0.5, -0.5), glm::dvec2(-0.5, 0.5), glm::dvec2(0.5, 0.5)})
            corners = std::min(corners, planeDepth(t, g, t.centre + corner));
        const double away = std::clamp(corners, lo, hi);
        const double toward = std::clamp(planeDepth(t, g, t.centre) + slopeBias * std::max(std::abs(g.x), std::abs(g.y)), lo, hi);
        // The centre depth comes from the gradient over up to ~90 texels: its error carries.
        const double reach = glm::length(t.centre - glm::dvec2(t.a)) + 1.0;
        const double depthTolerance = 1e-6 + (gradientTolerance + 1e-6 * (std::abs(g.x) + std::abs(g.y))) * reach;
        EXPECT_NEAR(got.z, away, depthTolerance) << what;
        EXPECT_NEAR(got.w, toward, depthTolerance) << what;
        for (int sy = 0; sy < 16; ++sy)
            for (int sx = 0; sx < 16; ++sx) {
                const glm::dvec2 s = t.centre + glm::dvec2((sx + 0.5) / 16.0 - 0.5, (sy + 0.5) / 16.0 - 0.5);
                if (!insideTriangle(t, s)) continue;
                ++checkedPoints;
                EXPECT_LE(double(got.z), planeDepth(t, g, s) + 1e-6) << what << " at (" << s.x << ", " << s.y << ")";
            }
    }
    EXPECT_GT(zeroArea, 0);
    EXPECT_GT(checkedPoints, 10000);
}

// The conservative raster's marks and grown front faces (common/shadow_caster_depth.glsl): a marked
// depth is the depth rounded up to the next float whose lowest bit says whether a face towards the
// light covers the texel's centre (0) or not, and reads back so; the point-in-triangle test against
// double precision (either winding, points off the edges); a front face grown past its edge writes
// its plane's farthest depth over the texel plus the slope bias and one texel of depth, never nearer
// than its nearest vertex, so it lies behind a face covering the centre in the same plane.
TEST(ShaderShadowCasterDepth, MarksRoundUpAndGrownFrontFacesYield) {
    std::mt19937 rng(37);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<glm::vec4> in;
    for (int k = 0; k < 600; ++k) {
        // x: a depth in [0, 1) (every 50th exactly representable with few bits), y: front (k odd);
        // z, w: a gradient (window depth per texel), for the grown depth; then a triangle and a point.
        const float depth = k % 50 == 0 ? float(k) / 1024.0f : float(unit(rng));
        in.emplace_back(depth, float(k % 2), float((unit(rng) - 0.5) * 0.02), float((unit(rng) - 0.5) * 0.02));
        in.emplace_back(float(unit(rng) * 16.0), float(unit(rng) * 16.0), float(unit(rng) * 16.0), float(unit(rng) * 16.0));
        in.emplace_back(float(unit(rng) * 16.0), float(unit(rng) * 16.0), float(unit(rng) * 16.0), float(unit(rng) * 16.0));
    }
    const float slopeBias = 1.0f, texelDepth = 0.003f;
    const std::string body = R"(
        uint i = gl_GlobalInvocationID.x;
        if (i % 3u != 0u) return vec4(0.0);
        vec4 d = inData[i], t = inData[i + 1u], u = inData[i + 2u];
        float marked = shadowDepthMarked(d.x, d.y > 0.5);
        float grown = grownFrontCasterDepth(d.x, d.zw, vec2(0.25, 0.75), 1.0, 0.003);
        bool inside = windowPointInTriangle(u.zw, t.xy, t.zw, u.xy);
        return vec4(marked, shadowDepthFrontAtCentre(marked) ? 1.0 : 0.0, grown, inside ? 1.0 : 0.0);)";
    const std::vector<glm::vec4> out = runGlsl({"common/shadow_caster_depth.glsl"}, body, in);
    int pointsChecked = 0;
    for (size_t k = 0; k < in.size() / 3; ++k) {
        const glm::vec4 d = in[3 * k], t = in[3 * k + 1], u = in[3 * k + 2], got = out[3 * k];
        const bool front = d.y > 0.5f;
        const std::string what = "case " + std::to_string(k) + ", depth " + std::to_string(d.x);
        EXPECT_GE(got.x, d.x) << what;
        EXPECT_LE(got.x, std::nextafter(d.x, 2.0f)) << what;
        uint32_t bits;
        std::memcpy(&bits, &got.x, sizeof bits);
        EXPECT_EQ((bits & 1u) == 0u, front) << what;
        EXPECT_EQ(got.y, front ? 1.0f : 0.0f) << what;
        const double gx = std::abs(double(d.z)), gy = std::abs(double(d.w));
        const double covering = double(d.x) + slopeBias * std::max(gx, gy);
        const double grown = std::max(covering + 0.5 * (gx + gy) + texelDepth, 0.25);
        EXPECT_NEAR(got.z, grown, 1e-6) << what;
        EXPECT_GT(double(got.z), covering + 0.99 * texelDepth) << what;
        // The point against the triangle: edge functions in double, points within 1e-3 of an edge skipped.
        const glm::dvec2 a(t.x, t.y), b(t.z, t.w), c(u.x, u.y), p(u.z, u.w);
        auto edge = [&](glm::dvec2 e0, glm::dvec2 e1) { return (e1.x - e0.x) * (p.y - e0.y) - (e1.y - e0.y) * (p.x - e0.x); };
        const double e[3] = {edge(a, b), edge(b, c), edge(c, a)};
        if (std::min({std::abs(e[0]), std::abs(e[1]), std::abs(e[2])}) < 1e-3) continue;
        ++pointsChecked;
        const bool inside = (e[0] > 0 && e[1] > 0 && e[2] > 0) || (e[0] < 0 && e[1] < 0 && e[2] < 0);
        EXPECT_EQ(got.w, inside ? 1.0f : 0.0f) << what;
    }
    EXPECT_GT(pointsChecked, 500);
}
