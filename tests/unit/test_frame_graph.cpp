// Frame-graph logic on synthetic passes and on the real frame builder (no GL: nothing executes).
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>

#include "engine/core/error.hpp"
#include "engine/graph/frame_graph.hpp"
#include "frame/frame_builder.hpp"

using namespace lp;
using fg::FrameGraph;
using fg::PassBuilder;
using fg::ResourceId;

namespace {
const fg::TextureDesc kDesc{64, 64, GL_RGBA16F};

std::vector<std::string> culledPasses(const FrameGraph& g) {
    std::vector<std::string> out;
    for (const auto& r : g.report())
        if (r.culled) out.push_back(r.name);
    return out;
}

std::string errorOf(FrameGraph& g) {
    try {
        g.compile();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}
}  // namespace

TEST(FrameGraph, OrdersByDependencyNotByInsertion) {
    FrameGraph g;
    // "present" is declared first and names its input by string: a forward reference.
    g.addPass("present", fg::PassKind::Compute, [](PassBuilder& b) { b.read("image", fg::Usage::Sampled); b.sideEffect(); }, nullptr);
    ResourceId a;
    g.addPass("producer", fg::PassKind::Compute, [&](PassBuilder& b) { a = b.create("a", kDesc, fg::Usage::ImageStore); }, nullptr);
    g.addPass("consumer", fg::PassKind::Compute, [&](PassBuilder& b) { b.read(a, fg::Usage::Sampled); b.create("image", kDesc, fg::Usage::ImageStore); }, nullptr);
    g.markOutput("image");
    g.compile();
    EXPECT_EQ(g.executionOrder(), (std::vector<std::string>{"producer", "consumer", "present"}));
    EXPECT_TRUE(culledPasses(g).empty());
}

TEST(FrameGraph, CullsPassWhoseWritesNobodyReads) {
    FrameGraph g;
    ResourceId a, b;
    g.addPass("A", fg::PassKind::Compute, [&](PassBuilder& p) { a = p.create("a", kDesc, fg::Usage::ImageStore); }, nullptr);
    g.addPass("B", fg::PassKind::Compute, [&](PassBuilder& p) { b = p.create("b", kDesc, fg::Usage::ImageStore); }, nullptr);  // read by nobody
    g.addPass("useB", fg::PassKind::Compute, [&](PassBuilder& p) { p.read(b, fg::Usage::Sampled); p.create("dead", kDesc, fg::Usage::ImageStore); }, nullptr);
    g.addPass("final", fg::PassKind::Compute, [&](PassBuilder& p) { p.read(a, fg::Usage::Sampled); p.create("out", kDesc, fg::Usage::ImageStore); }, nullptr);
    g.markOutput("out");
    g.compile();
    EXPECT_EQ(g.executionOrder(), (std::vector<std::string>{"A", "final"}));
    EXPECT_EQ(culledPasses(g), (std::vector<std::string>{"B", "useB"}));
    for (const auto& r : g.report())
        if (r.name == "useB") EXPECT_NE(r.reason.find("dead"), std::string::npos) << r.reason;
    for (const auto& r : g.resources())
        if (r.name == "b" || r.name == "dead") EXPECT_FALSE(r.live) << r.name;
}

TEST(FrameGraph, InPlaceWritesAreVersionedAndOrdered) {
    FrameGraph g;
    ResourceId hdr, hdr2, bloom;
    g.addPass("light", fg::PassKind::Compute, [&](PassBuilder& p) { hdr = p.create("hdr", kDesc, fg::Usage::ImageStore); }, nullptr);
    // bloom reads version 0 of hdr, before "local" writes version 1 in place.
    g.addPass("bloom", fg::PassKind::Compute, [&](PassBuilder& p) { p.read(hdr, fg::Usage::Sampled); bloom = p.create("bloom", kDesc, fg::Usage::ImageStore); }, nullptr);
    g.addPass("local", fg::PassKind::Compute, [&](PassBuilder& p) { hdr2 = p.write(hdr, fg::Usage::ImageLoadStore); }, nullptr);
    g.addPass("composite", fg::PassKind::Compute, [&](PassBuilder& p) { p.read(bloom, fg::Usage::Sampled); p.read(hdr2, fg::Usage::Sampled); p.create("out", kDesc, fg::Usage::ImageStore); }, nullptr);
    g.markOutput("out");
    g.compile();
    auto order = g.executionOrder();
    auto pos = [&](const std::string& n) { return std::find(order.begin(), order.end(), n) - order.begin(); };
    EXPECT_LT(pos("light"), pos("bloom"));
    EXPECT_LT(pos("bloom"), pos("local"));  // write-after-read: bloom must see version 0
    EXPECT_LT(pos("local"), pos("composite"));
    // Writing an old version a second time is refused.
    FrameGraph bad;
    ResourceId x;
    bad.addPass("p1", fg::PassKind::Compute, [&](PassBuilder& p) { x = p.create("x", kDesc, fg::Usage::ImageStore); }, nullptr);
    bad.addPass("p2", fg::PassKind::Compute, [&](PassBuilder& p) { p.write(x, fg::Usage::ImageLoadStore); }, nullptr);
    EXPECT_THROW(bad.addPass("p3", fg::PassKind::Compute, [&](PassBuilder& p) { p.write(x, fg::Usage::ImageLoadStore); }, nullptr), Error);
}

TEST(FrameGraph, InPlaceWriterKeepsItsProducerAlive) {
    FrameGraph g;
    ResourceId hdr;
    g.addPass("light", fg::PassKind::Compute, [&](PassBuilder& p) { hdr = p.create("hdr", kDesc, fg::Usage::ImageStore); }, nullptr);
    ResourceId hdr2;
    g.addPass("sky", fg::PassKind::Compute, [&](PassBuilder& p) { hdr2 = p.write(hdr, fg::Usage::ImageLoadStore); }, nullptr);
    g.markOutput(hdr2);
    g.compile();
    EXPECT_EQ(g.executionOrder(), (std::vector<std::string>{"light", "sky"}));
}

TEST(FrameGraph, CycleIsAClearError) {
    FrameGraph g;
    g.addPass("A", fg::PassKind::Compute, [&](PassBuilder& p) { p.read("y", fg::Usage::Sampled); p.create("x", kDesc, fg::Usage::ImageStore); }, nullptr);
    g.addPass("B", fg::PassKind::Compute, [&](PassBuilder& p) { p.read("x", fg::Usage::Sampled); p.create("y", kDesc, fg::Usage::ImageStore); }, nullptr);
    g.markOutput("y");
    std::string err = errorOf(g);
    EXPECT_NE(err.find("cycle"), std::string::npos) << err;
    EXPECT_NE(err.find("A"), std::string::npos) << err;
    EXPECT_NE(err.find("B"), std::string::npos) << err;
}

TEST(FrameGraph, ReadOfUnwrittenResourceIsAClearError) {
    FrameGraph g;
    g.addPass("A", fg::PassKind::Compute, [&](PassBuilder& p) { p.read("ghost", fg::Usage::Sampled); p.create("out", kDesc, fg::Usage::ImageStore); }, nullptr);
    g.markOutput("out");
    std::string err = errorOf(g);
    EXPECT_NE(err.find("'A' reads 'ghost'"), std::string::npos) << err;
}

TEST(FrameGraph, NoOutputIsAnError) {
    FrameGraph g;
    g.addPass("A", fg::PassKind::Compute, [&](PassBuilder& p) { p.create("out", kDesc, fg::Usage::ImageStore); }, nullptr);
    EXPECT_NE(errorOf(g).find("no output"), std::string::npos);
}

TEST(FrameGraph, LifetimesSpanFirstToLastUse) {
    FrameGraph g;
    ResourceId a, b;
    g.addPass("P0", fg::PassKind::Compute, [&](PassBuilder& p) { a = p.create("a", kDesc, fg::Usage::ImageStore); }, nullptr);
    g.addPass("P1", fg::PassKind::Compute, [&](PassBuilder& p) { p.read(a, fg::Usage::Sampled); b = p.create("b", kDesc, fg::Usage::ImageStore); }, nullptr);
    g.addPass("P2", fg::PassKind::Compute, [&](PassBuilder& p) { p.read(b, fg::Usage::Sampled); p.create("out", kDesc, fg::Usage::ImageStore); }, nullptr);
    g.markOutput("out");
    g.compile();
    for (const auto& r : g.resources()) {
        if (r.name == "a") EXPECT_EQ(std::make_pair(r.firstPass, r.lastPass), std::make_pair(0, 1));
        if (r.name == "b") EXPECT_EQ(std::make_pair(r.firstPass, r.lastPass), std::make_pair(1, 2));
        if (r.name == "out") EXPECT_EQ(r.lastPass, 3);  // outputs live past the last pass
    }
    EXPECT_NE(g.toDot().find("digraph"), std::string::npos);
    EXPECT_NE(g.describe().find("P1"), std::string::npos);
}

// The real frame: choosing a G-buffer debug view culls lighting and tone mapping by itself.
namespace {
Scene oneLightScene() {
    Scene s;
    ModelInstance m;
    m.name = "box";
    m.mesh.boundsMin = glm::vec3(-1);
    m.mesh.boundsMax = glm::vec3(1);
    s.models.push_back(m);
    s.directionalLights.push_back(DirectionalLight{});
    return s;
}

// The compiled graph of `scene` under `settings` (described only: nothing executes).
FrameGraph buildWith(const Scene& scene, const RenderSettings& settings) {
    FrameData frame = makeFrameData(scene, settings, 0.0f);
    FrameGraph g;
    PassStates passes;
    buildFrameGraph(g, passes, frame);
    g.compile();
    return g;
}

FrameGraph buildFor(const Scene& scene, DebugView view, bool keepHdr = false) {
    RenderSettings settings;
    settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    settings.autoExposure = false;       // and 0 EV
    settings.width = 320;
    settings.height = 200;
    settings.view = view;
    settings.keepHdr = keepHdr;
    return buildWith(scene, settings);
}
}  // namespace

TEST(FrameBuilder, FinalViewRunsLightingSkyAndToneMap) {
    Scene s = oneLightScene();
    FrameGraph g = buildFor(s, DebugView::Final);
    EXPECT_EQ(g.executionOrder(), (std::vector<std::string>{"gbuffer", "shadow_map_0", "ao_depth", "ao", "ao_blur", "ao_denoise", "global_lights", "sky", "tonemap"}));
    EXPECT_FALSE(g.hasPass("debug_view"));
}

// The default frame (RenderSettings{} but for its size): supersampled 2x2 (ssaa_downsample) and
// metered (auto_exposure: the scene sets no exposure); a G-buffer view is brought to the output
// size nearest-texel (upscale_debug).
TEST(FrameBuilder, DefaultFrameSupersamplesAndMeters) {
    Scene s = oneLightScene();
    RenderSettings settings;
    settings.width = 320;
    settings.height = 200;
    EXPECT_EQ(buildWith(s, settings).executionOrder(),
              (std::vector<std::string>{"gbuffer", "shadow_map_0", "ao_depth", "ao", "ao_blur", "ao_denoise", "global_lights", "sky",
                                        "ssaa_downsample", "auto_exposure", "tonemap"}));
    settings.view = DebugView::Normals;
    EXPECT_EQ(buildWith(s, settings).executionOrder(), (std::vector<std::string>{"gbuffer", "debug_view", "upscale_debug"}));
}

TEST(FrameBuilder, NormalsViewCullsLightingAndToneMap) {
    Scene s = oneLightScene();
    FrameGraph g = buildFor(s, DebugView::Normals);
    EXPECT_EQ(g.executionOrder(), (std::vector<std::string>{"gbuffer", "debug_view"}));
    EXPECT_FALSE(g.isLive("global_lights"));
    EXPECT_FALSE(g.isLive("tonemap"));
    EXPECT_FALSE(g.isLive("sky"));
}

TEST(FrameBuilder, EveryChannelViewReadsOnlyTheGBuffer) {
    Scene s = oneLightScene();
    for (DebugView v : allViews()) {
        if (v == DebugView::Final || v == DebugView::Lighting || isHdrView(v) || isShadingTermView(v)) continue;
        FrameGraph g = buildFor(s, v);
        // the environment views show the cubes / LUT, made by the bake in the first frame
        // the ao view shows the AO target, which the ao passes make from the G-buffer
        const std::vector<std::string> expected =
            isEnvironmentView(v) ? std::vector<std::string>{"ibl_bake", "gbuffer", "debug_view"}
            : v == DebugView::Ao ? std::vector<std::string>{"gbuffer", "ao_depth", "ao", "ao_blur", "ao_denoise", "debug_view"}
                                 : std::vector<std::string>{"gbuffer", "debug_view"};
        EXPECT_EQ(g.executionOrder(), expected) << viewName(v);
        bool texcoordLive = false, materialInputLive = false;
        for (const auto& r : g.resources()) {
            if (r.name == "gbuffer.texcoord") texcoordLive = r.live;
            if (r.name == "gbuffer.material_input") materialInputLive = r.live;
        }
        EXPECT_EQ(texcoordLive, v == DebugView::Texcoords) << viewName(v);
        EXPECT_EQ(materialInputLive, materialInputShown(v) != 0) << viewName(v);
    }
}

// The HDR views inspect the final HDR buffer in place of the tone map.
TEST(FrameBuilder, HdrViewsReplaceTheToneMap) {
    Scene s = oneLightScene();
    for (DebugView v : {DebugView::InvalidPixels, DebugView::ExposureEv}) {
        FrameGraph g = buildFor(s, v);
        EXPECT_EQ(g.executionOrder(), (std::vector<std::string>{"gbuffer", "shadow_map_0", "ao_depth", "ao", "ao_blur", "ao_denoise", "global_lights", "sky", "hdr_view"}))
            << viewName(v);
        EXPECT_FALSE(g.isLive("tonemap"));
    }
}

TEST(FrameBuilder, LightingViewSkipsDiffuseAndSky) {
    Scene s = oneLightScene();
    FrameGraph g = buildFor(s, DebugView::Lighting);
    EXPECT_EQ(g.executionOrder(), (std::vector<std::string>{"gbuffer", "shadow_map_0", "ao_depth", "ao", "ao_blur", "ao_denoise", "global_lights", "tonemap"}));
    for (const auto& r : g.report())
        if (r.name == "global_lights")
            EXPECT_EQ(std::count(r.reads.begin(), r.reads.end(), "gbuffer.diffuse"), 0);
}

TEST(FrameGraph, DisabledInPlacePassPassesItsInputThrough) {
    FrameGraph g;
    ResourceId hdr, hdr2;
    g.addPass("light", fg::PassKind::Compute, [&](PassBuilder& p) { hdr = p.create("hdr", kDesc, fg::Usage::ImageStore); }, nullptr);
    g.addPass("sky", fg::PassKind::Compute, [&](PassBuilder& p) { hdr2 = p.write(hdr, fg::Usage::ImageLoadStore); }, nullptr);
    g.addPass("tonemap", fg::PassKind::Compute, [&](PassBuilder& p) { p.read(hdr2, fg::Usage::Sampled); p.create("out", kDesc, fg::Usage::ImageStore); }, nullptr);
    g.markOutput("out");
    g.disablePass("sky");
    g.compile();
    EXPECT_EQ(g.executionOrder(), (std::vector<std::string>{"light", "tonemap"}));
    for (const auto& r : g.report()) {
        if (r.name == "sky") {
            EXPECT_TRUE(r.disabled);
            EXPECT_TRUE(r.culled);
            EXPECT_NE(r.reason.find("disabled"), std::string::npos);
        }
        if (r.name == "tonemap") EXPECT_EQ(r.reads, (std::vector<std::string>{"hdr"}));
    }
}

TEST(FrameGraph, DisabledCreatingPassClearsInsteadOfDrawing) {
    FrameGraph g;
    ResourceId a;
    bool drew = false;
    g.addPass("gbuf", fg::PassKind::Compute, [&](PassBuilder& p) { a = p.create("a", kDesc, fg::Usage::ImageStore); }, nullptr);
    g.addPass("light", fg::PassKind::Compute, [&](PassBuilder& p) { p.read(a, fg::Usage::Sampled); p.create("hdr", kDesc, fg::Usage::ImageStore); }, [&](const fg::PassResources&) { drew = true; });
    g.addPass("tonemap", fg::PassKind::Compute, [&](PassBuilder& p) { p.read("hdr", fg::Usage::Sampled); p.create("out", kDesc, fg::Usage::ImageStore); }, nullptr);
    g.markOutput("out");
    g.disablePass("light");
    g.compile();
    // light still runs (as a clear of hdr) but no longer reads the G-buffer, so gbuf is culled.
    EXPECT_EQ(g.executionOrder(), (std::vector<std::string>{"light", "tonemap"}));
    EXPECT_FALSE(g.isLive("gbuf"));
    EXPECT_FALSE(drew);
}

TEST(FrameBuilder, DisablingSkyRemovesItFromTheCompiledGraph) {
    Scene s = oneLightScene();
    RenderSettings settings;
    settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    settings.autoExposure = false;       // and 0 EV
    settings.width = 64;
    settings.height = 48;
    settings.disabledPasses = {"sky"};
    FrameData frame = makeFrameData(s, settings, 0.0f);
    FrameGraph g;
    PassStates passes;
    buildFrameGraph(g, passes, frame);
    g.compile();
    EXPECT_EQ(g.executionOrder(), (std::vector<std::string>{"gbuffer", "shadow_map_0", "ao_depth", "ao", "ao_blur", "ao_denoise", "global_lights", "tonemap"}));
}

// --disable-pass checks names against the frame's passes; a note on a pass (a shadow map's dropped
// cascades, named "shadow_map_0 cascades") is neither a pass to disable nor listed as one.
TEST(FrameBuilder, DisablePassNamesOnlyPasses) {
    Scene s = oneLightScene();
    RenderSettings settings;
    settings.width = 64;
    settings.height = 48;
    FrameData frame = makeFrameData(s, settings, 0.0f);
    FrameGraph g;
    PassStates passes;
    buildFrameGraph(g, passes, frame);
    g.skipPass("shadow_map_0 cascades", "the scene needs fewer");
    EXPECT_NO_THROW(checkDisabledPasses(g, {"sky"}));
    try {
        checkDisabledPasses(g, {"shadow_map_0 cascades"});
        ADD_FAILURE() << "a note on a pass was accepted as a pass";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("no such pass in this frame"), std::string::npos) << what;
        EXPECT_NE(what.find("gbuffer"), std::string::npos) << what;
        EXPECT_EQ(what.find("cascades"), what.rfind("cascades")) << "the note is listed as a pass: " << what;
    }
}

