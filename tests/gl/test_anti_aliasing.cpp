// Anti-aliasing and dithering: the SSAA resolve, FXAA and the dithered 8-bit quantisation, checked
// against analytic coverage and statistical properties, not one driver's pixels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/gl/handles.hpp"
#include "engine/scene/primitives.hpp"
#include "frame/renderer.hpp"
#include "tests/gl/gl_fixture.hpp"

using namespace lp;
using lp::test::runGlsl;

namespace {

const float kInf = std::numeric_limits<float>::infinity();
const float kNaN = std::numeric_limits<float>::quiet_NaN();

// A texture on unit 9 for the shader harness ("uSrc").
struct Source {
    int w, h;
    std::vector<glm::vec4> texels;
    gl::Texture texture;
    Source(int w_, int h_, const std::function<glm::vec4(int, int)>& f) : w(w_), h(h_) {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) texels.push_back(f(x, y));
        texture = gl::makeTexture2D(GL_RGBA32F, w, h, 1, "aa.source");
        glTextureSubImage2D(texture.id(), 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, texels.data());
        glBindTextureUnit(9, texture.id());
    }
    ~Source() { glBindTextureUnit(9, 0); }
    glm::vec4 at(int x, int y) const { return texels[size_t(y) * size_t(w) + size_t(x)]; }
    // One input per output pixel: (x, y, 0, 0).
    static std::vector<glm::vec4> pixels(int w, int h) {
        std::vector<glm::vec4> in;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) in.push_back(glm::vec4(x, y, 0, 0));
        return in;
    }
};
const char* kSrcGlobals = "layout(binding = 9) uniform sampler2D uSrc;\n";

// ---- the exact coverage of a pixel by a half-plane ------------------------------------------------

// Area of the unit pixel [x, x+1] x [y, y+1] where dot(n, q) < c (Sutherland-Hodgman clip of the
// square by the half-plane, then the shoelace formula), in double.
double pixelCoverage(double x, double y, glm::dvec2 n, double c) {
    std::vector<glm::dvec2> poly = {{x, y}, {x + 1, y}, {x + 1, y + 1}, {x, y + 1}}, out;
    for (size_t i = 0; i < poly.size(); ++i) {
        const glm::dvec2 a = poly[i], b = poly[(i + 1) % poly.size()];
        const double da = glm::dot(n, a) - c, db = glm::dot(n, b) - c;
        if (da < 0) out.push_back(a);
        if ((da < 0) != (db < 0)) out.push_back(a + (b - a) * (da / (da - db)));
    }
    double area = 0.0;
    for (size_t i = 0; i < out.size(); ++i) {
        const glm::dvec2 a = out[i], b = out[(i + 1) % out.size()];
        area += a.x * b.y - a.y * b.x;
    }
    return std::abs(area) * 0.5;
}

// A flat-lit (emissive-like: radiance = its albedo) square plane, white, seen straight down from
// 5 m against black, turned by `degrees` about the view axis and placed so that one straight edge
// crosses the view: a half-plane of radiance 1 with a known edge.
struct HalfPlaneScene {
    Scene scene;
    glm::dvec3 edgeA, edgeB;  // two world points of the edge
    glm::dvec3 inside;        // a world point on the plane

