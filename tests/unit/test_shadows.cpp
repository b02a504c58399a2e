// Shadow passes in the frame graph and the cascade fitting math (no GL: nothing executes).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/error.hpp"
#include "engine/graph/frame_graph.hpp"
#include "frame/frame_builder.hpp"
#include "engine/render/shadows.hpp"
#include "passes/shadow_map_pass.hpp"

using namespace lp;
using fg::FrameGraph;

namespace {

// A 20 m box of "geometry" (bounds only) at the origin, camera outside looking at it.
Scene boundsScene(glm::vec3 lo, glm::vec3 hi, std::vector<bool> lightCasts) {
    Scene s;
    ModelInstance m;
    m.name = "block";
    m.mesh.boundsMin = lo;
    m.mesh.boundsMax = hi;
    s.models.push_back(m);
    for (bool casts : lightCasts) {
        DirectionalLight l;
        l.direction = glm::vec3(-0.3f, -1.0f, -0.2f);
        l.castsShadows = casts;
        s.directionalLights.push_back(l);
    }
    s.camera.position = glm::vec3(0, 4, 12);
    s.camera.target = glm::vec3(0);
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 200.0f;
    return s;
}

std::vector<std::string> orderFor(const Scene& scene, const RenderSettings& settings) {
    FrameData frame = makeFrameData(scene, settings, 0.0f);
    FrameGraph g;
    PassStates passes;
    buildFrameGraph(g, passes, frame);
    g.compile();
    return g.executionOrder();
}

RenderSettings small(DebugView view = DebugView::Final) {
    RenderSettings s;
    s.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    s.autoExposure = false;       // and 0 EV
    s.width = 64;
    s.height = 48;
    s.view = view;
    return s;
}

bool hasShadowPass(const std::vector<std::string>& order) {
    return std::any_of(order.begin(), order.end(), [](const std::string& n) { return n.rfind("shadow_map", 0) == 0; });
}

}  // namespace

TEST(ShadowGraph, NoShadowCastingLightMeansNoShadowPass) {
    Scene s = boundsScene(glm::vec3(-10), glm::vec3(10), {false, false});
    const RenderSettings settings = small();
    FrameData frame = makeFrameData(s, settings, 0.0f);
    FrameGraph g;
    PassStates passes;
    buildFrameGraph(g, passes, frame);
    g.compile();
    for (const auto& r : g.report()) EXPECT_NE(r.name.rfind("shadow_map", 0), 0u) << r.name;
    EXPECT_FALSE(hasShadowPass(g.executionOrder()));
    ASSERT_FALSE(g.skippedPasses().empty());
    EXPECT_NE(g.describe().find("shadow_map: skipped: no directional light casts shadows"), std::string::npos);
}

TEST(ShadowGraph, ShadowsOffMeansNoShadowPass) {
    Scene s = boundsScene(glm::vec3(-10), glm::vec3(10), {true});
    RenderSettings settings = small();
    settings.shadows.enabled = false;
    EXPECT_FALSE(hasShadowPass(orderFor(s, settings)));
}

TEST(ShadowGraph, OnePassPerCastingLightBeforeGlobalLights) {
    Scene s = boundsScene(glm::vec3(-10), glm::vec3(10), {false, true, true});
    auto order = orderFor(s, small());
    auto pos = [&](const std::string& n) { return std::find(order.begin(), order.end(), n) - order.begin(); };
    EXPECT_EQ(std::count_if(order.begin(), order.end(), [](const std::string& n) { return n.rfind("shadow_map", 0) == 0; }), 2);
    EXPECT_EQ(pos("shadow_map_0"), long(order.size()));  // light 0 casts none
    EXPECT_LT(pos("shadow_map_1"), pos("global_lights"));
    EXPECT_LT(pos("shadow_map_2"), pos("global_lights"));
}

