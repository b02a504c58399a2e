// Motion blur (passes/motion_blur_pass, McGuire et al. 2012) on made-up inputs: zero motion leaves
// the frame bit-exact; a bright square moving sideways spreads |v| x shutter pixels along the motion
// and not across it, and the mean radiance is kept within 1%.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numeric>

#include "engine/graph/texture_pool.hpp"
#include "engine/scene/primitives.hpp"
#include "frame/renderer.hpp"
#include "passes/motion_blur_pass.hpp"
#include "tests/gl/gl_fixture.hpp"

namespace lp {
namespace {

constexpr int kW = 96, kH = 48;

struct Inputs {
    std::vector<glm::vec4> hdr;       // rows bottom first
    std::vector<glm::vec2> velocity;  // uv per frame
    float depth = 0.5f;               // window depth everywhere
};

struct Inject {
    fg::ResourceId hdr, velocity, depth;
};

// Runs the three motion-blur passes on `in`; returns the blurred HDR buffer.
std::vector<glm::vec4> blur(const Inputs& in, float shutter, int samples) {
    Scene scene;
    RenderSettings settings;
    settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    settings.autoExposure = false;       // and 0 EV
    settings.width = kW;
    settings.height = kH;
    settings.motionBlur.enabled = true;
    settings.motionBlur.shutter = shutter;
    settings.motionBlur.samples = samples;
    FrameData frame = makeFrameData(scene, settings, 0.0f);
    gl::ShaderLibrary shaders;
    frame.shaders = &shaders;
    fg::FrameGraph graph;
    fg::TexturePool pool;
    MotionBlurPass state;
    const Inject& inject = graph.addPass<Inject>(
        "inject", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, Inject& d) {
            d.hdr = b.create("hdr", {kW, kH, GL_RGBA16F}, fg::Usage::Transfer);
            d.velocity = b.create("velocity", {kW, kH, GL_RG16F}, fg::Usage::Transfer);
            d.depth = b.create("depth", {kW, kH, GL_DEPTH_COMPONENT32F}, fg::Usage::Transfer);
        },
        [&in](const Inject& d, const fg::PassResources& res) {
            glTextureSubImage2D(res.texture(d.hdr), 0, 0, 0, kW, kH, GL_RGBA, GL_FLOAT, in.hdr.data());
            glTextureSubImage2D(res.texture(d.velocity), 0, 0, 0, kW, kH, GL_RG, GL_FLOAT, in.velocity.data());
            std::vector<float> depth(size_t(kW) * kH, in.depth);
            glTextureSubImage2D(res.texture(d.depth), 0, 0, 0, kW, kH, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
        });
    GBuffer g;
    g.velocity = inject.velocity;
    g.depth = inject.depth;
    const fg::ResourceId out = addMotionBlurPasses(graph, state, frame, g, inject.hdr);
    graph.markOutput(out);
    graph.compile();
    graph.execute(pool);
    std::vector<glm::vec4> px(size_t(kW) * kH);
    glGetTextureImage(graph.outputTexture(out), 0, GL_RGBA, GL_FLOAT, GLsizei(px.size() * sizeof(glm::vec4)), px.data());
    return px;
}

TEST(MotionBlur, ZeroMotionLeavesTheFrameBitExact) {
    Inputs in;
    in.hdr.resize(size_t(kW) * kH);
    in.velocity.assign(size_t(kW) * kH, glm::vec2(0.0f));
    // Values a 16-bit float holds exactly (multiples of 1/8 below 128), so they read back bit for bit.
    for (size_t i = 0; i < in.hdr.size(); ++i)
        in.hdr[i] = glm::vec4(float(i % 97) * 0.375f, float(i % 13) * 1.5f, float(i % 7) * 20.0f, 1.0f);
    // Motion under half a pixel everywhere counts as none.
    for (size_t i = 0; i < in.velocity.size(); i += 3) in.velocity[i] = glm::vec2(0.4f / kW, 0.0f);
    const std::vector<glm::vec4> out = blur(in, 1.0f, 16);
    for (size_t i = 0; i < out.size(); ++i) ASSERT_EQ(out[i], in.hdr[i]) << i;
}

// A 10 x 8 square of radiance 8 on black; everything moves 12 px to the right per frame.
Inputs movingSquare(float pixelsPerFrame) {
    Inputs in;
    in.hdr.assign(size_t(kW) * kH, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    in.velocity.assign(size_t(kW) * kH, glm::vec2(pixelsPerFrame / kW, 0.0f));
    for (int y = 20; y < 28; ++y)
        for (int x = 43; x < 53; ++x) in.hdr[size_t(y) * kW + x] = glm::vec4(8.0f, 8.0f, 8.0f, 1.0f);
    return in;
}

double meanRadiance(const std::vector<glm::vec4>& px) {
    double sum = 0.0;
    for (const glm::vec4& p : px) sum += p.x;
    return sum / double(px.size());
}

TEST(MotionBlur, MovingSquareSpreadsAlongTheMotionAndKeepsItsMeanRadiance) {
    const float speed = 12.0f, shutter = 1.0f;  // blur 12 px long: +-6 px around each pixel
    const Inputs in = movingSquare(speed);
    const std::vector<glm::vec4> out = blur(in, shutter, 32);
    auto at = [&](int x, int y) { return out[size_t(y) * kW + x].x; };
    // Across the motion nothing spreads: the rows above and below stay black.
    for (int x = 0; x < kW; ++x) {
        EXPECT_EQ(at(x, 19), 0.0f) << x;
        EXPECT_EQ(at(x, 28), 0.0f) << x;
    }
    // Along it: the streak reaches half the blur length (6 px) beyond each side, no further.
    for (int y = 20; y < 28; ++y) {
        EXPECT_EQ(at(43 - 8, y), 0.0f);
        EXPECT_EQ(at(52 + 8, y), 0.0f);
        EXPECT_GT(at(43 - 4, y), 0.1f);
        EXPECT_GT(at(52 + 4, y), 0.1f);
        EXPECT_LT(at(43, y), 8.0f * 0.9f);  // the square's own edge is no longer sharp
        float lit = 0.0f;
        for (int x = 0; x < kW; ++x) lit += at(x, y) > 0.05f ? 1.0f : 0.0f;
        EXPECT_GE(lit, 10.0f + 0.6f * speed * shutter);  // about 10 + 12 px wide
        EXPECT_LE(lit, 10.0f + 1.2f * speed * shutter + 1.0f);
    }
    // Mean radiance kept within 1%: the gather's weights are normalised per pixel, not per source
    // pixel, so it need not be exact; with one velocity everywhere the kernel is symmetric and the
    // measured ratio is 1.0000 to four digits.
    const double before = meanRadiance(in.hdr), after = meanRadiance(out);
    std::printf("mean radiance %.5f before, %.5f after (ratio %.5f)\n", before, after, after / before);
    EXPECT_NEAR(after, before, 0.01 * before);
    // Half the shutter, half the streak.
    const std::vector<glm::vec4> half = blur(in, 0.5f, 32);
    for (int y = 20; y < 28; ++y) {
        EXPECT_EQ(half[size_t(y) * kW + 43 - 5].x, 0.0f);
        EXPECT_GT(half[size_t(y) * kW + 43 - 2].x, 0.1f);
    }
    EXPECT_NEAR(meanRadiance(half), before, 0.01 * before);
}

// shaders/common/motion_blur.glsl on the driver: the half blur vector (shutter, clamp to K, NaN), and
// the weights' shapes.
TEST(MotionBlur, CommonMathMatchesThePaper) {
    const auto half = test::runGlsl({"common/motion_blur.glsl"},
                                    "return vec4(motionBlurHalfVector(x.xy, vec2(200.0, 100.0), x.z, 10.0), 0.0, 0.0);",
                                    {{0.05f, 0.0f, 0.5f, 0}, {0.0f, -0.1f, 1.0f, 0}, {1.0f, 1.0f, 1.0f, 0}, {0, 0, 1, 0}});
    EXPECT_NEAR(half[0].x, 0.5f * 0.5f * 0.05f * 200.0f, 1e-5);  // 2.5 px
    EXPECT_NEAR(half[1].y, -5.0f, 1e-5);                           // 0.5 x 0.1 x 100
    EXPECT_NEAR(std::hypot(half[2].x, half[2].y), 10.0f, 1e-4);    // clamped to K, direction kept
    EXPECT_NEAR(half[2].x / half[2].y, 2.0f, 1e-4);
    EXPECT_EQ(half[3], glm::vec4(0.0f));
    const auto w = test::runGlsl({"common/motion_blur.glsl"},
                                 "return vec4(motionBlurCone(x.x, x.y), motionBlurCylinder(x.x, x.y), "
                                 "motionBlurInFront(x.z, x.w, 0.02), motionBlurTap(0, 4, 0.0));",
                                 {{2, 4, 1.0f, 1.0f}, {5, 4, 1.1f, 1.0f}, {0, 0.1f, 0.9f, 1.0f}, {4, 4, 1.01f, 1.0f}});
    EXPECT_NEAR(w[0].x, 0.5f, 1e-6);   // cone: 1 - d / |V|
    EXPECT_NEAR(w[0].y, 1.0f, 1e-6);   // cylinder: 1 inside
    EXPECT_NEAR(w[0].z, 1.0f, 1e-6);   // same depth: in front
    EXPECT_NEAR(w[1].x, 0.0f, 1e-6);
    EXPECT_NEAR(w[1].y, 0.0f, 1e-6);   // beyond 1.05 |V|
    EXPECT_NEAR(w[1].z, 0.0f, 1e-6);   // 10% behind: not in front
    EXPECT_NEAR(w[2].x, 1.0f, 1e-6);   // |V| under half a pixel counts as half a pixel
    EXPECT_NEAR(w[2].z, 1.0f, 1e-6);
    EXPECT_NEAR(w[3].y, 0.5f, 1e-6);   // cylinder edge: half
    EXPECT_NEAR(w[3].z, 0.5f, 1e-6);   // 1% behind over a 2% soft extent
    EXPECT_NEAR(w[0].w, -0.6f, 1e-6);  // tap 0 of 4: mix(-1, 1, 1/5)
}

// Through the renderer: a still camera skips motion blur with its reason and the image is the same
// as without it; a moving camera runs it and changes the image; switched off, it passes the frame through.
TEST(MotionBlur, RendererSkipsItWhenNothingMovesAndRunsItWhenTheCameraDoes) {
    Scene scene;
    ModelInstance m;
    m.name = "sphere";
    m.mesh = makeSphere(0.5f, 24, 12);
    scene.models.push_back(std::move(m));
    scene.directionalLights.push_back(DirectionalLight{});
    scene.camera.position = {0, 0, 3};
    scene.camera.target = {0, 0, 0};
    RenderSettings settings;
    settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    settings.autoExposure = false;       // and 0 EV
    settings.width = 64;
    settings.height = 48;
    Renderer plain(scene), blurred(scene);
    RenderSettings on = settings;
    on.motionBlur.enabled = true;
    for (float t : {0.0f, 0.1f}) {
        plain.render(settings, t, false);
        blurred.render(on, t, false);
    }
    EXPECT_EQ(plain.readDisplay().rgba, blurred.readDisplay().rgba);
    bool skipped = false;
    for (const auto& d : blurred.graph().explain())
        if (d.name == "motion_blur") skipped = !d.runs && d.reason.find("did not move") != std::string::npos;
    EXPECT_TRUE(skipped);
    scene.camera.position.x += 0.3f;
    scene.camera.target.x += 0.3f;
    plain.render(settings, 0.2f, false);
    blurred.render(on, 0.2f, false);
    bool runs = false;
    for (const auto& d : blurred.graph().explain())
        if (d.name == "motion_blur") runs = d.runs;
    EXPECT_TRUE(runs);
    EXPECT_NE(plain.readDisplay().rgba, blurred.readDisplay().rgba);
    // Switched off (--disable-pass motion_blur, the panel's checkbox): the frame passes through, and
    // the tile passes that only fed it are culled.
    RenderSettings off = on;
    off.disabledPasses = {"motion_blur"};
    scene.camera.position.x += 0.3f;
    scene.camera.target.x += 0.3f;
    plain.render(settings, 0.3f, false);
    blurred.render(off, 0.3f, false);
    EXPECT_EQ(plain.readDisplay().rgba, blurred.readDisplay().rgba);
    EXPECT_FALSE(blurred.graph().isLive("motion_blur_tiles"));
}

}  // namespace
}  // namespace lp
