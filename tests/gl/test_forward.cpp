// Forward+ (--render-path forward+) against the deferred path, and the transparent pass: the
// "over" composite of a half-opaque lit quad, back-to-front order whatever the scene's order, and
// opaque scenes left untouched (the pass is skipped, with its reason).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/scene/primitives.hpp"
#include "engine/scene/scene_loader.hpp"
#include "frame/renderer.hpp"
#include "tests/gl/render_fixture.hpp"
#include "gl_fixture.hpp"

using namespace lp;
using lp::test::renderHdr;

namespace {

RenderSettings small(RenderPath path) {
    RenderSettings s;
    s.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    s.autoExposure = false;       // and 0 EV
    s.width = 64;
    s.height = 48;
    s.keepHdr = true;
    s.renderPath = path;
    s.environment = test::smallIblBake(16);
    return s;
}

// The ways a frame is made: deferred with each G-buffer mode, and forward+ (no G-buffer to choose).
struct FrameWay {
    RenderPath path;
    GBufferMode mode;
};
std::vector<FrameWay> everyWay() {
    return {{RenderPath::Deferred, GBufferMode::Classic},
            {RenderPath::Deferred, GBufferMode::Visibility},
            {RenderPath::ForwardPlus, GBufferMode::Classic}};
}
std::string wayName(FrameWay w) {
    return w.path == RenderPath::ForwardPlus ? renderPathName(w.path)
                                             : std::string(renderPathName(w.path)) + ", " + gbufferModeName(w.mode) + " G-buffer";
}
RenderSettings small(FrameWay w) {
    RenderSettings s = small(w.path);
    s.gbuffer.mode = w.mode;
    return s;
}

// Every pass of one frame: "runs" or its skip reason.
std::map<std::string, std::string> decisions(const Scene& scene, const RenderSettings& s) {
    Renderer r(scene);
    r.render(s, 0.0f, false);
    std::map<std::string, std::string> out;
    for (const auto& d : r.graph().explain()) out[d.name] = d.runs ? "runs" : d.reason;
    return out;
}

std::string decision(const Scene& scene, const RenderSettings& s, const std::string& pass) {
    const auto all = decisions(scene, s);
    const auto it = all.find(pass);
    return it == all.end() ? "absent" : it->second;
}

struct Agreement {
    double meanRelative = 0.0, maxRelative = 0.0, litFraction = 0.0;
};
// Per channel |a - b| / max(|b|, floor), over every pixel and colour channel; litFraction: the share
// of channels above the floor (the comparison is not over a black image).
Agreement compare(const ImageF& a, const ImageF& b, double floor) {
    Agreement g;
    size_t n = 0, lit = 0;
    for (size_t i = 0; i < b.rgba.size(); ++i) {
        if (i % 4 == 3) continue;
        EXPECT_TRUE(std::isfinite(a.rgba[i]));
        const double ref = std::abs(double(b.rgba[i]));
        const double rel = std::abs(double(a.rgba[i]) - double(b.rgba[i])) / std::max(ref, floor);
        g.meanRelative += rel;
        g.maxRelative = std::max(g.maxRelative, rel);
        lit += ref > floor ? 1 : 0;
        ++n;
    }
    g.meanRelative /= double(std::max<size_t>(n, 1));
    g.litFraction = double(lit) / double(std::max<size_t>(n, 1));
    return g;
}

ModelInstance primitive(const std::string& name, MeshData mesh, glm::mat4 transform, glm::vec3 kd, float opacity,
                        bool flat) {
    ModelInstance m;
    m.name = name;
    m.primitive = name;
    m.mesh = std::move(mesh);
    for (auto& mat : m.mesh.materials) {
        mat.diffuse = kd;
        mat.specular = glm::vec3(0.04f);
        mat.shininess = 32.0f;
        mat.flat = flat;
        mat.opacity = opacity;
        mat.alphaMode = opacity < 1.0f ? AlphaMode::Blend : AlphaMode::Opaque;
    }
    m.transform = transform;
    return m;
}

// A quad of side `size` facing +Z (towards the camera) centred at (x, y, z).
glm::mat4 facingCamera(glm::vec3 at, float size) {
    glm::mat4 t = glm::translate(glm::mat4(1.0f), at);
    t = glm::rotate(t, glm::radians(90.0f), glm::vec3(1, 0, 0));
    return glm::scale(t, glm::vec3(size));
}

const glm::vec3 kBackground{0.2f, 0.3f, 0.4f};

// A flat-lit wall (radiance = its colour exactly) 2 m behind the origin, the camera 3 m in front.
Scene wallScene() {
    Scene s;
    s.models.push_back(primitive("plane", makePlane(1.0f), facingCamera({0, 0, -2}, 20.0f), kBackground, 1.0f, true));
    s.camera.position = {0.0f, 0.0f, 3.0f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    s.camera.fovYDegrees = 40.0f;
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 20.0f;
    s.ambient = glm::vec3(0.05f);
    return s;
}

glm::vec3 pixel(const ImageF& img, int x, int y) {
    const size_t i = (size_t(y) * size_t(img.width) + size_t(x)) * 4;
    return {img.rgba[i], img.rgba[i + 1], img.rgba[i + 2]};
}

}  // namespace

// Forward+ shades the Cornell box (sun with shadows, ambient, emission) like the deferred path.
// They differ by the G-buffer's quantisation (8-bit colour, the normal encoding), the position
// rebuilt from depth, and fp16 sums between the deferred passes against one fp32 sum. Bound
// (llvmpipe gives ~0.2% mean): mean relative error under 1%, and every channel within 5% of the
// deferred value or 0.02 absolute (a shadow-map tap may flip at a shadow edge: at most 1% of channels).
TEST(ForwardPlus, MatchesDeferredOnTheCornellBox) {
    const Scene scene = loadScene(test::repoPath("scenes/cornell.json"));
    const ImageF deferred = renderHdr(scene, small(RenderPath::Deferred));
    const ImageF forward = renderHdr(scene, small(RenderPath::ForwardPlus));
    const Agreement g = compare(forward, deferred, 0.02);
    RecordProperty("mean_relative", std::to_string(g.meanRelative));
    RecordProperty("max_relative", std::to_string(g.maxRelative));
    EXPECT_GT(g.litFraction, 0.5);
    EXPECT_LT(g.meanRelative, 0.01);
    size_t outliers = 0;
    for (size_t i = 0; i < deferred.rgba.size(); ++i)
        if (i % 4 != 3 && std::abs(forward.rgba[i] - deferred.rgba[i]) > std::max(0.05 * std::abs(deferred.rgba[i]), 0.02))
            ++outliers;
    EXPECT_LE(outliers, deferred.rgba.size() / 4 * 3 / 100) << "channels off by more than 5%";
}

// With IBL (the environment's SH diffuse and prefiltered specular) the same holds, with either
// specular method (--ibl-specular split-sum and sampled: the forward pass calls the same function).
TEST(ForwardPlus, MatchesDeferredWithImageBasedLighting) {
    const Scene scene = loadScene(test::repoPath("scenes/ibl-spheres.json"));
    std::vector<ImageF> deferred;
    double sampledAgreement = 0.0;
    for (IblSpecular specular : {IblSpecular::SplitSum, IblSpecular::Sampled}) {
        SCOPED_TRACE(iblSpecularName(specular));
        RenderSettings d = small(RenderPath::Deferred), f = small(RenderPath::ForwardPlus);
        d.environment.ibl = f.environment.ibl = true;
        d.environment.specular = f.environment.specular = specular;
        d.environment.specularRuntimeSamples = f.environment.specularRuntimeSamples = 8;
        // The sky's sun left in the map: the two methods differ most there (extraction is checked below).
        d.environment.extractLights = f.environment.extractLights = 0;
        deferred.push_back(renderHdr(scene, d));
        const Agreement g = compare(renderHdr(scene, f), deferred.back(), 0.02);
        RecordProperty(std::string("mean_relative_") + iblSpecularName(specular), std::to_string(g.meanRelative));
        EXPECT_GT(g.litFraction, 0.5);
        EXPECT_LT(g.meanRelative, 0.01);
        sampledAgreement = g.meanRelative;
    }
    // The two methods differ (about 1% here) far more than the paths do with the sampled one, so a
    // forward pass left on the split sum would fail.
    const Agreement methods = compare(deferred[1], deferred[0], 0.02);
    RecordProperty("sampled_against_split_sum", std::to_string(methods.meanRelative));
    EXPECT_GT(methods.meanRelative, 0.005);
    EXPECT_LT(sampledAgreement, 0.1 * methods.meanRelative);
    // With the sun taken out of the map and lit analytically (--ibl-extract-lights, the default) the
    // forward pass shades it as the ibl pass does; the extraction changes the image (the sun's
    // reflection through the BRDF instead of the prefiltered chain) far more than the paths differ.
    RenderSettings d = small(RenderPath::Deferred), f = small(RenderPath::ForwardPlus);
    d.environment.ibl = f.environment.ibl = true;
    ASSERT_GT(d.environment.extractLights, 0);
    const ImageF extracted = renderHdr(scene, d);
    const Agreement paths = compare(renderHdr(scene, f), extracted, 0.02);
    const Agreement extraction = compare(extracted, deferred[0], 0.02);
    RecordProperty("extracted_forward_against_deferred", std::to_string(paths.meanRelative));
    RecordProperty("extracted_against_not", std::to_string(extraction.meanRelative));
    EXPECT_LT(paths.meanRelative, 0.01);
    EXPECT_LT(paths.meanRelative, 0.2 * extraction.meanRelative);
}

// Local lights (points and a spot) from the froxels' lists match the deferred clustered method.
TEST(ForwardPlus, LocalLightsMatchTheDeferredClusteredMethod) {
    Scene s = wallScene();
    s.models[0].mesh.materials[0].flat = false;
    s.models.push_back(primitive("sphere", makeSphere(0.6f, 24, 12), glm::mat4(1.0f), {0.8f, 0.4f, 0.3f}, 1.0f, false));
    for (int i = 0; i < 12; ++i) {
        PointLight l;
        l.position = {-2.0f + 0.4f * float(i), 0.8f * std::sin(float(i)), -1.0f + 0.2f * float(i % 5)};
        l.range = 1.5f + 0.2f * float(i % 3);
        l.intensity = 0.6f;
        l.color = {1.0f, 0.5f + 0.04f * float(i), 0.3f};
        s.pointLights.push_back(l);
    }
    PointLight spot;
    spot.position = {0.0f, 1.5f, 1.0f};
    spot.range = 5.0f;
    spot.intensity = 3.0f;
    spot.spot = SpotCone{glm::normalize(glm::vec3(0.0f, -1.0f, -1.0f)), 10.0f, 25.0f};
    s.pointLights.push_back(spot);
    RenderSettings d = small(RenderPath::Deferred), f = small(RenderPath::ForwardPlus);
    d.localLights.method = LocalLightMethod::Clustered;
    RenderSettings off = d;
    off.localLights.enabled = false;
    const ImageF deferred = renderHdr(s, d), unlit = renderHdr(s, off);
    // The lights matter: a third of the channels are over 20% brighter than without them.
    size_t brighter = 0;
    for (size_t i = 0; i < deferred.rgba.size(); ++i)
        if (i % 4 != 3 && deferred.rgba[i] > 1.2f * unlit.rgba[i] + 1e-3f) ++brighter;
    EXPECT_GT(brighter, deferred.rgba.size() / 4);
    const Agreement g = compare(renderHdr(s, f), deferred, 0.02);
    RecordProperty("mean_relative", std::to_string(g.meanRelative));
    RecordProperty("max_relative", std::to_string(g.maxRelative));
    EXPECT_LT(g.meanRelative, 0.01);
    EXPECT_LT(g.maxRelative, 0.05);
}

// The graph of each path: forward+ runs depth_prepass and forward_opaque instead of the G-buffer and
// the deferred light passes, each skip with its reason, whatever the G-buffer mode (forward+ has no
// G-buffer). Deferred makes its G-buffer with the passes of its mode: gbuffer (classic) or
// gbuffer_visibility + gbuffer_resolve (visibility).
TEST(ForwardPlus, EachPathSkipsTheOthersPasses) {
    const Scene scene = loadScene(test::repoPath("scenes/cornell.json"));
    for (GBufferMode mode : allGBufferModes()) {
        SCOPED_TRACE(std::string(gbufferModeName(mode)) + " G-buffer");
        RenderSettings d = small(RenderPath::Deferred), f = small(RenderPath::ForwardPlus);
        d.gbuffer.mode = f.gbuffer.mode = mode;
        const auto df = decisions(scene, f), dd = decisions(scene, d);
        EXPECT_EQ(df.at("depth_prepass"), "runs");
        EXPECT_EQ(df.at("forward_opaque"), "runs");
        EXPECT_NE(df.at("global_lights").find("forward+"), std::string::npos);
        for (const char* pass : {"gbuffer", "gbuffer_visibility", "gbuffer_resolve"})
            EXPECT_NE(df.at(pass).find("forward+"), std::string::npos) << pass;
        const bool visibility = mode == GBufferMode::Visibility;
        EXPECT_EQ(dd.at("gbuffer") == "runs", !visibility);
        EXPECT_EQ(dd.at("gbuffer_visibility") == "runs", visibility);
        EXPECT_EQ(dd.at("gbuffer_resolve") == "runs", visibility);
        EXPECT_NE(dd.at("depth_prepass").find("deferred"), std::string::npos);
        EXPECT_EQ(dd.at("global_lights"), "runs");
        EXPECT_NE(dd.at("forward_opaque").find("deferred"), std::string::npos);
    }
}

// A lit quad at 50% opacity over a flat-lit wall: hdr = a L + (1 - a) B, where L is the quad's
// radiance drawn opaque by the deferred path (sun, ambient and a local light through the clusters).
// Bound: 1% relative (the deferred L passes through the 8-bit G-buffer) plus fp16 rounding.
TEST(Transparency, HalfOpaqueQuadIsTheOverComposite) {
    for (FrameWay way : everyWay()) {
        SCOPED_TRACE(wayName(way));
        Scene opaque = wallScene();
        DirectionalLight sun;
        sun.direction = glm::normalize(glm::vec3(-0.3f, -0.4f, -1.0f));
        sun.intensity = 1.5f;
        opaque.directionalLights.push_back(sun);
        PointLight l;
        l.position = {0.3f, 0.2f, 0.8f};
        l.range = 2.0f;
        l.intensity = 0.5f;
        opaque.pointLights.push_back(l);
        opaque.models.push_back(primitive("plane", makePlane(1.0f), facingCamera({0, 0, 0}, 1.5f), {0.8f, 0.6f, 0.1f}, 1.0f, false));
        Scene blended = opaque;
        blended.models[1].mesh.materials[0].opacity = 0.5f;
        blended.models[1].mesh.materials[0].alphaMode = AlphaMode::Blend;
        const ImageF L = renderHdr(opaque, small(FrameWay{RenderPath::Deferred, way.mode}));
        const ImageF got = renderHdr(blended, small(way));
        int checked = 0;
        for (int y = 16; y < 32; ++y)
            for (int x = 24; x < 40; ++x) {
                const glm::vec3 lq = pixel(L, x, y), c = pixel(got, x, y);
                ASSERT_GT(lq.x, kBackground.x + 0.05f) << "the quad covers the centre and is lit";
                const glm::vec3 expected = 0.5f * lq + 0.5f * kBackground;
                for (int k = 0; k < 3; ++k)
                    EXPECT_NEAR(c[k], expected[k], 0.01f * expected[k] + 2e-3f) << x << "," << y << " channel " << k;
                ++checked;
            }
        EXPECT_EQ(checked, 256);
        // Outside the quad the wall is untouched.
        const glm::vec3 corner = pixel(got, 1, 1);
        // Deferred paths read the wall's colour back from the 8-bit sRGB G-buffer, forward+ shades it exactly.
        const float wall = way.path == RenderPath::Deferred ? float(test::srgb8Stored(kBackground.z)) : kBackground.z;
        EXPECT_NEAR(corner.z, wall, 1e-3f);
    }
}

// Two overlapping flat-lit quads at 50% (red 0.5 m nearer than blue): near over (far over wall)
// whichever order the scene lists them in; the wrong order is far from it (the test can fail).
TEST(Transparency, OverlappingQuadsCompositeBackToFrontWhateverTheSceneOrder) {
    const glm::vec3 red{1.0f, 0.0f, 0.0f}, blue{0.0f, 0.0f, 1.0f};
    const glm::vec3 expected = 0.5f * red + 0.5f * (0.5f * blue + 0.5f * kBackground);
    const glm::vec3 wrong = 0.5f * blue + 0.5f * (0.5f * red + 0.5f * kBackground);
    ASSERT_GT(glm::length(expected - wrong), 0.3f);
    for (FrameWay way : everyWay())
        for (bool nearFirst : {true, false}) {
            SCOPED_TRACE(wayName(way) + (nearFirst ? ", near listed first" : ", far listed first"));
            Scene s = wallScene();
            ModelInstance nearQuad = primitive("plane", makePlane(1.0f), facingCamera({0, 0, 0.5f}, 1.0f), red, 0.5f, true);
            ModelInstance farQuad = primitive("plane", makePlane(1.0f), facingCamera({0.1f, 0, 0}, 1.0f), blue, 0.5f, true);
            if (nearFirst) {
                s.models.push_back(nearQuad);
                s.models.push_back(farQuad);
            } else {
                s.models.push_back(farQuad);
                s.models.push_back(nearQuad);
            }
            const ImageF img = renderHdr(s, small(way));
            const glm::vec3 c = pixel(img, 32, 24);
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], expected[k], 2e-3f) << "channel " << k;
        }
}