TEST(ShadowGraph, ChannelViewCullsShadowPassAndShadowMapViewKeepsOnlyIt) {
    Scene s = boundsScene(glm::vec3(-10), glm::vec3(10), {true});
    EXPECT_EQ(orderFor(s, small(DebugView::Normals)), (std::vector<std::string>{"gbuffer", "debug_view"}));
    EXPECT_EQ(orderFor(s, small(DebugView::ShadowMap)), (std::vector<std::string>{"shadow_map_0", "debug_view"}));
}

TEST(ShadowGraph, ShadowMapViewOfALightWithoutMapIsAnError) {
    Scene s = boundsScene(glm::vec3(-10), glm::vec3(10), {true, false});
    RenderSettings settings = small(DebugView::ShadowMap);
    settings.shadows.debugLight = 1;
    try {
        orderFor(s, settings);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("directional light 1 has no shadow map"), std::string::npos) << e.what();
    }
}

TEST(ShadowSettingsNames, ParseAndPrintRoundTrip) {
    for (auto f : {ShadowSettings::Filter::Off, ShadowSettings::Filter::Pcf3x3, ShadowSettings::Filter::Pcf5x5,
                   ShadowSettings::Filter::Poisson})
        EXPECT_EQ(ShadowSettings::parseFilter(ShadowSettings::filterName(f)), f);
    EXPECT_FALSE(ShadowSettings::parseFilter("7x7"));
    EXPECT_EQ(parseBrdf("ggx"), Brdf::Ggx);
    EXPECT_EQ(parseBrdf("blinn-phong"), Brdf::BlinnPhong);
    EXPECT_FALSE(parseBrdf("phong"));
    EXPECT_EQ(parseView("shadowmap"), DebugView::ShadowMap);
}

// Bound: splits are exact at both ends, strictly increasing, and lambda 0 / 1 give the linear and
// logarithmic schemes to 1e-12 relative.
TEST(ShadowCascades, PracticalSplitsInterpolateLinearAndLog) {
    auto lin = practicalSplits(0.1, 100.0, 4, 0.0), log = practicalSplits(0.1, 100.0, 4, 1.0);
    auto mid = practicalSplits(0.1, 100.0, 4, 0.75);
    for (int i = 0; i <= 4; ++i) {
        EXPECT_NEAR(lin[size_t(i)], 0.1 + 99.9 * i / 4.0, 1e-12 * 100);
        EXPECT_NEAR(log[size_t(i)], 0.1 * std::pow(1000.0, i / 4.0), 1e-12 * 100);
        if (i > 0) EXPECT_GT(mid[size_t(i)], mid[size_t(i) - 1]);
    }
    EXPECT_EQ(mid.front(), 0.1);
    EXPECT_EQ(mid.back(), 100.0);
}

// Every point of the camera's view volume that lies inside [lo, hi] falls inside its cascade's
// orthographic box (|x|, |y| <= 1, z in [-1, 1]) - checked on a 9x9x33 grid; returns the points checked.
int expectCascadesCover(const Scene& s, const RenderSettings& settings, glm::vec3 lo, glm::vec3 hi, const std::string& what,
                        const ShadowFrustum* previous = nullptr) {
    FrameData frame = makeFrameData(s, settings, 0.0f);
    ShadowFrustum fr = fitShadowFrustum(frame, s.directionalLights[0].direction, previous);
    const glm::mat4 invVp = glm::inverse(frame.projection * frame.view);
    int inside = 0;
    for (int iz = 0; iz <= 32; ++iz)
        for (int iy = 0; iy <= 8; ++iy)
            for (int ix = 0; ix <= 8; ++ix) {
                glm::vec4 ndc(ix / 4.0f - 1.0f, iy / 4.0f - 1.0f, iz / 16.0f - 1.0f, 1.0f);
                glm::vec4 w = invVp * ndc;
                glm::vec3 p = glm::vec3(w) / w.w;
                if (glm::any(glm::lessThan(p, lo)) || glm::any(glm::greaterThan(p, hi))) continue;
                const float depth = -(frame.view * glm::vec4(p, 1.0f)).z;
                size_t c = 0;
                while (c + 1 < fr.cascades.size() && depth > fr.cascades[c].splitFar) ++c;
                glm::vec4 clip = fr.cascades[c].worldToClip * glm::vec4(p, 1.0f);
                EXPECT_LE(std::abs(clip.x), 1.0f + 1e-4f) << what << ": cascade " << c << " depth " << depth;
                EXPECT_LE(std::abs(clip.y), 1.0f + 1e-4f) << what << ": cascade " << c << " depth " << depth;
                EXPECT_LE(std::abs(clip.z), 1.0f) << what << ": cascade " << c;
                ++inside;
            }
    for (size_t c = 1; c < fr.cascades.size(); ++c) EXPECT_GE(fr.cascades[c].texelWorld, fr.cascades[c - 1].texelWorld);
    return inside;
}