    explicit HalfPlaneScene(double degrees, double offset) {
        ModelInstance m;
        m.name = "half-plane";
        m.primitive = "plane";
        m.mesh = makePlane(1.0f, 1);
        for (auto& mat : m.mesh.materials) {
            mat.diffuse = glm::vec3(1.0f);
            mat.specular = glm::vec3(0.0f);
            mat.flat = true;
        }
        // Local plane [-0.5, 0.5]^2 scaled to 40 m; its +x edge (x = 20) moved to pass `offset` m from
        // the view axis, then the whole turned about y.
        const double a = glm::radians(degrees);
        const glm::dmat4 turn = glm::rotate(glm::dmat4(1.0), a, glm::dvec3(0, 1, 0));
        const glm::dmat4 place = turn * glm::translate(glm::dmat4(1.0), glm::dvec3(offset - 20.0, 0, 0)) *
                                 glm::scale(glm::dmat4(1.0), glm::dvec3(40.0));
        m.transform = glm::mat4(place);
        edgeA = glm::dvec3(place * glm::dvec4(0.5, 0, -0.5, 1));
        edgeB = glm::dvec3(place * glm::dvec4(0.5, 0, 0.5, 1));
        inside = glm::dvec3(place * glm::dvec4(0.0, 0, 0.0, 1));
        scene.models.push_back(std::move(m));
        scene.ambient = glm::vec3(0.0f);
        scene.environment.color = glm::vec3(0.0f);  // a black background
        scene.camera.position = glm::vec3(0, 5, 0);
        scene.camera.target = glm::vec3(0, 0, 0);
        scene.camera.up = glm::vec3(0, 0, -1);
        scene.camera.fovYDegrees = 50.0f;
        scene.camera.nearPlane = 0.1f;
        scene.camera.farPlane = 50.0f;
    }

    // World point -> pixel coordinates (x right, y down from the top row; pixel (i, j) spans
    // [i, i+1] x [j, j+1]).
    glm::dvec2 toPixel(glm::dvec3 p, int w, int h) const {
        const glm::dmat4 vp = glm::dmat4(scene.camera.projection(float(w) / float(h))) * glm::dmat4(scene.camera.view());
        const glm::dvec4 c = vp * glm::dvec4(p, 1.0);
        return {(c.x / c.w * 0.5 + 0.5) * w, (0.5 - c.y / c.w * 0.5) * h};
    }

    // Exact coverage of every pixel: the half-plane on `inside`'s side of the edge.
    std::vector<double> coverage(int w, int h) const {
        const glm::dvec2 a = toPixel(edgeA, w, h), b = toPixel(edgeB, w, h), in = toPixel(inside, w, h);
        glm::dvec2 n = glm::normalize(glm::dvec2(b.y - a.y, a.x - b.x));
        double c = glm::dot(n, a);
        if (glm::dot(n, in) > c) {
            n = -n;
            c = -c;
        }
        std::vector<double> cov(size_t(w) * h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) cov[size_t(y) * w + x] = pixelCoverage(x, y, n, c);
        return cov;
    }
};

RenderSettings aaSettings(int w, int h, AntiAliasing method, int ssaaScale = 2) {
    RenderSettings s;
    s.width = w;
    s.height = h;
    s.keepHdr = true;
    s.aa.method = method;
    s.aa.ssaaScale = ssaaScale;
    s.aa.dither = false;  // the tests compare quantisations exactly
    s.autoExposure = false;  // at 0 EV
    return s;
}

}  // namespace

// ---- SSAA --------------------------------------------------------------------------------------

// Bound: the box resolve is the mean of the S x S block (relative 1e-6), for S = 2, 3, 4, and a NaN
// or Inf sample gives a finite pixel (NaN -> 0, Inf -> 65504 before averaging).
TEST(ShaderDownsample, BoxIsTheMeanOfEachFootprint) {
    for (int scale : {2, 3, 4}) {
        const int ow = 5, oh = 3;
        Source src(ow * scale, oh * scale, [](int x, int y) {
            if (x == 1 && y == 0) return glm::vec4(kInf, 1.0f, kNaN, 1.0f);
            return glm::vec4(0.5f + 0.25f * x + 0.125f * y * y, float(x * y), 1e-3f * float(x + y), 1.0f);
        });
        auto out = runGlsl({"common/downsample.glsl"},
                           "return downsampleBox(uSrc, ivec2(x.xy), " + std::to_string(scale) + ");",
                           Source::pixels(ow, oh), kSrcGlobals);
        for (int y = 0; y < oh; ++y)
            for (int x = 0; x < ow; ++x) {
                glm::dvec4 sum(0.0);
                for (int j = 0; j < scale; ++j)
                    for (int i = 0; i < scale; ++i) {
                        glm::dvec4 t(src.at(x * scale + i, y * scale + j));
                        for (int c = 0; c < 3; ++c) t[c] = std::isnan(t[c]) ? 0.0 : std::clamp(t[c], 0.0, 65504.0);
                        sum += t;
                    }
                const glm::dvec4 e = sum / double(scale * scale);
                const glm::vec4 g = out[size_t(y) * ow + x];
                for (int c = 0; c < 4; ++c) {
                    ASSERT_TRUE(std::isfinite(g[c])) << scale << ": " << x << "," << y;
                    EXPECT_NEAR(g[c], e[c], 1e-6 * std::max(1.0, std::abs(e[c]))) << scale << ": " << x << "," << y;
                }
            }
    }
}

