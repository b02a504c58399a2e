// Headless renders of small scenes checked against analytic expectations, not golden images.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/render/gltf_brdf.hpp"
#include "frame/renderer.hpp"
#include "engine/scene/primitives.hpp"
#include "engine/graph/texture_pool.hpp"
#include "passes/debug_view_pass.hpp"
#include "passes/hdr_view_pass.hpp"
#include "tests/gl/gl_fixture.hpp"

using namespace lp;

namespace {

double tonemapRef(double c) {
    c = std::clamp(c, 0.0, 65504.0);
    return std::pow(c / (c + 1.0), 1.2);
}
double srgbRef(double x) {
    x = std::clamp(x, 0.0, 1.0);
    return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
}

// A 20 m plane at y = 0 under one directional light, seen from `eye`.
Scene planeScene(glm::vec3 eye, glm::vec3 target, glm::vec3 up, glm::vec3 kd, glm::vec3 ks, float shininess) {
    Scene s;
    ModelInstance m;
    m.name = "plane";
    m.primitive = "plane";
    m.mesh = makePlane(1.0f, 4);
    for (auto& mat : m.mesh.materials) {
        mat.diffuse = kd;
        mat.specular = ks;
        mat.shininess = shininess;
    }
    m.transform = glm::scale(glm::mat4(1.0f), glm::vec3(20.0f));
    s.models.push_back(std::move(m));
    DirectionalLight light;
    light.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.2f));
    light.color = glm::vec3(1.0f, 0.9f, 0.8f);
    light.intensity = 2.0f;
    s.directionalLights.push_back(light);
    s.ambient = glm::vec3(0.01f, 0.02f, 0.03f);
    s.camera.position = eye;
    s.camera.target = target;
    s.camera.up = up;
    s.camera.fovYDegrees = 50.0f;
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 50.0f;
    return s;
}

// World point on y = 0 seen through the centre of pixel (x, y) (row 0 = top), or false.
bool planePoint(const Scene& s, int w, int h, int x, int y, glm::dvec3& hit) {
    glm::dmat4 inv = glm::inverse(glm::dmat4(s.camera.projection(float(w) / float(h))) * glm::dmat4(s.camera.view()));
    double nx = (x + 0.5) / w * 2.0 - 1.0, ny = 1.0 - (y + 0.5) / h * 2.0;
    glm::dvec4 a = inv * glm::dvec4(nx, ny, -1.0, 1.0), b = inv * glm::dvec4(nx, ny, 1.0, 1.0);
    glm::dvec3 p0 = glm::dvec3(a) / a.w, p1 = glm::dvec3(b) / b.w;
    glm::dvec3 d = p1 - p0;
    if (std::abs(d.y) < 1e-12) return false;
    double t = -p0.y / d.y;
    if (t <= 0.0 || t >= 1.0) return false;
    hit = p0 + t * d;
    return std::abs(hit.x) < 9.5 && std::abs(hit.z) < 9.5;
}

// The radiance under `brdf`: Blinn-Phong's kd / pi + Ks (n + 8) / (8 pi) (N.H)^n, or (GGX) glTF 2.0's
// BRDF of the MTL material as a dielectric of F0 = Ks (grey) and alpha = sqrt(2 / (n + 2))
// (engine/render/gltf_brdf.hpp), whose diffuse layer the ambient lights as kd (1 - F0). Ks 0 is
// Lambertian under both (lightpass's f90 = 0 there: "no specular").
glm::dvec3 expectedRadiance(const Scene& s, glm::dvec3 p, Brdf brdf) {
    const auto& mat = s.models[0].mesh.materials[0];
    const auto& light = s.directionalLights[0];
    glm::dvec3 N(0, 1, 0), L = -glm::dvec3(light.direction), V = glm::normalize(glm::dvec3(s.camera.position) - p);
    glm::dvec3 H = glm::normalize(L + V);
    double nl = std::max(glm::dot(N, L), 0.0), nh = std::max(glm::dot(N, H), 0.0), n = mat.shininess;
    // The G-buffer stores the diffuse albedo in 8-bit sRGB (kd, or kd (1 - F0) under GGX): the renderer
    // shades with the stored value (the test's albedos are chosen away from rounding ties).
    const double f0 = mat.specular.x, transmitted = brdf == Brdf::Ggx ? 1.0 - f0 : 1.0;
    const glm::dvec3 kd = test::srgb8Stored(glm::dvec3(mat.diffuse) * transmitted) / transmitted;
    glm::dvec3 f;
    if (brdf == Brdf::Ggx && f0 > 0.0) {
        const GltfBrdfMaterial m{kd, 0.0, std::sqrt(std::sqrt(2.0 / (n + 2.0))), gltfIorOfF0(f0)};
        f = gltfBrdf(m, N, V, L);
    } else {
        f = kd / M_PI + glm::dvec3(mat.specular) * ((n + 8.0) / (8.0 * M_PI)) * std::pow(nh, n);
    }
    return f * glm::dvec3(light.color) * double(light.intensity) * nl + glm::dvec3(s.ambient) * kd * transmitted;
}

