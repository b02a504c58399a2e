// Attenuation and point-light shading on the GL driver against double-precision
// references; the four local-light methods against each other and an analytic plane; counters;
// NaN/Inf safety. Small images (64x48) keep llvmpipe fast.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/log.hpp"
#include "engine/gl/shader.hpp"
#include "engine/graph/texture_pool.hpp"
#include "frame/frame_builder.hpp"
#include "engine/render/light_clusters.hpp"
#include "engine/render/local_lights.hpp"
#include "engine/render/scene_gpu.hpp"
#include "engine/scene/primitives.hpp"
#include "tests/gl/gl_fixture.hpp"
#include "tests/gl/render_fixture.hpp"

using namespace lp;
using lp::test::runGlsl;

namespace {

double windowRef(double d, double range) {
    double x = d / range;
    double w = std::clamp(1.0 - x * x * x * x, 0.0, 1.0);
    return w * w;
}
double attenuationRef(double d, double range) {
    double dMin = std::min(0.01 * range, 0.01);  // held at 1% of the range, capped at 1 cm
    return windowRef(d, range) / std::max(d * d, dMin * dMin);
}

// ---- attenuation.glsl --------------------------------------------------------------------------

TEST(LocalLightShader, AttenuationMatchesDoubleReference) {
    std::vector<glm::vec4> in;
    for (float range : {0.05f, 1.0f, 30.0f})
        for (int i = 0; i <= 300; ++i) in.push_back({float(i) / 200.0f * range, range, 0, 0});  // d in [0, 1.5 R]
    auto out = runGlsl({"common/attenuation.glsl"},
                       "return vec4(lpPointAttenuation(x.x, x.y), lpRangeWindow(x.x, x.y), lpInverseSquare(x.x, x.y), 0.0);",
                       in);
    for (size_t i = 0; i < in.size(); ++i) {
        const double d = in[i].x, r = in[i].y;
        ASSERT_TRUE(std::isfinite(out[i].x)) << d << " " << r;
        // Bound: float32 evaluation, 1e-5 relative (plus 1e-7 of the d = 0 value where the window
        // cancels towards 0 near the range).
        const double e = attenuationRef(d, r);
        EXPECT_NEAR(out[i].x, e, 1e-5 * e + 1e-7 * attenuationRef(0.0, r)) << "d " << d << " range " << r;
        EXPECT_NEAR(out[i].y, windowRef(d, r), 1e-6) << "d " << d << " range " << r;
        if (d >= r) EXPECT_EQ(out[i].x, 0.0f) << "exactly zero at and past the range: d " << d << " range " << r;
    }
}

TEST(LocalLightShader, FiniteAtZeroDistanceAndZeroAtRange) {
    std::vector<glm::vec4> in = {{0.0f, 1.0f, 0, 0}, {0.0f, 1e-3f, 0, 0}, {1.0f, 1.0f, 0, 0}, {2.5f, 2.5f, 0, 0},
                                 {1e6f, 1.0f, 0, 0}};
    auto out = runGlsl({"common/attenuation.glsl"}, "return vec4(lpPointAttenuation(x.x, x.y));", in);
    // d = 0: the inverse square is held at d = min(0.01 R, 1 cm), so E/I = 1 / (0.01 R)^2 exactly for
    // R <= 1 (float rounding 1e-6).
    EXPECT_NEAR(out[0].x, 1e4, 1e4 * 1e-6);
    EXPECT_NEAR(out[1].x, 1e10, 1e10 * 1e-6);
    EXPECT_EQ(out[2].x, 0.0f);  // d = range
    EXPECT_EQ(out[3].x, 0.0f);
    EXPECT_EQ(out[4].x, 0.0f);  // d >> range
}

TEST(LocalLightShader, WindowValueAndSlopeVanishAtTheRange) {
    // window(1 - h) = (1 - (1 - h)^4)^2 <= (4h)^2 = 16 h^2: value O(h^2), so the one-sided slope
    // (window(1 - h) - window(1)) / h <= 16 h -> 0 (C1 at the range edge). Checked for h down to 1e-3
    // with 1e-4 relative float slack; past the range both are exactly 0.
    std::vector<glm::vec4> in;
    const float hs[] = {0.1f, 0.03f, 0.01f, 0.003f, 0.001f};
    for (float h : hs) in.push_back({1.0f - h, 1.0f, 1.0f + h, 0});
    auto out = runGlsl({"common/attenuation.glsl"},
                       "return vec4(lpRangeWindow(x.x, x.y), lpRangeWindow(x.z, x.y), lpRangeWindow(x.y, x.y), 0.0);", in);
    for (size_t i = 0; i < in.size(); ++i) {
        const double h = hs[i];
        EXPECT_LE(out[i].x, 16.0 * h * h * (1.0 + 1e-4) + 1e-9) << "value at 1 - " << h;
        EXPECT_LE(out[i].x / h, 16.0 * h * (1.0 + 1e-4) + 1e-6) << "slope at 1 - " << h;
        EXPECT_GE(out[i].x, 0.0f);
        EXPECT_EQ(out[i].y, 0.0f) << "past the range";
        EXPECT_EQ(out[i].z, 0.0f) << "at the range";
    }
}

TEST(LocalLightShader, LightOnTheSurfaceIsFiniteAndLitAlongTheNormal) {
    // P = light position: L falls back to N, E = I / dMin^2 with dMin = min(0.01 R, 1 cm) = 1 cm at R = 2.
    // The default BRDF (GGX; uBrdf unset) at N = V = L: diffuse kd / pi (V.H = 1: 1 - F's shape is 1),
    // specular D Vis F = 1 / (pi alpha^2) x 1 / 4 (height-correlated, N.V = N.L = 1) x F0, alpha of n = 16
    // = sqrt(2 / 18).
    std::vector<glm::vec4> in = {{0.0f, 0.0f, 0.0f, 2.0f}};
    auto out = runGlsl({"common/local_light.glsl"},
                       "vec3 c = lpLocalLightRadiance(x.xyz, x.w, vec3(1.0), x.xyz, vec3(0, 0, 1), vec3(0, 0, 1),"
                       " vec3(0.5), vec3(0.25), 16.0, LP_LOCAL_SPECULAR_RANGED); return vec4(c, 0.0);",
                       in);
    const double e = 1.0 / (0.01 * 0.01), a2 = 2.0 / 18.0;
    const double expected = (0.5 / M_PI + 1.0 / (M_PI * a2) * 0.25 * 0.25) * e;
    EXPECT_TRUE(std::isfinite(out[0].x));
    EXPECT_NEAR(out[0].x, expected, expected * 1e-5);  // float32: 1e-5 relative
}

// ---- spot cone falloff (local_light.glsl) -------------------------------------------------------

double smoothstepRef(double e0, double e1, double x) {
    const double t = std::clamp((x - e0) / std::max(e1 - e0, 1e-6), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

TEST(LocalLightShader, SpotFalloffIsSmoothstepBetweenTheConeCosines) {
    std::vector<glm::vec4> in;
    const std::pair<float, float> cones[] = {{10.0f, 30.0f}, {0.0f, 45.0f}, {25.0f, 25.0f}, {60.0f, 89.0f}};
    for (auto [inner, outer] : cones)
        for (int i = 0; i <= 200; ++i) {
            const float angle = float(i) / 200.0f * 120.0f;  // 0..120 degrees off the axis
            in.push_back({std::cos(glm::radians(angle)), std::cos(glm::radians(outer)), std::cos(glm::radians(inner)), 0});
        }
    // The point-light encoding: no falloff at any angle.
    for (int i = 0; i <= 20; ++i) in.push_back({std::cos(float(M_PI) * float(i) / 20.0f), -2.0f, -1.5f, 0});
    auto out = runGlsl({"common/local_light.glsl"}, "return vec4(lpSpotFalloff(x.x, x.y, x.z));", in);
    for (size_t i = 0; i < in.size(); ++i) {
        const double c = in[i].x, co = in[i].y, ci = in[i].z;
        const double expected = co < -1.0 ? 1.0 : smoothstepRef(co, ci, c);
        EXPECT_NEAR(out[i].x, expected, 2e-5) << "cos " << c << " outer " << co << " inner " << ci;
        if (c <= co) EXPECT_EQ(out[i].x, 0.0f) << "outside the outer cone: exactly 0";
        if (c >= ci) EXPECT_EQ(out[i].x, 1.0f) << "inside the inner cone: exactly 1";
    }
}

// ---- the four methods ---------------------------------------------------------------------------

// Everything one test needs to render frames and look at the local-light pass's state.
struct Rig {
    explicit Rig(const Scene& s) : scene(s), gpu(std::make_unique<SceneGpu>(scene)) {}
    const Scene& scene;
    std::unique_ptr<SceneGpu> gpu;
    gl::ShaderLibrary shaders;
    PassStates passes;
    fg::TexturePool pool;

    std::vector<float> renderHdr(RenderSettings settings, float time = 0.0f) {
        settings.keepHdr = true;
        FrameData frame = makeFrameData(scene, settings, time);
        frame.gpu = gpu.get();
        frame.shaders = &shaders;
        fg::FrameGraph graph;
        FrameOutputs out = buildFrameGraph(graph, passes, frame);
        graph.compile();
        graph.execute(pool);
        std::vector<float> px(size_t(settings.width) * settings.height * 4);
        glGetTextureImage(graph.outputTexture(out.hdr), 0, GL_RGBA, GL_FLOAT, GLsizei(px.size() * sizeof(float)),
                          px.data());
        gl::checkErrors("local-light test frame");
        return px;
    }
};

ModelInstance model(const std::string& primitive, MeshData mesh, glm::mat4 transform, glm::vec3 kd, glm::vec3 ks,
                    float n) {
    ModelInstance m;
    m.name = primitive;
    m.primitive = primitive;
    m.mesh = std::move(mesh);
    for (auto& mat : m.mesh.materials) {
        mat.diffuse = kd;
        mat.specular = ks;
        mat.shininess = n;
    }
    m.transform = transform;
    return m;
}

// A floor, a cube and a sphere under one sun and 20 point lights; light 0 holds the camera, light 1
// crosses the near plane with the camera outside it, the rest sit on a grid above the floor.
Scene twentyLightScene() {
    Scene s;
    s.models.push_back(model("plane", makePlane(1.0f, 4), glm::scale(glm::mat4(1.0f), glm::vec3(8.0f)),
                             {0.6f, 0.6f, 0.6f}, {0.4f, 0.4f, 0.4f}, 32.0f));
    s.models.push_back(model("cube", makeCube(1.0f), glm::translate(glm::mat4(1.0f), {-0.8f, 0.5f, -0.5f}),
                             {0.2f, 0.5f, 0.8f}, {0.2f, 0.2f, 0.2f}, 8.0f));
    s.models.push_back(model("sphere", makeSphere(0.5f, 24, 12), glm::translate(glm::mat4(1.0f), {1.0f, 0.5f, -0.8f}),
                             {0.8f, 0.3f, 0.2f}, {0.6f, 0.6f, 0.6f}, 128.0f));
    s.camera.position = {0.0f, 1.2f, 3.0f};
    s.camera.target = {0.0f, 0.3f, 0.0f};
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 30.0f;
    s.camera.fovYDegrees = 60.0f;
    DirectionalLight sun;
    sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.4f));
    sun.intensity = 0.5f;
    sun.castsShadows = false;
    s.directionalLights.push_back(sun);
    s.ambient = glm::vec3(0.01f);
    const glm::mat4 toWorld = glm::inverse(s.camera.view());
    PointLight inside;  // the camera is 0.5 m from its centre, range 1.5
    inside.position = glm::vec3(toWorld * glm::vec4(0.3f, -0.4f, -0.1f, 1.0f));
    inside.range = 1.5f;
    inside.intensity = 0.3f;
    inside.color = {1.0f, 0.9f, 0.7f};
    s.pointLights.push_back(inside);
    PointLight nearCrossing;  // |centre| = 1.37 m > range 1.3 m, but it reaches past the near plane
    nearCrossing.position = glm::vec3(toWorld * glm::vec4(1.2f, -0.6f, -0.3f, 1.0f));
    nearCrossing.range = 1.3f;
    nearCrossing.intensity = 0.4f;
    nearCrossing.color = {0.3f, 1.0f, 0.4f};
    s.pointLights.push_back(nearCrossing);
    for (int i = 0; i < 18; ++i) {
        PointLight l;
        l.position = {-2.5f + float(i % 6), 0.25f + 0.1f * float(i % 3), -2.5f + 1.2f * float(i / 6)};
        l.range = 0.8f + 0.1f * float(i % 4);
        l.intensity = 0.05f + 0.02f * float(i % 5);
        l.color = {0.4f + 0.1f * float(i % 7), 0.5f, 1.0f - 0.1f * float(i % 6)};
        s.pointLights.push_back(l);
    }
    return s;
}

// A 64 x 48 frame with `method`. The clustered method runs its own kernel at any light count
// (--clustered-kernel froxels; by default it leaves fewer than 32 lights to the tiled kernel and races
// the two from 32): these tests are about it. ClusteredLights.FewLightsShadeWithTheTiledKernel and
// AutoRacesBothKernelsAndKeepsTheFaster test the default.
RenderSettings smallSettings(LocalLightMethod method) {
    RenderSettings r;
    r.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    r.autoExposure = false;       // and 0 EV
    r.width = 64;
    r.height = 48;
    r.localLights.method = method;
    r.localLights.clusteredKernel = ClusteredKernel::Froxels;
    return r;
}

// The camera at the origin looking down -Z (60 degrees high) between `nearPlane` and `farPlane`, and
// no ambient light: the depth scenes of the clustered tests.
void lookDownMinusZ(Scene& s, float nearPlane, float farPlane) {
    s.camera.position = {0.0f, 0.0f, 0.0f};
    s.camera.target = {0.0f, 0.0f, -1.0f};
    s.camera.nearPlane = nearPlane;
    s.camera.farPlane = farPlane;
    s.camera.fovYDegrees = 60.0f;
    s.ambient = glm::vec3(0.0f);
}

// The bound between two methods' HDR values where `lights` lights reach the texel: one fp16 rounding
// per light added (2^-11 relative each) and 1e-3 relative (+ 1e-6) for the float sums' order.
double tiledBound(int lights, double value) {
    return ((lights + 1) * std::ldexp(1.0, -11) + 1e-3) * std::abs(value) + 1e-6;
}

// Lights whose scissor rectangle holds pixel (x, y) (row 0 = bottom): an upper bound on the number of
// lights that add to that pixel, hence on the number of fp16 roundings in a blended sum.
std::vector<int> lightsPerPixel(const Scene& s, const RenderSettings& settings) {
    FrameData f = makeFrameData(s, settings, 0.0f);
    std::vector<int> n(size_t(settings.width) * settings.height, 0);
    for (const auto& l : localLightsForFrame(s, settings.localLights, 0.0f)) {
        const BoundingSphere b = localLightBounds(l);
        glm::vec3 eye = glm::vec3(f.view * glm::vec4(b.center, 1.0f));
        ScissorRect r = sphereScissorRect(eye, b.radius, f.projection, f.nearPlane, settings.width, settings.height);
        for (int y = r.y; y < r.y + r.height; ++y)
            for (int x = r.x; x < r.x + r.width; ++x) ++n[size_t(y) * settings.width + x];
    }
    return n;
}

TEST(LocalLights, TestSceneHasCameraInsideAndNearPlaneCases) {
    Scene s = twentyLightScene();
    FrameData f = makeFrameData(s, smallSettings(LocalLightMethod::Scissor), 0.0f);
    glm::vec3 c0 = glm::vec3(f.view * glm::vec4(s.pointLights[0].position, 1.0f));
    glm::vec3 c1 = glm::vec3(f.view * glm::vec4(s.pointLights[1].position, 1.0f));
    EXPECT_LT(glm::length(c0), s.pointLights[0].range);
    EXPECT_GT(glm::length(c1), s.pointLights[1].range);
    EXPECT_GT(c1.z + s.pointLights[1].range, -f.nearPlane);
    EXPECT_TRUE(sphereScissorRect(c0, s.pointLights[0].range, f.projection, f.nearPlane, 64, 48).fullScreen);
    EXPECT_TRUE(sphereScissorRect(c1, s.pointLights[1].range, f.projection, f.nearPlane, 64, 48).fullScreen);
    EXPECT_EQ(s.pointLights.size(), 20u);
}

// The same image from all four methods, for each specular mode.
//   scissor and volumes vs fullscreen: bit-identical (each pixel gets the same lights added in the
//   same order; pixels a rectangle or volume leaves out would have received exactly +0).
//   tiled and clustered vs fullscreen: the sum is float32 with one fp16 store, the blended sum rounds to fp16
//   after each of the k lights reaching the pixel: |a - b| <= ((k + 1) 2^-11 + 1e-3) |b| + 1e-6.
TEST(LocalLights, FourMethodsGiveTheSameImage) {
    Scene s = twentyLightScene();
    Rig rig(s);
    RenderSettings off = smallSettings(LocalLightMethod::Fullscreen);
    off.localLights.enabled = false;
    const std::vector<float> unlit = rig.renderHdr(off);
    struct Mode {
        bool specular, outside;
    };
    for (Mode mode : {Mode{true, false}, Mode{false, false}, Mode{true, true}}) {
        SCOPED_TRACE(std::string("specular ") + (mode.specular ? "on" : "off") + (mode.outside ? ", outside range" : ""));
        auto settingsFor = [&](LocalLightMethod m) {
            RenderSettings r = smallSettings(m);
            r.localLights.specular = mode.specular;
            r.localLights.specularOutsideRange = mode.outside;
            return r;
        };
        const std::vector<float> ref = rig.renderHdr(settingsFor(LocalLightMethod::Fullscreen));
        EXPECT_EQ(rig.passes.localLights.stats.drawn, 20);
        // The lights matter (the comparison is not vacuous): over an eighth of the pixels change by > 1%.
        int changed = 0;
        for (size_t i = 0; i < ref.size(); i += 4)
            if (ref[i + 1] > 1.01f * unlit[i + 1] + 1e-4f) ++changed;
        EXPECT_GT(changed, 64 * 48 / 8);
        // Unbounded specular reaches every pixel: count every light there.
        std::vector<int> k = lightsPerPixel(s, settingsFor(LocalLightMethod::Scissor));
        for (LocalLightMethod m : {LocalLightMethod::Scissor, LocalLightMethod::Volumes, LocalLightMethod::Tiled,
                                   LocalLightMethod::Clustered}) {
            const bool compute = m == LocalLightMethod::Tiled || m == LocalLightMethod::Clustered;
            const std::vector<float> got = rig.renderHdr(settingsFor(m));
            double worst = 0.0;
            for (size_t i = 0; i < got.size(); ++i) {
                ASSERT_TRUE(std::isfinite(got[i]));
                const double diff = std::abs(double(got[i]) - double(ref[i]));
                if (!compute) {
                    EXPECT_EQ(got[i], ref[i]) << localLightMethodName(m) << " texel " << i / 4;
                    continue;
                }
                const int lights = mode.outside ? 20 : k[i / 4];
                const double bound = tiledBound(lights, ref[i]);
                EXPECT_LE(diff, bound) << localLightMethodName(m) << " texel " << i / 4 << " channel " << i % 4;
                worst = std::max(worst, diff / (std::abs(ref[i]) + 1e-6));
            }
            if (compute) RecordProperty(std::string(localLightMethodName(m)) + "_worst_relative", std::to_string(worst));
        }
    }
}

// The compute methods give the same bits on every run: each sums its lights in index order, so no
// scheduling of the invocations that test the lights can reorder the sum (tiled appended them with an
// atomic counter before, whose order a GPU's scheduling decides: this test catches that only where
// the scheduling varies, as on a GPU). 1000 lights: several batches of 256, many lights per tile.
TEST(LocalLights, ComputeMethodsGiveTheSameBitsOnEveryRun) {
    Scene s = twentyLightScene();
    Rig rig(s);
    for (LocalLightMethod m : {LocalLightMethod::Tiled, LocalLightMethod::Clustered}) {
        RenderSettings r = smallSettings(m);
        r.localLights.lightCount = 1000;
        const std::vector<float> first = rig.renderHdr(r);
        for (int run = 1; run < 4; ++run) {
            const std::vector<float> again = rig.renderHdr(r);
            ASSERT_EQ(again.size(), first.size());
            int differing = 0;
            for (size_t i = 0; i < first.size(); ++i) differing += again[i] != first[i] ? 1 : 0;
            EXPECT_EQ(differing, 0) << localLightMethodName(m) << " run " << run;
        }
    }
}

// Each method shades exactly the lights asked for (counter in LocalLightPass::stats), also for a
// generated set of 1000 (--light-count).
TEST(LocalLights, EachMethodDrawsTheRequestedLightCount) {
    Scene s = twentyLightScene();
    Rig rig(s);
    for (int count : {-1, 7, 1000}) {
        const int expected = count < 0 ? 20 : count;
        for (LocalLightMethod m : allLocalLightMethods()) {
            RenderSettings r = smallSettings(m);
            r.localLights.lightCount = count;
            rig.renderHdr(r);
            const LocalLightStats& st = rig.passes.localLights.stats;
            EXPECT_EQ(st.requested, expected) << localLightMethodName(m);
            if (m == LocalLightMethod::Scissor) {
                EXPECT_EQ(st.drawn + st.offscreen, expected);
                if (count == -1) {
                    EXPECT_EQ(st.offscreen, 0);  // all 20 are on screen
                    EXPECT_EQ(st.fullScreen, 2);  // the camera-inside and near-plane lights
                }
            } else {
                EXPECT_EQ(st.drawn, expected) << localLightMethodName(m);
            }
        }
    }
}

// One light above a matte plane, no other light: every method matches the analytic radiance
// kd/pi * I/d^2 * window * N.L within fp16 storage (2^-11) and float shading: 2e-3 relative.
TEST(LocalLights, SingleLightOverPlaneMatchesAnalyticRadiance) {
    Scene s;
    const glm::vec3 kd(0.6f, 0.4f, 0.2f);
    s.models.push_back(model("plane", makePlane(1.0f, 4), glm::scale(glm::mat4(1.0f), glm::vec3(8.0f)), kd,
                             glm::vec3(0.0f), 1.0f));
    s.camera.position = {0.0f, 3.0f, 0.01f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 10.0f;
    s.ambient = glm::vec3(0.0f);
    PointLight l;
    l.position = {0.3f, 0.4f, -0.2f};
    l.range = 1.5f;
    l.intensity = 0.7f;
    l.color = {1.0f, 0.8f, 0.5f};
    s.pointLights.push_back(l);
    Rig rig(s);
    const int w = 64, h = 48;
    const glm::dmat4 inv = glm::inverse(glm::dmat4(s.camera.projection(float(w) / float(h))) * glm::dmat4(s.camera.view()));
    const glm::dvec3 kd8 = test::srgb8Stored(glm::dvec3(kd));  // the G-buffer stores 8-bit sRGB albedo
    for (LocalLightMethod m : allLocalLightMethods()) {
        std::vector<float> img = rig.renderHdr(smallSettings(m));
        int lit = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                double nx = (x + 0.5) / w * 2.0 - 1.0, ny = (y + 0.5) / h * 2.0 - 1.0;  // row 0 = bottom
                glm::dvec4 a = inv * glm::dvec4(nx, ny, -1.0, 1.0), b = inv * glm::dvec4(nx, ny, 1.0, 1.0);
                glm::dvec3 p0 = glm::dvec3(a) / a.w, p1 = glm::dvec3(b) / b.w;
                glm::dvec3 p = p0 + (-p0.y / (p1.y - p0.y)) * (p1 - p0);
                glm::dvec3 toLight = glm::dvec3(l.position) - p;
                double d = glm::length(toLight);
                double e = double(l.intensity) * attenuationRef(d, l.range) * std::max(toLight.y / d, 0.0);
                for (int c = 0; c < 3; ++c) {
                    double expected = kd8[c] / M_PI * double(l.color[c]) * e;
                    double got = img[(size_t(y) * w + x) * 4 + c];
                    EXPECT_NEAR(got, expected, 2e-3 * expected + 1e-6)
                        << localLightMethodName(m) << " pixel " << x << "," << y << " channel " << c;
                }
                if (e > 0.0) ++lit;
            }
        EXPECT_GT(lit, 100) << "the light reaches a good part of the image";
    }
}

// A very bright light lying exactly on the floor: no NaN or Inf in the HDR buffer, and the pixels
// around it are bright (the clamp of d^2 at (0.01 R)^2 keeps them finite, not zero).
TEST(LocalLights, LightOnTheSurfaceLeavesNoNanOrInf) {
    Scene s = twentyLightScene();
    s.pointLights.resize(2);
    s.pointLights[1].position = {0.0f, 0.0f, 0.0f};  // on the plane y = 0, in view
    s.pointLights[1].intensity = 1e6f;
    s.pointLights[1].range = 2.0f;
    Rig rig(s);
    for (LocalLightMethod m : allLocalLightMethods()) {
        std::vector<float> img = rig.renderHdr(smallSettings(m));
        float brightest = 0.0f;
        for (float v : img) {
            ASSERT_TRUE(std::isfinite(v)) << localLightMethodName(m);
            ASSERT_GE(v, 0.0f) << localLightMethodName(m);
            brightest = std::max(brightest, v);
        }
        EXPECT_GE(brightest, 1000.0f) << localLightMethodName(m);
        EXPECT_LE(brightest, 65504.0f) << "largest half float";
    }
}

// Globes and the two overlay views render without GL errors and leave the buffer finite; the
// lights-per-tile view changes the picture (it is a heat map over it).
TEST(LocalLights, GlobesAndOverlayViewsRender) {
    Scene s = twentyLightScene();
    Rig rig(s);
    RenderSettings base = smallSettings(LocalLightMethod::Tiled);
    const std::vector<float> plain = rig.renderHdr(base);
    for (DebugView v : {DebugView::Final, DebugView::LightRanges, DebugView::LightsPerTile, DebugView::LightsPerCluster})
        for (LocalLightMethod m : {LocalLightMethod::Volumes, LocalLightMethod::Tiled, LocalLightMethod::Clustered}) {
            RenderSettings r = base;
            r.view = v;
            r.localLights.method = m;
            r.localLights.globes = v == DebugView::Final;
            std::vector<float> img = rig.renderHdr(r);
            size_t differ = 0;
            for (size_t i = 0; i < img.size(); ++i) {
                ASSERT_TRUE(std::isfinite(img[i])) << viewName(v);
                if (img[i] != plain[i]) ++differ;
            }
            EXPECT_GT(differ, 0u) << viewName(v) << " " << localLightMethodName(m);
        }
}

// The tiled and clustered passes' candidates from light_cluster_supertiles.comp change no bit of the
// image: a supertile only drops lights that cannot touch its tiles, and each pixel still adds its
// lights in index order. Twenty lights with the level forced on (2 x 2 and 1 x 1 tiles, and every
// list overflowing) against it off; 600 lights (the level on by default) against it off; with
// unbounded specular the level stays off. A second frame's lists are its own.
TEST(LocalLights, SupertileCandidatesChangeNoBit) {
    const Scene twenty = twentyLightScene();
    for (LocalLightMethod m : {LocalLightMethod::Tiled, LocalLightMethod::Clustered}) {
        SCOPED_TRACE(localLightMethodName(m));
        auto render = [&](const Scene& s, RenderSettings r, int tiles, int capacity) {
            Rig rig(s);
            rig.passes.localLights.supertileTiles = tiles;
            rig.passes.localLights.supertileCapacity = capacity;
            return rig.renderHdr(r);
        };
        const RenderSettings r = smallSettings(m);
        const std::vector<float> off = render(twenty, r, -1, 0);
        EXPECT_EQ(render(twenty, r, 2, 0), off) << "2 x 2 supertiles";
        EXPECT_EQ(render(twenty, r, 1, 0), off) << "a supertile a tile";
        EXPECT_EQ(render(twenty, r, 2, 1), off) << "every list overflowing";
        RenderSettings many = r;
        many.localLights.lightCount = 600;
        const std::vector<float> manyOff = render(twenty, many, -1, 0);
        EXPECT_EQ(render(twenty, many, 0, 0), manyOff) << "600 lights, the default supertiles";
        EXPECT_EQ(render(twenty, many, 1, 0), manyOff) << "600 lights, a supertile a tile";
        EXPECT_NE(manyOff, off) << "the 600 lights must add light for this test to see anything";
        // Above 2048 lights several work groups test a supertile's lights, and the last to finish
        // makes its list. The build leaves its counters of finished groups as it found them: a second
        // frame (2400 lights after 2100, two groups a supertile each) equals that frame rendered first.
        RenderSettings more = r, most = r;
        more.localLights.lightCount = 2100;
        most.localLights.lightCount = 2400;
        const std::vector<float> mostOff = render(twenty, most, -1, 0);
        Rig rig(twenty);
        EXPECT_EQ(rig.renderHdr(more), render(twenty, more, -1, 0)) << "2100 lights, two groups a supertile";
        EXPECT_EQ(rig.renderHdr(most), mostOff) << "a second frame's supertile lists";
    }
}

// The whole-froxel light lists are built once a frame: forward_opaque builds them, the transparent
// pass and the lights-per-cluster view read that build (they were built again by each). With orbiting
// lights, a second frame must still equal the same frame rendered first (no reader of the previous
// frame's lists), in forward+ with a see-through quad in front of the lights. On the deferred path
// the transparent pass builds the whole lists and the clustered method's view its own tight ones: two.
TEST(LocalLights, WholeClusterListsAreBuiltOnceAFrame) {
    Scene s = twentyLightScene();
    for (size_t i = 2; i < s.pointLights.size(); ++i) {
        s.pointLights[i].orbitCenter = s.pointLights[i].position + glm::vec3(0.3f, 0.0f, 0.2f);
        s.pointLights[i].orbitSpeed = 1.5f;
    }
    ModelInstance glass = model("glass", makePlane(1.0f, 1),
                                glm::translate(glm::mat4(1.0f), {0.0f, 0.6f, 0.5f}) *
                                    glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(1, 0, 0)) *
                                    glm::scale(glm::mat4(1.0f), glm::vec3(2.0f)),
                                {0.8f, 0.8f, 0.8f}, {0.04f, 0.04f, 0.04f}, 32.0f);
    for (Material& m : glass.mesh.materials) {
        m.opacity = 0.5f;
        m.alphaMode = AlphaMode::Blend;
    }
    s.models.push_back(std::move(glass));
    struct Case {
        const char* name;
        DebugView view;
        RenderPath path;
        int builds;  // a frame
    };
    for (const Case& c : {Case{"forward+", DebugView::Final, RenderPath::ForwardPlus, 1},
                          Case{"forward+, lights per cluster", DebugView::LightsPerCluster, RenderPath::ForwardPlus, 1},
                          Case{"deferred clustered, lights per cluster", DebugView::LightsPerCluster, RenderPath::Deferred, 2}}) {
        RenderSettings r = smallSettings(LocalLightMethod::Clustered);
        r.view = c.view;
        r.renderPath = c.path;
        Rig first(s);
        const std::vector<float> before = first.renderHdr(r, 0.0f);
        EXPECT_EQ(first.passes.localLights.clusterBuilds, c.builds) << c.name;
        const std::vector<float> after = first.renderHdr(r, 1.0f);
        EXPECT_EQ(first.passes.localLights.clusterBuilds, 2 * c.builds) << c.name << ": the same builds every frame";
        Rig fresh(s);
        const std::vector<float> alone = fresh.renderHdr(r, 1.0f);
        EXPECT_NE(before, alone) << c.name << ": the lights must move between the frames for this test to see anything";
        EXPECT_EQ(after, alone) << c.name << ": the second frame read lists other than its own";
    }
}