// --aa ssaa: a white flat-lit half-plane against black. Each output pixel's HDR value is the
// fraction of its S x S samples on the plane, so it must be the pixel's exact area coverage within
// what an ordered grid can resolve: 1/16 at S = 4 (the edge is at 33 degrees, offset by a fraction
// of a pixel), 1/(2S) at S = 2 and 3. The mean over the edge's pixels is unbiased (within 0.01).
TEST(SsaaRender, HalfPlaneCoversEachPixelByItsArea) {
    const int w = 48, h = 32;
    const HalfPlaneScene hp(33.0, 0.0137);
    const std::vector<double> exact = hp.coverage(w, h);
    for (int scale : {2, 3, 4}) {
        SCOPED_TRACE(scale);
        Renderer r(hp.scene);
        r.render(aaSettings(w, h, AntiAliasing::Ssaa, scale));
        EXPECT_TRUE(r.graph().isLive("ssaa_downsample"));
        EXPECT_FALSE(r.graph().isLive("upscale"));
        const ImageF hdr = r.readHdr();
        ASSERT_EQ(hdr.width, w);
        ASSERT_EQ(hdr.height, h);
        const double tolerance = scale == 4 ? 1.0 / 16.0 : 1.0 / (2.0 * scale);
        double worst = 0.0, biasSum = 0.0;
        int edgePixels = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const double e = exact[size_t(y) * w + x];
                const double got = hdr.rgba[(size_t(y) * w + x) * 4];
                worst = std::max(worst, std::abs(got - e));
                if (e > 0.0 && e < 1.0) {
                    biasSum += got - e;
                    ++edgePixels;
                }
            }
        EXPECT_GT(edgePixels, h);  // the edge crosses the whole image
        EXPECT_LE(worst, tolerance);
        EXPECT_LT(std::abs(biasSum / edgePixels), 0.01);
    }
    // Without anti-aliasing each pixel is all or nothing: the same edge is off by up to ~1/2.
    Renderer r(hp.scene);
    r.render(aaSettings(w, h, AntiAliasing::Off));
    const ImageF hdr = r.readHdr();
    double worst = 0.0;
    for (size_t i = 0; i < exact.size(); ++i) worst = std::max(worst, std::abs(hdr.rgba[i * 4] - exact[i]));
    EXPECT_GT(worst, 0.4);
}