// Whether every pixel within `radius` of (x, y) also sees the plane: at render scale < 1 the bilinear
// upsample blends up to 2 / scale output pixels, so the check stays that far from the plane's edge.
bool planeAround(const Scene& s, int w, int h, int x, int y, int radius) {
    glm::dvec3 p;
    for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx)
            if (!planePoint(s, w, h, x + dx, y + dy, p)) return false;
    return true;
}

void checkPlane(const Scene& s, float renderScale = 1.0f, Brdf brdf = RenderSettings{}.brdf) {
    for (GBufferMode mode : allGBufferModes()) {  // the analytic radiance holds for either G-buffer
        SCOPED_TRACE(std::string(gbufferModeName(mode)) + " G-buffer");
        const int w = 96, h = 64;
        Renderer r(s);
        RenderSettings settings;
        settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
        settings.autoExposure = false;       // and 0 EV
        settings.gbuffer.mode = mode;
        settings.width = w;
        settings.height = h;
        settings.keepHdr = true;
        settings.renderScale = renderScale;
        settings.brdf = brdf;
        settings.aa.dither = false;  // the display is checked against plain rounding (+-1 LSB)
        r.render(settings);
        EXPECT_EQ(r.graph().isLive("upscale"), renderScale < 1.0f);
        ImageF hdr = r.readHdr();
        Image8 ldr = r.readDisplay();
        ASSERT_EQ(hdr.width, w);  // the output size whatever the render scale
        ASSERT_EQ(ldr.height, h);
        const int margin = renderScale < 1.0f ? int(std::ceil(2.0f / renderScale)) : 0;
        int checked = 0;
        double worstHdr = 0.0, worstLdr = 0.0;
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                glm::dvec3 p;
                if (!planePoint(s, w, h, x, y, p)) continue;
                if (margin > 0 && !planeAround(s, w, h, x, y, margin)) continue;
                glm::dvec3 e = expectedRadiance(s, p, brdf);
                for (int c = 0; c < 3; ++c) {
                    double got = hdr.rgba[(size_t(y) * w + x) * 4 + c];
                    // fp16 storage: 2^-11 relative rounding; interpolated positions add ~1e-5.
                    double rel = std::abs(got - e[c]) / std::max(e[c], 1e-3);
                    worstHdr = std::max(worstHdr, rel);
                    double ldrExpected = srgbRef(tonemapRef(e[c])) * 255.0;
                    worstLdr = std::max(worstLdr, std::abs(ldr.rgba[(size_t(y) * w + x) * 4 + c] - ldrExpected));
                }
                ++checked;
            }
        }
        EXPECT_GT(checked, w * h / 4);
        EXPECT_LT(worstHdr, 2e-3) << "relative HDR error";
        EXPECT_LE(worstLdr, 1.0) << "display error in 1/255 steps";
    }
}

}  // namespace

TEST(RenderAnalytic, LambertPlaneMatchesBlinnPhongThroughToneMap) {
    checkPlane(planeScene({0, 6, 8}, {0, 0, 0}, {0, 1, 0}, {0.55f, 0.42f, 0.33f}, glm::vec3(0.0f), 1.0f));
}

// --brdf blinn-phong, the seeds' BRDF, stays as it was.
TEST(RenderAnalytic, GlossyPlaneMatchesBlinnPhongThroughToneMap) {
    checkPlane(planeScene({1, 4, 5}, {-1, 0, -1}, {0, 1, 0}, {0.21f, 0.33f, 0.62f}, glm::vec3(0.5f), 40.0f), 1.0f,
               Brdf::BlinnPhong);
}