TEST(FrameGraph, SkippedPassesAreReportedWithTheirReason) {
    FrameGraph g;
    g.addPass("A", fg::PassKind::Compute, [&](PassBuilder& p) { p.create("out", kDesc, fg::Usage::ImageStore); }, nullptr);
    g.skipPass("shadows", "scene has no shadow-casting light");
    g.markOutput("out");
    g.compile();
    EXPECT_EQ(g.executionOrder(), (std::vector<std::string>{"A"}));
    ASSERT_EQ(g.skippedPasses().size(), 1u);
    EXPECT_NE(g.describe().find("shadows: skipped: scene has no shadow-casting light"), std::string::npos);
}

// ---- usages, barriers and kinds -------------------------------------------------------------------

namespace {
// producer -> consumer over one 64x64 texture: the barrier the graph issues before the consumer.
GLbitfield barrierBetween(fg::Usage produced, fg::Usage consumed, bool inPlace) {
    FrameGraph g;
    ResourceId a;
    g.addPass("producer", fg::PassKind::Compute, [&](PassBuilder& p) { a = p.create("a", kDesc, produced); }, nullptr);
    g.addPass("consumer", fg::PassKind::Compute,
              [&](PassBuilder& p) {
                  if (inPlace) p.write(a, consumed);
                  else p.read(a, consumed);
                  p.create("out", kDesc, fg::Usage::ColorAttachment);
              },
              nullptr);
    g.markOutput("out");
    g.compile();
    return g.barriersBefore("consumer");
}
}  // namespace