// The light records are uploaded once a frame (by local_lights, or forward_opaque on the forward+
// path) and the overlays read that upload through the graph ("local_lights.records"). With orbiting
// lights, a frame at t = 1 s rendered after one at t = 0 must equal the same frame rendered first:
// an overlay that read the previous frame's records (stale) would draw the globes and the heat maps
// where the lights were at t = 0. Also with the filling pass disabled (the first overlay uploads
// them: never missing), and in every case exactly one upload a frame.
TEST(LocalLights, OverlaysReadThisFramesRecordsUploadedOnce) {
    Scene s = twentyLightScene();
    for (size_t i = 2; i < s.pointLights.size(); ++i) {  // the grid's lights orbit a point beside them
        s.pointLights[i].orbitCenter = s.pointLights[i].position + glm::vec3(0.3f, 0.0f, 0.2f);
        s.pointLights[i].orbitSpeed = 1.5f;
    }
    struct Case {
        const char* name;
        DebugView view;
        LocalLightMethod method;
        RenderPath path;
        const char* disabled;  // a pass switched off, or null
    };
    const Case cases[] = {
        {"globes, tiled", DebugView::Final, LocalLightMethod::Tiled, RenderPath::Deferred, nullptr},
        {"globes, forward+", DebugView::Final, LocalLightMethod::Clustered, RenderPath::ForwardPlus, nullptr},
        {"globes, local_lights disabled", DebugView::Final, LocalLightMethod::Tiled, RenderPath::Deferred, "local_lights"},
        {"globes, forward_opaque disabled", DebugView::Final, LocalLightMethod::Clustered, RenderPath::ForwardPlus,
         "forward_opaque"},
        {"lights per tile", DebugView::LightsPerTile, LocalLightMethod::Volumes, RenderPath::Deferred, nullptr},
        {"lights per cluster", DebugView::LightsPerCluster, LocalLightMethod::Clustered, RenderPath::Deferred, nullptr},
        {"lights per cluster, disabled", DebugView::LightsPerCluster, LocalLightMethod::Clustered, RenderPath::Deferred,
         "local_lights"},
        {"light ranges, volumes", DebugView::LightRanges, LocalLightMethod::Volumes, RenderPath::Deferred, nullptr},
    };
    for (const Case& c : cases) {
        RenderSettings r = smallSettings(c.method);
        r.view = c.view;
        r.renderPath = c.path;
        r.localLights.globes = c.view == DebugView::Final;
        if (c.disabled) r.disabledPasses.insert(c.disabled);
        Rig first(s);
        const std::vector<float> before = first.renderHdr(r, 0.0f);
        EXPECT_EQ(first.passes.localLights.recordFills, 1) << c.name;
        const std::vector<float> after = first.renderHdr(r, 1.0f);
        EXPECT_EQ(first.passes.localLights.recordFills, 2) << c.name << ": one upload a frame";
        Rig fresh(s);
        const std::vector<float> alone = fresh.renderHdr(r, 1.0f);
        EXPECT_NE(before, alone) << c.name << ": the lights must move between the frames for this test to see anything";
        EXPECT_EQ(after, alone) << c.name << ": the second frame read records other than its own";
        if (c.view == DebugView::Final) {  // the globes are there (records not missing)
            RenderSettings noGlobes = r;
            noGlobes.localLights.globes = false;
            EXPECT_NE(fresh.renderHdr(noGlobes, 1.0f), alone) << c.name;
        }
    }
}