// Coverage, with the origin on a one-texel grid and on coarser ones (--shadow-origin-step), from the
// middle of a large scene and from near its edge (where squares are pinned against it).
TEST(ShadowCascades, CascadesCoverTheVisibleSceneInsideTheirBoxes) {
    const glm::vec3 lo(-50, 0, -50), hi(50, 5, 50);
    Scene s = boundsScene(lo, hi, {true});
    s.camera.farPlane = 80.0f;
    RenderSettings settings = small();
    ASSERT_EQ(fitShadowFrustum(makeFrameData(s, settings, 0.0f), s.directionalLights[0].direction).cascades.size(), 4u);
    for (float step : {0.0f, 0.0625f, 0.25f}) {
        settings.shadows.originStep = step;
        s.camera.position = glm::vec3(0, 4, 12);
        s.camera.target = glm::vec3(0);
        EXPECT_GT(expectCascadesCover(s, settings, lo, hi, "middle, step " + std::to_string(step)), 500);
        s.camera.position = glm::vec3(47, 3, 46);
        s.camera.target = glm::vec3(30, 0, 20);
        EXPECT_GT(expectCascadesCover(s, settings, lo, hi, "edge, step " + std::to_string(step)), 500);
    }
}

// What --shadow-cache relies on: walking and zooming (a camera path's fov) leaves most cascades'
// matrices bit for bit as they were the frame before, with the origin step; with a one-texel grid
// the near cascade moves nearly every frame. A square wider than the scene never moves.
TEST(ShadowCascades, SquaresStayPutWhileTheCameraWalksAndZooms) {
    const glm::vec3 lo(-50, 0, -50), hi(50, 5, 50);
    auto keptShare = [&](float step) {
        Scene s = boundsScene(lo, hi, {true});
        s.camera.farPlane = 80.0f;
        RenderSettings settings = small();
        settings.shadows.originStep = step;
        std::vector<glm::mat4> previous;
        std::vector<int> kept(kMaxShadowCascades, 0), frames(kMaxShadowCascades, 0);
        for (int i = 0; i < 120; ++i) {
            s.camera.position = glm::vec3(0.03f * float(i), 4.0f, 12.0f - 0.05f * float(i));
            s.camera.target = s.camera.position + glm::vec3(0.1f, -4.0f, -12.0f);
            s.camera.fovYDegrees = 45.0f + 0.05f * float(i);
            FrameData frame = makeFrameData(s, settings, 0.0f);
            const ShadowFrustum fr = fitShadowFrustum(frame, s.directionalLights[0].direction);
            EXPECT_EQ(fr.cascades.size(), 4u);
            for (size_t c = 0; c < fr.cascades.size() && i > 0; ++c) {
                ++frames[c];
                kept[c] += c < previous.size() && std::memcmp(&previous[c], &fr.cascades[c].worldToClip, sizeof(glm::mat4)) == 0;
            }
            previous.clear();
            for (const auto& c : fr.cascades) previous.push_back(c.worldToClip);
        }
        std::vector<double> share;
        for (int c = 0; c < kMaxShadowCascades; ++c) share.push_back(frames[c] ? double(kept[c]) / frames[c] : 0.0);
        return share;
    };
    const std::vector<double> stepped = keptShare(0.0625f), texel = keptShare(0.0f);
    for (int c = 0; c < kMaxShadowCascades; ++c) {
        EXPECT_GE(stepped[size_t(c)], 0.6) << "cascade " << c;
        EXPECT_GE(stepped[size_t(c)], texel[size_t(c)]) << "cascade " << c;
    }
    EXPECT_LE(texel[0], 0.2) << "the near cascade on a one-texel grid should move nearly every frame";
}