TEST(FrameGraphBarriers, ImageStoresGetTheBitsOfTheirConsumersUsage) {
    using fg::Usage;
    EXPECT_EQ(barrierBetween(Usage::ImageStore, Usage::Sampled, false), GLbitfield(GL_TEXTURE_FETCH_BARRIER_BIT));
    EXPECT_EQ(barrierBetween(Usage::ImageStore, Usage::ImageLoadStore, true), GLbitfield(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT));
    // The case the hand-picked barriers missed: compute writes the HDR buffer, raster blends into it.
    EXPECT_EQ(barrierBetween(Usage::ImageStore, Usage::Blend, true), GLbitfield(GL_FRAMEBUFFER_BARRIER_BIT));
    EXPECT_EQ(barrierBetween(Usage::ImageStore, Usage::DepthTest, false), GLbitfield(GL_FRAMEBUFFER_BARRIER_BIT));
    EXPECT_EQ(barrierBetween(Usage::ImageLoadStore, Usage::Transfer, false), GLbitfield(GL_TEXTURE_UPDATE_BARRIER_BIT));
    EXPECT_NE(barrierBetween(Usage::ImageStore, Usage::Cuda, true) & GL_SHADER_IMAGE_ACCESS_BARRIER_BIT, 0u);
}

TEST(FrameGraphBarriers, CoherentWritesNeedNone) {
    using fg::Usage;
    // Attachments, clears and CUDA's map/unmap are ordered by GL itself.
    EXPECT_EQ(barrierBetween(Usage::ColorAttachment, Usage::Sampled, false), 0u);
    EXPECT_EQ(barrierBetween(Usage::DepthAttachment, Usage::ImageLoad, false), 0u);
    EXPECT_EQ(barrierBetween(Usage::Blend, Usage::ImageLoadStore, true), 0u);
    EXPECT_EQ(barrierBetween(Usage::Cuda, Usage::Sampled, false), 0u);
    EXPECT_EQ(barrierBetween(Usage::Transfer, Usage::Sampled, false), 0u);
}