// The twenty-light scene with a third of its lights turned into spots (narrow and wide cones, one
// holding the camera, one crossing the near plane).
Scene spotScene() {
    Scene s = twentyLightScene();
    for (size_t i = 0; i < s.pointLights.size(); i += 3) {
        const float outer = 15.0f + 5.0f * float(i);  // 15..105 -> clamped below 90
        s.pointLights[i].spot = SpotCone{glm::normalize(glm::vec3(0.2f * float(i % 4) - 0.3f, -1.0f, 0.1f * float(i % 3))),
                                         0.5f * std::min(outer, 85.0f), std::min(outer, 85.0f)};
        s.pointLights[i].range *= 1.5f;
        s.pointLights[i].intensity *= 3.0f;
    }
    return s;
}

// Spots through every method: the same image as the fullscreen reference (scissor and volumes
// bit-identical, tiled within the fp16 bound of FourMethodsGiveTheSameImage).
TEST(LocalLights, EveryMethodGivesTheSameImageWithSpots) {
    Scene s = spotScene();
    Rig rig(s);
    RenderSettings off = smallSettings(LocalLightMethod::Fullscreen);
    off.localLights.enabled = false;
    const std::vector<float> unlit = rig.renderHdr(off);
    const std::vector<float> ref = rig.renderHdr(smallSettings(LocalLightMethod::Fullscreen));
    int changed = 0;
    for (size_t i = 0; i < ref.size(); i += 4)
        if (ref[i + 1] > 1.01f * unlit[i + 1] + 1e-4f) ++changed;
    EXPECT_GT(changed, 64 * 48 / 8);
    std::vector<int> k = lightsPerPixel(s, smallSettings(LocalLightMethod::Scissor));
    for (LocalLightMethod m : allLocalLightMethods()) {
        if (m == LocalLightMethod::Fullscreen) continue;
        const std::vector<float> got = rig.renderHdr(smallSettings(m));
        for (size_t i = 0; i < got.size(); ++i) {
            ASSERT_TRUE(std::isfinite(got[i]));
            if (m == LocalLightMethod::Scissor || m == LocalLightMethod::Volumes) {
                ASSERT_EQ(got[i], ref[i]) << localLightMethodName(m) << " texel " << i / 4;
                continue;
            }
            const double bound = tiledBound(k[i / 4], ref[i]);
            ASSERT_LE(std::abs(double(got[i]) - double(ref[i])), bound) << localLightMethodName(m) << " texel " << i / 4;
        }
    }
}

