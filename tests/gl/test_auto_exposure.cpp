// Auto exposure on the driver against its CPU reference and the analytic answer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

#include "engine/graph/texture_pool.hpp"
#include "engine/render/exposure.hpp"
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
    // The left half 64x darker: the centre weights are mirror-symmetric, so each half holds half the
    // weight and the window (20%..70% of it) takes 30% dark and 20% bright.
    std::vector<float> lum;
    const float gpu = autoExposureOf(128, 64, [](int x, int) { return x < 64 ? 0.05f : 3.2f; }, &lum);
    const double cpu = autoExposureEvReference(lum, 128, 64);
    EXPECT_NEAR(gpu, cpu, 0.01);
    const double expected = std::log2(0.18) - (0.30 * std::log2(0.05) + 0.20 * std::log2(3.2)) / 0.50;
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
    EXPECT_NEAR(ramp, autoExposureEvReference(lum, 200, 100), 0.01);
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

// Which exposure a frame gets: a scene without "exposure" is metered by default; one with it is not,
// and shows exactly what --no-auto-exposure --exposure E shows on the scene without it; --auto-exposure
// and --no-auto-exposure override the scene; --exposure adds to the scene's fixed exposure.
TEST(AutoExposure, OnByDefaultUnlessTheSceneFixesTheExposure) {
    const Scene metered = loadScene(test::repoPath("scenes/cornell.json"));
    ASSERT_FALSE(metered.exposure.has_value());
    Scene fixed = metered;
    fixed.exposure = 1.5f;
    RenderSettings settings;
    settings.width = 64;
    settings.height = 48;
    EXPECT_TRUE(autoExposureOn(settings, metered));
    EXPECT_FALSE(autoExposureOn(settings, fixed));
    EXPECT_FLOAT_EQ(exposureEvBase(settings, fixed), 1.5f);
    settings.exposureEV = 0.5f;
    EXPECT_FLOAT_EQ(exposureEvBase(settings, fixed), 2.0f);
    EXPECT_FLOAT_EQ(exposureEvBase(settings, metered), 0.5f);  // the compensation
    settings.exposureEV = 0.0f;

    auto render = [&](const Scene& scene, const RenderSettings& s, bool expectMetered) {
        Renderer r(scene);
        r.render(s);
        EXPECT_EQ(r.graph().isLive("auto_exposure"), expectMetered);
        return r.readDisplay();
    };
    render(metered, settings, true);
    const Image8 fromScene = render(fixed, settings, false);
    RenderSettings manual = settings;
    manual.autoExposure = false;
    manual.exposureEV = 1.5f;
    const Image8 fromFlags = render(metered, manual, false);
    EXPECT_EQ(fromScene.rgba, fromFlags.rgba);
    RenderSettings forced = settings;
    forced.autoExposure = true;
    render(fixed, forced, true);
}

namespace {
// The names of the bundled scenes (scenes/*.json).
std::vector<std::string> bundledSceneNames() {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(test::repoPath("scenes")))
        if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

// The inverse of the default tone map and sRGB encoding of an 8-bit display value: the exposed
// radiance c with srgb((c / (c + 1))^1.2) = v.
double exposedRadiance(uint8_t code) {
    const double v = code / 255.0;
    const double linear = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
    const double x = std::pow(linear, 1.0 / 1.2);
    return x / std::max(1.0 - x, 1e-6);
}

class BundledSceneExposure : public ::testing::TestWithParam<std::string> {};
}  // namespace

// Every bundled scene, rendered as a user gets it (default settings, 192x108, a small IBL bake and
// shadow maps; the scene's own
// exposure, or auto exposure where it sets none), is exposed within 0.5 EV of middle grey on its main
// surfaces: the median, over the central half of the frame (width and height), of each pixel's EV
// against middle grey, log2(L / 0.18) of the exposed luminance read back from the displayed image
// (the default tone map and sRGB inverted per channel: the exposure-ev view's value, from what the
// user sees). The scenes that name ../shared/assets are skipped where it is absent.
TEST_P(BundledSceneExposure, MainSurfacesWithinHalfAStopOfMiddleGrey) {
    const std::string name = GetParam();
    const std::string path = test::repoPath("scenes/" + name + ".json");
    std::ifstream file(path);
    const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    if (text.find("shared/assets") != std::string::npos && !std::filesystem::exists(LIGHTPASS_SHARED_ASSETS))
        GTEST_SKIP() << name << " needs " << LIGHTPASS_SHARED_ASSETS;
    const Scene loaded = loadScene(path);
    RenderSettings settings;
    settings.width = 192;
    settings.height = 108;
    // Cheaper on a software rasteriser, the same exposure: a small IBL bake (the scene still says
    // whether IBL is on) and 512^2 shadow maps.
    settings.environment = test::smallIblBake(64);
    settings.environment.ibl.reset();
    settings.shadows.size = 512;
    Renderer r(loaded);
    r.render(settings);
    const Image8 img = r.readDisplay();
    std::vector<double> ev;
    for (int y = img.height / 4; y < img.height * 3 / 4; ++y)
        for (int x = img.width / 4; x < img.width * 3 / 4; ++x) {
            const uint8_t* px = &img.rgba[(size_t(y) * img.width + x) * 4];
            const double l = 0.2126 * exposedRadiance(px[0]) + 0.7152 * exposedRadiance(px[1]) +
                             0.0722 * exposedRadiance(px[2]);
            ev.push_back(std::log2(std::max(l, 1e-6) / 0.18));
        }
    std::nth_element(ev.begin(), ev.begin() + ev.size() / 2, ev.end());
    const double median = ev[ev.size() / 2];
    std::printf("  %s: main surfaces at %+.2f EV of middle grey (%s)\n", name.c_str(), median,
                autoExposureOn(settings, loaded) ? "auto exposure" : "the scene's exposure");
    EXPECT_LE(std::abs(median), 0.5) << name;
}

INSTANTIATE_TEST_SUITE_P(Scenes, BundledSceneExposure, ::testing::ValuesIn(bundledSceneNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                             std::string n = info.param;
                             std::replace(n.begin(), n.end(), '-', '_');
                             return n;
                         });
