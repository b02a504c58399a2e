// Bloom and toon without GL: kernel weights, fp16 rounding, settings resolution, the frame
// graph's shape, and CPU-reference properties.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "engine/core/error.hpp"
#include "engine/post/post_config.hpp"
#include "engine/post/post_math.hpp"
#include "engine/post/post_reference.hpp"
#include "frame/frame_builder.hpp"

using namespace lp;

namespace {

Scene postScene() {
    Scene s;
    ModelInstance m;
    m.name = "box";
    m.mesh.boundsMin = glm::vec3(-1);
    m.mesh.boundsMax = glm::vec3(1);
    s.models.push_back(m);
    s.directionalLights.push_back(DirectionalLight{});
    return s;
}

fg::FrameGraph buildFor(const Scene& scene, const RenderSettings& settings) {
    FrameData frame = makeFrameData(scene, settings, 0.0f);
    fg::FrameGraph g;
    PassStates passes;
    buildFrameGraph(g, passes, frame);
    g.compile();
    return g;
}

std::vector<std::string> liveOf(const fg::FrameGraph& g) { return g.executionOrder(); }
bool has(const std::vector<std::string>& v, const std::string& s) { return std::find(v.begin(), v.end(), s) != v.end(); }

}  // namespace

// Bound: w0 + 2 sum w_i = 1 within 1e-6 for every kernel 1..101; kernel 1 is the identity; the
// weights fall off monotonically; kernels outside 1..101 are an error.
TEST(PostWeights, NormalisedMonotoneAndRangeChecked) {
    for (int k = 1; k <= post::kMaxKernel; ++k) {
        const std::vector<float> w = post::gaussianWeights(k);
        ASSERT_EQ(int(w.size()), k / 2 + 1);
        double sum = w[0];
        for (size_t i = 1; i < w.size(); ++i) {
            sum += 2.0 * w[i];
            EXPECT_LT(w[i], w[i - 1]);
        }
        EXPECT_NEAR(sum, 1.0, 1e-6) << k;
    }
    EXPECT_EQ(post::gaussianWeights(1), std::vector<float>{1.0f});
    EXPECT_THROW(post::gaussianWeights(0), Error);
    EXPECT_THROW(post::gaussianWeights(102), Error);
}

// fp16 round-to-nearest-even, as RGBA16F stores: exact cases of IEEE 754 binary16.
TEST(PostHalf, RoundsLikeBinary16) {
    EXPECT_EQ(post::roundToHalf(1.0f), 1.0f);
    EXPECT_EQ(post::roundToHalf(1.0f + 1.0f / 2048.0f), 1.0f);                  // tie -> even
    EXPECT_EQ(post::roundToHalf(1.0f + 3.0f / 2048.0f), 1.0f + 2.0f / 1024.0f);  // tie -> even (up)
    EXPECT_EQ(post::roundToHalf(0.1f), 0.0999755859375f);
    EXPECT_EQ(post::roundToHalf(65504.0f), 65504.0f);
    EXPECT_TRUE(std::isinf(post::roundToHalf(70000.0f)));
    EXPECT_EQ(post::roundToHalf(1e-8f), 0.0f);  // below half the smallest subnormal (2^-25)
}

// Flags win over the scene; unset flags take effects.bloom / effects.toon; the bloom view turns
// the bloom on so there is something to show.
TEST(PostConfig, FlagsOverrideTheScene) {
    Effects fx;
    fx.bloom.enabled = true;
    fx.bloom.kernelSize = 33;
    fx.bloom.threshold = 2.0f;
    fx.toon.levels = 6;
    PostSettings s;
    post::PostConfig c = post::resolvePostConfig(fx, s, 50.0f);
    EXPECT_TRUE(c.bloom);
    EXPECT_FALSE(c.toon);
    EXPECT_EQ(c.bloomParams.kernel, 33);
    EXPECT_EQ(c.bloomParams.threshold, 2.0f);
    EXPECT_EQ(c.toonParams.levels, 6);
    EXPECT_EQ(c.toonParams.farDepth, 50.0f);
    s.bloom = false;
    s.toon = true;
    s.bloomKernel = 5;
    s.toonLevels = 3;
    c = post::resolvePostConfig(fx, s, 50.0f);
    EXPECT_FALSE(c.bloom);
    EXPECT_TRUE(c.toon);
    EXPECT_EQ(c.bloomParams.kernel, 5);
    EXPECT_EQ(c.toonParams.levels, 3);
    s.bloomOnly = true;
    EXPECT_TRUE(post::resolvePostConfig(fx, s, 50.0f).bloom);
    EXPECT_EQ(post::parseBloomMethod("mip-chain"), post::BloomMethod::MipChain);
    EXPECT_FALSE(post::parseBloomMethod("box").has_value());
    EXPECT_EQ(post::parseBackend("glsl"), PostSettings::Backend::Glsl);
}

