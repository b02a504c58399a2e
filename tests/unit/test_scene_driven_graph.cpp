// The scene-driven frame graph: which passes and G-buffer targets a scene under given settings gets
// (no GL: graphs are built and compiled, never executed), and the CPU frustum test behind "all local
// lights out of view".
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>
#include <map>
#include <set>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/error.hpp"
#include "engine/graph/frame_graph.hpp"
#include "frame/frame_builder.hpp"
#include "passes/visibility_resolve_pass.hpp"
#include "engine/scene/scene_loader.hpp"

using namespace lp;

namespace {

using Names = std::set<std::string>;

const Scene& bundledScene(const std::string& name) {
    static std::map<std::string, Scene> cache;  // each scene is loaded once for all tests
    auto it = cache.find(name);
    if (it == cache.end())
        it = cache.emplace(name, loadScene(std::string(LIGHTPASS_SOURCE_DIR) + "/scenes/" + name + ".json")).first;
    return it->second;
}

struct Built {
    Names runs;      // candidate passes that run
    Names skipped;   // candidate passes with a reason
    Names gbuffer;   // G-buffer targets that are allocated
    std::map<std::string, std::string> reasons;
    size_t transientBytes = 0;
};

// softwareRaster, maxStorageBlockBytes: the GPU the frame is for (--gbuffer-mode auto follows them).
Built build(const Scene& scene, const RenderSettings& settings, bool softwareRaster = true,
            uint64_t maxStorageBlockBytes = 0) {
    FrameData frame = makeFrameData(scene, settings, 0.0f);
    frame.softwareRaster = softwareRaster;
    frame.maxStorageBlockBytes = maxStorageBlockBytes;
    fg::FrameGraph graph;
    PassStates passes;
    buildFrameGraph(graph, passes, frame);
    graph.compile();
    Built b;
    for (const fg::PassDecision& d : graph.explain()) {
        (d.runs ? b.runs : b.skipped).insert(d.name);
        if (!d.runs) b.reasons[d.name] = d.reason;
    }
    for (const fg::ResourceReport& r : graph.resources())
        if (r.live && r.name.rfind("gbuffer.", 0) == 0) b.gbuffer.insert(r.name.substr(8));
    b.transientBytes = graph.liveTransientBytes();
    return b;
}

RenderSettings small() {
    RenderSettings s;
    s.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    s.autoExposure = false;       // and 0 EV
    s.width = 320;
    s.height = 180;
    return s;
}

Names minus(const Names& a, const Names& b) {
    Names out;
    std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::inserter(out, out.end()));
    return out;
}

std::string show(const Names& n) {
    std::string s;
    for (const auto& x : n) s += (s.empty() ? "" : " ") + x;
    return "{" + s + "}";
}

}  // namespace