// One spot straight down onto a matte plane: every method gives kd/pi * I * attenuation * N.L *
// smoothstep(cos outer, cos inner, cos angle) within 2e-3, exactly 0 outside the outer cone, and at
// the centre (on the axis) the full kd/pi * I / h^2 * window(h).
TEST(LocalLights, SpotOverPlaneMatchesAnalyticRadiance) {
    Scene s;
    const glm::vec3 kd(0.6f, 0.4f, 0.2f);
    s.models.push_back(model("plane", makePlane(1.0f, 4), glm::scale(glm::mat4(1.0f), glm::vec3(8.0f)), kd,
                             glm::vec3(0.0f), 1.0f));
    s.camera.position = {0.0f, 3.0f, 0.01f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 10.0f;
    s.ambient = glm::vec3(0.0f);
    PointLight l;
    l.position = {0.0f, 0.8f, 0.0f};
    l.range = 2.0f;
    l.intensity = 0.7f;
    l.color = {1.0f, 0.8f, 0.5f};
    l.spot = SpotCone{{0.0f, -1.0f, 0.0f}, 20.0f, 35.0f};
    s.pointLights.push_back(l);
    Rig rig(s);
    const int w = 64, h = 48;
    const glm::dmat4 inv = glm::inverse(glm::dmat4(s.camera.projection(float(w) / float(h))) * glm::dmat4(s.camera.view()));
    const glm::dvec3 kd8 = test::srgb8Stored(glm::dvec3(kd));
    const double cosOuter = std::cos(glm::radians(35.0)), cosInner = std::cos(glm::radians(20.0));
    for (LocalLightMethod m : allLocalLightMethods()) {
        std::vector<float> img = rig.renderHdr(smallSettings(m));
        int inside = 0, outside = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                double nx = (x + 0.5) / w * 2.0 - 1.0, ny = (y + 0.5) / h * 2.0 - 1.0;
                glm::dvec4 a = inv * glm::dvec4(nx, ny, -1.0, 1.0), b = inv * glm::dvec4(nx, ny, 1.0, 1.0);
                glm::dvec3 p0 = glm::dvec3(a) / a.w, p1 = glm::dvec3(b) / b.w;
                glm::dvec3 p = p0 + (-p0.y / (p1.y - p0.y)) * (p1 - p0);
                glm::dvec3 toLight = glm::dvec3(l.position) - p;
                double d = glm::length(toLight);
                double cosAngle = toLight.y / d;  // the axis is straight down
                double e = double(l.intensity) * attenuationRef(d, l.range) * std::max(toLight.y / d, 0.0) *
                           smoothstepRef(cosOuter, cosInner, cosAngle);
                // The position rebuilt from depth moves the cone's cosine by float rounding (measured
                // up to ~1e-5 on NVIDIA): near the outer edge, where smoothstep is ~3 t^2, that is a
                // large relative change of a small value, so the bound adds the slope times 2e-5.
                const double kCosRounding = 2e-5;
                const double slope = double(l.intensity) * attenuationRef(d, l.range) * std::max(toLight.y / d, 0.0) *
                                     std::abs(smoothstepRef(cosOuter, cosInner, cosAngle + kCosRounding) -
                                              smoothstepRef(cosOuter, cosInner, cosAngle - kCosRounding)) /
                                     (2.0 * kCosRounding);
                for (int c = 0; c < 3; ++c) {
                    double expected = kd8[c] / M_PI * double(l.color[c]) * e;
                    const double edgeBound = kd8[c] / M_PI * double(l.color[c]) * slope * kCosRounding;
                    double got = img[(size_t(y) * w + x) * 4 + c];
                    // Pixels within float rounding of the outer edge may be either side of it.
                    if (std::abs(cosAngle - cosOuter) < 1e-5) continue;
                    if (cosAngle < cosOuter) {
                        ASSERT_EQ(got, 0.0) << localLightMethodName(m) << " outside the cone at " << x << "," << y;
                        continue;
                    }
                    EXPECT_NEAR(got, expected, 2e-3 * expected + edgeBound + 1e-6)
                        << localLightMethodName(m) << " pixel " << x << "," << y << " channel " << c;
                }
                if (cosAngle < cosOuter) ++outside;
                else if (e > 0.0) ++inside;
            }
        EXPECT_GT(inside, 100) << "the cone covers a good part of the image";
        EXPECT_GT(outside, 100) << "and leaves a good part dark";
        // The centre of the image looks straight down the axis (camera above the light's foot).
        const double centre = kd8[0] / M_PI * l.color[0] * l.intensity * attenuationRef(0.8, 2.0);
        const size_t c = (size_t(h / 2) * w + w / 2) * 4;
        EXPECT_NEAR(img[c], centre, 0.02 * centre) << localLightMethodName(m) << ": at the centre, on the axis";
    }
}

