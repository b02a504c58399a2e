// The frame graph on the GPU: transient textures are pooled and reused, nothing leaks, and a pass
// that leaves a GL error is reported by name.
#include <gtest/gtest.h>

#include "engine/core/error.hpp"
#include "engine/graph/texture_pool.hpp"
#include "frame/renderer.hpp"
#include "engine/scene/scene_loader.hpp"
#include "tests/gl/gl_fixture.hpp"

using namespace lp;

TEST(FrameGraphGl, PoolReusesTexturesWhoseLifetimesDoNotOverlap) {
    fg::TexturePool pool;
    const fg::TextureDesc d{32, 32, GL_RGBA16F};
    fg::FrameGraph g;
    fg::ResourceId a, b;
    GLuint ta = 0, tc = 0;
    g.addPass("A", [&](fg::PassBuilder& p) { a = p.create("a", d); }, [&](const fg::PassResources& r) { ta = r.texture(a); });
    g.addPass("B", [&](fg::PassBuilder& p) { p.read(a); b = p.create("b", d); }, nullptr);
    fg::ResourceId c;
    // "c" is created after "a" dies, so it may take a's texture.
    g.addPass("C", [&](fg::PassBuilder& p) { p.read(b); c = p.create("c", d); }, [&](const fg::PassResources& r) { tc = r.texture(c); });
    g.markOutput(c);
    g.compile();
    g.execute(pool);
    EXPECT_EQ(pool.created(), 2u);  // a and c share one texture, b has its own
    EXPECT_EQ(ta, tc);
    // Across frames nothing new is created.
    for (int i = 0; i < 5; ++i) g.execute(pool);
    EXPECT_EQ(pool.created(), 2u);
}

TEST(FrameGraphGl, GlErrorInAPassIsReportedByName) {
    fg::TexturePool pool;
    fg::FrameGraph g;
    fg::ResourceId a;
    g.addPass(
        "broken", [&](fg::PassBuilder& p) { a = p.create("a", {8, 8, GL_RGBA8}); },
        [](const fg::PassResources&) { glEnable(GL_INVALID_ENUM); });
    g.markOutput(a);
    g.compile();
    try {
        g.execute(pool);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("pass 'broken'"), std::string::npos) << e.what();
    }
}

TEST(FrameGraphGl, RenderingAndResizingLeaksNoGlObjects) {
    Scene scene = loadScene(test::repoPath("scenes/cornell.json"));
    Renderer r(scene);
    RenderSettings s;
    auto settle = [&] {  // pool entries unused for a few frames are freed
        s.width = 64;
        s.height = 48;
        s.view = DebugView::Final;
        for (int i = 0; i < 6; ++i) r.render(s, 0.0f, false);
    };
    for (DebugView v : allViews()) {  // compile every program once
        s.view = v;
        r.render(s, 0.0f, false);
    }
    settle();
    const long before = gl::liveObjectCount();
    for (int i = 0; i < 100; ++i) {  // 100 resizes and view switches
        s.width = 64 + (i % 7) * 8;
        s.height = 48 + (i % 5) * 8;
        s.view = allViews()[size_t(i) % allViews().size()];
        r.render(s, 0.0f, false);
    }
    settle();
    EXPECT_EQ(gl::liveObjectCount(), before);
}

TEST(FrameGraphGl, DefaultSceneRendersEveryViewWithoutNan) {
    Scene scene = loadScene(test::repoPath("scenes/cornell.json"));
    Renderer r(scene);
    RenderSettings s;
    s.width = 96;
    s.height = 72;
    s.keepHdr = true;
    r.render(s);
    ImageF hdr = r.readHdr();
    double sum = 0.0;
    for (float v : hdr.rgba) {
        ASSERT_TRUE(std::isfinite(v));
        sum += v;
    }
    EXPECT_GT(sum, 0.0);  // something is lit
    for (DebugView v : allViews()) {
        s.view = v;
        s.keepHdr = false;
        r.render(s);
        Image8 img = r.readDisplay();
        EXPECT_EQ(img.width, 96);
        bool nonBlack = false;
        for (size_t i = 0; i < img.rgba.size(); i += 4) nonBlack |= img.rgba[i] || img.rgba[i + 1] || img.rgba[i + 2];
        EXPECT_TRUE(nonBlack) << viewName(v);
    }
}