// Stability: turning the camera, and moving it within one 2^(1/4) step of its distance to the
// scene, keeps each cascade's texel size (bitwise), and the cascade's square moves by whole texels
// only (to 1e-3 texel), so shadow edges do not shimmer.
TEST(ShadowCascades, TexelSizeIsConstantAndOffsetsSnapToTexels) {
    Scene s = boundsScene(glm::vec3(-100, 0, -100), glm::vec3(100, 10, 100), {true});
    RenderSettings settings = small();
    settings.shadows.size = 1024;
    FrameData a = makeFrameData(s, settings, 0.0f);
    ShadowFrustum fa = fitShadowFrustum(a, s.directionalLights[0].direction);
    s.camera.position += glm::vec3(0.37f, 0.0f, -1.13f);
    s.camera.target += glm::vec3(2.1f, 0.0f, 0.4f);
    FrameData b = makeFrameData(s, settings, 0.0f);
    ShadowFrustum fb = fitShadowFrustum(b, s.directionalLights[0].direction);
    for (size_t c = 0; c < fa.cascades.size(); ++c) {
        EXPECT_FLOAT_EQ(fa.cascades[c].texelWorld, fb.cascades[c].texelWorld) << c;
        // The world origin's position in each cascade's texel grid: its fractional part is the same.
        auto texelOfOrigin = [&](const ShadowCascade& sc) {
            glm::vec4 clip = sc.worldToClip * glm::vec4(0, 0, 0, 1);
            return glm::dvec2(clip.x, clip.y) * 0.5 * double(settings.shadows.size);
        };
        glm::dvec2 d = texelOfOrigin(fa.cascades[c]) - texelOfOrigin(fb.cascades[c]);
        EXPECT_NEAR(d.x, std::round(d.x), 1e-3) << c;
        EXPECT_NEAR(d.y, std::round(d.y), 1e-3) << c;
    }
}

// Huge bounds (1e30 m) and a far plane of 1e30: every matrix entry finite (Filament PR #6314's bug).
TEST(ShadowCascades, HugeSceneBoundsGiveFiniteMatrices) {
    Scene s = boundsScene(glm::vec3(-1e30f), glm::vec3(1e30f), {true});
    s.camera.farPlane = 1e30f;
    RenderSettings settings = small();
    FrameData frame = makeFrameData(s, settings, 0.0f);
    for (glm::vec3 dir : {glm::vec3(0, -1, 0), glm::vec3(-0.3f, -1, -0.2f), glm::vec3(1, 0, 0)}) {
        ShadowFrustum fr = fitShadowFrustum(frame, dir);
        for (const auto& c : fr.cascades) {
            for (int i = 0; i < 4; ++i)
                for (int j = 0; j < 4; ++j) {
                    EXPECT_TRUE(std::isfinite(c.worldToClip[i][j]));
                    EXPECT_TRUE(std::isfinite(c.eyeToClip[i][j]));
                }
            EXPECT_TRUE(std::isfinite(c.texelWorld) && c.texelWorld > 0.0f);
            EXPECT_TRUE(std::isfinite(c.depthRange) && c.depthRange > 0.0f);
        }
    }
    // An empty scene and a zero direction: finite, or a one-line error.
    Scene empty;
    FrameData ef = makeFrameData(empty, settings, 0.0f);
    ShadowFrustum fr = fitShadowFrustum(ef, glm::vec3(0, -1, 0));
    for (const auto& c : fr.cascades) EXPECT_TRUE(std::isfinite(c.worldToClip[0][0]));
    EXPECT_THROW(fitShadowFrustum(frame, glm::vec3(0.0f)), Error);
}