// ---- clustered: the froxel grid's light lists ----------------------------------------------------

struct ClusterReadback {
    std::vector<GLuint> counts, lists;
};
ClusterReadback readClusters(const LocalLightPass& st) {
    ClusterReadback r;
    const size_t n = size_t(st.clusterGrid.count());
    r.counts.resize(n);
    r.lists.resize(n * kMaxLightsPerCluster);
    glGetNamedBufferSubData(st.clusterCounts.id(), 0, GLsizeiptr(n * sizeof(GLuint)), r.counts.data());
    glGetNamedBufferSubData(st.clusterLists.id(), 0, GLsizeiptr(r.lists.size() * sizeof(GLuint)), r.lists.data());
    return r;
}

std::vector<GpuLocalLight> eyeLights(const Scene& s, const RenderSettings& r) {
    FrameData f = makeFrameData(s, r, 0.0f);
    std::vector<GpuLocalLight> out;
    for (const auto& l : localLightsForFrame(s, r.localLights, 0.0f)) out.push_back(gpuLocalLight(l, f.view, -1));
    return out;
}

// The whole-froxel lists (light_clusters.comp, built here by forward+'s opaque pass) against the
// double-precision reference of the same test on a 4 x 3 x 8 grid: every light the reference lists
// (with the bounds shrunk by 1e-4) is listed, and every listed light is in the reference with the
// bounds grown by 1e-2. And the reference itself is conservative: points sampled all through each
// light's lit region (its sector) fall in froxels that list it. The build's first level
// (light_cluster_supertiles.comp) must change none of it: skipped (the default below 257 lights), with
// its default 8 x 8 supertiles (one here), with supertiles of 2 x 2 tiles (the 4 x 3 grid split four
// ways, the last ones partial) and single tiles, and with every supertile's list overflowing
// (capacity 1: each tile tests every light).
TEST(ClusteredLights, EveryLightTouchingAClusterIsInItsList) {
  for (const glm::ivec2 supertile :
       {glm::ivec2(0, 0), glm::ivec2(8, 0), glm::ivec2(2, 0), glm::ivec2(1, 0), glm::ivec2(2, 1)}) {
    SCOPED_TRACE("supertile " + std::to_string(supertile.x) + " tiles, capacity " + std::to_string(supertile.y));
    Scene s = spotScene();
    Rig rig(s);
    rig.passes.localLights.supertileTiles = supertile.x;
    rig.passes.localLights.supertileCapacity = supertile.y;
    RenderSettings r = smallSettings(LocalLightMethod::Clustered);
    r.renderPath = RenderPath::ForwardPlus;
    r.localLights.clusterSize = 16;
    r.localLights.clusterSlices = 8;
    rig.renderHdr(r);
    const LocalLightPass& st = rig.passes.localLights;
    const ClusterGrid& g = st.clusterGrid;
    ASSERT_EQ(g.tilesX, 4);
    ASSERT_EQ(g.tilesY, 3);
    ASSERT_EQ(g.slices, 8);
    EXPECT_EQ(st.stats.clusters, 96);
    const ClusterReadback gpu = readClusters(st);
    FrameData f = makeFrameData(s, r, 0.0f);
    const std::vector<GpuLocalLight> lights = eyeLights(s, r);
    const auto inner = referenceClusterLists(g, f.projection, lights, -1e-4);
    const auto outer = referenceClusterLists(g, f.projection, lights, 1e-2);
    const auto exact = referenceClusterLists(g, f.projection, lights, 0.0);
    size_t listed = 0;
    for (int c = 0; c < g.count(); ++c) {
        const GLuint n = gpu.counts[size_t(c)];
        ASSERT_LE(n, GLuint(kMaxLightsPerCluster));
        std::vector<int> got(gpu.lists.begin() + long(c) * kMaxLightsPerCluster,
                             gpu.lists.begin() + long(c) * kMaxLightsPerCluster + long(n));
        EXPECT_TRUE(std::is_sorted(got.begin(), got.end())) << "cluster " << c;
        for (int i : inner[size_t(c)])
            EXPECT_NE(std::find(got.begin(), got.end(), i), got.end()) << "cluster " << c << " misses light " << i;
        for (int i : got)
            EXPECT_NE(std::find(outer[size_t(c)].begin(), outer[size_t(c)].end(), i), outer[size_t(c)].end())
                << "cluster " << c << " lists light " << i << " that does not reach it";
        listed += n;
    }
    EXPECT_GT(listed, 100u) << "the grid is not trivially empty";
    // Sample each light's sector; every sample inside the view lands in a froxel listing the light.
    const std::vector<PointLight> world = localLightsForFrame(s, r.localLights, 0.0f);
    int samples = 0;
    for (size_t li = 0; li < world.size(); ++li) {
        const PointLight& l = world[li];
        const glm::dvec3 axis = l.spot ? glm::dvec3(l.spot->direction) : glm::dvec3(0, 0, -1);
        const double outerAngle = l.spot ? glm::radians(double(l.spot->outerDegrees)) : M_PI;
        const glm::dvec3 u = glm::normalize(glm::cross(axis, glm::dvec3(0.36, 0.48, 0.8))), v = glm::cross(axis, u);
        for (int i = 1; i <= 12; ++i)
            for (int j = 0; j <= 12; ++j)
                for (int k = 0; k < 12; ++k) {
                    const double d = l.range * i / 12.0 * 0.999, a = outerAngle * j / 12.0 * 0.999, t = M_PI * k / 6.0;
                    const glm::dvec3 p = glm::dvec3(l.position) +
                                         d * (std::cos(a) * axis + std::sin(a) * (std::cos(t) * u + std::sin(t) * v));
                    const glm::dvec4 e = glm::dmat4(f.view) * glm::dvec4(p, 1.0);
                    const glm::dvec4 clip = glm::dmat4(f.projection) * e;
                    if (clip.w <= 0.0) continue;
                    const double px = (clip.x / clip.w * 0.5 + 0.5) * g.width, py = (clip.y / clip.w * 0.5 + 0.5) * g.height;
                    const double depth = -e.z;
                    if (px < 0 || py < 0 || px >= g.width || py >= g.height || depth < g.nearPlane || depth > g.farPlane) continue;
                    const int c = g.index(int(px) / g.tileSize, int(py) / g.tileSize, clusterSliceOf(g, depth));
                    const auto& list = exact[size_t(c)];
                    ASSERT_NE(std::find(list.begin(), list.end(), int(li)), list.end())
                        << "light " << li << " reaches cluster " << c << " but the reference test misses it";
                    ++samples;
                }
    }
    EXPECT_GT(samples, 1000);
  }
}