TEST(FrameGraphBarriers, OneBarrierCoversEveryEarlierStoreAndIsNotRepeated) {
    using fg::Usage;
    FrameGraph g;
    ResourceId a, b;
    g.addPass("A", fg::PassKind::Compute, [&](PassBuilder& p) { a = p.create("a", kDesc, Usage::ImageStore); }, nullptr);
    g.addPass("B", fg::PassKind::Compute, [&](PassBuilder& p) { b = p.create("b", kDesc, Usage::ImageStore); }, nullptr);
    g.addPass("readsBoth", fg::PassKind::Compute,
              [&](PassBuilder& p) {
                  p.read(a, Usage::Sampled);
                  p.read(b, Usage::Sampled);
                  p.create("c", kDesc, Usage::ColorAttachment);
              },
              nullptr);
    g.addPass("readsAAgain", fg::PassKind::Compute,
              [&](PassBuilder& p) {
                  p.read(a, Usage::Sampled);
                  p.read("c", Usage::Sampled);
                  p.create("out", kDesc, Usage::ImageStore);
              },
              nullptr);
    g.markOutput("out");
    g.compile();
    // A's store may reuse a texture the previous frame still reads (write after read); B's cannot:
    // nothing was read or released since A's barrier.
    EXPECT_EQ(g.barriersBefore("A"), GLbitfield(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT));
    EXPECT_EQ(g.barriersBefore("B"), 0u);
    EXPECT_EQ(g.barriersBefore("readsBoth"), GLbitfield(GL_TEXTURE_FETCH_BARRIER_BIT));
    // Its reads are covered; but "out" may reuse b's texture, which readsBoth fetched and released.
    EXPECT_EQ(g.barriersBefore("readsAAgain"), GLbitfield(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT));
    // The output was stored by a shader: what the application does next (readback, blit) is covered.
    EXPECT_NE(g.barriersAfterFrame() & GL_TEXTURE_UPDATE_BARRIER_BIT, 0u);
    EXPECT_NE(g.barriersAfterFrame() & GL_FRAMEBUFFER_BARRIER_BIT, 0u);
}