// Scenes x settings -> exactly the passes that run and the G-buffer targets that are allocated.
TEST(SceneDrivenGraph, TableOfScenesAndSettings) {
    const Names lit = {"depth", "normal", "diffuse", "position", "specular"};
    struct Row {
        std::string scene, label;
        std::function<void(RenderSettings&)> set;
        Names runs, gbuffer;
    };
    const std::vector<Row> rows = {
        {"cornell", "defaults", [](RenderSettings&) {},
         {"ibl_bake", "gbuffer", "ao_depth", "ao", "ao_blur", "ao_denoise", "shadow_map_0", "global_lights", "local_lights", "sky", "tonemap"}, lit},
        {"cornell", "positions rebuilt from depth",
         [](RenderSettings& s) { s.gbuffer.position = GBufferPositionMode::Depth; },
         {"ibl_bake", "gbuffer", "ao_depth", "ao", "ao_blur", "ao_denoise", "shadow_map_0", "global_lights", "local_lights", "sky", "tonemap"},
         {"depth", "normal", "diffuse", "specular"}},
        {"cornell", "lighting view (no albedo, no sky)", [](RenderSettings& s) { s.view = DebugView::Lighting; },
         {"gbuffer", "ao_depth", "ao", "ao_blur", "ao_denoise", "shadow_map_0", "global_lights", "local_lights", "tonemap"},
         {"depth", "normal", "position", "specular"}},
        {"cornell", "--no-shadows", [](RenderSettings& s) { s.shadows.enabled = false; },
         {"ibl_bake", "gbuffer", "ao_depth", "ao", "ao_blur", "ao_denoise", "global_lights", "local_lights", "sky", "tonemap"}, lit},
        {"cornell", "--no-local-lights", [](RenderSettings& s) { s.localLights.enabled = false; },
         {"ibl_bake", "gbuffer", "ao_depth", "ao", "ao_blur", "ao_denoise", "shadow_map_0", "global_lights", "sky", "tonemap"}, lit},
        {"cornell", "--ibl --bloom --toon",
         [](RenderSettings& s) {
             s.environment.ibl = true;
             s.post.bloom = true;
             s.post.toon = true;
         },
         {"ibl_bake", "gbuffer", "ao_depth", "ao", "ao_blur", "ao_denoise", "shadow_map_0", "global_lights", "ibl", "local_lights", "sky", "bloom",
          "bloom_composite", "toon", "tonemap"},
         lit},
        {"cornell", "texcoords view", [](RenderSettings& s) { s.view = DebugView::Texcoords; },
         {"gbuffer", "debug_view"}, {"depth", "texcoord"}},
        {"unlit", "defaults", [](RenderSettings&) {}, {"gbuffer", "ao_depth", "ao", "ao_blur", "ao_denoise", "global_lights", "tonemap"}, lit},
        {"unlit", "--all-passes", [](RenderSettings& s) { s.allPasses = true; },
         {"ibl_bake", "gbuffer", "ao_depth", "ao", "ao_blur", "ao_denoise", "global_lights", "ibl", "local_lights", "sky", "bloom", "bloom_composite",
          "tonemap"},
         lit},
        {"ibl-spheres", "defaults", [](RenderSettings&) {},
         {"ibl_bake", "gbuffer", "ao_depth", "ao", "ao_blur", "ao_denoise", "global_lights", "ibl", "sky", "tonemap"}, lit},
        {"cornell", "--no-ao", [](RenderSettings& s) { s.ao.enabled = false; },
         {"ibl_bake", "gbuffer", "shadow_map_0", "global_lights", "local_lights", "sky", "tonemap"}, lit},
        {"cornell", "ao view (computed regardless of --no-ao)",
         [](RenderSettings& s) {
             s.view = DebugView::Ao;
             s.ao.enabled = false;
         },
         {"gbuffer", "ao_depth", "ao", "ao_blur", "ao_denoise", "debug_view"}, {"depth", "normal", "position", "specular"}},
        {"lights-4k", "defaults", [](RenderSettings&) {}, {"gbuffer", "ao_depth", "ao", "ao_blur", "ao_denoise", "global_lights", "local_lights", "tonemap"}, lit},
        // The visibility buffer: the same targets (plus the id target), made by two passes.
        {"cornell", "--gbuffer-mode visibility",
         [](RenderSettings& s) { s.gbuffer.mode = GBufferMode::Visibility; },
         {"ibl_bake", "gbuffer_visibility", "gbuffer_resolve", "ao_depth", "ao", "ao_blur", "ao_denoise", "shadow_map_0", "global_lights",
          "local_lights", "sky", "tonemap"},
         {"depth", "normal", "diffuse", "position", "specular", "visibility"}},
        {"cornell", "--gbuffer-mode visibility, positions from depth",
         [](RenderSettings& s) {
             s.gbuffer.mode = GBufferMode::Visibility;
             s.gbuffer.position = GBufferPositionMode::Depth;
         },
         {"ibl_bake", "gbuffer_visibility", "gbuffer_resolve", "ao_depth", "ao", "ao_blur", "ao_denoise", "shadow_map_0", "global_lights",
          "local_lights", "sky", "tonemap"},
         {"depth", "normal", "diffuse", "specular", "visibility"}},
        {"cornell", "--gbuffer-mode visibility, texcoords view",
         [](RenderSettings& s) {
             s.gbuffer.mode = GBufferMode::Visibility;
             s.view = DebugView::Texcoords;
         },
         {"gbuffer_visibility", "gbuffer_resolve", "debug_view"}, {"depth", "texcoord", "visibility"}},
        // forward+: the pre-pass writes what later passes read: depth, plus AO's normals and specular.
        {"cornell", "forward+", [](RenderSettings& s) { s.renderPath = RenderPath::ForwardPlus; },
         {"ibl_bake", "depth_prepass", "ao_depth", "ao", "ao_blur", "ao_denoise", "shadow_map_0", "forward_opaque", "sky", "tonemap"},
         {"depth", "normal", "position", "specular"}},
        {"cornell", "forward+ --no-ao (depth alone)",
         [](RenderSettings& s) {
             s.renderPath = RenderPath::ForwardPlus;
             s.ao.enabled = false;
         },
         {"ibl_bake", "depth_prepass", "shadow_map_0", "forward_opaque", "sky", "tonemap"}, {"depth"}},
        {"cornell", "forward+ --aa taa (depth and motion)",
         [](RenderSettings& s) {
             s.renderPath = RenderPath::ForwardPlus;
             s.ao.enabled = false;
             s.aa.method = AntiAliasing::Taa;
         },
         {"ibl_bake", "depth_prepass", "shadow_map_0", "forward_opaque", "sky", "taa", "tonemap"}, {"depth", "velocity"}},
        {"glass", "defaults (transparent pass)", [](RenderSettings&) {},
         {"gbuffer", "ao_depth", "ao", "ao_blur", "ao_denoise", "shadow_map_0", "global_lights", "local_lights", "sky", "transparent", "tonemap"},
         lit},
    };
    for (const Row& row : rows) {
        RenderSettings s = small();
        row.set(s);
        const Built b = build(bundledScene(row.scene), s);
        EXPECT_EQ(b.runs, row.runs) << row.scene << " / " << row.label << ": runs " << show(b.runs) << ", expected "
                                    << show(row.runs);
        EXPECT_EQ(b.gbuffer, row.gbuffer) << row.scene << " / " << row.label << ": G-buffer " << show(b.gbuffer)
                                          << ", expected " << show(row.gbuffer);
    }
}