// The kernel is in output pixels: at render scale S the blur spans S x as many of its own pixels.
TEST(PostConfig, BloomKernelFollowsRenderScale) {
    EXPECT_EQ(post::bloomKernelAtRenderSize(25, 1920, 1920), 25);
    EXPECT_EQ(post::bloomKernelAtRenderSize(25, 960, 1920), 13);   // 12.5 rounds up
    EXPECT_EQ(post::bloomKernelAtRenderSize(100, 480, 1920), 25);
    EXPECT_EQ(post::bloomKernelAtRenderSize(1, 480, 1920), 1);     // never below one tap
    EXPECT_EQ(post::bloomKernelAtRenderSize(5, 0, 0), 5);          // degenerate sizes: unchanged
}

// Bloom and toon are in the graph only when enabled, sit between sky and tone map, and a G-buffer
// view culls them; the bloom view keeps the bloom pass and culls the composite and toon.
TEST(PostGraph, PassesAppearWhenEnabledAndCullWithViews) {
    Scene scene = postScene();
    RenderSettings s;
    s.width = 64;
    s.height = 48;
    EXPECT_FALSE(buildFor(scene, s).hasPass("bloom"));
    scene.effects.bloom.enabled = true;
    s.post.toon = true;
    std::vector<std::string> order = liveOf(buildFor(scene, s));
    auto pos = [&](const std::string& n) { return std::find(order.begin(), order.end(), n) - order.begin(); };
    ASSERT_TRUE(has(order, "bloom") && has(order, "bloom_composite") && has(order, "toon")) << order.size();
    EXPECT_LT(pos("sky"), pos("bloom"));
    EXPECT_LT(pos("bloom_composite"), pos("toon"));
    EXPECT_LT(pos("toon"), pos("tonemap"));
    s.view = DebugView::Normals;
    order = liveOf(buildFor(scene, s));
    EXPECT_FALSE(has(order, "bloom") || has(order, "toon"));
    s.view = DebugView::Final;
    s.post.bloomOnly = true;
    fg::FrameGraph g = buildFor(scene, s);
    EXPECT_TRUE(g.isLive("bloom"));
    EXPECT_FALSE(g.isLive("bloom_composite"));
    EXPECT_FALSE(g.isLive("toon"));
}

// CPU-reference property: the separable bloom of one bright texel (threshold 0) is the outer
// product of the 1D weights, so it sums to the texel's value (interior; float rounding, 1e-5).
TEST(PostReference, SeparableImpulseKeepsEnergy) {
    ImageF img;
    img.width = 64;
    img.height = 48;
    img.rgba.assign(64 * 48 * 4, 0.0f);
    img.rgba[(size_t(24) * 64 + 32) * 4] = 10.0f;
    post::BloomParams p;
    p.threshold = 0.0f;
    p.knee = 0.0f;
    p.kernel = 25;
    ImageF b = post::bloomBuffer(img, p, post::Storage::Float);
    double sum = 0.0;
    for (size_t i = 0; i < b.rgba.size(); i += 4) sum += b.rgba[i];
    EXPECT_NEAR(sum, 10.0, 1e-4);
    const std::vector<float> w = post::gaussianWeights(25);
    EXPECT_NEAR(b.rgba[(size_t(24) * 64 + 32) * 4], 10.0 * w[0] * w[0], 1e-5);
}