// Write after read: a shader's image stores may overtake an earlier command's texture fetches of the
// same texture unless a barrier lies between (an H100 overlaps consecutive dispatches).
TEST(FrameGraphBarriers, ImageStoresAfterShaderReadsOfTheirTextureGetABarrier) {
    using fg::Usage;
    FrameGraph g;
    ResourceId a, b;
    g.addPass("store", fg::PassKind::Compute, [&](PassBuilder& p) { a = p.create("a", kDesc, Usage::ImageStore); }, nullptr);
    g.addPass("fetch", fg::PassKind::Compute,
              [&](PassBuilder& p) {
                  p.read(a, Usage::Sampled);
                  b = p.create("b", kDesc, Usage::ColorAttachment);
              },
              nullptr);
    g.addPass("restore", fg::PassKind::Compute, [&](PassBuilder& p) { a = p.write(a, Usage::ImageStore); }, nullptr);
    g.addPass("draw", fg::PassKind::Raster,
              [&](PassBuilder& p) {
                  p.read(a, Usage::Sampled);
                  b = p.write(b, Usage::ColorAttachment);
              },
              nullptr);
    g.markOutput(b);
    g.compile();
    EXPECT_EQ(g.barriersBefore("fetch"), GLbitfield(GL_TEXTURE_FETCH_BARRIER_BIT));
    EXPECT_EQ(g.barriersBefore("restore"), GLbitfield(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT));
    EXPECT_EQ(g.barriersBefore("draw"), GLbitfield(GL_TEXTURE_FETCH_BARRIER_BIT));
    // An imported texture (a history) was read by the previous frame: its first store waits too.
    FrameGraph h;
    ResourceId history = h.importTexture("history", kDesc, GLuint(7));
    h.addPass("keep", fg::PassKind::Compute, [&](PassBuilder& p) { history = p.write(history, Usage::ImageStore); }, nullptr);
    h.markOutput(history);  // the stored version: the pass is live
    h.compile();
    ASSERT_TRUE(h.isLive("keep"));
    EXPECT_EQ(h.barriersBefore("keep"), GLbitfield(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT));
}