// Where does the ray from the eye (the origin) along dir enter the box [lo, hi]? Its eye distance
// (-z), or NaN when it misses.
double rayBoxEntryDepth(glm::dvec3 dir, glm::dvec3 lo, glm::dvec3 hi) {
    double t0 = 0.0, t1 = 1e300;
    for (int i = 0; i < 3; ++i) {
        if (std::abs(dir[i]) < 1e-15) {
            if (0.0 < lo[i] || 0.0 > hi[i]) return std::nan("");
            continue;
        }
        double u = lo[i] / dir[i], v = hi[i] / dir[i];
        if (u > v) std::swap(u, v);
        t0 = std::max(t0, u);
        t1 = std::min(t1, v);
    }
    return t0 <= t1 ? -(t0 * dir.z) : std::nan("");
}

// The deferred clustered method's tight froxels on a scene of known depth: the camera at the origin
// looking down -z at a thin pillar (front face 2 m away) before a wall 8 m away, the top rows empty,
// 4 x 3 tiles x 8 slices (2 m in slice 4, 8 m in slice 6). Each pixel's eye distance is ray-cast
// here; from them the CPU reference (referenceTightClusterLists) gives each froxel's list. The GPU's
// lists hold every light of the reference with the bounds shrunk by 1e-3, and only lights of the
// reference with the bounds and depth ranges grown by 1%; unoccupied froxels list nothing; lights
// crossing only the empty depth between pillar and wall are dropped (they are in the whole-froxel
// lists); every light reaching a pixel's surface point is listed in that pixel's froxel; and the
// image equals the tiled method's within the fp16 bound.
TEST(ClusteredLights, TightFroxelsListEveryLightReachingTheirPixels) {
    Scene s;
    const glm::vec3 wallLo(-20.0f, -20.0f, -8.2f), wallHi(20.0f, 2.31f, -8.0f);
    // The pillar: NDC x from -0.75 to -0.25 at 2 m (pixels 8 to 24 of 64), the full height.
    const glm::vec3 pillarLo(-1.1547f, -5.0f, -2.02f), pillarHi(-0.3849f, 5.0f, -2.0f);
    for (auto [lo, hi] : {std::pair{wallLo, wallHi}, std::pair{pillarLo, pillarHi}})
        s.models.push_back(model("cube", makeCube(1.0f),
                                 glm::scale(glm::translate(glm::mat4(1.0f), 0.5f * (lo + hi)), hi - lo),
                                 {0.5f, 0.5f, 0.5f}, {0.2f, 0.2f, 0.2f}, 16.0f));
    lookDownMinusZ(s, 0.1f, 30.0f);
    // 90 lights through the view at 1-10 m, ranges 0.3-2.5 m, every third a spot.
    uint32_t seed = 12345u;
    auto next = [&seed] {
        seed = seed * 1664525u + 1013904223u;
        return double(seed >> 8) / double(1u << 24);
    };
    for (int i = 0; i < 90; ++i) {
        const double d = 1.0 + 9.0 * next();
        PointLight l;
        l.position = glm::vec3(float((next() * 2.0 - 1.0) * 0.75 * d), float((next() * 2.0 - 1.0) * 0.58 * d), float(-d));
        l.range = float(0.3 + 2.2 * next());
        l.intensity = 0.2f;
        if (i % 3 == 0)
            l.spot = SpotCone{glm::normalize(glm::vec3(float(next() - 0.5), float(next() - 0.5), float(next() - 0.5))),
                              15.0f, float(20.0 + 50.0 * next())};
        s.pointLights.push_back(l);
    }
    Rig rig(s);
    RenderSettings r = smallSettings(LocalLightMethod::Clustered);
    r.localLights.clusterSize = 16;
    r.localLights.clusterSlices = 8;
    const std::vector<float> img = rig.renderHdr(r);
    // The shading pass keeps its froxels in shared memory; the lights-per-cluster view builds the
    // same tight froxels' lists from the G-buffer (light_clusters_tight.comp).
    RenderSettings view = r;
    view.view = DebugView::LightsPerCluster;
    rig.renderHdr(view);
    const LocalLightPass& st = rig.passes.localLights;
    const ClusterGrid& g = st.clusterGrid;
    ASSERT_EQ(g.count(), 96);
    ASSERT_EQ(clusterSliceOf(g, 2.0), 4);
    ASSERT_EQ(clusterSliceOf(g, 8.0), 6);
    const ClusterReadback gpu = readClusters(st);

    FrameData f = makeFrameData(s, r, 0.0f);
    const glm::dmat4 proj(f.projection);
    std::vector<double> depth(size_t(g.width) * g.height);
    std::vector<glm::dvec3> point(depth.size());
    for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x) {
            const glm::dvec3 dir(((x + 0.5) / g.width * 2.0 - 1.0) / proj[0][0], ((y + 0.5) / g.height * 2.0 - 1.0) / proj[1][1], -1.0);
            double d = rayBoxEntryDepth(dir, glm::dvec3(pillarLo), glm::dvec3(pillarHi));
            if (std::isnan(d)) d = rayBoxEntryDepth(dir, glm::dvec3(wallLo), glm::dvec3(wallHi));
            depth[size_t(y) * g.width + x] = d;
            point[size_t(y) * g.width + x] = dir * d;
        }
    const std::vector<FroxelDepth> occupied = occupiedFroxelDepths(g, depth);
    std::vector<FroxelDepth> grown = occupied;
    for (FroxelDepth& fd : grown)
        if (fd.occupied()) fd = {fd.nearest * 0.99, fd.farthest * 1.01};
    const std::vector<GpuLocalLight> lights = eyeLights(s, r);
    const auto inner = referenceTightClusterLists(g, f.projection, lights, occupied, -1e-3);
    const auto outer = referenceTightClusterLists(g, f.projection, lights, grown, 1e-2);
    const auto whole = referenceClusterLists(g, f.projection, lights, 0.0);
    int occupiedCount = 0;
    size_t listed = 0, dropped = 0;
    for (int c = 0; c < g.count(); ++c) {
        const GLuint n = gpu.counts[size_t(c)];
        ASSERT_LE(n, GLuint(kMaxLightsPerCluster));
        std::vector<int> got(gpu.lists.begin() + long(c) * kMaxLightsPerCluster,
                             gpu.lists.begin() + long(c) * kMaxLightsPerCluster + long(n));
        if (!occupied[size_t(c)].occupied()) {
            EXPECT_EQ(n, 0u) << "unoccupied cluster " << c;
            continue;
        }
        ++occupiedCount;
        EXPECT_TRUE(std::is_sorted(got.begin(), got.end())) << "cluster " << c;
        for (int i : inner[size_t(c)])
            EXPECT_NE(std::find(got.begin(), got.end(), i), got.end()) << "cluster " << c << " misses light " << i;
        for (int i : got)
            EXPECT_NE(std::find(outer[size_t(c)].begin(), outer[size_t(c)].end(), i), outer[size_t(c)].end())
                << "cluster " << c << " lists light " << i << " that does not reach its pixels' depths";
        for (int i : whole[size_t(c)])
            if (std::find(got.begin(), got.end(), i) == got.end()) ++dropped;
        listed += n;
    }
    // The wall (slice 6) is in all 12 tiles (up to row 35), the pillar (slice 4) in tile columns 0, 1.
    EXPECT_EQ(occupiedCount, 12 + 6);
    EXPECT_GT(listed, 30u) << "the grid is not trivially empty";
    EXPECT_GT(dropped, 30u) << "tightening drops the lights in the empty depth";
    // Every light reaching a pixel's surface point is in that pixel's froxel's list.
    int reached = 0;
    for (size_t px = 0; px < depth.size(); ++px) {
        if (std::isnan(depth[px])) continue;
        const int c = g.index(int(px % size_t(g.width)) / g.tileSize, int(px / size_t(g.width)) / g.tileSize,
                              clusterSliceOf(g, depth[px]));
        const GLuint n = gpu.counts[size_t(c)];
        const GLuint* list = gpu.lists.data() + size_t(c) * kMaxLightsPerCluster;
        for (size_t i = 0; i < lights.size(); ++i) {
            const glm::dvec3 toPoint = point[px] - glm::dvec3(lights[i].positionRange);
            const double dist = glm::length(toPoint);
            if (dist >= 0.999 * lights[i].positionRange.w) continue;
            if (lights[i].directionCos.w >= -1.0f &&
                glm::dot(toPoint, glm::dvec3(lights[i].directionCos)) <= (lights[i].directionCos.w + 1e-4) * dist)
                continue;
            ++reached;
            ASSERT_NE(std::find(list, list + n, GLuint(i)), list + n)
                << "light " << i << " reaches pixel " << px << " but cluster " << c << " does not list it";
        }
    }
    EXPECT_GT(reached, 1000);
    // And the image: the tiled method's within FourMethodsGiveTheSameImage's bound.
    const std::vector<float> tiled = rig.renderHdr(smallSettings(LocalLightMethod::Tiled));
    std::vector<int> k = lightsPerPixel(s, smallSettings(LocalLightMethod::Scissor));
    int lit = 0;
    for (size_t i = 0; i < img.size(); ++i) {
        ASSERT_TRUE(std::isfinite(img[i]));
        const double bound = 2.0 * tiledBound(k[i / 4], tiled[i]);
        ASSERT_LE(std::abs(double(img[i]) - double(tiled[i])), bound) << "texel " << i / 4 << " channel " << i % 4;
        if (i % 4 == 1 && tiled[i] > 1e-3f) ++lit;
    }
    EXPECT_GT(lit, 64 * 48 / 8);
    // 8-pixel tiles: 64 lights a batch, so the 90 lights take two batches (the second in the other
    // half of the shared bits) in tiles split by the pillar's edge.
    RenderSettings small = r;
    small.localLights.clusterSize = 8;
    const std::vector<float> img8 = rig.renderHdr(small);
    for (size_t i = 0; i < img8.size(); ++i) {
        const double bound = 2.0 * tiledBound(k[i / 4], tiled[i]);
        ASSERT_LE(std::abs(double(img8[i]) - double(tiled[i])), bound) << "8 px: texel " << i / 4 << " channel " << i % 4;
    }
}