// The default BRDF: the MTL's Kd, Ks and Ns shaded as glTF 2.0's dielectric of F0 = Ks.
TEST(RenderAnalytic, GlossyPlaneMatchesTheGltfBrdfThroughToneMap) {
    ASSERT_EQ(RenderSettings{}.brdf, Brdf::Ggx);
    checkPlane(planeScene({1, 4, 5}, {-1, 0, -1}, {0, 1, 0}, {0.21f, 0.33f, 0.62f}, glm::vec3(0.5f), 40.0f));
}

// --render-scale: a Lambertian plane under a sun has constant radiance, so the upsampled image must
// still match the analytic value everywhere the bilinear footprint stays on the plane.
TEST(RenderAnalytic, LambertPlaneMatchesAtRenderScales) {
    const Scene s = planeScene({0, 6, 8}, {0, 0, 0}, {0, 1, 0}, {0.55f, 0.42f, 0.33f}, glm::vec3(0.0f), 1.0f);
    for (float scale : {0.5f, 0.25f}) {
        SCOPED_TRACE(scale);
        checkPlane(s, scale);
    }
}

TEST(RenderAnalytic, NormalsViewEncodesPlaneNormal) {
    // Looking straight down: the plane's eye-space normal is +Z, encoded (0.5, 0.5, 1); at render
    // scale 0.25 too (the debug view is upsampled to the output size, nearest).
    Scene s = planeScene({0, 5, 0}, {0, 0, 0}, {0, 0, -1}, glm::vec3(0.5f), glm::vec3(0.0f), 1.0f);
    for (float scale : {1.0f, 0.25f}) {
        Renderer r(s);
        RenderSettings settings;
        settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
        settings.autoExposure = false;       // and 0 EV
        settings.width = 64;
        settings.height = 64;
        settings.view = DebugView::Normals;
        settings.renderScale = scale;
        r.render(settings);
        EXPECT_FALSE(r.graph().isLive("global_lights"));
        Image8 img = r.readDisplay();
        ASSERT_EQ(img.width, 64);
        ASSERT_EQ(img.rgba.size(), size_t(64 * 64 * 4));
        for (size_t i = 0; i < img.rgba.size(); i += 4) {
            EXPECT_NEAR(img.rgba[i + 0], 127.5, 0.5);
            EXPECT_NEAR(img.rgba[i + 1], 127.5, 0.5);
            EXPECT_EQ(img.rgba[i + 2], 255);
        }
    }
}

TEST(RenderAnalytic, DepthViewIsMonotoneWithDistance) {
    // A plane seen at a slant: along the centre column, farther points are higher in the image.
    Scene s = planeScene({0, 2, 8}, {0, 0, 0}, {0, 1, 0}, glm::vec3(0.5f), glm::vec3(0.0f), 1.0f);
    const int w = 64, h = 96;
    Renderer r(s);
    RenderSettings settings;
    settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    settings.autoExposure = false;       // and 0 EV
    settings.width = w;
    settings.height = h;
    settings.view = DebugView::Depth;
    r.render(settings);
    Image8 img = r.readDisplay();
    double prevDist = 1e30;
    int prevValue = 256, rows = 0;
    for (int y = 0; y < h; ++y) {
        glm::dvec3 p;
        if (!planePoint(s, w, h, w / 2, y, p)) continue;
        double dist = glm::length(p - glm::dvec3(s.camera.position));
        int value = img.rgba[(size_t(y) * w + w / 2) * 4];
        EXPECT_LT(dist, prevDist);         // rows go from far (top) to near (bottom)
        EXPECT_LE(value, prevValue) << y;  // so the depth view must not increase
        prevDist = dist;
        prevValue = value;
        ++rows;
    }
    EXPECT_GT(rows, h / 3);
    EXPECT_EQ(img.rgba[0], 255);  // the sky above the horizon is at the far plane
}

TEST(RenderAnalytic, HdrBufferHasNoNanOrInf) {
    // A light of irradiance 1e30 overflows fp16; the buffer must clamp, not store Inf/NaN.
    Scene s = planeScene({0, 6, 8}, {0, 0, 0}, {0, 1, 0}, glm::vec3(0.5f), glm::vec3(1.0f), 10000.0f);
    s.directionalLights[0].intensity = 1e30f;
    Renderer r(s);
    RenderSettings settings;
    settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    settings.autoExposure = false;       // and 0 EV
    settings.width = 48;
    settings.height = 32;
    settings.keepHdr = true;
    r.render(settings);
    ImageF hdr = r.readHdr();
    for (float v : hdr.rgba) ASSERT_TRUE(std::isfinite(v));
}