TEST(SceneDrivenGraph, SkippedPassesSayWhy) {
    const Built unlit = build(bundledScene("unlit"), small());
    EXPECT_EQ(unlit.reasons.at("shadow_map"), "skipped: no directional light casts shadows");
    EXPECT_EQ(unlit.reasons.at("local_lights"), "skipped: scene has no local lights");
    EXPECT_EQ(unlit.reasons.at("ibl"), "skipped: scene has no environment map");
    EXPECT_EQ(unlit.reasons.at("ibl_bake"), "skipped: scene has no environment map");
    EXPECT_EQ(unlit.reasons.at("sky"), "skipped: scene has no environment (black, no map)");
    EXPECT_NE(unlit.reasons.at("bloom").find("skipped: off in the scene"), std::string::npos);
    // The bake runs where something samples the environment: the final image's sky, an environment view.
    RenderSettings view = small();
    view.view = DebugView::Normals;
    EXPECT_EQ(build(bundledScene("cornell"), view).reasons.at("ibl_bake"),
              "skipped: nothing in this view samples the environment");
    view.view = DebugView::Prefiltered;
    EXPECT_TRUE(build(bundledScene("cornell"), view).runs.count("ibl_bake"));
    EXPECT_TRUE(build(bundledScene("cornell"), small()).runs.count("ibl_bake"));
    RenderSettings off = small();
    off.localLights.enabled = false;
    EXPECT_EQ(build(bundledScene("lights-4k"), off).reasons.at("local_lights"),
              "skipped: local lights are off (--no-local-lights)");
}

// Toggling one effect adds or removes exactly that effect's passes, and nothing else.
TEST(SceneDrivenGraph, TogglingAnEffectChangesExactlyItsPasses) {
    struct Toggle {
        std::string label;
        std::function<void(RenderSettings&, bool)> set;
        Names passes;
        std::string skippedAs;  // the name it is listed under when off ("" when never listed)
    };
    const std::vector<Toggle> toggles = {
        {"shadows", [](RenderSettings& s, bool on) { s.shadows.enabled = on; }, {"shadow_map_0"}, "shadow_map"},
        {"local lights", [](RenderSettings& s, bool on) { s.localLights.enabled = on; }, {"local_lights"}, "local_lights"},
        {"light globes", [](RenderSettings& s, bool on) { s.localLights.globes = on; }, {"light_globes"}, ""},
        {"ibl", [](RenderSettings& s, bool on) { s.environment.ibl = on; }, {"ibl"}, "ibl"},
        {"bloom", [](RenderSettings& s, bool on) { s.post.bloom = on; }, {"bloom", "bloom_composite"}, "bloom"},
        {"toon", [](RenderSettings& s, bool on) { s.post.toon = on; }, {"toon"}, "toon"},
        {"ambient occlusion", [](RenderSettings& s, bool on) { s.ao.enabled = on; }, {"ao_depth", "ao", "ao_blur", "ao_denoise"}, "ao"},
    };
    for (const Toggle& t : toggles) {
        RenderSettings on = small(), off = small();
        t.set(on, true);
        t.set(off, false);
        const Built a = build(bundledScene("cornell"), on), b = build(bundledScene("cornell"), off);
        EXPECT_EQ(minus(a.runs, b.runs), t.passes) << t.label << " on adds " << show(minus(a.runs, b.runs));
        EXPECT_EQ(minus(b.runs, a.runs), Names{}) << t.label << " on removes " << show(minus(b.runs, a.runs));
        if (!t.skippedAs.empty()) {
            EXPECT_TRUE(b.skipped.count(t.skippedAs)) << t.label << " off: not listed as skipped";
            EXPECT_FALSE(a.skipped.count(t.skippedAs)) << t.label << " on: still listed as skipped";
        }
    }
}

// A pass the scene does not need costs no texture: the graph's live transients shrink by exactly
// the bytes of what it would have created (shadow maps) and of the targets only it reads.
TEST(SceneDrivenGraph, SkippedPassesAllocateNothing) {
    RenderSettings s = small();
    const Built normal = build(bundledScene("unlit"), s);
    s.allPasses = true;
    const Built all = build(bundledScene("unlit"), s);
    auto bytes = [](GLenum format) { return fg::TextureDesc{320, 180, format}.bytes(); };
    // The AO's half-size depth, raw and blurred targets.
    const size_t halfBytes = fg::TextureDesc{160, 90, GL_R32F}.bytes() + 2 * fg::TextureDesc{160, 90, GL_R16F}.bytes();
    // depth, normal, diffuse, position, specular; the AO's half-size targets and full-size target (its
    // ambient is lit); hdr; ldr.final: nothing for shadows, lights, sky, IBL.
    EXPECT_EQ(normal.transientBytes, bytes(GL_DEPTH_COMPONENT32F) + bytes(gbufferNormalFormat(s.gbuffer.normal)) +
                                         bytes(GL_RGBA8) + bytes(GL_RGBA32F) + bytes(gbufferSpecularFormat(s.gbuffer.normal)) +
                                         halfBytes + bytes(GL_R8) +
                                         bytes(GL_RGBA16F) + bytes(GL_RGBA8));
    EXPECT_GT(all.transientBytes, normal.transientBytes);  // bloom's buffers

    // cornell with shadows off: exactly the shadow atlas less when it is transient (--shadow-cache
    // off); with the cache on the atlas is kept outside the graph (imported) and costs no transient.
    for (bool cache : {false, true}) {
        RenderSettings on = small(), off = small();
        on.shadows.cache = off.shadows.cache = cache;
        off.shadows.enabled = false;
        FrameData frame = makeFrameData(bundledScene("cornell"), on, 0.0f);
        fg::FrameGraph g;
        PassStates passes;
        buildFrameGraph(g, passes, frame);
        g.compile();
        size_t shadowBytes = 0;
        for (const auto& r : g.resources())
            if (r.name.rfind("shadow_map_", 0) == 0 && r.live) {
                shadowBytes += r.desc.bytes();
                EXPECT_EQ(r.imported, cache) << r.name;
            }
        ASSERT_GT(shadowBytes, 0u);
        EXPECT_EQ(build(bundledScene("cornell"), on).transientBytes - build(bundledScene("cornell"), off).transientBytes,
                  cache ? 0u : shadowBytes);
    }
}