// The fused clustered pass at tile sizes other than its 16 x 16 work group (a pixel per
// invocation): smaller tiles (fewer invocations, smaller batches), larger ones (several pixels per
// invocation, partial tiles at the image's edges), and 1, 7 or 64 slices: the fullscreen image
// within the bound of EveryMethodGivesTheSameImageWithSpots.
TEST(ClusteredLights, EveryTileSizeAndSliceCountGivesTheSameImage) {
    Scene s = spotScene();
    Rig rig(s);
    const std::vector<float> ref = rig.renderHdr(smallSettings(LocalLightMethod::Fullscreen));
    std::vector<int> k = lightsPerPixel(s, smallSettings(LocalLightMethod::Scissor));
    for (int tile : {8, 12, 24, 40})
        for (int slices : {1, 7, 64}) {
            RenderSettings r = smallSettings(LocalLightMethod::Clustered);
            r.localLights.clusterSize = tile;
            r.localLights.clusterSlices = slices;
            const std::vector<float> got = rig.renderHdr(r);
            EXPECT_EQ(rig.passes.localLights.stats.clusters,
                      ((64 + tile - 1) / tile) * ((48 + tile - 1) / tile) * slices);
            for (size_t i = 0; i < got.size(); ++i) {
                const double bound = tiledBound(k[i / 4], ref[i]);
                ASSERT_LE(std::abs(double(got[i]) - double(ref[i])), bound)
                    << "tile " << tile << " slices " << slices << " texel " << i / 4;
            }
        }
}

// A tile spanning more slices than a light's 32-bit slice mask holds (the clustered pass counts a
// tile's slices from its nearest occupied one, the farthest sharing the last bit): a pillar 0.3 m
// from the camera before a wall 60 m away, 64 slices. Lights on the wall and around the pillar give
// the fullscreen image.
Scene pillarBeforeWallScene() {
    Scene s;
    const glm::mat4 wall = glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, -60.0f}) *
                           glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), {1.0f, 0.0f, 0.0f}) *
                           glm::scale(glm::mat4(1.0f), glm::vec3(100.0f));
    s.models.push_back(model("plane", makePlane(1.0f, 4), wall, {0.6f, 0.6f, 0.6f}, {0.3f, 0.3f, 0.3f}, 16.0f));
    s.models.push_back(model("cube", makeCube(1.0f),
                             glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, -0.3f}) *
                                 glm::scale(glm::mat4(1.0f), {0.04f, 1.0f, 0.04f}),
                             {0.8f, 0.3f, 0.2f}, {0.5f, 0.5f, 0.5f}, 64.0f));
    lookDownMinusZ(s, 0.05f, 100.0f);
    for (int i = 0; i < 20; ++i) {  // on the wall: 2 m before it, reaching 7.7 m of it
        PointLight l;
        l.position = {-24.0f + 12.0f * float(i % 5), -15.0f + 10.0f * float(i / 5), -58.0f};
        l.range = 8.0f;
        l.intensity = 40.0f;
        l.color = {1.0f, 0.8f - 0.03f * float(i), 0.5f + 0.02f * float(i)};
        s.pointLights.push_back(l);
    }
    for (int i = 0; i < 4; ++i) {  // around the pillar
        PointLight l;
        l.position = {-0.06f + 0.04f * float(i), 0.1f * float(i) - 0.15f, -0.2f};
        l.range = 0.25f;
        l.intensity = 0.02f;
        s.pointLights.push_back(l);
    }
    return s;
}

TEST(ClusteredLights, TilesSpanningMoreSlicesThanAMaskHoldsShadeEveryLight) {
    const Scene s = pillarBeforeWallScene();
    Rig rig(s);
    const std::vector<float> ref = rig.renderHdr(smallSettings(LocalLightMethod::Fullscreen));
    const std::vector<int> k = lightsPerPixel(s, smallSettings(LocalLightMethod::Scissor));
    const ClusterGrid g = makeClusterGrid(64, 48, 16, 64, s.camera.nearPlane, s.camera.farPlane);
    ASSERT_GT(clusterSliceOf(g, 59.0) - clusterSliceOf(g, 0.32), 32) << "the pillar's and the wall's slices";
    for (int tile : {16, 40}) {
        RenderSettings r = smallSettings(LocalLightMethod::Clustered);
        r.localLights.clusterSize = tile;
        r.localLights.clusterSlices = 64;
        const std::vector<float> got = rig.renderHdr(r);
        int wallLit = 0;
        for (size_t i = 0; i < got.size(); ++i) {
            const double bound = tiledBound(k[i / 4], ref[i]);
            ASSERT_LE(std::abs(double(got[i]) - double(ref[i])), bound) << "tile " << tile << " texel " << i / 4;
            const int x = int(i / 4) % 64;
            if (i % 4 == 0 && ref[i] > 1e-3f && x >= 24 && x < 40) ++wallLit;
        }
        EXPECT_GT(wallLit, 0) << "lit wall in the pillar's tiles";
    }
}

// By default (--clustered-kernel auto) the clustered method leaves frames with fewer than 32 lights to
// the tiled kernel when its froxel tiles are the tiled kernel's (16 px): the same bits as the tiled
// method. --clustered-kernel froxels runs the slices' kernel at any light count, and other tile sizes
// always do. Every case gives the fullscreen image.
TEST(ClusteredLights, FewLightsShadeWithTheTiledKernel) {
    const Scene s = twentyLightScene();
    Rig rig(s);
    const std::vector<float> tiled = rig.renderHdr(smallSettings(LocalLightMethod::Tiled));
    RenderSettings r = smallSettings(LocalLightMethod::Clustered);
    r.localLights.clusteredKernel = ClusteredKernel::Auto;  // the default
    EXPECT_EQ(rig.renderHdr(r), tiled) << "20 lights, 16-pixel tiles: the tiled kernel";
    EXPECT_FALSE(rig.passes.localLights.stats.slicesShaded);
    EXPECT_EQ(rig.passes.localLights.stats.clusters, 4 * 3 * r.localLights.clusterSlices) << "the grid it stands for";
    const std::vector<float> ref = rig.renderHdr(smallSettings(LocalLightMethod::Fullscreen));
    const std::vector<int> k = lightsPerPixel(s, smallSettings(LocalLightMethod::Fullscreen));
    for (const auto& [size, kernel] : {std::pair{16, ClusteredKernel::Froxels}, std::pair{8, ClusteredKernel::Auto}}) {
        SCOPED_TRACE(std::to_string(size) + " px, " + clusteredKernelName(kernel));
        r.localLights.clusterSize = size;
        r.localLights.clusteredKernel = kernel;
        const std::vector<float> got = rig.renderHdr(r);
        EXPECT_TRUE(rig.passes.localLights.stats.slicesShaded);
        for (size_t i = 0; i < got.size(); ++i) {
            const double bound = tiledBound(k[i / 4], ref[i]);
            ASSERT_LE(std::abs(double(got[i]) - double(ref[i])), bound) << "texel " << i / 4;
        }
    }
}

