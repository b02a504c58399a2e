// Frame-graph logic on synthetic passes and on the real frame builder (no GL: nothing executes).
#include <gtest/gtest.h>

#include <algorithm>

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
    g.addPass("present", [](PassBuilder& b) { b.read("image"); b.sideEffect(); }, nullptr);
    ResourceId a;
    g.addPass("producer", [&](PassBuilder& b) { a = b.create("a", kDesc); }, nullptr);
    g.addPass("consumer", [&](PassBuilder& b) { b.read(a); b.create("image", kDesc); }, nullptr);
    g.markOutput("image");
    g.compile();
    EXPECT_EQ(g.executionOrder(), (std::vector<std::string>{"producer", "consumer", "present"}));
    EXPECT_TRUE(culledPasses(g).empty());
}

TEST(FrameGraph, CullsPassWhoseWritesNobodyReads) {
    FrameGraph g;
    ResourceId a, b;
    g.addPass("A", [&](PassBuilder& p) { a = p.create("a", kDesc); }, nullptr);
    g.addPass("B", [&](PassBuilder& p) { b = p.create("b", kDesc); }, nullptr);  // read by nobody
    g.addPass("useB", [&](PassBuilder& p) { p.read(b); p.create("dead", kDesc); }, nullptr);
    g.addPass("final", [&](PassBuilder& p) { p.read(a); p.create("out", kDesc); }, nullptr);
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
    g.addPass("light", [&](PassBuilder& p) { hdr = p.create("hdr", kDesc); }, nullptr);
    // bloom reads version 0 of hdr, before "local" writes version 1 in place.
    g.addPass("bloom", [&](PassBuilder& p) { p.read(hdr); bloom = p.create("bloom", kDesc); }, nullptr);
    g.addPass("local", [&](PassBuilder& p) { hdr2 = p.write(hdr); }, nullptr);
    g.addPass("composite", [&](PassBuilder& p) { p.read(bloom); p.read(hdr2); p.create("out", kDesc); }, nullptr);
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
    bad.addPass("p1", [&](PassBuilder& p) { x = p.create("x", kDesc); }, nullptr);
    bad.addPass("p2", [&](PassBuilder& p) { p.write(x); }, nullptr);
    EXPECT_THROW(bad.addPass("p3", [&](PassBuilder& p) { p.write(x); }, nullptr), Error);
}

TEST(FrameGraph, InPlaceWriterKeepsItsProducerAlive) {
    FrameGraph g;
    ResourceId hdr;
    g.addPass("light", [&](PassBuilder& p) { hdr = p.create("hdr", kDesc); }, nullptr);
    ResourceId hdr2;
    g.addPass("sky", [&](PassBuilder& p) { hdr2 = p.write(hdr); }, nullptr);
    g.markOutput(hdr2);
    g.compile();
    EXPECT_EQ(g.executionOrder(), (std::vector<std::string>{"light", "sky"}));
}

TEST(FrameGraph, CycleIsAClearError) {
    FrameGraph g;
    g.addPass("A", [&](PassBuilder& p) { p.read("y"); p.create("x", kDesc); }, nullptr);
    g.addPass("B", [&](PassBuilder& p) { p.read("x"); p.create("y", kDesc); }, nullptr);
    g.markOutput("y");
    std::string err = errorOf(g);
    EXPECT_NE(err.find("cycle"), std::string::npos) << err;
    EXPECT_NE(err.find("A"), std::string::npos) << err;
    EXPECT_NE(err.find("B"), std::string::npos) << err;
}

TEST(FrameGraph, ReadOfUnwrittenResourceIsAClearError) {
    FrameGraph g;
    g.addPass("A", [&](PassBuilder& p) { p.read("ghost"); p.create("out", kDesc); }, nullptr);
    g.markOutput("out");
    std::string err = errorOf(g);
    EXPECT_NE(err.find("'A' reads 'ghost'"), std::string::npos) << err;
}

TEST(FrameGraph, NoOutputIsAnError) {
    FrameGraph g;
    g.addPass("A", [&](PassBuilder& p) { p.create("out", kDesc); }, nullptr);
    EXPECT_NE(errorOf(g).find("no output"), std::string::npos);
}