// The default frame is anti-aliased: a render with RenderSettings{} (only the size set and the HDR
// buffer kept) supersamples, and the same tilted edge as above (33 degrees, a sub-pixel offset) comes
// out near its exact coverage in one frame: every pixel within 1/4 (2x2 samples), and the RMS error
// over the image under half that of --aa off (on llvmpipe: RMS 0.013 against 0.042, worst 0.16
// against 0.49). A render scale below 1 keeps the render scale and leaves SSAA out.
TEST(DefaultAntiAliasing, OneHeadlessFrameCoversATiltedEdge) {
    const int w = 48, h = 32;
    const HalfPlaneScene hp(33.0, 0.0137);
    const std::vector<double> exact = hp.coverage(w, h);
    auto errors = [&](const RenderSettings& s, double* worst) {
        Renderer r(hp.scene);
        r.render(s);
        const ImageF hdr = r.readHdr();
        double sum = 0.0;
        *worst = 0.0;
        for (size_t i = 0; i < exact.size(); ++i) {
            const double e = std::abs(hdr.rgba[i * 4] - exact[i]);
            sum += e * e;
            *worst = std::max(*worst, e);
        }
        return std::sqrt(sum / double(exact.size()));
    };
    RenderSettings defaults;
    defaults.width = w;
    defaults.height = h;
    defaults.keepHdr = true;
    EXPECT_EQ(defaults.aa.method, AntiAliasing::Ssaa);
    EXPECT_TRUE(supersampled(defaults));
    double worst = 0.0, worstOff = 0.0;
    const double rms = errors(defaults, &worst);
    RenderSettings off = defaults;
    off.aa.method = AntiAliasing::Off;
    const double rmsOff = errors(off, &worstOff);
    std::printf("  default: RMS %.4f, worst %.3f; --aa off: RMS %.4f, worst %.3f\n", rms, worst, rmsOff, worstOff);
    EXPECT_LE(worst, 0.25);
    EXPECT_LT(rms, 0.5 * rmsOff);

    RenderSettings scaled = defaults;
    scaled.renderScale = 0.5f;
    EXPECT_FALSE(supersampled(scaled));
    EXPECT_FLOAT_EQ(internalRenderScale(scaled), 0.5f);
    Renderer r(hp.scene);
    r.render(scaled);
    EXPECT_FALSE(r.graph().isLive("ssaa_downsample"));
    EXPECT_TRUE(r.graph().isLive("upscale"));
}

// ---- FXAA --------------------------------------------------------------------------------------

namespace {
std::vector<glm::vec4> fxaaOf(const Source& src) {
    return runGlsl({"common/fxaa.glsl"}, "return vec4(fxaaQuality(uSrc, ivec2(x.xy)), 1.0);", Source::pixels(src.w, src.h),
                   kSrcGlobals);
}
}  // namespace

// A flat region, straight pixel-aligned horizontal and vertical edges (full width / full height,
// light on dark and dark on light) and one- and two-pixel lines along the axes come out exactly as
// they went in: there is nothing to anti-alias there.
TEST(ShaderFxaa, LeavesFlatRegionsAndPixelAlignedEdgesUnchanged) {
    const int w = 40, h = 24;
    const std::vector<std::function<glm::vec4(int, int)>> images = {
        [](int, int) { return glm::vec4(0.4f, 0.5f, 0.6f, 1.0f); },
        [](int, int y) { return y < 11 ? glm::vec4(1.0f) : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f); },
        [](int x, int) { return x < 17 ? glm::vec4(0.05f, 0.1f, 0.1f, 1.0f) : glm::vec4(0.9f, 0.8f, 0.7f, 1.0f); },
        [](int, int y) { return y >= 8 && y < 10 ? glm::vec4(0.8f, 0.8f, 0.8f, 1.0f) : glm::vec4(0.2f, 0.2f, 0.2f, 1.0f); },
        [](int x, int) { return x == 30 ? glm::vec4(0.1f, 0.1f, 0.1f, 1.0f) : glm::vec4(0.7f, 0.6f, 0.5f, 1.0f); },
    };
    for (size_t k = 0; k < images.size(); ++k) {
        Source src(w, h, images[k]);
        const auto out = fxaaOf(src);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const glm::vec4 e = src.at(x, y), g = out[size_t(y) * w + x];
                for (int c = 0; c < 3; ++c) ASSERT_NEAR(g[c], e[c], 1e-6) << "image " << k << " at " << x << "," << y;
            }
    }
}