TEST(ShadowCascades, BadSettingsAreOneLineErrors) {
    Scene s = boundsScene(glm::vec3(-1), glm::vec3(1), {true});
    RenderSettings settings = small();
    settings.shadows.cascades = 5;
    FrameData frame = makeFrameData(s, settings, 0.0f);
    EXPECT_THROW(fitShadowFrustum(frame, glm::vec3(0, -1, 0)), Error);
    settings.shadows.cascades = 2;
    settings.shadows.size = 8;
    EXPECT_THROW(fitShadowFrustum(frame, glm::vec3(0, -1, 0)), Error);
}

// The depth range the cascades split is the part of the scene's bounds inside the view frustum:
// a 1 m box 5 m ahead spans view depths 4.5..5.5; a box behind the camera or off to the side is out
// of view; with the camera inside the box the range starts at the near plane; a long box is cut by
// the far plane and the frustum's sides.
TEST(ShadowCascades, VisibleDepthRangeIsTheBoundsInsideTheFrustum) {
    const glm::dmat4 view = glm::lookAt(glm::dvec3(0, 0, 0), glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0));
    const double t = std::tan(glm::radians(30.0));
    auto ahead = visibleDepthRange(glm::dvec3(-0.5, -0.5, -5.5), glm::dvec3(0.5, 0.5, -4.5), view, 0.1, 100.0, t, t);
    ASSERT_TRUE(ahead);
    EXPECT_NEAR(ahead->x, 4.5, 1e-9);
    EXPECT_NEAR(ahead->y, 5.5, 1e-9);
    EXPECT_FALSE(visibleDepthRange(glm::dvec3(-0.5, -0.5, 4.5), glm::dvec3(0.5, 0.5, 5.5), view, 0.1, 100.0, t, t));
    EXPECT_FALSE(visibleDepthRange(glm::dvec3(20, -0.5, -5.5), glm::dvec3(21, 0.5, -4.5), view, 0.1, 100.0, t, t));
    auto inside = visibleDepthRange(glm::dvec3(-1, -1, -3), glm::dvec3(1, 1, 1), view, 0.1, 100.0, t, t);
    ASSERT_TRUE(inside);
    EXPECT_NEAR(inside->x, 0.1, 1e-9);
    EXPECT_NEAR(inside->y, 3.0, 1e-9);
    // A corridor 1000 m long starting 1 m ahead: its end face is in view at d = 1, its walls (|x|,
    // |y| = 2) enter the frustum (half-width 0.577 d) at d = 3.46 and stay to the far plane.
    auto corridor = visibleDepthRange(glm::dvec3(-2, -2, -1000), glm::dvec3(2, 2, -1), view, 0.1, 100.0, t, t);
    ASSERT_TRUE(corridor);
    EXPECT_NEAR(corridor->x, 1.0, 1e-9);
    EXPECT_NEAR(corridor->y, 100.0, 1e-9);
}

