// Motion vectors (gbuffer.velocity) against a CPU reprojection from depth and the two frames'
// matrices; jitter moves the image but not the velocity; the velocity view's colours.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/graph/texture_pool.hpp"
#include "engine/render/local_lights.hpp"
#include "engine/render/motion.hpp"
#include "engine/render/scene_gpu.hpp"
#include "engine/scene/primitives.hpp"
#include "frame/renderer.hpp"
#include "passes/gbuffer_pass.hpp"
#include "passes/local_light_pass.hpp"
#include "tests/gl/gl_fixture.hpp"
#include "tests/gl/render_fixture.hpp"

namespace lp {
namespace {

using test::VelocityImage;

// A floor, a cube and a sphere at different depths, open sky behind them.
Scene motionScene() {
    Scene s;
    auto add = [&](const char* name, MeshData mesh, glm::mat4 transform) {
        ModelInstance m;
        m.name = name;
        m.mesh = std::move(mesh);
        m.transform = transform;
        s.models.push_back(std::move(m));
    };
    add("floor", makePlane(1.0f, 2), glm::scale(glm::mat4(1.0f), glm::vec3(6.0f)));
    add("cube", makeCube(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(-0.8f, 0.5f, -1.0f)));
    add("sphere", makeSphere(0.6f, 24, 12), glm::translate(glm::mat4(1.0f), glm::vec3(0.9f, 0.6f, 0.5f)));
    s.camera.position = {0.0f, 1.5f, 4.0f};
    s.camera.target = {0.0f, 0.5f, 0.0f};
    s.camera.fovYDegrees = 50.0f;
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 30.0f;
    return s;
}

// Frame `current` of `scene` (camera as given) with `previous` as the frame before it.
FrameData frameAfter(const Scene& scene, const RenderSettings& settings, const FrameData* previous, glm::vec2 jitter,
                     float time) {
    FrameData f = makeFrameData(scene, settings, time);
    applyMotion(f, previous ? motionHistoryOf(*previous) : MotionHistory{}, jitter);
    return f;
}

// The CPU reference at every pixel: the surface point from the pixel's centre and its depth through
// the current (jittered) projection, reprojected with the unjittered current and previous matrices;
// the background as a direction at infinity. Returns the largest error in output pixels.
double largestVelocityErrorPixels(const VelocityImage& img, const FrameData& frame, int* surfacePixels) {
    const glm::dmat4 rasterInverse = glm::inverse(glm::dmat4(frame.projection) * glm::dmat4(frame.view));
    const glm::dmat4 current = glm::dmat4(frame.unjitteredProjection) * glm::dmat4(frame.view);
    const glm::dmat4 previous = glm::dmat4(frame.previousViewProjection);
    double worst = 0.0;
    *surfacePixels = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const double depth = img.depth[size_t(y) * size_t(img.width) + size_t(x)];
            const glm::dvec2 ndc((x + 0.5) / img.width * 2.0 - 1.0, (y + 0.5) / img.height * 2.0 - 1.0);
            glm::dvec2 expected;
            if (depth < 1.0) {
                const glm::dvec4 p = rasterInverse * glm::dvec4(ndc, depth * 2.0 - 1.0, 1.0);
                expected = velocityOfPoint(current, previous, glm::dvec3(p) / p.w);
                ++*surfacePixels;
            } else {  // a direction: translation does not move it
                const glm::dvec4 far = rasterInverse * glm::dvec4(ndc, 1.0, 1.0);
                const glm::dvec4 near = rasterInverse * glm::dvec4(ndc, -1.0, 1.0);
                const glm::dvec4 d(glm::dvec3(far) / far.w - glm::dvec3(near) / near.w, 0.0);
                const glm::dvec4 c = current * d, pr = previous * d;
                expected = 0.5 * (glm::dvec2(c) / c.w - glm::dvec2(pr) / pr.w);
            }
            const glm::dvec2 error = (glm::dvec2(img.at(x, y)) - expected) * glm::dvec2(frame.outputWidth, frame.outputHeight);
            worst = std::max(worst, glm::length(error));
        }
    return worst;
}

RenderSettings smallSettings() {
    RenderSettings s;
    s.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    s.autoExposure = false;       // and 0 EV
    s.width = 64;
    s.height = 48;
    return s;
}

// Tolerance: RG16F keeps 11 significant bits (a relative 2^-11 of a velocity up to about 0.1 uv, i.e.
// 0.003 px at 64 px) and the pixel's surface point is rebuilt from a 32-bit depth; 0.02 output
// pixels covers both with room and is far below any visible motion.
constexpr double kTolerancePixels = 0.02;

TEST(Motion, CameraTranslationMatchesReprojectionPerPixel) {
    Scene scene = motionScene();
    const RenderSettings settings = smallSettings();
    const FrameData first = frameAfter(scene, settings, nullptr, glm::vec2(0.0f), 0.0f);
    const glm::vec3 step(0.25f, 0.1f, -0.3f);  // the camera slides; its orientation stays
    scene.camera.position += step;
    scene.camera.target += step;
    const FrameData second = frameAfter(scene, settings, &first, glm::vec2(0.0f), 1.0f / 30.0f);
    ASSERT_TRUE(second.hasPrevious);
    const VelocityImage img = test::renderGBufferVelocity(scene, second);
    int surface = 0;
    EXPECT_LT(largestVelocityErrorPixels(img, second, &surface), kTolerancePixels);
    EXPECT_GT(surface, img.width * img.height / 2);  // most pixels are geometry
    // Not trivially zero: the nearer the surface, the larger its motion.
    float largest = 0.0f;
    for (const glm::vec2& v : img.velocity) largest = std::max(largest, glm::length(v * glm::vec2(64.0f, 48.0f)));
    EXPECT_GT(largest, 2.0f);
    // Sky is at infinity: a pure translation leaves it where it was.
    EXPECT_EQ(img.at(32, 47), glm::vec2(0.0f));
}

TEST(Motion, CameraRotationAndJitterMatchReprojectionIncludingTheBackground) {
    Scene scene = motionScene();
    const RenderSettings settings = smallSettings();
    const FrameData first = frameAfter(scene, settings, nullptr, glm::vec2(0.3f, -0.2f), 0.0f);
    const glm::mat4 yaw = glm::rotate(glm::mat4(1.0f), glm::radians(3.0f), glm::vec3(0, 1, 0));
    scene.camera.target = scene.camera.position + glm::vec3(yaw * glm::vec4(scene.camera.target - scene.camera.position, 0.0f));
    scene.camera.position += glm::vec3(0.05f, 0.0f, 0.0f);
    const FrameData second = frameAfter(scene, settings, &first, glm::vec2(-0.4f, 0.35f), 1.0f / 30.0f);
    const VelocityImage img = test::renderGBufferVelocity(scene, second);
    int surface = 0;
    EXPECT_LT(largestVelocityErrorPixels(img, second, &surface), kTolerancePixels);
    EXPECT_LT(surface, img.width * img.height);  // some sky is in view, and it moved
    EXPECT_GT(std::abs(img.at(32, 47).x * 64.0f), 1.0f);
}

TEST(Motion, StaticCameraGivesZeroVelocityEvenWithJitter) {
    const Scene scene = motionScene();
    const RenderSettings settings = smallSettings();
    const FrameData first = frameAfter(scene, settings, nullptr, glm::vec2(0.0f), 0.0f);
    const FrameData second = frameAfter(scene, settings, &first, glm::vec2(0.45f, -0.3f), 0.5f);
    for (const FrameData* f : {&first, &second}) {
        const VelocityImage img = test::renderGBufferVelocity(scene, *f);
        for (const glm::vec2& v : img.velocity) ASSERT_EQ(v, glm::vec2(0.0f));
    }
}

// Through the Renderer: it keeps the previous frame itself; jitter shifts the final image and the
// velocity view stays black (zero motion) while the camera stands still.
TEST(Motion, RendererJitterChangesTheImageButNotTheVelocity) {
    Scene scene = motionScene();
    scene.directionalLights.push_back(DirectionalLight{});
    RenderSettings settings = smallSettings();
    Renderer renderer(scene);
    renderer.render(settings, 0.0f, false);
    const Image8 plain = renderer.readDisplay();
    renderer.setJitterPixels({0.5f, 0.5f});
    renderer.render(settings, 0.1f, false);
    const Image8 jittered = renderer.readDisplay();
    EXPECT_NE(plain.rgba, jittered.rgba);
    settings.view = DebugView::Velocity;
    renderer.setJitterPixels({-0.25f, 0.4f});
    renderer.render(settings, 0.2f, false);
    EXPECT_TRUE(renderer.graph().explain().size() > 0);
    const Image8 velocity = renderer.readDisplay();
    for (size_t i = 0; i < velocity.rgba.size(); i += 4) {
        ASSERT_EQ(velocity.rgba[i], 0);
        ASSERT_EQ(velocity.rgba[i + 1], 0);
        ASSERT_EQ(velocity.rgba[i + 2], 0);
    }
    // The camera moves: the view lights up, brighter for the nearer surfaces.
    scene.camera.position.x += 0.2f;
    scene.camera.target.x += 0.2f;
    renderer.render(settings, 0.3f, false);
    const Image8 moving = renderer.readDisplay();
    int lit = 0;
    for (size_t i = 0; i < moving.rgba.size(); i += 4) lit += (moving.rgba[i] + moving.rgba[i + 1] + moving.rgba[i + 2]) > 0;
    EXPECT_GT(lit, int(moving.rgba.size() / 4) / 3);  // the geometry; the sky does not move under translation
    // A cut: the next frame has no previous one, so nothing moves.
    renderer.cutMotion();
    scene.camera.position.x += 0.2f;
    renderer.render(settings, 0.4f, false);
    const Image8 cut = renderer.readDisplay();
    for (size_t i = 0; i < cut.rgba.size(); i += 4) ASSERT_EQ(cut.rgba[i] + cut.rgba[i + 1] + cut.rgba[i + 2], 0);
}

// Only frames that read motion create the target: the final image of a still scene has none.
TEST(Motion, VelocityTargetExistsOnlyWhenSomethingReadsIt) {
    const Scene scene = motionScene();
    RenderSettings settings = smallSettings();
    auto hasVelocity = [&](DebugView view) {
        settings.view = view;
        FrameData frame = makeFrameData(scene, settings, 0.0f);
        fg::FrameGraph graph;
        PassStates passes;
        buildFrameGraph(graph, passes, frame);
        graph.compile();
        return graph.describe().find("gbuffer.velocity") != std::string::npos;
    };
    EXPECT_FALSE(hasVelocity(DebugView::Final));
    EXPECT_FALSE(hasVelocity(DebugView::Normals));
    EXPECT_TRUE(hasVelocity(DebugView::Velocity));
}

// ---- light globes -------------------------------------------------------------------------------

// motionScene with globes: an orbiting light (3 rad/s about +Y through (0, 1.2, 1)) and a still one,
// both in front of the geometry.
Scene globeScene() {
    Scene s = motionScene();
    s.lightGlobes = true;
    PointLight orbiting;
    orbiting.position = {0.7f, 1.2f, 1.0f};
    orbiting.orbitCenter = {0.0f, 1.2f, 1.0f};
    orbiting.orbitSpeed = 3.0f;
    orbiting.range = 6.0f;
    PointLight still;
    still.position = {-0.9f, 1.3f, 1.2f};
    still.range = 6.0f;
    s.pointLights = {orbiting, still};
    return s;
}

// The G-buffer (with velocity), a cleared HDR buffer and the globe pass; gbuffer.velocity as the
// globe pass leaves it.
VelocityImage renderGlobeVelocity(const Scene& scene, FrameData frame) {
    SceneGpu gpu(scene);
    gl::ShaderLibrary shaders;
    frame.gpu = &gpu;
    frame.shaders = &shaders;
    GBufferPass gbufferState;
    LocalLightPass lightState;
    fg::FrameGraph graph;
    fg::TexturePool pool;
    GBufferChannels channels;
    channels.velocity = true;
    GBuffer g = addGBufferPass(graph, gbufferState, frame, channels);
    const fg::ResourceId gbufferVelocity = g.velocity;
    struct HdrData {
        fg::ResourceId hdr;
    };
    const fg::ResourceId hdr = graph.addPass<HdrData>(
        "test_hdr", fg::PassKind::Raster,
        [&](fg::PassBuilder& b, HdrData& d) {
            d.hdr = b.create("hdr", {frame.width, frame.height, GL_RGBA16F}, fg::Usage::Transfer);
        },
        [](const HdrData& d, const fg::PassResources& res) {
            const float zero[4] = {0, 0, 0, 0};
            glClearTexImage(res.texture(d.hdr), 0, GL_RGBA, GL_FLOAT, zero);
        }).hdr;
    addLocalLightOverlayPasses(graph, lightState, frame, g, hdr, importLocalLightRecords(graph, lightState, frame, {}));
    EXPECT_NE(g.velocity.version, gbufferVelocity.version);  // the globes wrote a new version
    graph.markOutput(g.velocity);
    graph.compile();
    graph.execute(pool);
    gl::checkErrors("globe velocity test frame");
    VelocityImage out;
    out.width = frame.width;
    out.height = frame.height;
    const size_t n = size_t(frame.width) * size_t(frame.height);
    out.velocity.resize(n);
    glGetTextureImage(graph.outputTexture(g.velocity), 0, GL_RG, GL_FLOAT, GLsizei(n * sizeof(glm::vec2)),
                      out.velocity.data());
    return out;
}

// The expected motion at the pixel that holds a globe's centre now: the globe's surface point under
// that pixel's centre (a ray against the sphere of radius 0.04 x range, the globe's size), which
// moves rigidly with the light from its position at the previous frame's time.
struct GlobeExpectation {
    glm::ivec2 pixel;
    glm::dvec2 velocity;    // uv_current - uv_previous
    glm::dvec2 cameraOnly;  // the same surface point held still: the camera's motion alone
};
GlobeExpectation expectGlobe(const FrameData& frame, const PointLight& light) {
    const glm::dmat4 current = glm::dmat4(frame.unjitteredProjection) * glm::dmat4(frame.view);
    const glm::dmat4 previous(frame.previousViewProjection);
    const glm::dvec3 centre(orbitPosition(light, frame.time));
    const glm::dvec3 before(orbitPosition(light, frame.previousTime));
    const glm::dvec4 c = glm::dmat4(frame.projection) * glm::dmat4(frame.view) * glm::dvec4(centre, 1.0);  // rasterised
    GlobeExpectation e;
    e.pixel = glm::ivec2(glm::floor((glm::dvec2(c) / c.w * 0.5 + 0.5) * glm::dvec2(frame.width, frame.height)));
    const glm::dmat4 rasterInverse = glm::inverse(glm::dmat4(frame.projection) * glm::dmat4(frame.view));
    const glm::dvec2 ndc((e.pixel.x + 0.5) / frame.width * 2.0 - 1.0, (e.pixel.y + 0.5) / frame.height * 2.0 - 1.0);
    const glm::dvec4 n = rasterInverse * glm::dvec4(ndc, -1.0, 1.0), f = rasterInverse * glm::dvec4(ndc, 1.0, 1.0);
    const glm::dvec3 origin = glm::dvec3(n) / n.w, dir = glm::normalize(glm::dvec3(f) / f.w - origin);
    const double radius = 0.04 * light.range;
    const glm::dvec3 oc = origin - centre;
    const double bHalf = glm::dot(oc, dir), disc = bHalf * bHalf - (glm::dot(oc, oc) - radius * radius);
    EXPECT_GT(disc, 0.0);
    const glm::dvec3 p = origin + (-bHalf - std::sqrt(std::max(disc, 0.0))) * dir;
    // The moving point p(t) = p + (centre(t) - centre): the previous matrix composed with that shift.
    e.velocity = velocityOfPoint(current, previous * glm::translate(glm::dmat4(1.0), before - centre), p);
    e.cameraOnly = velocityOfPoint(current, previous, p);
    return e;
}

// An orbiting light's globe carries the orbit's motion (plus the camera's), a still light's the
// camera's alone, measured at each globe's centre pixel against the CPU reference. Jittered frames:
// the velocity stays unjittered.
TEST(Motion, LightGlobesWriteTheirOrbitMotion) {
    Scene scene = globeScene();
    RenderSettings settings;
    settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    settings.autoExposure = false;       // and 0 EV
    settings.width = 96;
    settings.height = 72;
    const FrameData first = frameAfter(scene, settings, nullptr, glm::vec2(0.3f, -0.2f), 0.5f);
    scene.camera.position += glm::vec3(0.1f, 0.05f, 0.0f);
    scene.camera.target += glm::vec3(0.1f, 0.05f, 0.0f);
    const FrameData second = frameAfter(scene, settings, &first, glm::vec2(-0.25f, 0.4f), 0.6f);
    ASSERT_TRUE(second.hasPrevious);
    const VelocityImage img = renderGlobeVelocity(scene, second);
    const glm::dvec2 size(second.outputWidth, second.outputHeight);
    const GlobeExpectation orbiting = expectGlobe(second, scene.pointLights[0]);
    const GlobeExpectation still = expectGlobe(second, scene.pointLights[1]);
    // RG16F and the icosphere's flat faces against the true sphere: 0.05 output pixels.
    const double tolerance = 0.05;
    const glm::dvec2 got(img.at(orbiting.pixel.x, orbiting.pixel.y));
    EXPECT_LT(glm::length((got - orbiting.velocity) * size), tolerance)
        << "got " << got.x * size.x << ", " << got.y * size.y << " px, expected " << orbiting.velocity.x * size.x
        << ", " << orbiting.velocity.y * size.y;
    EXPECT_GT(glm::length((orbiting.velocity - orbiting.cameraOnly) * size), 2.0);  // the orbit shows
    const glm::dvec2 gotStill(img.at(still.pixel.x, still.pixel.y));
    EXPECT_LT(glm::length((gotStill - still.cameraOnly) * size), tolerance);
    EXPECT_GT(glm::length(still.cameraOnly * size), 0.5);  // the camera moved
    // Without a previous frame every globe stands still.
    const VelocityImage cut = renderGlobeVelocity(scene, frameAfter(scene, settings, nullptr, glm::vec2(0.0f), 0.6f));
    for (const glm::vec2& v : cut.velocity) ASSERT_EQ(v, glm::vec2(0.0f));
}

// Through the frame builder: motion blur runs for an orbiting light's globe under a still camera, and
// the globes write velocity before the blur reads it.
TEST(Motion, MotionBlurRunsForMovingGlobesUnderAStillCamera) {
    const Scene scene = globeScene();
    RenderSettings settings = smallSettings();
    settings.motionBlur.enabled = true;
    Renderer renderer(scene);
    renderer.render(settings, 0.5f, false);
    renderer.render(settings, 0.6f, false);
    const std::vector<std::string> order = renderer.graph().executionOrder();
    const auto at = [&](const char* name) { return std::find(order.begin(), order.end(), name) - order.begin(); };
    ASSERT_LT(at("light_globes"), std::ptrdiff_t(order.size()));
    EXPECT_LT(at("light_globes"), at("motion_blur_tiles"));
    EXPECT_LT(at("motion_blur_tiles"), std::ptrdiff_t(order.size()));
    bool readsGlobeVelocity = false;  // the blur's tiles read the version the globes wrote
    for (const fg::PassReport& r : renderer.graph().report())
        if (r.name == "motion_blur_tiles")
            for (const std::string& read : r.reads) readsGlobeVelocity |= read.rfind("gbuffer.velocity@", 0) == 0;
    EXPECT_TRUE(readsGlobeVelocity);
    Scene still = scene;
    still.pointLights[0].orbitSpeed = 0.0f;
    Renderer stillRenderer(still);
    stillRenderer.render(settings, 0.5f, false);
    stillRenderer.render(settings, 0.6f, false);
    for (const auto& d : stillRenderer.graph().explain())
        if (d.name == "motion_blur") EXPECT_FALSE(d.runs);
}

// shaders/common/velocity.glsl on the driver: the clip-space difference against the double reference,
// and the view's colours (direction as hue, length as brightness).
TEST(Motion, VelocityGlslMatchesReferenceAndColoursByDirection) {
    const glm::dmat4 vp = glm::dmat4(glm::perspective(0.8f, 1.5f, 0.1f, 20.0f)) *
                          glm::dmat4(glm::lookAt(glm::vec3(0, 1, 3), glm::vec3(0), glm::vec3(0, 1, 0)));
    const glm::dmat4 previous = vp * glm::translate(glm::dmat4(1.0), glm::dvec3(0.1, -0.05, 0.2));
    std::vector<glm::vec4> points = {{0, 0, 0, 0}, {0.5f, 0.2f, -1, 0}, {-1, 0.7f, 0.4f, 0}, {2, -0.3f, -3, 0}};
    std::vector<glm::vec4> inputs;  // x: index
    for (size_t i = 0; i < points.size(); ++i) inputs.push_back(glm::vec4(float(i), 0, 0, 0));
    // The points and matrices as literals (the harness sets no uniforms).
    auto literal = [](const glm::dmat4& m) {
        std::string text = "mat4(";
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) {
                char b[32];
                std::snprintf(b, sizeof b, "%s%.9g", (c || r) ? ", " : "", m[c][r]);
                text += b;
            }
        return text + ")";
    };
    std::string globals = "const mat4 VP = " + literal(vp) + ";\nconst mat4 PREV = " + literal(previous) +
                          ";\nconst vec3 P[4] = vec3[4](";
    for (size_t i = 0; i < points.size(); ++i) {
        char b[96];
        std::snprintf(b, sizeof b, "%svec3(%.9g, %.9g, %.9g)", i ? ", " : "", points[i].x, points[i].y, points[i].z);
        globals += b;
    }
    globals += ");\n";
    const auto out = test::runGlsl({"common/velocity.glsl"},
                                   "vec3 p = P[int(x.x)]; return vec4(velocityFromClip(VP * vec4(p, 1.0), PREV * vec4(p, 1.0)), 0.0, 0.0);",
                                   inputs, globals);
    for (size_t i = 0; i < points.size(); ++i) {
        const glm::dvec2 expected = velocityOfPoint(vp, previous, glm::dvec3(points[i]));
        EXPECT_NEAR(out[i].x, expected.x, 1e-5) << i;
        EXPECT_NEAR(out[i].y, expected.y, 1e-5) << i;
    }
    // Colours: right red, up yellow-green, left cyan, zero black; half the full scale is half as bright.
    const auto colour = test::runGlsl({"common/velocity.glsl"}, "return vec4(velocityViewColour(x.xy, 16.0), 0.0);",
                                      {{16, 0, 0, 0}, {0, 32, 0, 0}, {-16, 0, 0, 0}, {0, 0, 0, 0}, {8, 0, 0, 0}, {0, -16, 0, 0}});
    EXPECT_NEAR(colour[0].x, 1.0f, 1e-5);
    EXPECT_NEAR(colour[0].y, 0.0f, 1e-5);
    EXPECT_NEAR(colour[0].z, 0.0f, 1e-5);
    EXPECT_NEAR(colour[1].x, 0.5f, 1e-5);  // hue 1/4: yellow-green
    EXPECT_NEAR(colour[1].y, 1.0f, 1e-5);
    EXPECT_NEAR(colour[1].z, 0.0f, 1e-5);
    EXPECT_NEAR(colour[2].x, 0.0f, 1e-5);
    EXPECT_NEAR(colour[2].y, 1.0f, 1e-5);
    EXPECT_NEAR(colour[2].z, 1.0f, 1e-5);
    EXPECT_EQ(colour[3], glm::vec4(0.0f));
    EXPECT_NEAR(colour[4].x, 0.5f, 1e-5);
    EXPECT_NEAR(colour[5].x, 0.5f, 1e-5);  // hue 3/4: violet
    EXPECT_NEAR(colour[5].y, 0.0f, 1e-5);
    EXPECT_NEAR(colour[5].z, 1.0f, 1e-5);
}

}  // namespace
}  // namespace lp