TEST(FrameGraph, LifetimesSpanFirstToLastUse) {
    FrameGraph g;
    ResourceId a, b;
    g.addPass("P0", [&](PassBuilder& p) { a = p.create("a", kDesc); }, nullptr);
    g.addPass("P1", [&](PassBuilder& p) { p.read(a); b = p.create("b", kDesc); }, nullptr);
    g.addPass("P2", [&](PassBuilder& p) { p.read(b); p.create("out", kDesc); }, nullptr);
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

FrameGraph buildFor(const Scene& scene, DebugView view, bool keepHdr = false) {
    RenderSettings settings;
    settings.width = 320;
    settings.height = 200;
    settings.view = view;
    settings.keepHdr = keepHdr;
    FrameData frame = makeFrameData(scene, settings, 0.0f);
    FrameGraph g;
    PassStates passes;
    buildFrameGraph(g, passes, frame);
    g.compile();
    return g;
}
}  // namespace

TEST(FrameBuilder, FinalViewRunsLightingSkyAndToneMap) {
    Scene s = oneLightScene();
    FrameGraph g = buildFor(s, DebugView::Final);
    EXPECT_EQ(g.executionOrder(), (std::vector<std::string>{"gbuffer", "shadow_map_0", "global_lights", "sky", "tonemap"}));
    EXPECT_FALSE(g.hasPass("debug_view"));
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
        if (v == DebugView::Final || v == DebugView::Lighting) continue;
        FrameGraph g = buildFor(s, v);
        // the environment views show the cubes / LUT, made by the bake in the first frame
        const std::vector<std::string> expected = isEnvironmentView(v)
                                                      ? std::vector<std::string>{"ibl_bake", "gbuffer", "debug_view"}
                                                      : std::vector<std::string>{"gbuffer", "debug_view"};
        EXPECT_EQ(g.executionOrder(), expected) << viewName(v);
        bool texcoordLive = false;
        for (const auto& r : g.resources())
            if (r.name == "gbuffer.texcoord") texcoordLive = r.live;
        EXPECT_EQ(texcoordLive, v == DebugView::Texcoords) << viewName(v);
    }
}

TEST(FrameBuilder, LightingViewSkipsDiffuseAndSky) {
    Scene s = oneLightScene();
    FrameGraph g = buildFor(s, DebugView::Lighting);
    EXPECT_EQ(g.executionOrder(), (std::vector<std::string>{"gbuffer", "shadow_map_0", "global_lights", "tonemap"}));
    for (const auto& r : g.report())
        if (r.name == "global_lights")
            EXPECT_EQ(std::count(r.reads.begin(), r.reads.end(), "gbuffer.diffuse"), 0);
}

TEST(FrameGraph, DisabledInPlacePassPassesItsInputThrough) {
    FrameGraph g;
    ResourceId hdr, hdr2;
    g.addPass("light", [&](PassBuilder& p) { hdr = p.create("hdr", kDesc); }, nullptr);
    g.addPass("sky", [&](PassBuilder& p) { hdr2 = p.write(hdr); }, nullptr);
    g.addPass("tonemap", [&](PassBuilder& p) { p.read(hdr2); p.create("out", kDesc); }, nullptr);
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
    g.addPass("gbuf", [&](PassBuilder& p) { a = p.create("a", kDesc); }, nullptr);
    g.addPass("light", [&](PassBuilder& p) { p.read(a); p.create("hdr", kDesc); }, [&](const fg::PassResources&) { drew = true; });
    g.addPass("tonemap", [&](PassBuilder& p) { p.read("hdr"); p.create("out", kDesc); }, nullptr);
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
    settings.width = 64;
    settings.height = 48;
    settings.disabledPasses = {"sky"};
    FrameData frame = makeFrameData(s, settings, 0.0f);
    FrameGraph g;
    PassStates passes;
    buildFrameGraph(g, passes, frame);
    g.compile();
    EXPECT_EQ(g.executionOrder(), (std::vector<std::string>{"gbuffer", "shadow_map_0", "global_lights", "tonemap"}));
}

TEST(FrameGraph, SkippedPassesAreReportedWithTheirReason) {
    FrameGraph g;
    g.addPass("A", [&](PassBuilder& p) { p.create("out", kDesc); }, nullptr);
    g.skipPass("shadows", "scene has no shadow-casting light");
    g.markOutput("out");
    g.compile();
    EXPECT_EQ(g.executionOrder(), (std::vector<std::string>{"A"}));
    ASSERT_EQ(g.skippedPasses().size(), 1u);
    EXPECT_NE(g.describe().find("shadows: skipped: scene has no shadow-casting light"), std::string::npos);
}