TEST(SceneDrivenGraph, LocalLightsAllOutOfViewSkipThePass) {
    Scene scene = bundledScene("lights-4k");
    RenderSettings s = small();
    EXPECT_EQ(localLightsInView(makeFrameData(scene, s, 0.0f)), int(scene.pointLights.size()));
    // Turn the camera around: every light is inside the box, now behind the camera.
    scene.camera.target = scene.camera.position + (scene.camera.position - scene.camera.target);
    EXPECT_EQ(localLightsInView(makeFrameData(scene, s, 0.0f)), 0);
    const Built b = build(scene, s);
    EXPECT_EQ(b.runs, (Names{"gbuffer", "ao_depth", "ao", "ao_blur", "ao_denoise", "global_lights", "tonemap"}));
    EXPECT_EQ(b.reasons.at("local_lights"), "skipped: all 4096 local lights are out of view");
    s.allPasses = true;
    EXPECT_TRUE(build(scene, s).runs.count("local_lights"));
}

// Ambient occlusion runs only where there is indirect light to occlude: IBL or a non-zero ambient.
TEST(SceneDrivenGraph, AmbientOcclusionOnlyWithIndirectLight) {
    Scene scene = bundledScene("lights-4k");  // no environment map; ambient 0.005
    RenderSettings s = small();
    EXPECT_TRUE(build(scene, s).runs.count("ao"));
    scene.ambient = glm::vec3(0.0f);
    const Built dark = build(scene, s);
    for (const char* pass : {"ao_depth", "ao", "ao_blur", "ao_denoise"}) {
        EXPECT_FALSE(dark.runs.count(pass)) << pass;
        EXPECT_EQ(dark.reasons.at(pass), "skipped: no indirect light to occlude (IBL off, ambient 0)") << pass;
    }
    scene.ambient = glm::vec3(0.0f, 0.0f, 1e-3f);  // one channel is enough
    EXPECT_TRUE(build(scene, s).runs.count("ao_denoise"));

    // IBL alone (ibl-spheres has ambient 0) calls for it; IBL off there leaves nothing indirect.
    RenderSettings ibl = small();
    EXPECT_TRUE(build(bundledScene("ibl-spheres"), ibl).runs.count("ao"));
    ibl.environment.ibl = false;
    EXPECT_EQ(build(bundledScene("ibl-spheres"), ibl).reasons.at("ao"),
              "skipped: no indirect light to occlude (IBL off, ambient 0)");

    RenderSettings off = small();
    off.ao.enabled = false;
    EXPECT_EQ(build(bundledScene("cornell"), off).reasons.at("ao"), "skipped: ambient occlusion is off (--no-ao)");
    off.allPasses = true;  // --all-passes does not override an explicit --no-ao
    EXPECT_FALSE(build(bundledScene("cornell"), off).runs.count("ao"));
    scene.ambient = glm::vec3(0.0f);
    s.allPasses = true;  // but adds it without indirect light
    EXPECT_TRUE(build(scene, s).runs.count("ao"));
}

// Spheres against a 90-degree frustum looking down -Z (near 1, far 10): the distance to a side
// plane x = -z is |x + z| / sqrt(2), so a sphere at (x, 0, -5) touches it when x - 5 = r * sqrt(2).
TEST(SceneDrivenGraph, SphereFrustumTestMatchesPlaneDistances) {
    const glm::mat4 vp = glm::perspective(glm::radians(90.0f), 1.0f, 1.0f, 10.0f);
    const float r = 1.0f, touch = 5.0f + r * std::sqrt(2.0f);
    EXPECT_TRUE(sphereIntersectsFrustum(vp, {0, 0, -5}, 0.1f));
    EXPECT_TRUE(sphereIntersectsFrustum(vp, {touch - 1e-3f, 0, -5}, r));
    EXPECT_FALSE(sphereIntersectsFrustum(vp, {touch + 1e-3f, 0, -5}, r));
    EXPECT_FALSE(sphereIntersectsFrustum(vp, {0, 0, 2.0f}, 0.9f));     // behind the near plane (z = -1) by 3
    EXPECT_TRUE(sphereIntersectsFrustum(vp, {0, 0, 2.0f}, 3.01f));
    EXPECT_FALSE(sphereIntersectsFrustum(vp, {0, 0, -12.0f}, 1.99f));  // past the far plane by 2
    EXPECT_TRUE(sphereIntersectsFrustum(vp, {0, 0, -12.0f}, 2.01f));
    // A camera that has moved: the same test in world space through the view matrix.
    const glm::mat4 view = glm::lookAt(glm::vec3(3, 0, 0), glm::vec3(3, 0, -1), glm::vec3(0, 1, 0));
    EXPECT_TRUE(sphereIntersectsFrustum(vp * view, {3, 0, -5}, 0.1f));
    EXPECT_FALSE(sphereIntersectsFrustum(vp * view, {3 + touch + 1e-3f, 0, -5}, r));
}

