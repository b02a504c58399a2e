// The frame graph on the GPU: transient textures are pooled and reused, nothing leaks, and a pass
// that leaves a GL error is reported by name.
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

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
    g.addPass("A", fg::PassKind::Compute, [&](fg::PassBuilder& p) { a = p.create("a", d, fg::Usage::ImageStore); }, [&](const fg::PassResources& r) { ta = r.texture(a); });
    g.addPass("B", fg::PassKind::Compute, [&](fg::PassBuilder& p) { p.read(a, fg::Usage::Sampled); b = p.create("b", d, fg::Usage::ImageStore); }, nullptr);
    fg::ResourceId c;
    // "c" is created after "a" dies, so it may take a's texture.
    g.addPass("C", fg::PassKind::Compute, [&](fg::PassBuilder& p) { p.read(b, fg::Usage::Sampled); c = p.create("c", d, fg::Usage::ImageStore); }, [&](const fg::PassResources& r) { tc = r.texture(c); });
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
        "broken", fg::PassKind::Compute, [&](fg::PassBuilder& p) { a = p.create("a", {8, 8, GL_RGBA8}, fg::Usage::ImageStore); },
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

namespace {
std::string executeError(fg::FrameGraph& g, fg::TexturePool& pool) {
    try {
        g.execute(pool);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}
}  // namespace

TEST(FrameGraphGl, APassCannotUseWhatItDidNotDeclare) {
    fg::TexturePool pool;
    fg::FrameGraph g;
    fg::ResourceId a, b;
    g.addPass("A", fg::PassKind::Compute, [&](fg::PassBuilder& p) { a = p.create("a", {8, 8, GL_RGBA8}, fg::Usage::ImageStore); },
              nullptr);
    g.addPass("B", fg::PassKind::Compute,
              [&](fg::PassBuilder& p) {
                  p.read(a, fg::Usage::Sampled);
                  b = p.create("b", {8, 8, GL_RGBA8}, fg::Usage::ImageStore);
              },
              [&](const fg::PassResources& r) { r.texture(b), r.texture(a); });  // both declared: fine
    g.addPass("sneaky", fg::PassKind::Compute, [&](fg::PassBuilder& p) { p.write(b, fg::Usage::ImageLoadStore); },
              [&](const fg::PassResources& r) { r.texture(a); });  // a is not its own
    g.markOutput("b");
    g.compile();
    const std::string e = executeError(g, pool);
    EXPECT_NE(e.find("pass 'sneaky' uses 'a', which it did not declare"), std::string::npos) << e;
}

TEST(FrameGraphGl, LazyImportIsAskedWhenThePassRuns) {
    fg::TexturePool pool;
    fg::FrameGraph g;
    gl::Texture made;  // made by the first pass, as ibl_bake makes the environment cube
    const fg::ResourceId imported = g.importTexture("made_later", {4, 4, GL_RGBA8}, [&] { return made.id(); });
    fg::ResourceId written, out;
    GLuint seen = 0;
    g.addPass("make", fg::PassKind::Compute, [&](fg::PassBuilder& p) { written = p.write(imported, fg::Usage::ImageStore); },
              [&](const fg::PassResources&) { made = gl::makeTexture2D(GL_RGBA8, 4, 4, 1, "made_later"); });
    g.addPass("use", fg::PassKind::Compute,
              [&](fg::PassBuilder& p) {
                  p.read(written, fg::Usage::Sampled);
                  out = p.create("out", {4, 4, GL_RGBA8}, fg::Usage::ImageStore);
              },
              [&](const fg::PassResources& r) { seen = r.texture(written); });
    g.markOutput(out);
    g.compile();
    g.execute(pool);
    EXPECT_NE(seen, 0u);
    EXPECT_EQ(seen, made.id());
    EXPECT_EQ(g.barriersBefore("use"), GLbitfield(GL_TEXTURE_FETCH_BARRIER_BIT));
}

// An imported buffer is asked for its GL name when a pass asks (after the writer refilled it); a
// pass gets it only if it declared it, and only as a buffer (texture() on it, buffer() on a texture,
// are errors naming both).
TEST(FrameGraphGl, ImportedBufferIsAskedWhenThePassRunsAndOnlyByItsReaders) {
    fg::TexturePool pool;
    gl::Buffer first = gl::makeBuffer(16, nullptr, 0, "first"), second = gl::makeBuffer(16, nullptr, 0, "second");
    GLuint current = first.id();
    auto run = [&](const std::function<void(const fg::PassResources&, fg::ResourceId, fg::ResourceId)>& use) {
        fg::FrameGraph g;
        const fg::ResourceId buffer = g.importBuffer("records", [&] { return current; });
        fg::ResourceId out;
        g.addPass("fill", fg::PassKind::Compute, [&](fg::PassBuilder& p) { p.write(buffer, fg::Usage::Transfer); },
                  [&](const fg::PassResources&) { current = second.id(); });  // a refill: another buffer
        g.addPass("use", fg::PassKind::Compute,
                  [&](fg::PassBuilder& p) {
                      p.read("records", fg::Usage::StorageBuffer);
                      out = p.create("out", {4, 4, GL_RGBA8}, fg::Usage::ImageStore);
                  },
                  [&](const fg::PassResources& r) { use(r, buffer, out); });
        g.markOutput(out);
        g.compile();
        return executeError(g, pool);
    };
    GLuint seen = 0;
    EXPECT_EQ(run([&](const fg::PassResources& r, fg::ResourceId b, fg::ResourceId) { seen = r.buffer(b); }), "");
    EXPECT_EQ(seen, second.id());
    const std::string asTexture = run([](const fg::PassResources& r, fg::ResourceId b, fg::ResourceId) { r.texture(b); });
    EXPECT_NE(asTexture.find("pass 'use' asks for 'records' as a texture, but it is a buffer"), std::string::npos)
        << asTexture;
    const std::string asBuffer = run([](const fg::PassResources& r, fg::ResourceId, fg::ResourceId o) { r.buffer(o); });
    EXPECT_NE(asBuffer.find("asks for 'out' as a buffer, but it is a texture"), std::string::npos) << asBuffer;
    // A pass that did not declare the buffer cannot reach it.
    fg::FrameGraph g;
    const fg::ResourceId buffer = g.importBuffer("records", [&] { return current; });
    fg::ResourceId out;
    g.addPass("sneaky", fg::PassKind::Compute, [&](fg::PassBuilder& p) { out = p.create("out", {4, 4, GL_RGBA8}, fg::Usage::ImageStore); },
              [&](const fg::PassResources& r) { r.buffer(buffer); });
    g.markOutput(out);
    g.compile();
    const std::string e = executeError(g, pool);
    EXPECT_NE(e.find("pass 'sneaky' uses 'records', which it did not declare"), std::string::npos) << e;
}

// A pass's beforeFrame work (the local-light records' upload) runs before the first pass executes,
// so outside every pass's timer, and only for passes that run.
TEST(FrameGraphGl, BeforeFrameWorkRunsBeforeTheFirstPassAndOnlyForLivePasses) {
    fg::TexturePool pool;
    fg::FrameGraph g;
    std::vector<std::string> events;
    fg::ResourceId a, out;
    g.addPass("first", fg::PassKind::Compute, [&](fg::PassBuilder& p) { a = p.create("a", {4, 4, GL_RGBA8}, fg::Usage::ImageStore); },
              [&](const fg::PassResources&) { events.push_back("first runs"); });
    g.addPass("second", fg::PassKind::Compute,
              [&](fg::PassBuilder& p) {
                  p.read(a, fg::Usage::Sampled);
                  out = p.create("out", {4, 4, GL_RGBA8}, fg::Usage::ImageStore);
                  p.beforeFrame([&] { events.push_back("second prepares"); });
              },
              [&](const fg::PassResources&) { events.push_back("second runs"); });
    g.addPass("culled", fg::PassKind::Compute,
              [&](fg::PassBuilder& p) {
                  p.create("unread", {4, 4, GL_RGBA8}, fg::Usage::ImageStore);
                  p.beforeFrame([&] { events.push_back("culled prepares"); });
              },
              [&](const fg::PassResources&) { events.push_back("culled runs"); });
    g.markOutput(out);
    g.compile();
    g.execute(pool);
    EXPECT_EQ(events, (std::vector<std::string>{"second prepares", "first runs", "second runs"}));
}

// With the state check on, a pass that leaves watched GL state changed is named; every real pass runs
// under it in the other GL tests (CTest sets LIGHTPASS_GL_STATE_CHECKS=1 for them); off, it costs
// nothing and says nothing.
TEST(FrameGraphGl, StateCheckNamesThePassThatLeavesStateChanged) {
    struct Leak {
        const char* what;
        std::function<void()> leave, undo;
    };
    gl::Texture t = gl::makeTexture2D(GL_RGBA8, 4, 4, 1, "leak");
    const Leak leaks[] = {
        {"GL_BLEND 1 (was 0)", [] { glEnable(GL_BLEND); }, [] { glDisable(GL_BLEND); }},
        {"GL_DEPTH_FUNC", [] { glDepthFunc(GL_GREATER); }, [] { glDepthFunc(GL_LESS); }},
        {"texture unit 5 2D", [&] { glBindTextureUnit(5, t.id()); }, [] { glBindTextureUnit(5, 0); }},
        {"image unit 0", [&] { glBindImageTexture(0, t.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8); },
         [] { glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8); }},
    };
    for (const Leak& leak : leaks) {
        fg::TexturePool pool;
        fg::FrameGraph g;
        fg::ResourceId a;
        g.addPass("clean", fg::PassKind::Compute, [&](fg::PassBuilder& p) { a = p.create("a", {8, 8, GL_RGBA8}, fg::Usage::ImageStore); },
                  nullptr);
        g.addPass("leaky", fg::PassKind::Raster, [&](fg::PassBuilder& p) { p.write(a, fg::Usage::ColorAttachment); },
                  [&](const fg::PassResources&) { leak.leave(); });
        g.markOutput("a");
        g.compile();
        g.setStateChecks(true);
        const std::string e = executeError(g, pool);
        leak.undo();
        EXPECT_NE(e.find("pass 'leaky' left GL state changed"), std::string::npos) << e;
        EXPECT_NE(e.find(leak.what), std::string::npos) << e;
        g.setStateChecks(false);
        EXPECT_EQ(executeError(g, pool), "") << leak.what;
        leak.undo();
    }
}

