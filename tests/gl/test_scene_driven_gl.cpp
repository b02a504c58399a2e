// The scene-driven frame graph on the GPU: what a scene does not need costs no GPU time and no
// texture memory, targets nothing reads are never allocated, and the IBL bake runs only in the frame
// where the environment (or its bake settings) changed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "frame/renderer.hpp"
#include "engine/scene/scene_loader.hpp"
#include "gl_fixture.hpp"

using namespace lp;

namespace {

RenderSettings tiny() {
    RenderSettings s;
    s.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    s.autoExposure = false;       // and 0 EV
    s.width = 64;
    s.height = 48;
    // small bakes: the software rasteriser bakes in well under a second
    s.environment.cubeSize = 32;
    s.environment.specularSize = 16;
    s.environment.specularLevels = 3;
    s.environment.specularSamples = 16;
    s.environment.irradianceSize = 8;
    s.environment.irradianceSamples = 16;
    s.environment.dfgSize = 16;
    s.environment.dfgSamples = 16;
    return s;
}

bool timed(gl::GpuTimerRing& timers, const std::string& prefix) {
    for (const auto& name : timers.passOrder())
        if (name.rfind(prefix, 0) == 0) return true;
    return false;
}

}  // namespace

TEST(SceneDrivenGl, UnneededPassesCostNoTimeAndNoMemory) {
    Scene scene = loadScene(test::repoPath("scenes/unlit.json"));
    Renderer r(scene);
    RenderSettings s = tiny();
    r.render(s, 0.0f, true);
    r.render(s, 0.0f, true);
    glFinish();
    r.timers().flush();
    for (const char* pass : {"shadow_map", "local_lights", "sky", "ibl", "bloom", "toon"})
        EXPECT_FALSE(timed(r.timers(), pass)) << pass << " was timed in a scene that does not need it";
    EXPECT_TRUE(timed(r.timers(), "gbuffer"));
    EXPECT_EQ(r.persistentTextureBytes(), 0u);  // no environment cube, no IBL bake
    // Everything the pool holds is this graph's (reused across lifetimes, so at most its live bytes).
    const size_t needed = r.pool().totalBytes();
    EXPECT_GT(needed, 0u);
    EXPECT_LE(needed, r.graph().liveTransientBytes());

    Renderer all(scene);
    s.allPasses = true;
    all.render(s, 0.0f, true);
    all.render(s, 0.0f, true);
    glFinish();
    all.timers().flush();
    for (const char* pass : {"local_lights", "sky", "ibl", "bloom"})
        EXPECT_TRUE(timed(all.timers(), pass)) << pass << " not timed with --all-passes";
    // before pooling (bloom's buffers can reuse freed G-buffer memory, so the pool may not grow)
    EXPECT_GT(all.graph().liveTransientBytes(), r.graph().liveTransientBytes());
    EXPECT_GE(all.pool().totalBytes(), needed);
    EXPECT_GT(all.persistentTextureBytes(), 0u);
}

// The texcoords view reads only depth and texcoords: the other G-buffer targets get texture 0 and
// the G-buffer pass (classic) or the resolve (visibility) writes without them (no GL error), and the
// view is still the texcoords. The pool holds depth, texcoords and the display, plus the R32UI
// triangle ids in visibility mode (the one target that mode adds).
TEST(SceneDrivenGl, UnreadGBufferTargetsAreNotAllocated) {
    Scene scene = loadScene(test::repoPath("scenes/cornell.json"));
    auto bytes = [](GLenum format) { return fg::TextureDesc{64, 48, format}.bytes(); };
    for (GBufferMode mode : allGBufferModes()) {
        SCOPED_TRACE(std::string(gbufferModeName(mode)) + " G-buffer");
        Renderer r(scene);
        RenderSettings s = tiny();
        s.view = DebugView::Texcoords;
        s.gbuffer.mode = mode;
        ASSERT_NO_THROW(r.render(s, 0.0f, false));
        const bool visibility = mode == GBufferMode::Visibility;
        ASSERT_EQ(r.graph().isLive("gbuffer_resolve"), visibility);
        EXPECT_EQ(r.pool().totalBytes(), bytes(GL_DEPTH_COMPONENT32F) + bytes(GL_RG32F) + bytes(GL_RGBA8) +
                                             (visibility ? bytes(GL_R32UI) : 0));
        bool idsLive = false;
        for (const auto& res : r.graph().resources()) {
            if (res.name == "gbuffer.normal" || res.name == "gbuffer.diffuse" || res.name == "gbuffer.specular")
                EXPECT_FALSE(res.live) << res.name;
            if (res.name == "gbuffer.visibility") idsLive = res.live;
        }
        EXPECT_EQ(idsLive, visibility) << "gbuffer.visibility";
    }
}

TEST(SceneDrivenGl, IblBakeRunsOnlyWhenTheEnvironmentChanged) {
    Scene scene = loadScene(test::repoPath("scenes/ibl-spheres.json"));
    Renderer r(scene);
    RenderSettings s = tiny();
    auto bakeRuns = [&] {
        r.render(s, 0.0f, false);
        return r.graph().isLive("ibl_bake");
    };
    EXPECT_TRUE(bakeRuns());
    EXPECT_FALSE(bakeRuns());
    bool listed = false;
    for (const auto& d : r.graph().explain())
        if (d.name == "ibl_bake") listed = d.reason == "skipped: environment unchanged since its bake (cached)";
    EXPECT_TRUE(listed);
    s.environment.specularSamples = 32;  // a bake setting: baked again, once
    EXPECT_TRUE(bakeRuns());
    EXPECT_FALSE(bakeRuns());
    scene.environment.rotationDegrees = 90.0f;  // another environment
    EXPECT_TRUE(bakeRuns());
    EXPECT_FALSE(bakeRuns());
}

// Switching any one pass off still gives a frame: no GL error (a disabled pass clears what it
// creates, integer and depth targets included), no GL state left changed, no NaN.
TEST(SceneDrivenGl, DisablingAnyPassLeavesAValidFrame) {
    Scene scene = loadScene(test::repoPath("scenes/cornell.json"));
    for (GBufferMode mode : allGBufferModes()) {  // each mode's own G-buffer passes disabled too
        SCOPED_TRACE(std::string(gbufferModeName(mode)) + " G-buffer");
        RenderSettings s = tiny();
        s.environment.ibl = true;
        s.post.bloom = true;
        s.post.toon = true;
        s.post.bloomMethod = PostSettings::BloomMethod::MipChain;
        s.post.backend = PostSettings::Backend::Glsl;
        s.autoExposure = true;
        s.keepHdr = true;
        s.gbuffer.normal = GBufferNormalFormat::Oct16;  // an integer target
        s.gbuffer.mode = mode;
        Renderer r(scene);
        r.render(s, 0.0f, false);
        std::vector<std::string> passes = r.graph().executionOrder();
        ASSERT_GE(passes.size(), size_t(9));
        EXPECT_EQ(std::count(passes.begin(), passes.end(), "gbuffer_resolve"), mode == GBufferMode::Visibility ? 1 : 0);
        for (const std::string& name : passes) {
            RenderSettings off = s;
            off.disabledPasses = {name};
            ASSERT_NO_THROW(r.render(off, 0.0f, false)) << name;
            for (float v : r.readHdr().rgba) ASSERT_TRUE(std::isfinite(v)) << "with " << name << " off";
            EXPECT_EQ(r.readDisplay().width, s.width);
        }
    }
}