// ---- views of seed 003 and the HDR inspection views ---------------------------------------------

TEST(RenderAnalytic, WorldPositionAndEyeVectorViewsEncodeThePlane) {
    // Straight down onto the 20 m plane (bounds 20 x 0 x 20 around the origin): world position maps
    // x, z from [-10, 10] to [0, 1] and y = 0 to 0.5; the eye vector at the centre is +Y.
    Scene s = planeScene({0, 5, 0}, {0, 0, 0}, {0, 0, -1}, glm::vec3(0.5f), glm::vec3(0.0f), 1.0f);
    const int w = 64, h = 64;
    Renderer r(s);
    RenderSettings settings;
    settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    settings.autoExposure = false;       // and 0 EV
    settings.width = w;
    settings.height = h;
    settings.view = DebugView::WorldPosition;
    r.render(settings);
    EXPECT_FALSE(r.graph().isLive("global_lights"));
    Image8 img = r.readDisplay();
    for (int y : {4, 32, 60})
        for (int x : {4, 32, 60}) {
            glm::dvec3 p;
            ASSERT_TRUE(planePoint(s, w, h, x, y, p));
            const uint8_t* px = &img.rgba[(size_t(y) * w + x) * 4];
            EXPECT_NEAR(px[0], (p.x / 10.0 * 0.5 + 0.5) * 255.0, 1.5) << x << "," << y;
            EXPECT_NEAR(px[1], 127.5, 1.0);
            EXPECT_NEAR(px[2], (p.z / 10.0 * 0.5 + 0.5) * 255.0, 1.5) << x << "," << y;
        }
    settings.view = DebugView::EyeVector;
    r.render(settings);
    img = r.readDisplay();
    for (int y : {4, 32, 60})
        for (int x : {4, 32, 60}) {
            glm::dvec3 p;
            ASSERT_TRUE(planePoint(s, w, h, x, y, p));
            const glm::dvec3 v = glm::normalize(glm::dvec3(s.camera.position) - p);
            const uint8_t* px = &img.rgba[(size_t(y) * w + x) * 4];
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(px[c], (v[c] * 0.5 + 0.5) * 255.0, 1.5) << x << "," << y << " c" << c;
        }
}

TEST(RenderAnalytic, DepthFittedViewSpansTheScenesRange) {
    // Far plane 50, scene 20 m: the plain depth view uses a fraction of the grey ramp, the fitted one
    // runs from the scene's nearest to its farthest bound, so it uses more of it, still monotone.
    Scene s = planeScene({0, 2, 8}, {0, 0, 0}, {0, 1, 0}, glm::vec3(0.5f), glm::vec3(0.0f), 1.0f);
    const int w = 64, h = 96;
    Renderer r(s);
    RenderSettings settings;
    settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    settings.autoExposure = false;       // and 0 EV
    settings.width = w;
    settings.height = h;
    auto column = [&](DebugView view) {
        settings.view = view;
        r.render(settings);
        Image8 img = r.readDisplay();
        std::vector<int> values;
        for (int y = 0; y < h; ++y) {
            glm::dvec3 p;
            if (planePoint(s, w, h, w / 2, y, p)) values.push_back(img.rgba[(size_t(y) * w + w / 2) * 4]);
        }
        return values;
    };
    const std::vector<int> plain = column(DebugView::Depth), fitted = column(DebugView::DepthFitted);
    ASSERT_EQ(plain.size(), fitted.size());
    ASSERT_GT(fitted.size(), size_t(h / 3));
    for (size_t i = 1; i < fitted.size(); ++i) EXPECT_LE(fitted[i], fitted[i - 1]);  // near rows are darker
    const int plainSpan = plain.front() - plain.back(), fittedSpan = fitted.front() - fitted.back();
    EXPECT_GT(fittedSpan, 2 * plainSpan) << "plain " << plainSpan << ", fitted " << fittedSpan;
    // The range itself: the bounds' corners seen from the camera, inside near..far.
    const FrameData frame = makeFrameData(s, settings, 0.0f);
    const glm::vec2 range = sceneDepthRange(frame);
    EXPECT_GE(range.x, frame.nearPlane);
    EXPECT_LE(range.y, frame.farPlane);
    EXPECT_NEAR(range.y, 8.0f + 10.0f * 8.0f / std::sqrt(68.0f) + 2.0f * 2.0f / std::sqrt(68.0f), 0.6f);
}