TEST(FrameGraphGl, RenderingAndResizingLeaksNoGlObjects) {
    Scene scene = loadScene(test::repoPath("scenes/cornell.json"));
    Renderer r(scene);
    RenderSettings s;
    // Each frame waited for: a gl::StreamBuffer adds a buffer to its ring when the GPU still reads all
    // the others (by design, bounded by the frames in flight), so without the wait the count would
    // depend on the driver's timing.
    auto render = [&] {
        r.render(s, 0.0f, false);
        glFinish();
    };
    auto settle = [&] {  // pool entries unused for a few frames are freed
        s.width = 64;
        s.height = 48;
        s.view = DebugView::Final;
        for (int i = 0; i < 6; ++i) render();
    };
    for (DebugView v : allViews()) {  // compile every program once
        s.view = v;
        render();
    }
    settle();
    const long before = gl::liveObjectCount();
    for (int i = 0; i < 100; ++i) {  // 100 resizes and view switches
        s.width = 64 + (i % 7) * 8;
        s.height = 48 + (i % 5) * 8;
        s.view = allViews()[size_t(i) % allViews().size()];
        render();
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
        if (v == DebugView::Velocity) continue;  // black while the camera stands still (test_motion.cpp)
        // The Cornell box's MTL materials are dielectrics that emit nothing (test_material_views.cpp).
        // No coat either (KHR_materials_clearcoat): the clearcoat view is black there (test_gltf_brdf.cpp).
        if (v == DebugView::Metallic || v == DebugView::Emissive || v == DebugView::TermClearcoat) continue;
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

namespace {
// Stands in for CUDA's shared textures: ordinary textures, counted, RGBA16F only.
struct CountingSource final : fg::ExternalTextureSource {
    struct Made final : fg::ExternalTexture {
        gl::Texture t;
        GLuint texture() const override { return t.id(); }
    };
    std::vector<GLuint> made;
    std::shared_ptr<fg::ExternalTexture> make(const fg::TextureDesc& d, const std::string& label) override {
        if (d.format != GL_RGBA16F) return nullptr;
        auto m = std::make_shared<Made>();
        m->t = gl::makeTexture2D(d.format, d.width, d.height, d.levels, label);
        made.push_back(m->t.id());
        return m;
    }
};
}  // namespace

// Resources a live pass touches with Usage::Cuda come from the pool's external source (once, then
// reused across frames); others, and formats the source declines, stay ordinary; a different source
// drops the old shared textures.
TEST(FrameGraphGl, CudaTouchedResourcesComeFromTheExternalSource) {
    const long objectsBefore = gl::liveObjectCount();
    {
        CountingSource source;
        fg::TexturePool pool;
        pool.setExternalSource(&source);
        const fg::TextureDesc half{16, 8, GL_RGBA16F}, full{16, 8, GL_RGBA32F};
        GLuint hdrTex = 0, plainTex = 0, posTex = 0;
        for (int frame = 0; frame < 3; ++frame) {
            fg::FrameGraph g;
            fg::ResourceId hdr, plain, pos;
            g.addPass("light", fg::PassKind::Compute, [&](fg::PassBuilder& p) {
                hdr = p.create("hdr", half, fg::Usage::ImageStore);
                plain = p.create("plain", half, fg::Usage::ImageStore);
                pos = p.create("position", full, fg::Usage::ImageStore);
            }, nullptr);
            fg::ResourceId out;
            g.addPass("post", fg::PassKind::Cuda, [&](fg::PassBuilder& p) {
                out = p.write(hdr, fg::Usage::Cuda);
                p.read(pos, fg::Usage::Cuda);
                p.read(plain, fg::Usage::Sampled);
            }, [&](const fg::PassResources& r) {
                hdrTex = r.texture(out);
                plainTex = r.texture(plain);
                posTex = r.texture(pos);
            });
            g.markOutput(out);
            g.compile();
            g.execute(pool);
        }
        ASSERT_EQ(source.made.size(), 1u);  // the RGBA16F HDR buffer, once for three frames
        EXPECT_EQ(hdrTex, source.made[0]);
        EXPECT_NE(plainTex, source.made[0]);
        EXPECT_NE(posTex, 0u);  // RGBA32F declined: an ordinary texture
        EXPECT_EQ(pool.externalCount(), 1u);
        // A new source: the shared HDR buffer is still held (the last frame's output, readable until
        // the next frame), so it goes once idle; ordinary textures take its place meanwhile.
        pool.setExternalSource(nullptr);
        for (int frame = 0; frame < 5; ++frame) {
            fg::FrameGraph g;
            fg::ResourceId hdr;
            g.addPass("post", fg::PassKind::Cuda, [&](fg::PassBuilder& p) { hdr = p.create("hdr", half, fg::Usage::Cuda); },
                      [&](const fg::PassResources& r) { EXPECT_NE(r.texture(hdr), source.made[0]); });
            g.markOutput(hdr);
            g.compile();
            g.execute(pool);
        }
        EXPECT_EQ(pool.externalCount(), 0u);
        EXPECT_EQ(source.made.size(), 1u);
    }
    EXPECT_EQ(gl::liveObjectCount(), objectsBefore);
}