// A point-sampled (stair-stepped) edge at 20 degrees from horizontal: FXAA moves its pixels towards
// the exact coverage (the error against it at least halves), and every output stays between the two
// sides' values.
TEST(ShaderFxaa, SmoothsAStairSteppedEdgeTowardsItsCoverage) {
    const int w = 64, h = 32;
    const double a = glm::radians(20.0);
    const glm::dvec2 n(-std::sin(a), std::cos(a));  // the edge y = tan(a) x + 9.3 (in pixel units)
    const double c = glm::dot(n, glm::dvec2(0.0, 9.3));
    Source src(w, h, [&](int x, int y) {
        const float v = glm::dot(n, glm::dvec2(x + 0.5, y + 0.5)) < c ? 1.0f : 0.0f;  // one sample a pixel
        return glm::vec4(v, v, v, 1.0f);
    });
    const auto out = fxaaOf(src);
    double errorOff = 0.0, errorFxaa = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = 4; x < w - 4; ++x) {
            const double cov = pixelCoverage(x, y, n, c);
            const float g = out[size_t(y) * w + x].x;
            ASSERT_GE(g, 0.0f);
            ASSERT_LE(g, 1.0f);
            errorOff += std::abs(src.at(x, y).x - cov);
            errorFxaa += std::abs(g - cov);
        }
    EXPECT_GT(errorOff, 10.0);
    EXPECT_LT(errorFxaa, 0.5 * errorOff) << "off " << errorOff << ", fxaa " << errorFxaa;
    std::printf("stair-stepped edge: sum |error| off %.2f, fxaa %.2f\n", errorOff, errorFxaa);
}

// --aa fxaa on a rendered edge: the display image is nearer the 4x4 SSAA display image than without
// anti-aliasing (the summed absolute difference in 8-bit steps falls by 15% at least), and the graph
// has the fxaa pass. FXAA cannot reach SSAA here: it blends the tone-mapped,
// sRGB-encoded values, while SSAA averages radiance before the (concave) tone curve, so a half-covered
// pixel is 141/255 under SSAA and at most about 88/255 from FXAA's blend of 0 and 176.
TEST(FxaaRender, ReducesTheErrorAgainstSsaaOfARenderedEdge) {
    const int w = 64, h = 40;
    const HalfPlaneScene hp(21.0, 0.0231);
    auto display = [&](AntiAliasing method, int scale = 2) {
        Renderer r(hp.scene);
        r.render(aaSettings(w, h, method, scale));
        EXPECT_EQ(r.graph().isLive("fxaa"), method == AntiAliasing::Fxaa);
        return r.readDisplay();
    };
    const Image8 reference = display(AntiAliasing::Ssaa, 4), off = display(AntiAliasing::Off),
                 fxaa = display(AntiAliasing::Fxaa);
    double errorOff = 0.0, errorFxaa = 0.0;
    for (size_t i = 0; i < reference.rgba.size(); i += 4) {
        errorOff += std::abs(int(off.rgba[i]) - int(reference.rgba[i]));
        errorFxaa += std::abs(int(fxaa.rgba[i]) - int(reference.rgba[i]));
    }
    EXPECT_GT(errorOff, 0.0);
    EXPECT_LT(errorFxaa, 0.85 * errorOff) << "off " << errorOff << ", fxaa " << errorFxaa;
}

// ---- dithering ---------------------------------------------------------------------------------

namespace {
// quantize8 over a w x h field of values v(x, y) in [0, 1]; returns the 8-bit levels.
std::vector<int> quantized(int w, int h, bool dither, const std::function<float(int, int)>& v) {
    std::vector<glm::vec4> in;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) in.push_back(glm::vec4(x, y, v(x, y), 0.0f));
    const auto out = runGlsl({"common/dither.glsl"},
                             std::string("return vec4(quantize8(vec3(x.z), ivec2(x.xy), ") + (dither ? "true" : "false") +
                                 ") * 255.0, 0.0);",
                             in);
    std::vector<int> levels;
    for (const glm::vec4& o : out) {
        EXPECT_EQ(o.x, std::round(o.x));  // whole levels, exactly
        EXPECT_EQ(o.x, o.y);              // grey noise: the same for every channel
        levels.push_back(int(o.x));
    }
    return levels;
}
}  // namespace

