// Point-light shadows (passes/point_shadow_pass): a point light's cube map against a CPU ray cast
// from the light to each floor point, in every path that shades local lights; a point light without
// castsShadow stays as it was; a kept cube is what a redraw writes; no pass without a casting point.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/scene/primitives.hpp"
#include "engine/scene/scene.hpp"
#include "frame/frame_builder.hpp"
#include "frame/renderer.hpp"
#include "passes/point_shadow_pass.hpp"
#include "tests/gl/gl_fixture.hpp"
#include "tests/gl/render_fixture.hpp"

using namespace lp;

namespace {

constexpr int kWidth = 64, kHeight = 48;

struct Box {
    glm::dvec3 lo, hi;
};

ModelInstance grey(const std::string& name, MeshData mesh, glm::mat4 transform) {
    ModelInstance m;
    m.name = name;
    m.mesh = std::move(mesh);
    for (auto& mat : m.mesh.materials) {
        mat.diffuse = glm::vec3(0.5f);
        mat.specular = glm::vec3(0.0f);
        mat.shininess = 1.0f;
    }
    m.transform = transform;
    return m;
}

// A point light 1.2 m over an 8 m floor (y = 0) with two boxes: one beside and below it (its shadow
// falls through the cube's +X face) and one under it (the -Y face), seen from above. No ambient, a black background.
struct PointScene {
    Scene scene;
    std::vector<Box> boxes;
    glm::dvec3 light;
};
PointScene pointOverOccluders(bool castsShadow) {
    PointScene p;
    Scene& s = p.scene;
    s.models.push_back(grey("floor", makePlane(1.0f, 4), glm::scale(glm::mat4(1.0f), glm::vec3(8.0f))));
    const glm::vec3 centres[2] = {{1.0f, 0.6f, 0.2f}, {-0.3f, 0.3f, -0.3f}};
    const float halves[2] = {0.15f, 0.12f};
    for (int i = 0; i < 2; ++i) {
        s.models.push_back(grey("box" + std::to_string(i), makeCube(1.0f),
                                glm::scale(glm::translate(glm::mat4(1.0f), centres[i]), glm::vec3(2.0f * halves[i]))));
        p.boxes.push_back({glm::dvec3(centres[i] - halves[i]), glm::dvec3(centres[i] + halves[i])});
    }
    s.camera.position = {0.6f, 4.0f, 2.0f};
    s.camera.target = {0.6f, 0.0f, 0.0f};
    s.camera.fovYDegrees = 60.0f;
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 20.0f;
    s.ambient = glm::vec3(0.0f);
    s.environment.color = glm::vec3(0.0f);  // a black background: a transparent floor adds nothing of it
    PointLight l;
    l.position = {0.0f, 1.2f, 0.0f};
    l.range = 5.0f;
    l.intensity = 2.0f;
    l.castsShadow = castsShadow;
    s.pointLights.push_back(l);
    p.light = glm::dvec3(l.position);
    return p;
}

RenderSettings smallSettings() {
    RenderSettings r;
    r.aa.method = AntiAliasing::Off;  // one sample a pixel, as the reference
    r.autoExposure = false;
    r.width = kWidth;
    r.height = kHeight;
    r.shadows.size = 2048;  // the default: faces of 1024^2
    r.localLights.clusteredKernel = ClusteredKernel::Froxels;
    return r;
}

// The passes the frame of `scene` runs, and why point_shadows is skipped (empty when it runs).
std::set<std::string> passesRun(const Scene& scene, const RenderSettings& settings, std::string* pointSkip = nullptr) {
    FrameData f = makeFrameData(scene, settings, 0.0f);
    fg::FrameGraph graph;
    PassStates states;
    buildFrameGraph(graph, states, f);
    graph.compile();
    std::set<std::string> runs;
    for (const fg::PassDecision& d : graph.explain()) {
        if (d.runs) runs.insert(d.name);
        if (d.name == "point_shadows" && pointSkip) *pointSkip = d.reason;
    }
    return runs;
}

std::string pointShadowNote(const Renderer& renderer) {
    for (const fg::PassDecision& d : renderer.graph().explain())
        if (d.name == "point_shadows" && !d.notes.empty()) return d.notes.front();
    return "";
}

struct Way {
    std::string name;
    RenderSettings settings;
};
std::vector<Way> everyWay() {
    std::vector<Way> ways;
    for (LocalLightMethod m : {LocalLightMethod::Fullscreen, LocalLightMethod::Scissor, LocalLightMethod::Volumes,
                               LocalLightMethod::Tiled, LocalLightMethod::Clustered}) {
        RenderSettings r = smallSettings();
        r.localLights.method = m;
        ways.push_back({std::string("deferred ") + localLightMethodName(m), r});
    }
    RenderSettings visibility = smallSettings();
    visibility.gbuffer.mode = GBufferMode::Visibility;
    ways.push_back({"deferred, visibility G-buffer", visibility});
    RenderSettings forward = smallSettings();
    forward.renderPath = RenderPath::ForwardPlus;
    ways.push_back({"forward+", forward});
    return ways;
}

// The band about a shadow's edge left out of the comparison at floor point q: 6 texels of the face q
// projects into (the widest filter reaches 3.6, the normal offset 1), measured on the floor (a
// texel's footprint there is its size over the cosine of the light's angle to the floor's normal),
// and at least 3 cm.
double penumbraBand(glm::dvec3 q, glm::dvec3 light, const RenderSettings& settings) {
    const int tile = pointShadowTileSize(settings.shadows.size, 1);
    const double texelSlope = 2.0 * double(pointShadowFaceTan(tile)) / double(tile);
    const glm::dvec3 d = q - light;
    const double axis = std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
    const double cosine = std::max(-d.y / glm::length(d), 0.05);
    return std::max(0.03, 6.0 * axis * texelSlope / cosine);
}

// Floor pixels: where the light's segment to the floor point meets a box (and does so for every
// point within the penumbra band) the light adds nothing; where no point within the band is blocked
// it adds what it adds without the shadow map (to fp16). Pixels whose view of the floor a box (grown
// by 3 cm) hides are left out.
void expectRayCastShadow(const PointScene& p, const ImageF& shadowed, const ImageF& unshadowed, const std::string& way,
                         const RenderSettings& settings = smallSettings()) {
    int dark = 0, lit = 0, faces = 0;
    std::set<int> darkFaces;
    const glm::dvec3 eye(p.scene.camera.position);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const std::optional<glm::dvec3> q = test::planePoint(p.scene.camera, kWidth, kHeight, x, y);
            if (!q) continue;
            bool hidden = false;
            for (const Box& b : p.boxes) hidden |= test::segmentHitsBox(eye, *q, b.lo - 0.03, b.hi + 0.03);
            if (hidden) continue;
            int hits = 0;
            const double band = penumbraBand(*q, p.light, settings);
            for (int k = 0; k < 9; ++k) {
                const glm::dvec3 s = *q + band * glm::dvec3(k % 3 - 1, 0, k / 3 - 1);
                bool blocked = false;
                for (const Box& b : p.boxes) blocked |= test::segmentHitsBox(s, p.light, b.lo, b.hi);
                hits += blocked ? 1 : 0;
            }
            const size_t i = (size_t(y) * kWidth + size_t(x)) * 4 + 1;
            const float ref = unshadowed.rgba[i], img = shadowed.rgba[i];
            if (hits == 9) {
                EXPECT_LE(img, 1e-3f * ref + 1e-7f) << way << ": shadowed floor point at pixel (" << x << ", " << y << ")";
                if (ref > 1e-3f) {
                    ++dark;
                    darkFaces.insert(pointShadowFace(glm::vec3(*q - p.light)));
                }
            } else if (hits == 0) {
                EXPECT_NEAR(img, ref, 2e-3f * ref + 1e-6f) << way << ": lit floor point at pixel (" << x << ", " << y << ")";
                if (ref > 1e-3f) ++lit;
            }
        }
    faces = int(darkFaces.size());
    EXPECT_GT(dark, 20) << way << ": the shadows are in view";
    EXPECT_GT(lit, 1000) << way;
    EXPECT_GE(faces, 2) << way << ": the shadowed floor points lie behind more than one cube face";
}