// sortTransparentDraws orders blended draws farthest first and leaves opaque ones out.
TEST(Transparency, DrawsAreSortedFarthestFirst) {
    Scene s = wallScene();
    for (float z : {0.5f, -1.0f, 1.5f, 0.0f})
        s.models.push_back(primitive("plane", makePlane(1.0f), facingCamera({0, 0, z}, 0.5f), {1, 1, 1}, 0.5f, true));
    const SceneGpu gpu(s);
    const std::vector<TransparentDraw> order = sortTransparentDraws(gpu, s.camera.view());
    ASSERT_EQ(order.size(), 4u);
    const int expectedMeshes[4] = {2, 4, 1, 3};  // z -1, 0, 0.5, 1.5 (mesh 0 is the opaque wall)
    for (size_t i = 0; i < 4; ++i) EXPECT_EQ(order[i].mesh, expectedMeshes[i]) << i;
}

// An opaque-only scene skips the transparent pass (with its reason), and a transparent surface hidden
// inside an opaque sphere changes no pixel: it is neither in the G-buffer nor a shadow caster, and
// the blend of a fragment behind opaque depth never happens. The opaque frame is bit-identical.
TEST(Transparency, OpaqueScenesSkipThePassAndAreUnchanged) {
    const Scene cornell = loadScene(test::repoPath("scenes/cornell.json"));
    for (FrameWay way : everyWay()) {
        SCOPED_TRACE(wayName(way));
        EXPECT_EQ(decision(cornell, small(way), "transparent"), "skipped: no material of the scene is alpha-blended or transmissive");
        Scene withGlass = cornell;
        // at the centre of the glossy sphere: the pass runs and draws it, and depth hides all of it
        const glm::vec3 centre = glm::vec3(cornell.models[1].transform[3]);
        withGlass.models.push_back(primitive("cube", makeCube(0.02f), glm::translate(glm::mat4(1.0f), centre), {1, 0, 0}, 0.5f, false));
        EXPECT_EQ(decision(withGlass, small(way), "transparent"), "runs");
        const ImageF a = renderHdr(cornell, small(way)), b = renderHdr(withGlass, small(way));
        EXPECT_TRUE(test::imagesNear(a, b, 0.0f, "an unseen transparent surface changed the opaque frame"));
    }
}