namespace {
// Every live resource's size, by name.
std::map<std::string, glm::ivec2> liveSizes(const Scene& scene, const RenderSettings& settings, Names* runs) {
    FrameData frame = makeFrameData(scene, settings, 0.0f);
    fg::FrameGraph graph;
    PassStates passes;
    buildFrameGraph(graph, passes, frame);
    graph.compile();
    std::map<std::string, glm::ivec2> sizes;
    for (const fg::ResourceReport& r : graph.resources())
        if (r.live && !r.imported) sizes[r.name] = {r.desc.width, r.desc.height};
    if (runs)
        for (const fg::PassDecision& d : graph.explain())
            if (d.runs) runs->insert(d.name);
    return sizes;
}
}  // namespace

// --render-scale S: the G-buffer and the HDR buffer are round(S x output); the upscale pass and the
// tone map's target are the output size. At S = 1 the upscale pass is skipped with its reason.
TEST(SceneDrivenGraph, RenderScaleShrinksGBufferAndLightingOnly) {
    RenderSettings s = small();  // 320 x 180
    s.post.bloom = true;
    Built full = build(bundledScene("cornell"), s);
    EXPECT_FALSE(full.runs.count("upscale"));
    EXPECT_NE(full.reasons["upscale"].find("render scale 1"), std::string::npos) << full.reasons["upscale"];

    for (float scale : {0.5f, 0.25f, 0.3f}) {
        s.renderScale = scale;
        Names runs;
        auto sizes = liveSizes(bundledScene("cornell"), s, &runs);
        const glm::ivec2 inner(int(std::lround(320 * scale)), int(std::lround(180 * scale)));
        EXPECT_TRUE(runs.count("upscale")) << scale;
        EXPECT_TRUE(runs.count("bloom")) << scale;
        EXPECT_EQ(sizes["gbuffer.depth"], inner) << scale;
        EXPECT_EQ(sizes["gbuffer.normal"], inner) << scale;
        EXPECT_EQ(sizes["hdr"], inner) << scale;
        EXPECT_EQ(sizes["bloom"], inner) << scale;
        EXPECT_EQ(sizes["hdr.output"], glm::ivec2(320, 180)) << scale;
        EXPECT_EQ(sizes["ldr.final"], glm::ivec2(320, 180)) << scale;
    }
    // A debug view is upsampled too (nearest), so every view keeps the output size.
    s.renderScale = 0.5f;
    s.view = DebugView::Normals;
    Names runs;
    auto sizes = liveSizes(bundledScene("cornell"), s, &runs);
    EXPECT_TRUE(runs.count("upscale_debug"));
    EXPECT_FALSE(runs.count("upscale"));  // the HDR path is culled in a channel view
    EXPECT_EQ(sizes["ldr.debug"], glm::ivec2(160, 90));
    EXPECT_EQ(sizes["ldr.debug.output"], glm::ivec2(320, 180));
}

TEST(SceneDrivenGraph, ScaledRenderSizeRoundsAndNeverReachesZero) {
    EXPECT_EQ(scaledRenderSize(1920, 1080, 1.0f), glm::ivec2(1920, 1080));
    EXPECT_EQ(scaledRenderSize(1920, 1080, 0.5f), glm::ivec2(960, 540));
    EXPECT_EQ(scaledRenderSize(1920, 1080, 0.75f), glm::ivec2(1440, 810));
    EXPECT_EQ(scaledRenderSize(3, 1, 0.25f), glm::ivec2(1, 1));
    EXPECT_EQ(scaledRenderSize(64, 64, std::nanf("")), glm::ivec2(64, 64));  // not finite: full size
}