TEST(PointShadows, MatchARayCastFromTheLightInEveryShadingPath) {
    const PointScene shadowedScene = pointOverOccluders(true), plainScene = pointOverOccluders(false);
    for (const Way& way : everyWay()) {
        SCOPED_TRACE(way.name);
        const ImageF unshadowed = test::renderHdr(plainScene.scene, way.settings);
        const ImageF shadowed = test::renderHdr(shadowedScene.scene, way.settings);
        expectRayCastShadow(shadowedScene, shadowed, unshadowed, way.name, way.settings);
    }
}

// Every filter (off, 3x3, 5x5, Poisson) keeps the same lit and shadowed regions (the band covers the widest).
TEST(PointShadows, EveryFilterMatchesTheRayCast) {
    const PointScene shadowedScene = pointOverOccluders(true), plainScene = pointOverOccluders(false);
    RenderSettings r = smallSettings();
    r.localLights.method = LocalLightMethod::Tiled;
    const ImageF unshadowed = test::renderHdr(plainScene.scene, r);
    for (ShadowSettings::Filter f : {ShadowSettings::Filter::Off, ShadowSettings::Filter::Pcf3x3,
                                     ShadowSettings::Filter::Pcf5x5, ShadowSettings::Filter::Poisson}) {
        r.shadows.filter = f;
        expectRayCastShadow(shadowedScene, test::renderHdr(shadowedScene.scene, r), unshadowed,
                            "filter " + std::to_string(int(f)), r);
    }
}