// A small scene (a 0.56 m box seen from 0.8 m, the Cornell box's proportions) fills the first
// cascade's square: asking for 4 cascades gives 1 (its atlas tile stays the one it has among 4), the graph says which were
// dropped and why, and that cascade serves every depth. Cascades past the visible depths are
// dropped too. A large open scene keeps all 4.
TEST(ShadowCascades, SmallSceneGetsFewerCascades) {
    Scene s = boundsScene(glm::vec3(0.0f), glm::vec3(0.556f, 0.549f, 0.559f), {true});
    s.camera.position = glm::vec3(0.278f, 0.273f, -0.8f);
    s.camera.target = glm::vec3(0.278f, 0.273f, 0.0f);
    s.camera.fovYDegrees = 39.3f;
    s.camera.nearPlane = 0.05f;
    s.camera.farPlane = 3.0f;
    RenderSettings settings = small();
    settings.shadows.cascades = 4;
    FrameData frame = makeFrameData(s, settings, 0.0f);
    ShadowFrustum fr = fitShadowFrustum(frame, s.directionalLights[0].direction);
    ASSERT_EQ(fr.cascades.size(), 1u);
    // It keeps the tile it has among the 4 asked for (the atlas holds tiles 0..1, tile 0 unused), so
    // its tile stays put when the nearer cascade comes back into view (--shadow-cache).
    EXPECT_EQ(fr.cascades[0].tile, 1);
    EXPECT_EQ(fr.columns * fr.rows, 2);
    EXPECT_EQ(fr.cascades[0].splitFar, std::numeric_limits<float>::max());
    // The box is visible from its open front (0.8 m) to the back wall (1.359 m). The splits start at
    // the bounding sphere's nearest depth (0.598 m, snapped down to 2^(-3/4)): the first slice,
    // 0.595..0.795 m, holds nothing visible and goes; the second already spans the scene.
    EXPECT_NEAR(fr.visibleNear, 0.8, 1e-6);
    EXPECT_NEAR(fr.visibleFar, 1.359, 1e-6);
    EXPECT_LE(fr.cascades[0].splitNear, 0.8f);
    const std::string why = droppedCascadesReason(fr, 4);
    EXPECT_NE(why.find("cascade 1 (view depth 0.595..0.795 m) is nearer than the visible scene"), std::string::npos) << why;
    EXPECT_NE(why.find("cascades 3..4 of 4 dropped: cascade 2's square already covers the whole scene"), std::string::npos) << why;
    FrameGraph g;
    PassStates passes;
    buildFrameGraph(g, passes, frame);
    g.compile();
    EXPECT_NE(g.describe().find("shadow_map_0 cascades: skipped: cascade 1 (view depth"), std::string::npos) << g.describe();

    // A corridor (2 x 2 x 64 m) seen from inside, looking at its end wall 4 m away: the bounding
    // sphere's depth range reaches 60 m, but nothing past 4 m is visible, so the cascades whose
    // slices start beyond it are dropped and the last one kept serves every depth.
    Scene corridor = boundsScene(glm::vec3(-1, -1, -4), glm::vec3(1, 1, 60), {true});
    corridor.camera.position = glm::vec3(0.0f);
    corridor.camera.target = glm::vec3(0, 0, -1);
    corridor.camera.nearPlane = 0.1f;
    corridor.camera.farPlane = 200.0f;
    FrameData corridorFrame = makeFrameData(corridor, settings, 0.0f);
    ShadowFrustum cf = fitShadowFrustum(corridorFrame, corridor.directionalLights[0].direction);
    ASSERT_GE(cf.cascades.size(), 1u);
    ASSERT_LT(cf.cascades.size(), 4u);
    EXPECT_LE(cf.cascades.back().splitNear, 4.0f);
    EXPECT_EQ(cf.cascades.back().splitFar, std::numeric_limits<float>::max());
    EXPECT_NEAR(cf.visibleFar, 4.0, 1e-6);
    EXPECT_NE(droppedCascadesReason(cf, 4).find("beyond the visible scene"), std::string::npos) << droppedCascadesReason(cf, 4);

    Scene big = boundsScene(glm::vec3(-50, 0, -50), glm::vec3(50, 5, 50), {true});
    big.camera.farPlane = 80.0f;
    FrameData bigFrame = makeFrameData(big, settings, 0.0f);
    ShadowFrustum bigFr = fitShadowFrustum(bigFrame, big.directionalLights[0].direction);
    EXPECT_EQ(bigFr.cascades.size(), 4u);
    EXPECT_EQ(droppedCascadesReason(bigFr, 4), "");
}