// A flat field keeps its mean: within 0.05 LSB of the exact value away from the ends (plain
// rounding is off by up to 0.5), within 0.5 LSB next to them; the noise is at most 1 level either
// way of plain rounding, and 0 and 1 stay exact.
TEST(ShaderDither, FlatFieldKeepsItsMean) {
    const int w = 64, h = 64;
    for (double level : {0.0, 0.3, 1.0, 17.25, 100.5, 128.0, 200.75, 254.6, 255.0}) {
        const float v = float(level / 255.0);
        const auto d = quantized(w, h, true, [&](int, int) { return v; });
        double mean = 0.0;
        for (int k : d) {
            mean += k;
            EXPECT_LE(std::abs(k - std::round(double(v) * 255.0)), 1.0) << level;
        }
        mean /= double(d.size());
        const bool nearEnd = level < 1.0 || level > 254.0;
        EXPECT_NEAR(mean, double(v) * 255.0, nearEnd ? 0.5 : 0.05) << level;
        if (level == 0.0 || level == 255.0)
            for (int k : d) ASSERT_EQ(k, int(level));
    }
}

// A slow gradient (4 levels over 256 columns) bands without dither: runs of one level 64 columns
// long and column means off by up to 0.5 LSB. Dithered, the runs along a row are short and each
// column's mean over 64 rows tracks the exact gradient (RMS under 0.1 LSB, against 0.29 for plain
// rounding).
TEST(ShaderDither, BreaksTheBandsOfASlowGradient) {
    const int w = 256, h = 64;
    auto value = [](int x, int) { return float((100.0 + 4.0 * (x + 0.5) / 256.0) / 255.0); };
    auto stats = [&](bool dither, double& meanRun, double& rmsColumn) {
        const auto q = quantized(w, h, dither, value);
        int runs = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) runs += x == 0 || q[size_t(y) * w + x] != q[size_t(y) * w + x - 1];
        meanRun = double(w * h) / runs;
        double sq = 0.0;
        for (int x = 0; x < w; ++x) {
            double m = 0.0;
            for (int y = 0; y < h; ++y) m += q[size_t(y) * w + x];
            m /= h;
            const double e = 100.0 + 4.0 * (x + 0.5) / 256.0;
            sq += (m - e) * (m - e);
        }
        rmsColumn = std::sqrt(sq / w);
    };
    double runPlain, rmsPlain, runDither, rmsDither;
    stats(false, runPlain, rmsPlain);
    stats(true, runDither, rmsDither);
    EXPECT_GT(runPlain, 50.0);
    EXPECT_GT(rmsPlain, 0.25);
    EXPECT_LT(runDither, 4.0);
    EXPECT_LT(rmsDither, 0.1);
}

// The tone map dithers the displayed image unless --no-dither: a flat-lit plane filling the view at
// a radiance between two 8-bit levels gives one level without dither and a mix whose mean is within
// 0.15 LSB of the exact encoded value with it (fp16 HDR rounding included).
TEST(DitherRender, ToneMapDithersTheDisplayUnlessSwitchedOff) {
    const int w = 64, h = 48;
    HalfPlaneScene hp(0.0, 30.0);  // the edge far out of view: the plane fills it
    // An albedo the 8-bit sRGB G-buffer stores exactly (sRGB code 188), away from the rounding ties
    // drivers break either way.
    const double kd = test::srgbDecode(188.0 / 255.0);
    for (auto& mat : hp.scene.models[0].mesh.materials) mat.diffuse = glm::vec3(float(kd));
    const double t = std::pow(kd / (kd + 1.0), 1.2);
    const double exact = 255.0 * (t <= 0.0031308 ? 12.92 * t : 1.055 * std::pow(t, 1.0 / 2.4) - 0.055);
    for (bool dither : {false, true}) {
        Renderer r(hp.scene);
        RenderSettings s = aaSettings(w, h, AntiAliasing::Off);
        s.aa.dither = dither;
        r.render(s);
        const Image8 img = r.readDisplay();
        double mean = 0.0;
        int lo = 255, hi = 0;
        for (size_t i = 0; i < img.rgba.size(); i += 4) {
            mean += img.rgba[i];
            lo = std::min(lo, int(img.rgba[i]));
            hi = std::max(hi, int(img.rgba[i]));
        }
        mean /= double(w * h);
        if (!dither) {
            EXPECT_EQ(lo, hi);
            EXPECT_EQ(lo, int(std::lround(exact)));
        } else {
            EXPECT_GE(hi - lo, 1);
            EXPECT_NEAR(mean, exact, 0.15);
        }
    }
}

