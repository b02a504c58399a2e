// A bare model (models/pbr_spheres.glb: no lights of its own) rendered with the default settings is
// lit: by the bundled studio map through IBL, with the sky behind it, and by the key and fill light
// when the environment is removed (--env none) or IBL switched off (--brdf-only); the two are of
// the same order, neither dark nor doubled. The bake is small (llvmpipe); the rest is the default.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "engine/scene/scene_loader.hpp"
#include "frame/renderer.hpp"
#include "tests/gl/gl_fixture.hpp"

using namespace lp;

namespace {

constexpr int kWidth = 96, kHeight = 54;

RenderSettings defaults() {
    RenderSettings s;
    s.width = kWidth;
    s.height = kHeight;
    s.keepHdr = true;
    const EnvironmentSettings small = lp::test::smallIblBake(64);
    s.environment.cubeSize = small.cubeSize;
    s.environment.specularSize = small.specularSize;
    s.environment.specularSamples = small.specularSamples;
    s.environment.irradianceSize = small.irradianceSize;
    s.environment.irradianceSamples = small.irradianceSamples;
    s.environment.dfgSize = small.dfgSize;
    s.environment.dfgSamples = small.dfgSamples;
    return s;  // IBL unset: the scene's
}

double luminance(const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

// The model's pixels: those the frame without its sky pass left above zero (the background is 0).
std::vector<size_t> modelPixels(const ImageF& skyless) {
    std::vector<size_t> px;
    for (size_t i = 0; i < size_t(kWidth) * kHeight; ++i)
        if (luminance(&skyless.rgba[i * 4]) > 0.0) px.push_back(i);
    return px;
}

double meanLuminance(const ImageF& hdr, const std::vector<size_t>& pixels) {
    double sum = 0.0;
    for (size_t i : pixels) sum += luminance(&hdr.rgba[i * 4]);
    return pixels.empty() ? 0.0 : sum / double(pixels.size());
}

}  // namespace

// The default frame of the bare model runs the bake, IBL and the sky and no shadow map; the spheres
// (a tenth of the frame) average a radiance of 0.1 to 1 (the studio gives an upward surface an
// irradiance of about 3: a grey Lambertian surface of albedo 0.5 facing it shows 0.48). Without the
// environment (--env none), and with IBL off (--brdf-only), the key and fill light the same pixels
// to within a factor of 2.5 of that mean: neither doubled nor dark. No pixel is NaN or Inf.
TEST(ModelEnvironmentGl, BareModelIsLitByDefault) {
    Scene scene = sceneForModel(lp::test::repoPath("models/pbr_spheres.glb"));
    ASSERT_TRUE(scene.environment.ibl);
    Renderer r(scene);
    RenderSettings s = defaults();
    r.render(s, 0.0f, false);
    for (const char* pass : {"ibl_bake", "ibl", "sky"}) EXPECT_TRUE(r.graph().isLive(pass)) << pass;
    EXPECT_FALSE(r.graph().isLive("shadow_map_0"));
    for (float v : r.readHdr().rgba) ASSERT_TRUE(std::isfinite(v));

    s.disabledPasses.insert("sky");
    r.render(s, 0.0f, false);
    const ImageF studio = r.readHdr();
    const std::vector<size_t> model = modelPixels(studio);
    EXPECT_GT(model.size(), size_t(kWidth) * kHeight / 20);
    const double lit = meanLuminance(studio, model);
    EXPECT_GT(lit, 0.1);
    EXPECT_LT(lit, 1.0);

    RenderSettings brdfOnly = s;
    brdfOnly.environment.ibl = false;
    r.render(brdfOnly, 0.0f, false);
    EXPECT_TRUE(r.graph().isLive("shadow_map_0"));
    EXPECT_FALSE(r.graph().isLive("ibl"));
    const double keyFillNoIbl = meanLuminance(r.readHdr(), model);

    Scene bare = scene;
    replaceEnvironment(bare, {});
    Renderer rig(bare);
    rig.render(s, 0.0f, false);
    EXPECT_TRUE(rig.graph().isLive("shadow_map_0"));
    EXPECT_FALSE(rig.graph().isLive("ibl"));
    const double keyFill = meanLuminance(rig.readHdr(), model);
    std::printf("  spheres' mean radiance: studio %.4f, key and fill %.4f (without IBL %.4f), %zu pixels\n", lit,
                keyFill, keyFillNoIbl, model.size());
    EXPECT_NEAR(keyFill, keyFillNoIbl, 1e-3 * keyFill) << "the same lights either way";
    EXPECT_GT(keyFill, lit / 2.5);
    EXPECT_LT(keyFill, lit * 2.5);
}