// --aa ssaa: the G-buffer, lighting and post effects run at S x the output size, the downsample pass
// brings the HDR buffer to the output size (no upscale pass). A --render-scale below 1 is kept
// instead and SSAA left out.
TEST(SceneDrivenGraph, SsaaRendersAboveTheOutputSizeAndDownsamples) {
    RenderSettings s = small();  // 320 x 180
    s.post.bloom = true;
    s.aa.method = AntiAliasing::Ssaa;
    {
        RenderSettings scaled = s;
        scaled.renderScale = 0.5f;
        EXPECT_FLOAT_EQ(internalRenderScale(scaled), 0.5f);
        Built built = build(bundledScene("cornell"), scaled);
        EXPECT_NE(built.reasons["ssaa_downsample"].find("--render-scale below 1"), std::string::npos)
            << built.reasons["ssaa_downsample"];
    }
    for (int scale : {2, 3, 4}) {
        s.aa.ssaaScale = scale;
        EXPECT_FLOAT_EQ(internalRenderScale(s), float(scale));
        Names runs;
        auto sizes = liveSizes(bundledScene("cornell"), s, &runs);
        EXPECT_TRUE(runs.count("ssaa_downsample")) << scale;
        EXPECT_FALSE(runs.count("upscale")) << scale;
        EXPECT_FALSE(runs.count("fxaa")) << scale;
        EXPECT_EQ(sizes["gbuffer.depth"], glm::ivec2(320 * scale, 180 * scale)) << scale;
        EXPECT_EQ(sizes["hdr"], glm::ivec2(320 * scale, 180 * scale)) << scale;
        EXPECT_EQ(sizes["bloom"], glm::ivec2(320 * scale, 180 * scale)) << scale;
        EXPECT_EQ(sizes["hdr.output"], glm::ivec2(320, 180)) << scale;
        EXPECT_EQ(sizes["ldr.final"], glm::ivec2(320, 180)) << scale;
    }
    Built built = build(bundledScene("cornell"), s);
    EXPECT_NE(built.reasons["upscale"].find("--aa ssaa"), std::string::npos) << built.reasons["upscale"];
    // A debug view at ssaa is brought to the output size by the nearest-texel pass.
    s.view = DebugView::Normals;
    Names runs;
    auto sizes = liveSizes(bundledScene("cornell"), s, &runs);
    EXPECT_TRUE(runs.count("upscale_debug"));
    EXPECT_EQ(sizes["ldr.debug.output"], glm::ivec2(320, 180));
    // Off: the render scale applies again, and neither AA pass runs (each skipped with its reason).
    s = small();
    EXPECT_FLOAT_EQ(internalRenderScale(s), 1.0f);
    built = build(bundledScene("cornell"), s);
    EXPECT_FALSE(built.runs.count("ssaa_downsample"));
    EXPECT_FALSE(built.runs.count("fxaa"));
    EXPECT_NE(built.reasons["ssaa_downsample"].find("not ssaa"), std::string::npos);
    EXPECT_NE(built.reasons["fxaa"].find("not fxaa"), std::string::npos);
}

// --aa fxaa: the tone map writes RGBA16F (no quantisation there) and the fxaa pass the RGBA8 display
// image at the output size, also at render scale < 1.
TEST(SceneDrivenGraph, FxaaFollowsAFloatToneMap) {
    RenderSettings s = small();
    s.aa.method = AntiAliasing::Fxaa;
    for (float scale : {1.0f, 0.5f}) {
        s.renderScale = scale;
        FrameData frame = makeFrameData(bundledScene("cornell"), s, 0.0f);
        fg::FrameGraph graph;
        PassStates passes;
        buildFrameGraph(graph, passes, frame);
        graph.compile();
        EXPECT_TRUE(graph.isLive("fxaa"));
        EXPECT_TRUE(graph.isLive("tonemap"));
        EXPECT_EQ(graph.isLive("upscale"), scale < 1.0f);
        std::map<std::string, fg::TextureDesc> live;
        for (const fg::ResourceReport& r : graph.resources())
            if (r.live) live[r.name] = r.desc;
        ASSERT_TRUE(live.count("ldr.tonemapped"));
        EXPECT_EQ(live["ldr.tonemapped"].format, GLenum(GL_RGBA16F));
        EXPECT_EQ(live["ldr.final"].format, GLenum(GL_RGBA8));
        EXPECT_EQ(live["ldr.final"].width, 320);
    }
}

// --aa taa: the G-buffer writes velocity, the taa pass reads it with the imported history and its
// result goes to the tone map; a G-buffer view is not anti-aliased (nor jittered).
TEST(SceneDrivenGraph, TaaReadsVelocityAndImportsItsHistory) {
    RenderSettings s = small();
    s.aa.method = AntiAliasing::Taa;
    EXPECT_TRUE(temporalAntiAliasing(s));
    Built built = build(bundledScene("cornell"), s);
    EXPECT_TRUE(built.runs.count("taa"));
    EXPECT_TRUE(built.gbuffer.count("velocity"));
    EXPECT_FALSE(built.runs.count("fxaa"));
    EXPECT_FALSE(built.runs.count("ssaa_downsample"));
    s.view = DebugView::Normals;
    EXPECT_FALSE(temporalAntiAliasing(s));
    built = build(bundledScene("cornell"), s);
    EXPECT_FALSE(built.runs.count("taa"));
    EXPECT_NE(built.reasons["taa"].find("G-buffer view"), std::string::npos) << built.reasons["taa"];
    s = small();
    built = build(bundledScene("cornell"), s);
    EXPECT_FALSE(built.gbuffer.count("velocity"));  // only TAA (or the velocity view) asks for it
    EXPECT_NE(built.reasons["taa"].find("not taa"), std::string::npos);
}