// --shadow-scroll's offset: along a walk, a cascade whose square moved (same rotation, size and
// depth range) scrolls by the whole-texel distance its origin moved, in the direction the content
// moves in the tile (a world point's texel moves by the offset); a resized square does not scroll;
// and the strips plus the kept rectangle tile the square exactly, the strips covering the newly
// exposed texels and kShadowScrollMargin texels of the old tile's edge.
TEST(ShadowScroll, OffsetIsTheOriginsWholeTexelMove) {
    const glm::vec3 lo(-50, 0, -50), hi(50, 5, 50);
    Scene s = boundsScene(lo, hi, {true});
    s.camera.farPlane = 80.0f;
    RenderSettings settings = small();
    settings.shadows.size = 512;
    const ShadowSettings::Raster raster = ShadowSettings::Raster::Plain;
    std::vector<ShadowTileKey> previous;
    int scrolled = 0;
    for (int i = 0; i < 80; ++i) {
        s.camera.position = glm::vec3(0.05f * float(i), 4.0f, 12.0f - 0.2f * float(i));
        s.camera.target = s.camera.position + glm::vec3(0.1f, -4.0f, -12.0f);
        const ShadowFrustum fr = fitShadowFrustum(makeFrameData(s, settings, 0.0f), s.directionalLights[0].direction);
        const std::vector<ShadowTileKey> keys = shadowTileKeys(fr, settings.shadows, raster, false);
        for (size_t c = 0; c < keys.size() && c < previous.size(); ++c) {
            const std::optional<glm::ivec2> offset = shadowTileScroll(previous[c], keys[c]);
            const bool sameSize = glm::mat3(previous[c].worldToClip) == glm::mat3(keys[c].worldToClip);
            if (!sameSize) {
                EXPECT_FALSE(offset) << "frame " << i << " cascade " << c << ": a resized square must be redrawn whole";
                continue;
            }
            if (previous[c] == keys[c]) {
                EXPECT_FALSE(offset) << "an unchanged tile is kept, not scrolled";
                continue;
            }
            ASSERT_TRUE(offset) << "frame " << i << " cascade " << c;
            ++scrolled;
            // A world point inside both squares: its texel in the new tile is its old texel + offset.
            const glm::vec4 p = glm::inverse(previous[c].worldToClip) * glm::vec4(0.1f, -0.2f, 0.3f, 1.0f);
            const glm::vec4 a = previous[c].worldToClip * p, b = keys[c].worldToClip * p;
            const glm::dvec2 move = (glm::dvec2(b.x, b.y) - glm::dvec2(a.x, a.y)) * 0.5 * double(fr.tileSize);
            EXPECT_NEAR(move.x, double(offset->x), 1e-2);
            EXPECT_NEAR(move.y, double(offset->y), 1e-2);
            // The origin step (1/16 of the tile here) or a multiple of it.
            EXPECT_EQ(offset->x % originStepTexels(settings.shadows), 0);
            EXPECT_EQ(offset->y % originStepTexels(settings.shadows), 0);
        }
        previous = keys;
    }
    EXPECT_GT(scrolled, 3) << "the walk moved no square by whole steps";

    // Strips: kept rectangle + strips = the tile, each texel once.
    const int side = 64;
    for (const glm::ivec2 offset : {glm::ivec2(4, 0), glm::ivec2(-4, 0), glm::ivec2(0, 8), glm::ivec2(-8, 12), glm::ivec2(1, -1)}) {
        std::vector<int> covered(size_t(side * side), 0);
        const TileRect k = shadowScrollKeptRect(offset, side);
        std::vector<TileRect> all = shadowScrollRegions(offset, side);
        EXPECT_LE(all.size(), 4u);
        all.push_back(k);
        for (const TileRect& r : all)
            for (int y = r.y; y < r.y + r.height; ++y)
                for (int x = r.x; x < r.x + r.width; ++x) ++covered[size_t(y * side + x)];
        for (int v : covered) ASSERT_EQ(v, 1) << offset.x << ", " << offset.y;
        // The kept rectangle holds only old texels at least kShadowScrollMargin inside the old tile
        // along an axis the tile moves along; along one it does not, the whole old extent (its
        // border texels stay at the border).
        const int mx = offset.x != 0 ? kShadowScrollMargin : 0, my = offset.y != 0 ? kShadowScrollMargin : 0;
        EXPECT_GE(k.x - offset.x, mx);
        EXPECT_GE(k.y - offset.y, my);
        EXPECT_LE(k.x + k.width - offset.x, side - mx);
        EXPECT_LE(k.y + k.height - offset.y, side - my);
        EXPECT_EQ(k.width, side - std::max(std::abs(offset.x) + mx, 2 * mx));
        EXPECT_EQ(k.height, side - std::max(std::abs(offset.y) + my, 2 * my));
    }
    // An offset past the tile: nothing to keep, the whole tile drawn.
    ShadowTileKey a, b;
    a.tileSize = b.tileSize = side;
    b.worldToClip[3].x = 2.0f;  // a whole tile to the side
    EXPECT_FALSE(shadowTileScroll(a, b));
    b.worldToClip[3].x = 2.0f * 3.0f / float(side);  // three texels
    ASSERT_TRUE(shadowTileScroll(a, b));
    EXPECT_EQ(*shadowTileScroll(a, b), glm::ivec2(3, 0));
    b.worldToClip[3].x = 2.0f * 3.5f / float(side);  // not a whole texel
    EXPECT_FALSE(shadowTileScroll(a, b));
    b.worldToClip[3].x = 2.0f * 3.0f / float(side);
    b.slopeBias = 2.0f;  // anything else differing: no scroll
    EXPECT_FALSE(shadowTileScroll(a, b));
}