// The scene-file field "material": {"opacity": a} makes a model alpha-blended.
TEST(Transparency, BundledGlassSceneRendersFiniteAndBlended) {
    const Scene scene = loadScene(test::repoPath("scenes/glass.json"));
    EXPECT_TRUE(sceneHasTransparency(scene));
    for (FrameWay way : everyWay()) {
        SCOPED_TRACE(wayName(way));
        EXPECT_EQ(decision(scene, small(way), "transparent"), "runs");
        const ImageF img = renderHdr(scene, small(way));
        for (float v : img.rgba) ASSERT_TRUE(std::isfinite(v));
    }
}

// Every view renders in forward+ (no GL error, no state-check failure), against deferred with each
// G-buffer mode. With the classic G-buffer the channel views read what the depth pre-pass writes for
// them, the same raster and material code as the G-buffer pass, so they are byte-identical to the
// deferred path's; the ao view too (its inputs are those channels). With the visibility G-buffer the
// deferred channels are the resolve's rebuild of the raster's values in compute arithmetic, equal to
// them only to rounding (VisibilityBuffer.GBufferEqualsClassicOnEveryBundledScene's bounds): an 8-bit
// view may round a value the other way, so each channel view is within 2 levels with at most 1% of
// its values different, and the ao view, whose horizon angles (acos of normalised position
// differences) and depth-aware blur turn those last bits into whole levels, has at most 1% of its
// values more than 2 levels apart (VisibilityBuffer.EveryViewMatchesClassic's bound). The lighting
// view agrees like the final image in both modes.
TEST(ForwardPlus, EveryViewRendersAndChannelViewsMatchDeferred) {
    const Scene scene = loadScene(test::repoPath("scenes/cornell.json"));
    const std::vector<DebugView> same = {DebugView::Depth,     DebugView::Normals,       DebugView::Diffuse,
                                         DebugView::Position,  DebugView::Shininess,     DebugView::Specular,
                                         DebugView::Texcoords, DebugView::WorldPosition, DebugView::EyeVector,
                                         DebugView::DepthFitted, DebugView::Tangent,     DebugView::Ao};
    for (DebugView view : everyView()) {
        RenderSettings f = small(RenderPath::ForwardPlus);
        f.keepHdr = false;
        f.view = view;
        Renderer rf(scene);
        rf.render(f, 0.0f, false);
        const Image8 b = rf.readDisplay();
        for (GBufferMode mode : allGBufferModes()) {
            SCOPED_TRACE(std::string(viewName(view)) + ", deferred with the " + gbufferModeName(mode) + " G-buffer");
            RenderSettings d = f;
            d.renderPath = RenderPath::Deferred;
            d.gbuffer.mode = mode;
            Renderer rd(scene);
            rd.render(d, 0.0f, false);
            EXPECT_FALSE(rd.graph().isLive(mode == GBufferMode::Visibility ? "gbuffer" : "gbuffer_resolve"));
            const Image8 a = rd.readDisplay();
            ASSERT_EQ(a.rgba.size(), b.rgba.size());
            if (std::find(same.begin(), same.end(), view) != same.end()) {
                if (mode == GBufferMode::Classic) {
                    EXPECT_TRUE(test::valuesNear(std::vector<float>(a.rgba.begin(), a.rgba.end()),
                                                 std::vector<float>(b.rgba.begin(), b.rgba.end()), a.width, 4, 0.0f,
                                                 "the channel differs between the paths"));
                    continue;
                }
                int worst = 0;
                size_t differ = 0, over = 0;
                for (size_t i = 0; i < a.rgba.size(); ++i) {
                    const int diff = std::abs(int(a.rgba[i]) - int(b.rgba[i]));
                    worst = std::max(worst, diff);
                    differ += diff > 0;
                    over += diff > 2;
                }
                RecordProperty(std::string("visibility_") + viewName(view) + "_differ", std::to_string(differ));
                const double limit = 0.01 * double(a.rgba.size());
                if (view == DebugView::Ao) {
                    EXPECT_LE(double(over), limit) << "ao values more than 2 levels apart (largest " << worst << ")";
                } else {
                    EXPECT_LE(worst, 2) << "the channel is more than 2 levels off";
                    EXPECT_LE(double(differ), limit) << "the channel differs at more than 1% of its values";
                }
                continue;
            }
            if (view != DebugView::Lighting) continue;
            double diff = 0.0;
            for (size_t i = 0; i < a.rgba.size(); ++i) diff += std::abs(int(a.rgba[i]) - int(b.rgba[i]));
            EXPECT_LT(diff / double(a.rgba.size()), 1.0) << "mean 8-bit difference of the lighting view";
        }
    }
}