// Halton(2,3): the known first terms, 16 distinct phases inside the pixel, centred on average.
TEST(SceneDrivenGraph, TaaJitterIsHalton23In16Phases) {
    EXPECT_DOUBLE_EQ(halton(1, 2), 0.5);
    EXPECT_DOUBLE_EQ(halton(2, 2), 0.25);
    EXPECT_DOUBLE_EQ(halton(3, 2), 0.75);
    EXPECT_DOUBLE_EQ(halton(1, 3), 1.0 / 3.0);
    EXPECT_DOUBLE_EQ(halton(2, 3), 2.0 / 3.0);
    EXPECT_DOUBLE_EQ(halton(4, 3), 1.0 / 9.0 + 1.0 / 3.0);
    std::set<std::pair<float, float>> phases;
    glm::dvec2 mean(0.0);
    for (uint64_t i = 0; i < 16; ++i) {
        const glm::vec2 j = taaJitterPixels(i);
        EXPECT_GE(j.x, -0.5f);
        EXPECT_LT(j.x, 0.5f);
        EXPECT_GE(j.y, -0.5f);
        EXPECT_LT(j.y, 0.5f);
        phases.insert({j.x, j.y});
        mean += glm::dvec2(j) / 16.0;
        EXPECT_EQ(taaJitterPixels(i + 16), j);  // 16 phases repeat
    }
    EXPECT_EQ(phases.size(), 16u);
    EXPECT_LT(std::abs(mean.x), 0.05);
    EXPECT_LT(std::abs(mean.y), 0.05);
}

// The history is used only by the next frame of the same size and settings with a previous frame.
TEST(SceneDrivenGraph, TaaHistoryResetsOnCutResizeAndSettingChange) {
    RenderSettings s = small();
    s.aa.method = AntiAliasing::Taa;
    FrameData frame = makeFrameData(bundledScene("cornell"), s, 0.0f);
    frame.hasPrevious = true;
    TaaPass state;
    state.latest = 0;
    state.size = {frame.outputWidth, frame.outputHeight};
    state.signature = settingsSignature(s);
    EXPECT_TRUE(taaHistoryUsable(state, frame, settingsSignature(s)));
    FrameData cut = frame;
    cut.hasPrevious = false;  // a camera cut, the first frame, a rewind
    EXPECT_FALSE(taaHistoryUsable(state, cut, settingsSignature(s)));
    state.size = {frame.outputWidth + 1, frame.outputHeight};  // a resize
    EXPECT_FALSE(taaHistoryUsable(state, frame, settingsSignature(s)));
    state.size = {frame.outputWidth, frame.outputHeight};
    RenderSettings changed = s;
    changed.exposureEV = 1.0f;
    EXPECT_NE(settingsSignature(changed), settingsSignature(s));
    EXPECT_FALSE(taaHistoryUsable(state, frame, settingsSignature(changed)));
    changed = s;
    changed.aa.taaHistoryWeight = 0.2f;
    EXPECT_NE(settingsSignature(changed), settingsSignature(s));
    state.latest = -1;  // nothing resolved yet
    EXPECT_FALSE(taaHistoryUsable(state, frame, settingsSignature(s)));
}

// --gbuffer-mode auto (the default): the visibility buffer on a GPU's rasteriser, the classic pass on
// a software one (llvmpipe: the resolve costs 13x the classic raster there) or with none known; the
// skipped passes say why.
TEST(SceneDrivenGraph, GBufferModeAutoFollowsTheRasteriser) {
    EXPECT_TRUE(FrameData().softwareRaster) << "no GPU known: classic";
    EXPECT_EQ(RenderSettings().gbuffer.mode, GBufferMode::Auto) << "the default";
    for (bool software : {true, false}) {
        RenderSettings s = small();
        s.gbuffer.mode = GBufferMode::Auto;
        const Built b = build(bundledScene("cornell"), s, software);
        SCOPED_TRACE(software ? "software rasteriser" : "GPU rasteriser");
        EXPECT_EQ(b.runs.count("gbuffer"), software ? 1u : 0u);
        EXPECT_EQ(b.runs.count("gbuffer_visibility"), software ? 0u : 1u);
        EXPECT_EQ(b.runs.count("gbuffer_resolve"), software ? 0u : 1u);
        const std::string why = software ? b.reasons.at("gbuffer_visibility") : b.reasons.at("gbuffer");
        EXPECT_NE(why.find("--gbuffer-mode auto"), std::string::npos) << why;
        EXPECT_NE(why.find(software ? "software rasteriser" : "GPU rasteriser"), std::string::npos) << why;
        const GBufferModeChoice c = chooseGBufferMode(GBufferMode::Auto, software, "");
        EXPECT_EQ(c.mode, software ? GBufferMode::Classic : GBufferMode::Visibility);
    }
    for (GBufferMode fixed : allGBufferModes())
        for (bool software : {true, false}) EXPECT_EQ(chooseGBufferMode(fixed, software, "").mode, fixed);
}