// --shadow-size-hold: a camera that zooms in a little keeps every square's side (it still holds the
// slice), zooming back out keeps it too, zooming out far grows it, and zooming in far (past
// kShadowSizeHoldRatio) shrinks it; without the setting or without a previous frame the fit is the
// usual one. Every held square still covers what the cascade needs (its side >= the slice's need).
TEST(ShadowCascades, SizeHoldKeepsTheSquaresSideWithinTheBand) {
    const glm::vec3 lo(-50, 0, -50), hi(50, 5, 50);
    Scene s = boundsScene(lo, hi, {true});
    s.camera.farPlane = 80.0f;
    RenderSettings settings = small();
    settings.shadows.sizeHold = true;
    auto fit = [&](float fov, const ShadowFrustum* previous) {
        s.camera.fovYDegrees = fov;
        return fitShadowFrustum(makeFrameData(s, settings, 0.0f), s.directionalLights[0].direction, previous);
    };
    const ShadowFrustum first = fit(45.0f, nullptr);
    ASSERT_EQ(first.cascades.size(), 4u);
    const ShadowFrustum unheld = fit(42.0f, nullptr);
    const ShadowFrustum held = fit(42.0f, &first);
    size_t smallerWithoutHold = 0;
    for (size_t c = 0; c < 4; ++c) {
        EXPECT_EQ(held.cascades[c].side, first.cascades[c].side) << c;
        EXPECT_EQ(glm::mat3(held.cascades[c].worldToClip), glm::mat3(first.cascades[c].worldToClip)) << c;
        EXPECT_GE(held.cascades[c].side, unheld.cascades[c].side) << c;
        smallerWithoutHold += unheld.cascades[c].side < first.cascades[c].side ? 1 : 0;
    }
    EXPECT_GT(smallerWithoutHold, 0u) << "the zoom changed no square: the test proves nothing";
    const ShadowFrustum back = fit(45.0f, &held);
    for (size_t c = 0; c < 4; ++c) EXPECT_EQ(back.cascades[c].side, first.cascades[c].side) << c;
    const ShadowFrustum wider = fit(60.0f, &back), narrower = fit(30.0f, &back);
    for (size_t c = 0; c + 1 < 4; ++c) {  // the near ones (the last may span the scene whatever the zoom)
        EXPECT_GT(wider.cascades[c].side, first.cascades[c].side) << c;
        EXPECT_LT(narrower.cascades[c].side, first.cascades[c].side) << c;
        EXPECT_EQ(narrower.cascades[c].side, fit(30.0f, nullptr).cascades[c].side) << c;
    }
    settings.shadows.sizeHold = false;
    const ShadowFrustum off = fit(42.0f, &first);
    for (size_t c = 0; c < 4; ++c) EXPECT_EQ(off.cascades[c].side, unheld.cascades[c].side) << c;
    settings.shadows.sizeHold = true;
    // The held squares still cover the visible scene inside their boxes (as the unheld ones must).
    s.camera.fovYDegrees = 42.0f;
    EXPECT_GT(expectCascadesCover(s, settings, lo, hi, "held", &first), 500);
}