// A NaN and an Inf injected into the HDR buffer by a test pass are painted by the invalid-pixels view;
// the rest of the image is dimmed grey.
TEST(RenderAnalytic, InvalidPixelsViewPaintsInjectedNanAndInf) {
    Scene s = planeScene({0, 5, 0}, {0, 0, 0}, {0, 0, -1}, glm::vec3(0.5f), glm::vec3(0.0f), 1.0f);
    RenderSettings settings;
    settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    settings.autoExposure = false;       // and 0 EV
    settings.width = 16;
    settings.height = 8;
    settings.view = DebugView::InvalidPixels;
    FrameData frame = makeFrameData(s, settings, 0.0f);
    gl::ShaderLibrary shaders;
    frame.shaders = &shaders;
    fg::FrameGraph graph;
    fg::TexturePool pool;
    HdrViewPass state;
    const fg::ResourceId hdr = graph.addPass<fg::ResourceId>(
        "inject", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, fg::ResourceId& out) { out = b.create("hdr", {16, 8, GL_RGBA16F}, fg::Usage::Transfer); },
        [](const fg::ResourceId& out, const fg::PassResources& res) {
            const float grey[4] = {0.5f, 0.5f, 0.5f, 1.0f};
            const float nan[4] = {std::nanf(""), 0.0f, 0.0f, 1.0f};
            const float inf[4] = {0.0f, std::numeric_limits<float>::infinity(), 0.0f, 1.0f};
            glClearTexImage(res.texture(out), 0, GL_RGBA, GL_FLOAT, grey);
            glClearTexSubImage(res.texture(out), 0, 3, 2, 0, 1, 1, 1, GL_RGBA, GL_FLOAT, nan);
            glClearTexSubImage(res.texture(out), 0, 10, 5, 0, 1, 1, 1, GL_RGBA, GL_FLOAT, inf);
        });
    const fg::ResourceId view = addHdrViewPass(graph, state, frame, hdr, {}, DebugView::InvalidPixels);
    graph.markOutput(view);
    graph.compile();
    graph.execute(pool);
    std::vector<uint8_t> px(16 * 8 * 4);
    glGetTextureImage(graph.outputTexture(view), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(px.size()), px.data());
    auto at = [&](int x, int y) { return glm::ivec3(px[(y * 16 + x) * 4], px[(y * 16 + x) * 4 + 1], px[(y * 16 + x) * 4 + 2]); };
    EXPECT_EQ(at(3, 2), glm::ivec3(255, 0, 255));   // NaN: magenta
    EXPECT_EQ(at(10, 5), glm::ivec3(0, 255, 255));  // Inf: cyan
    const glm::ivec3 valid = at(0, 0);
    EXPECT_EQ(valid.x, valid.y);
    EXPECT_EQ(valid.y, valid.z);
    EXPECT_GT(valid.x, 0);
    EXPECT_LT(valid.x, 110);  // dimmed to 40%
}

TEST(RenderAnalytic, ExposureEvViewOfALitPlaneIsOneBand) {
    // A Lambert plane lit head-on has one radiance; the view shows its EV band everywhere on it.
    Scene s = planeScene({0, 5, 0}, {0, 0, 0}, {0, 0, -1}, glm::vec3(0.5f), glm::vec3(0.0f), 1.0f);
    s.directionalLights[0].direction = glm::vec3(0.0f, -1.0f, 0.0f);
    s.directionalLights[0].color = glm::vec3(1.0f);
    s.directionalLights[0].intensity = float(0.18 * 8.0 * M_PI / 0.5);  // radiance 0.18 x 8: +3 EV
    s.ambient = glm::vec3(0.0f);
    Renderer r(s);
    RenderSettings settings;
    settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    settings.autoExposure = false;       // and 0 EV
    settings.width = 32;
    settings.height = 32;
    settings.shadows.enabled = false;
    settings.view = DebugView::ExposureEv;
    r.render(settings);
    EXPECT_TRUE(r.graph().isLive("hdr_view"));
    EXPECT_FALSE(r.graph().isLive("tonemap"));
    Image8 img = r.readDisplay();
    for (size_t i = 0; i < img.rgba.size(); i += 4) {  // +3: orange (1, 0.55, 0)
        EXPECT_EQ(img.rgba[i], 255);
        EXPECT_NEAR(img.rgba[i + 1], 0.55 * 255, 1.0);
        EXPECT_EQ(img.rgba[i + 2], 0);
    }
}