// A scene the visibility buffer cannot hold on this GPU (its vertices or indices beyond the storage
// block limit the resolve reads them through): auto makes the classic G-buffer there and the skipped
// passes say why; an explicit --gbuffer-mode visibility is a one-line error naming the limit. Every
// material kind the scenes use (opaque, MASK, blended, textured, normal-mapped, glTF) is the
// visibility buffer's (VisibilityBuffer.GBufferEqualsClassicOnEveryBundledScene), so the size is
// the only thing auto has to check.
TEST(SceneDrivenGraph, GBufferModeAutoFallsBackWhereTheVisibilityBufferCannotHoldTheScene) {
    const Scene& scene = bundledScene("cornell");
    uint64_t vertexBytes = 0, indexBytes = 0;
    for (const ModelInstance& m : scene.models) {
        vertexBytes += m.mesh.vertices.size() * sizeof(GpuVertex);
        indexBytes += m.mesh.indices.size() * sizeof(uint32_t);
    }
    ASSERT_GT(vertexBytes, indexBytes);
    EXPECT_EQ(visibilityBufferUnsupported(scene, 0), "") << "unknown limit: not checked";
    EXPECT_EQ(visibilityBufferUnsupported(scene, vertexBytes), "") << "exactly at the limit fits";
    const std::string why = visibilityBufferUnsupported(scene, vertexBytes - 1);
    EXPECT_NE(why.find("vertices"), std::string::npos) << why;
    EXPECT_NE(why.find("GL_MAX_SHADER_STORAGE_BLOCK_SIZE"), std::string::npos) << why;
    EXPECT_NE(visibilityBufferUnsupported(scene, indexBytes - 1), "");

    RenderSettings s = small();
    s.gbuffer.mode = GBufferMode::Auto;
    const Built fits = build(scene, s, false, vertexBytes);
    EXPECT_EQ(fits.runs.count("gbuffer_resolve"), 1u);
    const Built tooLarge = build(scene, s, false, vertexBytes - 1);
    EXPECT_EQ(tooLarge.runs.count("gbuffer"), 1u);
    EXPECT_EQ(tooLarge.runs.count("gbuffer_visibility"), 0u);
    const std::string reason = tooLarge.reasons.at("gbuffer_resolve");
    EXPECT_NE(reason.find("--gbuffer-mode auto: classic"), std::string::npos) << reason;
    EXPECT_NE(reason.find(why), std::string::npos) << reason;
    // forward+ has no G-buffer to choose: unaffected.
    s.renderPath = RenderPath::ForwardPlus;
    EXPECT_EQ(build(scene, s, false, vertexBytes - 1).runs.count("depth_prepass"), 1u);

    s = small();
    s.gbuffer.mode = GBufferMode::Visibility;
    try {
        build(scene, s, false, vertexBytes - 1);
        ADD_FAILURE() << "--gbuffer-mode visibility built a scene the visibility buffer cannot hold";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind("--gbuffer-mode visibility: " + why, 0), 0u) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

// --gbuffer-mode: each mode's passes run and the other's are skipped with the reason; the resolve's
// image stores are followed by the barrier the lighting passes' texture fetches need, and nothing
// needs one before the resolve (it samples a colour attachment).
TEST(SceneDrivenGraph, GBufferModeChoosesItsPassesAndBarriers) {
    for (GBufferMode mode : allGBufferModes()) {
        RenderSettings s = small();
        s.gbuffer.mode = mode;
        FrameData frame = makeFrameData(bundledScene("cornell"), s, 0.0f);
        fg::FrameGraph graph;
        PassStates passes;
        buildFrameGraph(graph, passes, frame);
        graph.compile();
        std::map<std::string, std::string> reasons;
        for (const fg::PassDecision& d : graph.explain())
            if (!d.runs) reasons[d.name] = d.reason;
        const bool visibility = mode == GBufferMode::Visibility;
        SCOPED_TRACE(gbufferModeName(mode));
        for (const char* pass : {"gbuffer_visibility", "gbuffer_resolve"}) {
            EXPECT_EQ(graph.isLive(pass), visibility) << pass;
            if (!visibility) EXPECT_NE(reasons[pass].find("--gbuffer-mode classic"), std::string::npos) << reasons[pass];
        }
        EXPECT_EQ(graph.isLive("gbuffer"), !visibility);
        if (visibility) {
            EXPECT_NE(reasons["gbuffer"].find("--gbuffer-mode visibility"), std::string::npos) << reasons["gbuffer"];
            EXPECT_EQ(graph.passKind("gbuffer_resolve"), fg::PassKind::Compute);
            EXPECT_EQ(graph.passKind("gbuffer_visibility"), fg::PassKind::Raster);
            // Its inputs are raster output (no barrier for them), but its image stores may overtake
            // the previous frame's fetches of the pooled G-buffer textures (write after read): an
            // image-access barrier is due before it, its own or an earlier pass's in this frame (the
            // IBL bake's, which image-stores an imported texture, already orders the previous frame).
            GLbitfield upToResolve = 0;
            for (const std::string& pass : graph.executionOrder()) {
                upToResolve |= graph.barriersBefore(pass);
                if (pass == "gbuffer_resolve") break;
            }
            EXPECT_NE(upToResolve & GL_SHADER_IMAGE_ACCESS_BARRIER_BIT, 0u);
            EXPECT_EQ(graph.barriersBefore("gbuffer_resolve") & ~GLbitfield(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT), 0u);
            EXPECT_NE((graph.barriersBefore("ao") | graph.barriersBefore("global_lights")) & GL_TEXTURE_FETCH_BARRIER_BIT, 0u);
        }
    }
}