TEST(FrameGraphBarriers, DescribeAndDotShowKindsBarriersAndUsages) {
    FrameGraph g;
    ResourceId a;
    g.addPass("draw", fg::PassKind::Raster, [&](PassBuilder& p) { a = p.create("a", kDesc, fg::Usage::ImageStore); }, nullptr);
    g.addPass("blend", fg::PassKind::Raster, [&](PassBuilder& p) { p.write(a, fg::Usage::Blend); }, nullptr);
    g.markOutput("a");
    g.compile();
    const std::string text = g.describe();
    EXPECT_NE(text.find("1. draw  [raster]"), std::string::npos) << text;
    EXPECT_NE(text.find("barrier: framebuffer"), std::string::npos) << text;
    EXPECT_NE(g.toDot().find("label=\"blend\""), std::string::npos) << g.toDot();
    EXPECT_EQ(fg::usageName(fg::Usage::Blend | fg::Usage::ImageLoadStore), "image-load/store+blend");
}

TEST(FrameBuilder, PassesDeclareTheirKindAndTheBarriersFollow) {
    Scene s = oneLightScene();
    s.pointLights.push_back(PointLight{});
    s.pointLights.back().position = glm::vec3(0.0f, 0.5f, 0.0f);
    s.pointLights.back().range = 5.0f;
    for (LocalLightMethod method : {LocalLightMethod::Tiled, LocalLightMethod::Volumes}) {
        RenderSettings settings;
        settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
        settings.autoExposure = false;       // and 0 EV
        settings.width = 320;
        settings.height = 200;
        settings.localLights.method = method;
        FrameGraph g = buildWith(s, settings);
        ASSERT_TRUE(g.isLive("local_lights")) << g.explainText();
        EXPECT_EQ(g.passKind("gbuffer"), fg::PassKind::Raster);
        EXPECT_EQ(g.passKind("shadow_map_0"), fg::PassKind::Raster);
        EXPECT_EQ(g.passKind("global_lights"), fg::PassKind::Compute);
        EXPECT_EQ(g.passKind("tonemap"), fg::PassKind::Compute);
        // global_lights image-stores the HDR buffer; the local lights read it as their method does.
        const GLbitfield before = g.barriersBefore("local_lights");
        if (method == LocalLightMethod::Tiled) {
            EXPECT_EQ(g.passKind("local_lights"), fg::PassKind::Compute);
            EXPECT_EQ(before, GLbitfield(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT));
        } else {
            EXPECT_EQ(g.passKind("local_lights"), fg::PassKind::Raster);
            EXPECT_EQ(before, GLbitfield(GL_FRAMEBUFFER_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT));
        }
        // Nothing is stored before it, but it image-stores the background into pooled targets the
        // previous frame's passes may still read (write after read): the image-access barrier only.
        EXPECT_EQ(g.barriersBefore("gbuffer"), GLbitfield(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT));
        EXPECT_NE(g.barriersBefore("tonemap") & GL_TEXTURE_FETCH_BARRIER_BIT, 0u);
    }
}

TEST(FrameBuilder, BloomScratchIsAGraphTransientCountedInMemory) {
    Scene s = oneLightScene();
    for (auto method : {PostSettings::BloomMethod::Separable, PostSettings::BloomMethod::MipChain}) {
        RenderSettings settings;
        settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
        settings.autoExposure = false;       // and 0 EV
        settings.width = 320;
        settings.height = 200;
        settings.post.bloom = true;
        settings.post.bloomMethod = method;
        settings.post.backend = PostSettings::Backend::Glsl;
        FrameGraph g = buildWith(s, settings);
        std::vector<std::string> scratch;
        size_t scratchBytes = 0;
        for (const auto& r : g.resources())
            if (r.name.rfind("bloom.", 0) == 0 && r.live) {
                scratch.push_back(r.name);
                scratchBytes += r.desc.bytes();
                EXPECT_EQ(r.firstPass, r.lastPass) << r.name << " lives only inside the bloom pass";
            }
        if (method == PostSettings::BloomMethod::Separable)
            EXPECT_EQ(scratch, (std::vector<std::string>{"bloom.bright", "bloom.blur_h"}));
        else
            EXPECT_EQ(scratch, (std::vector<std::string>{"bloom.mips"}));
        EXPECT_GT(scratchBytes, 0u);
        EXPECT_GE(g.liveTransientBytes(), scratchBytes);
        EXPECT_TRUE(g.isLive("bloom_composite"));
    }
}