TEST(RenderAnalytic, TangentViewEncodesThePlanesTangent) {
    // The plane's tangent (along +u), through the view into eye space, encoded t x 0.5 + 0.5.
    Scene s = planeScene({0, 5, 0}, {0, 0, 0}, {0, 0, -1}, glm::vec3(0.5f), glm::vec3(0.0f), 1.0f);
    const glm::vec3 worldTangent = glm::normalize(glm::mat3(s.models[0].transform) * glm::vec3(s.models[0].mesh.vertices[0].tangent));
    const glm::vec3 eye = glm::normalize(glm::mat3(s.camera.view()) * worldTangent);
    Renderer r(s);
    RenderSettings settings;
    settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    settings.autoExposure = false;       // and 0 EV
    settings.width = 32;
    settings.height = 32;
    settings.view = DebugView::Tangent;
    r.render(settings);
    bool tangentTarget = false;
    for (const auto& res : r.graph().resources()) tangentTarget = tangentTarget || (res.name == "gbuffer.tangent" && res.live);
    EXPECT_TRUE(tangentTarget);
    Image8 img = r.readDisplay();
    for (size_t i = 0; i < img.rgba.size(); i += 4)
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(img.rgba[i + size_t(c)], (eye[c] * 0.5 + 0.5) * 255.0, 1.5) << c;
    // Any other view leaves the tangent target out.
    settings.view = DebugView::Normals;
    r.render(settings);
    for (const auto& res : r.graph().resources()) EXPECT_FALSE(res.name == "gbuffer.tangent" && res.live);
}

// A flat-lit material (seed 003) shows its diffuse colour whatever lights the scene: suns, ambient,
// local lights in every method, IBL. The same plane not flat is lit.
TEST(RenderAnalytic, FlatLitMaterialIsItsColourUnderEveryLight) {
    Scene s = planeScene({0, 5, 0}, {0, 0, 0}, {0, 0, -1}, glm::vec3(0.3f, 0.5f, 0.7f), glm::vec3(0.2f), 32.0f);
    PointLight point;
    point.position = glm::vec3(0.0f, 1.0f, 0.0f);
    point.range = 6.0f;
    point.intensity = 5.0f;
    s.pointLights.push_back(point);
    s.environment.map = test::repoPath("hdr/sky.exr");
    s.environment.ibl = true;
    for (bool flat : {true, false})
        for (LocalLightMethod method : {LocalLightMethod::Tiled, LocalLightMethod::Volumes}) {
            for (auto& m : s.models[0].mesh.materials) m.flat = flat;
            Renderer r(s);
            RenderSettings settings;
            settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
            settings.autoExposure = false;       // and 0 EV
            settings.width = 24;
            settings.height = 24;
            settings.keepHdr = true;
            settings.localLights.method = method;
            settings.environment = test::smallIblBake(16);
            r.render(settings);
            ASSERT_TRUE(r.graph().isLive("local_lights"));
            ASSERT_TRUE(r.graph().isLive("ibl"));
            const ImageF hdr = r.readHdr();
            double worst = 0.0, worstCodes = 0.0;
            for (size_t i = 0; i < hdr.rgba.size(); i += 4)
                for (int c = 0; c < 3; ++c) {
                    const double got = hdr.rgba[i + size_t(c)], want = glm::dvec3(0.3, 0.5, 0.7)[c];
                    worst = std::max(worst, std::abs(got - want));
                    worstCodes = std::max(worstCodes, 255.0 * std::abs(test::srgbEncode(got) - test::srgbEncode(want)));
                }
            // The colour through the 8-bit sRGB diffuse target (one code: drivers may round x.5
            // either way), then fp16 (half an ulp at 0.7: 0.04 of a code there).
            if (flat) EXPECT_LE(worstCodes, 1.05) << localLightMethodName(method);
            else EXPECT_GT(worst, 0.05) << localLightMethodName(method);       // lit: not its colour
        }
}
