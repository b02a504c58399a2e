// Auto exposure on the driver against its CPU reference and the analytic answer.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "engine/graph/texture_pool.hpp"
#include "engine/scene/scene_loader.hpp"
#include "frame/renderer.hpp"
#include "passes/auto_exposure_pass.hpp"
#include "tests/gl/gl_fixture.hpp"

using namespace lp;

namespace {
// Runs the auto_exposure pass over a `width` x `height` HDR image of grey radiances `grey(x, y)`.
template <class Grey>
float autoExposureOf(int width, int height, Grey grey, std::vector<float>* luminances = nullptr) {
    std::vector<float> rgba(size_t(width) * height * 4);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float g = grey(x, y);
            float* px = &rgba[(size_t(y) * width + x) * 4];
            px[0] = px[1] = px[2] = g;
            px[3] = 1.0f;
            if (luminances) luminances->push_back(g);
        }
    gl::Texture hdr = gl::makeTexture2D(GL_RGBA32F, width, height, 1, "test.hdr");
    glTextureSubImage2D(hdr.id(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, rgba.data());
    Scene scene;
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    FrameData frame = makeFrameData(scene, settings, 0.0f);
    gl::ShaderLibrary shaders;
    frame.shaders = &shaders;
    fg::FrameGraph graph;
    fg::TexturePool pool;
    AutoExposurePass state;
    const fg::ResourceId in = graph.importTexture("hdr", {width, height, GL_RGBA32F}, hdr.id());
    const fg::ResourceId exposure = addAutoExposurePass(graph, state, frame, in);
    graph.markOutput(exposure);
    graph.compile();
    graph.execute(pool);
    float ev = 0.0f;
    glGetTextureImage(graph.outputTexture(exposure), 0, GL_RED, GL_FLOAT, sizeof ev, &ev);
    return ev;
}
}  // namespace

TEST(AutoExposure, UniformRadiancePutOnMiddleGrey) {
    // L = 0.18 x 2^k needs -k stops; the fixed-point place in the bin keeps it within 0.01 EV.
    for (int k : {-10, -3, 0, 2, 7}) {
        const float l = 0.18f * std::exp2(float(k));
        EXPECT_NEAR(autoExposureOf(64, 48, [&](int, int) { return l; }), -float(k), 0.01f) << "L " << l;
    }
}

TEST(AutoExposure, MatchesTheCpuReferenceOnMixedImages) {
    // Half the pixels 64x darker: the window (40%..95% of pixels) takes 10% dark and 45% bright.
    std::vector<float> lum;
    const float gpu = autoExposureOf(128, 64, [](int x, int) { return x < 64 ? 0.05f : 3.2f; }, &lum);
    const double cpu = autoExposureEvReference(lum);
    EXPECT_NEAR(gpu, cpu, 0.01);
    const double expected = std::log2(0.18) - (0.10 * std::log2(0.05) + 0.45 * std::log2(3.2)) / 0.55;
    EXPECT_NEAR(cpu, expected, 0.02);
    // A ramp over 20 stops, with black pixels (not counted) and NaN / Inf ones.
    lum.clear();
    const float ramp = autoExposureOf(
        200, 100,
        [](int x, int y) {
            if (x == 0) return 0.0f;
            if (x == 1 && y == 0) return std::nanf("");
            if (x == 2 && y == 0) return std::numeric_limits<float>::infinity();
            return std::exp2(-10.0f + 20.0f * float(x) / 200.0f + 0.001f * float(y));
        },
        &lum);
    EXPECT_NEAR(ramp, autoExposureEvReference(lum), 0.01);
    // A black frame: nothing counted, exposure 0.
    EXPECT_EQ(autoExposureOf(16, 16, [](int, int) { return 0.0f; }), 0.0f);
}

TEST(AutoExposure, TheRendererUsesItAndManualIsCompensation) {
    // The same scene twice as bright gives the same displayed image under auto exposure.
    Scene scene = loadScene(test::repoPath("scenes/cornell.json"));
    RenderSettings settings;
    settings.width = 64;
    settings.height = 48;
    settings.autoExposure = true;
    auto render = [&](float ambientScale, float compensation) {
        Scene s = scene;
        for (auto& l : s.directionalLights) l.intensity *= ambientScale;
        for (auto& l : s.pointLights) l.intensity *= ambientScale;
        s.ambient *= ambientScale;
        s.environment.intensity *= ambientScale;
        s.environment.color *= ambientScale;
        Renderer r(s);
        settings.exposureEV = compensation;
        r.render(settings);
        EXPECT_TRUE(r.graph().isLive("auto_exposure"));
        return r.readDisplay();
    };
    const Image8 once = render(1.0f, 0.0f), twice = render(2.0f, 0.0f), brighter = render(1.0f, 1.0f);
    double diff = 0.0, lift = 0.0;
    for (size_t i = 0; i < once.rgba.size(); i += 4) {
        diff = std::max(diff, std::abs(double(once.rgba[i + 1]) - double(twice.rgba[i + 1])));
        lift += double(brighter.rgba[i + 1]) - double(once.rgba[i + 1]);
    }
    EXPECT_LE(diff, 2.0);  // exposure compensates the doubled light (fp16 rounding aside)
    EXPECT_GT(lift, 0.0);  // +1 EV of compensation brightens
}