TEST(FrameBuilder, EnvironmentTexturesAreImportedAndWrittenByTheBake) {
    Scene s = oneLightScene();
    s.environment.map = "sky.exr";  // never read: nothing executes
    s.environment.ibl = true;
    RenderSettings settings;
    settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    settings.autoExposure = false;       // and 0 EV
    settings.width = 64;
    settings.height = 48;
    FrameGraph g = buildWith(s, settings);
    const auto order = g.executionOrder();
    ASSERT_FALSE(order.empty());
    EXPECT_EQ(order.front(), "ibl_bake");  // first: ibl and sky read what it writes
    bool cubeImported = false;
    for (const auto& r : g.resources())
        if (r.name == "environment.cube") cubeImported = r.imported && r.desc.cube;
    EXPECT_TRUE(cubeImported);
    for (const auto& r : g.report())
        if (r.name == "sky") EXPECT_NE(std::find(r.reads.begin(), r.reads.end(), "environment.cube@1"), r.reads.end());
    // Imported lookups are not streamed: they are not in the floor's bytes.
    EXPECT_EQ(g.passTrafficBytes("ibl_bake"), 0u);
}

// Light globes (seed 003): the scene's lightGlobes turns them on, --globes / --no-globes override it.
TEST(FrameBuilder, LightGlobesFollowTheSceneUnlessOverridden) {
    Scene s = oneLightScene();
    s.pointLights.push_back(PointLight{});
    s.pointLights.back().range = 5.0f;
    auto globes = [&](bool sceneOn, std::optional<bool> setting) {
        s.lightGlobes = sceneOn;
        RenderSettings settings;
        settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
        settings.autoExposure = false;       // and 0 EV
        settings.width = 64;
        settings.height = 48;
        settings.localLights.globes = setting;
        FrameGraph g = buildWith(s, settings);
        return g.isLive("light_globes");
    };
    EXPECT_FALSE(globes(false, std::nullopt));
    EXPECT_TRUE(globes(true, std::nullopt));
    EXPECT_FALSE(globes(true, false));
    EXPECT_TRUE(globes(false, true));
}