// Transparent surfaces are lit through the forward path with the same cube: a floor at opacity 0.5
// (drawn by the transparent pass) shadowed where the ray cast says, lit as without the map elsewhere.
TEST(PointShadows, TransparentSurfacesAreShadowedToo) {
    PointScene shadowedScene = pointOverOccluders(true), plainScene = pointOverOccluders(false);
    for (Scene* s : {&shadowedScene.scene, &plainScene.scene})
        for (auto& mat : s->models[0].mesh.materials) {
            mat.opacity = 0.5f;
            mat.alphaMode = AlphaMode::Blend;
        }
    RenderSettings r = smallSettings();
    ASSERT_TRUE(passesRun(shadowedScene.scene, r).count("transparent"));
    expectRayCastShadow(shadowedScene, test::renderHdr(shadowedScene.scene, r), test::renderHdr(plainScene.scene, r),
                        "transparent floor");
}

// A point light without castsShadow shades as it did while another light's cube is drawn and
// sampled: the frame with a second, casting light of zero intensity equals the frame without it.
TEST(PointShadows, LightWithoutCastsShadowIsUnchanged) {
    const PointScene alone = pointOverOccluders(false);
    PointScene withCaster = alone;
    PointLight caster;
    caster.position = {-1.0f, 1.0f, 0.5f};
    caster.range = 3.0f;
    caster.intensity = 0.0f;
    caster.castsShadow = true;
    withCaster.scene.pointLights.push_back(caster);
    for (const Way& way : everyWay()) {
        SCOPED_TRACE(way.name);
        ASSERT_TRUE(passesRun(withCaster.scene, way.settings).count("point_shadows"));
        EXPECT_TRUE(test::imagesNear(test::renderHdr(withCaster.scene, way.settings),
                                     test::renderHdr(alone.scene, way.settings), 0.0f, way.name));
    }
}

// --shadow-cache: the second frame keeps the cube (the note says so) and equals a frame whose cube
// was drawn anew (cache off), bit for bit; the light moving (its orbit) redraws it, again equal to a
// fresh redraw.
TEST(PointShadows, KeptCubeEqualsARedrawnOne) {
    PointScene p = pointOverOccluders(true);
    p.scene.pointLights[0].orbitCenter = glm::vec3(0.1f, 0.8f, 0.0f);
    p.scene.pointLights[0].orbitSpeed = 0.5f;
    RenderSettings cached = smallSettings();
    cached.localLights.method = LocalLightMethod::Tiled;
    RenderSettings uncached = cached;
    uncached.shadows.cache = false;
    Renderer renderer(p.scene);
    test::renderHdr(renderer, cached, 0.0f);
    EXPECT_NE(pointShadowNote(renderer).find("redrawn (nothing kept)"), std::string::npos) << pointShadowNote(renderer);
    const ImageF kept = test::renderHdr(renderer, cached, 0.0f);
    EXPECT_NE(pointShadowNote(renderer).find("kept (unchanged)"), std::string::npos) << pointShadowNote(renderer);
    EXPECT_TRUE(test::imagesNear(kept, test::renderHdr(p.scene, uncached, 0.0f), 0.0f, "kept cube"));
    const ImageF moved = test::renderHdr(renderer, cached, 0.4f);
    EXPECT_NE(pointShadowNote(renderer).find("redrawn (light moved)"), std::string::npos) << pointShadowNote(renderer);
    EXPECT_TRUE(test::imagesNear(moved, test::renderHdr(p.scene, uncached, 0.4f), 0.0f, "redrawn cube"));
    // Cache off: drawn every frame.
    Renderer off(p.scene);
    test::renderHdr(off, uncached, 0.0f);
    test::renderHdr(off, uncached, 0.0f);
    EXPECT_NE(pointShadowNote(off).find("redrawn (cache off)"), std::string::npos) << pointShadowNote(off);
}

// The pass runs only for a point light with castsShadow, with shadows on; --explain says why not.
TEST(PointShadows, PassOnlyForACastingPointLight) {
    RenderSettings r = smallSettings();
    std::string why;
    EXPECT_TRUE(passesRun(pointOverOccluders(true).scene, r, &why).count("point_shadows"));
    EXPECT_FALSE(passesRun(pointOverOccluders(false).scene, r, &why).count("point_shadows"));
    EXPECT_NE(why.find("no point light casts a shadow"), std::string::npos) << why;
    // A casting spot is not a point light: the spots' pass runs, this one does not.
    Scene spot = pointOverOccluders(false).scene;
    spot.pointLights[0].spot = SpotCone{};
    spot.pointLights[0].castsShadow = true;
    const std::set<std::string> spotRuns = passesRun(spot, r, &why);
    EXPECT_TRUE(spotRuns.count("spot_shadows"));
    EXPECT_FALSE(spotRuns.count("point_shadows"));
    RenderSettings off = r;
    off.shadows.enabled = false;
    EXPECT_FALSE(passesRun(pointOverOccluders(true).scene, off, &why).count("point_shadows"));
    EXPECT_NE(why.find("--no-shadows"), std::string::npos) << why;
}

}  // namespace