// From 32 lights, --clustered-kernel auto times the clustered and the tiled kernel in turn on the GPU
// (GL timestamps, read frames later) and then runs the one with the smaller median; both give the
// fullscreen image. --clustered-kernel tiles gives the tiled method's bits.
TEST(ClusteredLights, AutoRacesBothKernelsAndKeepsTheFaster) {
    const Scene s = twentyLightScene();
    Rig rig(s);
    RenderSettings full = smallSettings(LocalLightMethod::Fullscreen);
    full.localLights.lightCount = 40;
    const std::vector<float> ref = rig.renderHdr(full);
    const std::vector<int> k = lightsPerPixel(s, full);
    RenderSettings r = smallSettings(LocalLightMethod::Clustered);
    r.localLights.clusteredKernel = ClusteredKernel::Auto;  // the default
    r.localLights.lightCount = 40;
    bool ran[2] = {false, false};  // froxels, tiles
    int frames = 0;
    for (; frames < 40; ++frames) {
        const std::vector<float> got = rig.renderHdr(r);
        const LocalLightStats& st = rig.passes.localLights.stats;
        ran[st.slicesShaded ? 0 : 1] = true;
        for (size_t i = 0; i < got.size(); ++i) {
            const double bound = tiledBound(k[i / 4], ref[i]);
            ASSERT_LE(std::abs(double(got[i]) - double(ref[i])), bound) << "frame " << frames << " texel " << i / 4;
        }
        if (!st.kernelRacing) break;
    }
    ASSERT_LT(frames, 40) << "the round never ended: its timestamps were never read";
    EXPECT_TRUE(ran[0] && ran[1]) << "both kernels timed";
    const LocalLightStats& st = rig.passes.localLights.stats;
    ASSERT_GT(st.froxelKernelMs, 0.0);
    ASSERT_GT(st.tileKernelMs, 0.0);
    const bool froxelsFaster = st.froxelKernelMs <= st.tileKernelMs;  // a tie keeps the first choice, froxels
    for (int f = 0; f < 5; ++f) {
        rig.renderHdr(r);
        EXPECT_FALSE(rig.passes.localLights.stats.kernelRacing);
        EXPECT_EQ(rig.passes.localLights.stats.slicesShaded, froxelsFaster) << "frame " << f << " after the round";
    }
    RenderSettings t = smallSettings(LocalLightMethod::Tiled);
    t.localLights.lightCount = 40;
    r.localLights.clusteredKernel = ClusteredKernel::Tiles;
    EXPECT_EQ(rig.renderHdr(r), rig.renderHdr(t)) << "--clustered-kernel tiles";
}

// Past the cap: 300 lights around one point. The cluster counts all 300, lists the first 256 (lowest
// indices), the overflow is counted (stats, one build late) and warned about, the image stays finite.
TEST(ClusteredLights, OverflowPastTheCapIsCountedAndWarned) {
    Scene s = twentyLightScene();
    s.pointLights.clear();
    for (int i = 0; i < 300; ++i) {
        PointLight l;
        l.position = {0.01f * float(i % 10), 0.5f + 0.01f * float(i / 10 % 10), 0.01f * float(i / 100)};
        l.range = 1.0f;
        l.intensity = 0.001f;
        s.pointLights.push_back(l);
    }
    Rig rig(s);
    RenderSettings r = smallSettings(LocalLightMethod::Clustered);
    r.localLights.clusterSize = 16;
    r.localLights.clusterSlices = 8;
    const std::vector<float> img = rig.renderHdr(r);
    // The deferred clustered method writes no lists; the lights-per-cluster view builds them.
    r.view = DebugView::LightsPerCluster;
    const int warningsBefore = warningCount();
    rig.renderHdr(r);
    EXPECT_EQ(rig.passes.localLights.stats.clustersOverflowing, -1) << "no earlier build to read";
    rig.renderHdr(r);
    const LocalLightPass& st = rig.passes.localLights;
    const ClusterReadback gpu = readClusters(st);
    int over = 0;
    for (int c = 0; c < st.clusterGrid.count(); ++c) {
        if (gpu.counts[size_t(c)] <= GLuint(kMaxLightsPerCluster)) continue;
        ++over;
        EXPECT_EQ(gpu.counts[size_t(c)], 300u);
        for (int k = 0; k < kMaxLightsPerCluster; ++k)
            ASSERT_EQ(gpu.lists[size_t(c) * kMaxLightsPerCluster + size_t(k)], GLuint(k)) << "cluster " << c;
    }
    EXPECT_GT(over, 0);
    EXPECT_EQ(st.stats.clustersOverflowing, over);
    EXPECT_GT(warningCount(), warningsBefore);
    // Shading never stops at the cap: two batches of lights (256 + 44), and with 8-pixel tiles five
    // (64 a batch, alternating between the two halves of the shared bits), give the tiled image.
    const std::vector<float> tiled = rig.renderHdr(smallSettings(LocalLightMethod::Tiled));
    RenderSettings small = smallSettings(LocalLightMethod::Clustered);
    small.localLights.clusterSize = 8;
    small.localLights.clusterSlices = 8;
    const std::vector<float> img8 = rig.renderHdr(small);
    const std::vector<int> k = lightsPerPixel(s, smallSettings(LocalLightMethod::Scissor));
    int lit = 0;
    for (size_t i = 0; i < img.size(); ++i) {
        ASSERT_TRUE(std::isfinite(img[i]));
        const double bound = 2.0 * tiledBound(k[i / 4], tiled[i]);
        ASSERT_LE(std::abs(double(img[i]) - double(tiled[i])), bound) << "texel " << i / 4 << " channel " << i % 4;
        ASSERT_LE(std::abs(double(img8[i]) - double(tiled[i])), bound) << "8 px: texel " << i / 4 << " channel " << i % 4;
        if (i % 4 == 1 && k[i / 4] > 256) ++lit;
    }
    EXPECT_GT(lit, 0) << "some pixel is reached by more lights than the cap";
}

// ---- spot shadows ---------------------------------------------------------------------------------

// A shadow-casting spot over a floor with a cube between them. Floor points whose path to the light
// the cube blocks (and all floor points within 3 cm of them) receive nothing from the spot; points
// 3 cm clear of any blocked point get exactly what they get without the shadow map (to fp16), in the
// fullscreen, tiled and clustered methods. castsShadow adds the spot_shadows pass, and only then.
TEST(LocalLights, ShadowedSpotDarkensBehindAnOccluder) {
    Scene s;
    s.models.push_back(model("plane", makePlane(1.0f, 4), glm::scale(glm::mat4(1.0f), glm::vec3(8.0f)),
                             glm::vec3(0.5f), glm::vec3(0.0f), 1.0f));
    const glm::vec3 cubeCentre(0.3f, 0.6f, 0.0f), cubeHalf(0.15f);
    s.models.push_back(model("cube", makeCube(1.0f),
                             glm::scale(glm::translate(glm::mat4(1.0f), cubeCentre), glm::vec3(2.0f * cubeHalf)),
                             glm::vec3(0.5f), glm::vec3(0.0f), 1.0f));
    s.camera.position = {0.0f, 3.0f, 1.2f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 10.0f;
    s.ambient = glm::vec3(0.0f);
    PointLight l;
    l.position = {0.0f, 1.5f, 0.0f};
    l.range = 4.0f;
    l.intensity = 1.0f;
    l.spot = SpotCone{{0.0f, -1.0f, 0.0f}, 40.0f, 55.0f};
    s.pointLights.push_back(l);
    Scene shadowed = s;
    shadowed.pointLights[0].castsShadow = true;
    Rig plain(s), shaded(shadowed);
    const int w = 64, h = 48;
    const glm::dmat4 inv = glm::inverse(glm::dmat4(s.camera.projection(float(w) / float(h))) * glm::dmat4(s.camera.view()));
    const glm::dvec3 lo = glm::dvec3(cubeCentre - cubeHalf), hi = glm::dvec3(cubeCentre + cubeHalf);
    const glm::dvec3 eye(s.camera.position), light(l.position);
    auto blocked = [&](glm::dvec3 p) { return test::segmentHitsBox(p, light, lo, hi); };
    for (LocalLightMethod m : {LocalLightMethod::Fullscreen, LocalLightMethod::Tiled, LocalLightMethod::Clustered}) {
        const std::vector<float> ref = plain.renderHdr(smallSettings(m));
        const std::vector<float> img = shaded.renderHdr(smallSettings(m));
        int dark = 0, lit = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                double nx = (x + 0.5) / w * 2.0 - 1.0, ny = (y + 0.5) / h * 2.0 - 1.0;
                glm::dvec4 a = inv * glm::dvec4(nx, ny, -1.0, 1.0), b = inv * glm::dvec4(nx, ny, 1.0, 1.0);
                glm::dvec3 p0 = glm::dvec3(a) / a.w, p1 = glm::dvec3(b) / b.w;
                glm::dvec3 p = p0 + (-p0.y / (p1.y - p0.y)) * (p1 - p0);
                if (test::segmentHitsBox(eye, p, lo - 0.03, hi + 0.03)) continue;  // the camera sees the cube here
                int hits = 0;
                for (int k = 0; k < 9; ++k) hits += blocked(p + 0.03 * glm::dvec3(k % 3 - 1, 0, k / 3 - 1)) ? 1 : 0;
                const size_t i = (size_t(y) * w + x) * 4;
                if (hits == 9) {
                    EXPECT_LE(img[i + 1], 1e-3 * ref[i + 1] + 1e-7) << localLightMethodName(m) << " shadowed " << x << "," << y;
                    if (ref[i + 1] > 1e-3f) ++dark;
                } else if (hits == 0) {
                    EXPECT_NEAR(img[i + 1], ref[i + 1], 2e-3 * ref[i + 1] + 1e-6) << localLightMethodName(m) << " lit " << x << "," << y;
                    if (ref[i + 1] > 1e-3f) ++lit;
                }
            }
        EXPECT_GT(dark, 20) << localLightMethodName(m) << ": the shadow is in view";
        EXPECT_GT(lit, 200) << localLightMethodName(m);
    }
    // The pass exists only for a spot that casts a shadow.
    auto passes = [](const Scene& scene) {
        RenderSettings r = smallSettings(LocalLightMethod::Tiled);
        FrameData f = makeFrameData(scene, r, 0.0f);
        fg::FrameGraph graph;
        PassStates states;
        buildFrameGraph(graph, states, f);
        graph.compile();
        std::set<std::string> runs;
        for (const fg::PassDecision& d : graph.explain())
            if (d.runs) runs.insert(d.name);
        return runs;
    };
    EXPECT_TRUE(passes(shadowed).count("spot_shadows"));
    EXPECT_FALSE(passes(s).count("spot_shadows"));
}

}  // namespace