// ---- TAA ---------------------------------------------------------------------------------------

// The resolve's parts: motion agreement within max(0.5 px, 20%), clipping into the neighbourhood's
// box (a history inside it is kept, one outside is moved onto its boundary towards the centre), and
// the luma-weighted blend (weight 1: the current frame; equal colours: unchanged).
TEST(ShaderTaa, RejectsDisagreeingMotionClipsAndBlends) {
    auto agree = runGlsl({"common/taa.glsl"}, "return vec4(taaMotionAgrees(x.xy, x.zw) ? 1.0 : 0.0);",
                         {glm::vec4(0, 0, 0, 0), glm::vec4(0, 0, 0.4f, 0), glm::vec4(0, 0, 3, 0), glm::vec4(10, 0, 11.5f, 0),
                          glm::vec4(10, 0, 13, 0), glm::vec4(0, 0, -5, 2)});
    const float expected[] = {1, 1, 0, 1, 0, 0};
    for (size_t i = 0; i < std::size(expected); ++i) EXPECT_EQ(agree[i].x, expected[i]) << i;

    const std::string neighbourhood = R"(
        TaaNeighbourhood n;
        n.mean = rgbToYCoCg(vec3(0.5)); n.sigma = vec3(0.1, 0.05, 0.05);
        n.lo = n.mean - vec3(0.3); n.hi = n.mean + vec3(0.3);
    )";
    auto clipped = runGlsl({"common/taa.glsl"}, neighbourhood + "return vec4(rgbToYCoCg(taaClipHistory(x.xyz, n)), 0.0);",
                           {glm::vec4(0.55f, 0.55f, 0.55f, 0), glm::vec4(1.0f, 1.0f, 1.0f, 0), glm::vec4(0.5f, 0.9f, 0.5f, 0)});
    EXPECT_NEAR(clipped[0].x, 0.55f, 1e-5);  // inside: kept
    EXPECT_NEAR(clipped[1].x, 0.6f, 1e-5);   // grey 1.0: luma clipped to mean + sigma
    EXPECT_NEAR(clipped[1].y, 0.0f, 1e-5);
    for (const glm::vec4& c : clipped) {
        EXPECT_LE(std::abs(c.x - 0.5f), 0.1f + 1e-5f);
        EXPECT_LE(std::abs(c.y), 0.05f + 1e-5f);
        EXPECT_LE(std::abs(c.z), 0.05f + 1e-5f);
    }
    auto blended = runGlsl({"common/taa.glsl"}, "return vec4(taaBlend(vec3(x.x), vec3(x.y), x.z), 0.0);",
                           {glm::vec4(0.3f, 0.3f, 0.1f, 0), glm::vec4(2.0f, 0.0f, 1.0f, 0), glm::vec4(1.0f, 0.0f, 0.5f, 0)});
    EXPECT_NEAR(blended[0].x, 0.3f, 1e-6);
    EXPECT_NEAR(blended[1].x, 2.0f, 1e-6);
    EXPECT_NEAR(blended[2].x, 0.5 / 2.0 / (0.5 / 2.0 + 0.5), 1e-5);  // the bright sample weighs 1 / (1 + 1)
}