// Buffers (importBuffer): ordered like textures (readers after the writer whose version they
// read), written only by an upload (transfer) and read only as a storage block or a copy; a texture
// is never a storage buffer. Each misuse is a clear error naming the pass and the resource.
TEST(FrameGraph, ImportedBuffersAreOrderedAndTheirUsagesChecked) {
    FrameGraph g;
    const ResourceId records = g.importBuffer("records", [] { return GLuint(0); });
    ResourceId out;
    g.addPass("reader", fg::PassKind::Compute,
              [&](PassBuilder& b) {
                  b.read("records", fg::Usage::StorageBuffer);  // the last version: the writer's
                  out = b.create("out", kDesc, fg::Usage::ColorAttachment);
              },
              nullptr);
    g.addPass("writer", fg::PassKind::Compute, [&](PassBuilder& b) { b.write(records, fg::Usage::Transfer); }, nullptr);
    g.markOutput(out);
    g.compile();
    EXPECT_EQ(g.executionOrder(), (std::vector<std::string>{"writer", "reader"}));
    EXPECT_EQ(g.barriersBefore("reader"), 0u);  // an upload is ordered by GL itself
    bool listed = false;
    for (const fg::ResourceReport& r : g.resources()) listed = listed || (r.name == "records" && r.buffer && r.imported);
    EXPECT_TRUE(listed);
    EXPECT_NE(g.toDot().find("records\\nbuffer"), std::string::npos);

    auto misuse = [](const std::function<void(FrameGraph&, ResourceId, ResourceId)>& declare) {
        FrameGraph m;
        const ResourceId buffer = m.importBuffer("buf", [] { return GLuint(0); });
        const ResourceId texture = m.importTexture("tex", kDesc, GLuint(0));
        try {
            declare(m, buffer, texture);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    const std::string storedBuffer = misuse([](FrameGraph& m, ResourceId buffer, ResourceId) {
        m.addPass("p", fg::PassKind::Compute, [&](PassBuilder& b) { b.write(buffer, fg::Usage::ImageStore); }, nullptr);
    });
    EXPECT_NE(storedBuffer.find("pass 'p' writes buffer 'buf' as image-store"), std::string::npos) << storedBuffer;
    const std::string sampledBuffer = misuse([](FrameGraph& m, ResourceId buffer, ResourceId) {
        m.addPass("p", fg::PassKind::Compute, [&](PassBuilder& b) { b.read(buffer, fg::Usage::Sampled); }, nullptr);
    });
    EXPECT_NE(sampledBuffer.find("pass 'p' reads buffer 'buf' as sampled"), std::string::npos) << sampledBuffer;
    const std::string storageTexture = misuse([](FrameGraph& m, ResourceId, ResourceId texture) {
        m.addPass("p", fg::PassKind::Compute, [&](PassBuilder& b) { b.read(texture, fg::Usage::StorageBuffer); }, nullptr);
    });
    EXPECT_NE(storageTexture.find("pass 'p' reads texture 'tex' as storage-buffer"), std::string::npos) << storageTexture;
    EXPECT_TRUE(misuse([](FrameGraph& m, ResourceId buffer, ResourceId) {
                    m.addPass("p", fg::PassKind::Compute, [&](PassBuilder& b) { b.read(buffer, fg::Usage::Transfer); },
                              nullptr);
                }).empty());
}

// A buffer a shader writes (the skinning pass's posed vertices: storage-buffer) is incoherent: the
// passes that draw from it get the vertex-attrib barrier, a copy out of it the buffer-update one,
// and the writer itself one against the previous frame's reads (the buffer is imported).
TEST(FrameGraph, ShaderWrittenBufferGetsTheBarriersOfItsReaders) {
    FrameGraph g;
    const ResourceId posed = g.importBuffer("posed", [] { return GLuint(0); });
    ResourceId out;
    g.addPass("writer", fg::PassKind::Compute, [&](PassBuilder& b) { b.write(posed, fg::Usage::StorageBuffer); }, nullptr);
    g.addPass("draw", fg::PassKind::Raster,
              [&](PassBuilder& b) {
                  b.read("posed", fg::Usage::VertexBuffer);
                  out = b.create("out", kDesc, fg::Usage::ColorAttachment);
              },
              nullptr);
    g.addPass("copy", fg::PassKind::Compute,
              [&](PassBuilder& b) {
                  b.read("posed", fg::Usage::Transfer);
                  b.write(out, fg::Usage::ImageStore);
              },
              nullptr);
    g.markOutput("out");
    g.compile();
    EXPECT_EQ(g.executionOrder(), (std::vector<std::string>{"writer", "draw", "copy"}));
    EXPECT_NE(g.barriersBefore("writer") & GL_SHADER_STORAGE_BARRIER_BIT, 0u);
    EXPECT_EQ(g.barriersBefore("draw"), GLbitfield(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT));
    EXPECT_NE(g.barriersBefore("copy") & GL_BUFFER_UPDATE_BARRIER_BIT, 0u);
    EXPECT_EQ(g.barriersBefore("copy") & GL_TEXTURE_UPDATE_BARRIER_BIT, 0u);
    // A texture is no vertex buffer.
    FrameGraph m;
    const ResourceId texture = m.importTexture("tex", kDesc, GLuint(0));
    EXPECT_THROW(m.addPass("p", fg::PassKind::Raster, [&](PassBuilder& b) { b.read(texture, fg::Usage::VertexBuffer); }, nullptr), Error);
}

// The local lights' GPU records are one buffer a frame: the pass that shades the lights first fills
// it (local_lights; forward_opaque on the forward+ path) and the transparent pass and every overlay
// read that version. A disabled filler passes the imported version through (the first overlay then
// uploads them: tests/gl/test_local_lights.cpp).
TEST(FrameBuilder, OverlaysReadTheLightRecordsTheLightingPassFilled) {
    Scene s = oneLightScene();
    s.pointLights.push_back(PointLight{});
    s.pointLights.back().range = 5.0f;
    s.lightGlobes = true;
    auto passReport = [](const FrameGraph& g, const std::string& name) {
        for (const fg::PassReport& r : g.report())
            if (r.name == name) return r;
        return fg::PassReport{};
    };
    auto has = [](const std::vector<std::string>& v, const std::string& x) {
        return std::find(v.begin(), v.end(), x) != v.end();
    };
    for (RenderPath path : {RenderPath::Deferred, RenderPath::ForwardPlus})
        for (DebugView view : {DebugView::Final, DebugView::LightRanges, DebugView::LightsPerTile, DebugView::LightsPerCluster}) {
            RenderSettings settings;
            settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
            settings.autoExposure = false;       // and 0 EV
            settings.width = 64;
            settings.height = 48;
            settings.renderPath = path;
            settings.view = view;
            const char* filler = path == RenderPath::Deferred ? "local_lights" : "forward_opaque";
            const FrameGraph g = buildWith(s, settings);
            EXPECT_TRUE(has(passReport(g, filler).writes, "local_lights.records@1")) << filler;
            const char* overlay = view == DebugView::Final          ? "light_globes"
                                  : view == DebugView::LightRanges  ? "light_ranges"
                                  : view == DebugView::LightsPerTile ? "lights_per_tile"
                                                                      : "lights_per_cluster";
            ASSERT_TRUE(g.isLive(overlay)) << overlay;
            EXPECT_TRUE(has(passReport(g, overlay).reads, "local_lights.records@1")) << overlay << " " << filler;
            settings.disabledPasses.insert(filler);
            const FrameGraph off = buildWith(s, settings);
            EXPECT_TRUE(has(passReport(off, overlay).reads, "local_lights.records")) << overlay << " without " << filler;
        }
}

// LIGHTPASS_GL_STATE_CHECKS: 1/ON turn the per-pass GL state check on, 0/OFF/empty leave it off (the
// default, what `lightpass` users get), anything else is refused (a warning, and off).
TEST(FrameGraph, StateCheckFlagValues) {
    for (const char* on : {"1", "ON", "on", "On"}) EXPECT_EQ(gl::parseStateChecksFlag(on), std::optional<bool>(true)) << on;
    for (const char* off : {"", "0", "OFF", "off"}) EXPECT_EQ(gl::parseStateChecksFlag(off), std::optional<bool>(false)) << off;
    for (const char* bad : {"2", "yes", " 1", "ONE"}) EXPECT_EQ(gl::parseStateChecksFlag(bad), std::nullopt) << bad;
    FrameGraph g;
    EXPECT_EQ(g.stateChecks(), gl::stateChecksFromEnvironment());
    g.setStateChecks(!g.stateChecks());
    EXPECT_NE(g.stateChecks(), gl::stateChecksFromEnvironment());
}