namespace {
double rmse(const ImageF& a, const ImageF& b) {
    double sq = 0.0;
    for (size_t i = 0; i < a.rgba.size(); i += 4) sq += (a.rgba[i] - b.rgba[i]) * (a.rgba[i] - b.rgba[i]);
    return std::sqrt(sq / double(a.rgba.size() / 4));
}
}  // namespace

// --aa taa with a still camera: the jittered frames accumulate towards the 4x4 SSAA image of the
// half-plane edge. After 48 frames the HDR RMSE against it is below 0.03 and under 70% of the
// unfiltered image's (0.027 against 0.042 on llvmpipe): the exponential blend (current weight 0.1)
// weighs the 16 jitter phases unevenly, and the clip to the current neighbourhood holds edge pixels
// back, so TAA approaches SSAA without reaching it.
TEST(TaaRender, StillCameraConvergesToSsaa) {
    const int w = 48, h = 32;
    const HalfPlaneScene hp(33.0, 0.0137);
    Renderer ref(hp.scene);
    ref.render(aaSettings(w, h, AntiAliasing::Ssaa, 4));
    const ImageF reference = ref.readHdr();
    Renderer off(hp.scene);
    off.render(aaSettings(w, h, AntiAliasing::Off));
    const double errorOff = rmse(off.readHdr(), reference);
    Renderer taa(hp.scene);
    const RenderSettings s = aaSettings(w, h, AntiAliasing::Taa);
    for (int i = 0; i < 48; ++i) taa.render(s, 0.0f, false);
    EXPECT_TRUE(taa.graph().isLive("taa"));
    const double errorTaa = rmse(taa.readHdr(), reference);
    std::printf("HDR RMSE against SSAA 4x4: off %.4f, taa after 48 frames %.4f\n", errorOff, errorTaa);
    EXPECT_LT(errorTaa, 0.03);
    EXPECT_LT(errorTaa, 0.7 * errorOff);
}

// A moving object leaves no trail: the camera slides sideways for 12 frames, so the plane's edge
// sweeps across the image (the background it uncovers has another motion than the plane had). Every
// pixel more than 1.5 px from the edge's current position holds the current side's value (0 or 1
// within 0.02), none of the plane's old colour lingers behind it.
TEST(TaaRender, MovingEdgeLeavesNoTrail) {
    const int w = 48, h = 32;
    HalfPlaneScene hp(33.0, 0.0137);
    Renderer taa(hp.scene);
    const RenderSettings s = aaSettings(w, h, AntiAliasing::Taa);
    for (int i = 0; i < 16; ++i) taa.render(s, 0.0f, false);  // a converged history
    for (int i = 1; i <= 12; ++i) {
        hp.scene.camera.position.x = 0.05f * float(i);  // about 0.5 px a frame
        hp.scene.camera.target.x = 0.05f * float(i);
        taa.render(s, 0.0f, false);
    }
    const std::vector<double> exact = hp.coverage(w, h);
    const ImageF img = taa.readHdr();
    int checked = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            bool nearEdge = false;  // within 1.5 px of a partly covered pixel
            for (int dy = -2; dy <= 2 && !nearEdge; ++dy)
                for (int dx = -2; dx <= 2 && !nearEdge; ++dx) {
                    const int xx = std::clamp(x + dx, 0, w - 1), yy = std::clamp(y + dy, 0, h - 1);
                    const double c = exact[size_t(yy) * w + xx];
                    nearEdge = c > 0.0 && c < 1.0;
                }
            if (nearEdge) continue;
            const double e = exact[size_t(y) * w + x];
            EXPECT_NEAR(img.rgba[(size_t(y) * w + x) * 4], e, 0.02) << x << "," << y;
            ++checked;
        }
    EXPECT_GT(checked, w * h / 2);
}
