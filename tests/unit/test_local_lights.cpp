// CPU side: scissor rectangles of projected spheres, the circumscribing icosphere,
// which lights a frame draws, and the frame graph with and without local lights.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/graph/frame_graph.hpp"
#include "frame/frame_builder.hpp"
#include "engine/render/local_lights.hpp"

using namespace lp;

namespace {

// Pixel bounds of densely sampled points of the sphere (all in front of the near plane here).
void sampledBounds(glm::dvec3 c, double r, const glm::dmat4& proj, int w, int h, double lo[2], double hi[2]) {
    lo[0] = lo[1] = 1e30;
    hi[0] = hi[1] = -1e30;
    const int n = 600;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j < 2 * n; ++j) {
            double th = M_PI * i / n, ph = M_PI * j / n;
            glm::dvec3 p = c + r * glm::dvec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
            glm::dvec4 q = proj * glm::dvec4(p, 1.0);
            double px = (q.x / q.w * 0.5 + 0.5) * w, py = (q.y / q.w * 0.5 + 0.5) * h;
            lo[0] = std::min(lo[0], px), hi[0] = std::max(hi[0], px);
            lo[1] = std::min(lo[1], py), hi[1] = std::max(hi[1], py);
        }
}

TEST(LocalLightBounds, ScissorRectIsTheTightBoundOfTheProjectedSphere) {
    const int w = 640, h = 480;
    const glm::mat4 proj = glm::perspective(glm::radians(60.0f), float(w) / float(h), 0.1f, 100.0f);
    const glm::vec3 centres[] = {{0, 0, -5}, {1.5f, -0.7f, -4}, {-2.0f, 1.0f, -3}, {0.3f, 0.2f, -1.5f}, {2.5f, 1.5f, -6}};
    for (glm::vec3 c : centres) {
        const float r = 0.8f;
        ScissorRect rect = sphereScissorRect(c, r, proj, 0.1f, w, h);
        ASSERT_FALSE(rect.empty());
        EXPECT_FALSE(rect.fullScreen);
        double lo[2], hi[2];
        sampledBounds(glm::dvec3(c), r, glm::dmat4(proj), w, h, lo, hi);
        const int rlo[2] = {rect.x, rect.y}, rhi[2] = {rect.x + rect.width, rect.y + rect.height};
        for (int a = 0; a < 2; ++a) {
            const double size = a == 0 ? w : h;
            // Holds every sampled point (clipped to the viewport) ...
            EXPECT_LE(rlo[a], std::max(std::floor(lo[a]), 0.0)) << "axis " << a;
            EXPECT_GE(rhi[a], std::min(std::ceil(hi[a]), size)) << "axis " << a;
            // ... and is tight: at most one pixel of outward rounding past the sampled bounds
            // (the 600x1200 sampling misses the true extreme by < 0.01 px at these sizes).
            EXPECT_GE(rlo[a], std::max(lo[a], 0.0) - 1.01) << "axis " << a;
            EXPECT_LE(rhi[a], std::min(hi[a], size) + 1.01) << "axis " << a;
        }
    }
}

TEST(LocalLightBounds, NearPlaneCasesAreFullScreenOrEmpty) {
    const glm::mat4 proj = glm::perspective(glm::radians(50.0f), 1.5f, 0.1f, 100.0f);
    // Camera inside the sphere.
    EXPECT_TRUE(sphereScissorRect({0.2f, 0.1f, -0.3f}, 1.0f, proj, 0.1f, 64, 48).fullScreen);
    // Camera outside, sphere crossing the near plane (|c| = 1.2 > r = 1, c.z + r = 0.7 > -0.1).
    ScissorRect crossing = sphereScissorRect({1.15f, 0.0f, -0.3f}, 1.0f, proj, 0.1f, 64, 48);
    EXPECT_TRUE(crossing.fullScreen);
    EXPECT_EQ(crossing.width, 64);
    EXPECT_EQ(crossing.height, 48);
    // Wholly behind the near plane (behind the camera): nothing to draw.
    EXPECT_TRUE(sphereScissorRect({0.0f, 0.0f, 3.0f}, 1.0f, proj, 0.1f, 64, 48).empty());
    // In front but off to the side of the frustum: empty.
    EXPECT_TRUE(sphereScissorRect({40.0f, 0.0f, -5.0f}, 1.0f, proj, 0.1f, 64, 48).empty());
}

TEST(LocalLightBounds, IcosphereCircumscribesTheUnitSphere) {
    for (int sub : {0, 1, 2}) {
        std::vector<glm::vec3> tris = circumscribingIcosphere(sub);
        ASSERT_EQ(tris.size(), size_t(20 * std::pow(4, sub) * 3));
        double nearest = 1e9;
        for (size_t i = 0; i < tris.size(); i += 3) {
            glm::dvec3 a(tris[i]), b(tris[i + 1]), c(tris[i + 2]);
            glm::dvec3 n = glm::cross(b - a, c - a);
            // Counter-clockwise seen from outside (the volumes method culls front faces).
            EXPECT_GT(glm::dot(n, a), 0.0);
            nearest = std::min(nearest, glm::dot(glm::normalize(n), a));
        }
        // Every face plane at distance >= 1 (covers the sphere), and at most 0.2% + the subdivision's
        // sag beyond it (not wasteful): the unscaled inradius is 0.79, 0.93, 0.98 for 0, 1, 2.
        EXPECT_GE(nearest, 1.0);
        EXPECT_LE(nearest, 1.002);
    }
}

Scene sceneWithLights(int n) {
    Scene s;
    ModelInstance m;
    m.primitive = "plane";
    m.mesh.boundsMin = glm::vec3(-1.0f, 0.0f, -1.0f);
    m.mesh.boundsMax = glm::vec3(1.0f, 0.5f, 1.0f);
    s.models.push_back(m);
    s.directionalLights.push_back(DirectionalLight{});
    for (int i = 0; i < n; ++i) {
        PointLight l;
        l.position = glm::vec3(float(i), 1.0f, 0.0f);
        l.range = 1.0f + float(i);
        s.pointLights.push_back(l);
    }
    return s;
}

TEST(LocalLightSelection, CountSelectsOrGeneratesLights) {
    Scene s = sceneWithLights(3);
    LocalLightSettings ls;
    EXPECT_EQ(localLightsForFrame(s, ls, 0.0f).size(), 3u);
    ls.lightCount = 2;
    auto two = localLightsForFrame(s, ls, 0.0f);
    ASSERT_EQ(two.size(), 2u);
    EXPECT_EQ(two[1].range, 2.0f);  // the first N of the scene's, in order
    ls.lightCount = 4096;
    auto many = localLightsForFrame(s, ls, 0.0f);
    ASSERT_EQ(many.size(), 4096u);
    EXPECT_EQ(many[2].range, 3.0f);  // the scene's lights first
    glm::vec3 lo, hi;
    s.bounds(lo, hi);
    for (size_t i = 3; i < many.size(); ++i) {
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(many[i].position, lo - 1e-5f)) &&
                    glm::all(glm::lessThanEqual(many[i].position, hi + 1e-5f)))
            << "demo light " << i << " inside the scene's bounds";
        EXPECT_GT(many[i].range, 0.0f);
        EXPECT_GT(many[i].intensity, 0.0f);
    }
    // Deterministic: the same set every time.
    auto again = localLightsForFrame(s, ls, 0.0f);
    EXPECT_EQ(again[100].position, many[100].position);
    ls.enabled = false;
    EXPECT_TRUE(localLightsForFrame(s, ls, 0.0f).empty());
}

TEST(LocalLightSelection, OrbitRotatesAboutTheCentreAtItsSpeed) {
    PointLight l;
    l.position = {2.0f, 1.0f, 0.0f};
    l.orbitCenter = {1.0f, 0.0f, 0.0f};
    l.orbitSpeed = 0.5f;
    // After t = pi s at 0.5 rad/s: a quarter turn about +Y through the centre: (1,1,0) offset -> (0,1,-1).
    glm::vec3 p = orbitPosition(l, float(M_PI));
    EXPECT_NEAR(p.x, 1.0f, 1e-5f);
    EXPECT_NEAR(p.y, 1.0f, 1e-5f);  // the height above the centre is kept
    EXPECT_NEAR(p.z, -1.0f, 1e-5f);
    l.orbitSpeed = 0.0f;
    EXPECT_EQ(orbitPosition(l, 10.0f), l.position);
}

// The records the shaders read are the view matrix's products (glm's mat4 * vec4), to the bit, for
// point lights and spots; a point light's bounding sphere is its range sphere.
TEST(LocalLightSelection, GpuRecordsAreTheViewTransformsToTheBit) {
    const glm::mat4 view = glm::lookAt(glm::vec3(1.3f, 2.7f, -4.1f), glm::vec3(0.2f, 0.5f, 0.3f), glm::vec3(0, 1, 0));
    PointLight point;
    point.position = {0.37f, -1.91f, 2.23f};
    point.range = 3.5f;
    PointLight spot = point;
    spot.spot = SpotCone{};
    spot.spot->direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    spot.spot->outerDegrees = 30.0f;
    spot.spot->innerDegrees = 20.0f;
    for (const PointLight& l : {point, spot}) {
        const GpuLocalLight g = gpuLocalLight(l, view, -1);
        const glm::vec3 eye = glm::vec3(view * glm::vec4(l.position, 1.0f));
        EXPECT_EQ(glm::vec3(g.positionRange), eye);
        EXPECT_EQ(g.positionRange.w, l.range);
        const BoundingSphere b = localLightBounds(l);
        EXPECT_EQ(glm::vec3(g.bound), glm::vec3(view * glm::vec4(b.center, 1.0f)));
        EXPECT_EQ(g.bound.w, b.radius);
        if (l.spot)
            EXPECT_EQ(glm::vec3(g.directionCos), glm::normalize(glm::vec3(view * glm::vec4(l.spot->direction, 0.0f))));
    }
}

// An orbit keeps a light's height exactly and its horizontal distance from the centre.
TEST(LocalLightSelection, OrbitKeepsTheHeightExactly) {
    PointLight l;
    l.position = {2.1f, 0.3f, -0.7f};
    l.orbitCenter = {0.4f, 0.3f, 0.9f};
    l.orbitSpeed = 0.37f;
    const float radius = glm::length(glm::vec2(l.position.x - l.orbitCenter.x, l.position.z - l.orbitCenter.z));
    for (float t : {0.1f, 1.0f, 7.3f, 100.0f}) {
        const glm::vec3 p = orbitPosition(l, t);
        EXPECT_EQ(p.y, l.position.y) << "t " << t;
        EXPECT_NEAR(glm::length(glm::vec2(p.x - l.orbitCenter.x, p.z - l.orbitCenter.z)), radius, 1e-5f) << "t " << t;
    }
}

// A frame carries its lights, made once with it (every pass reads that list), equal to
// localLightsForFrame's at the frame's time.
TEST(LocalLightSelection, FrameCarriesTheLightsOfItsTime) {
    Scene s = sceneWithLights(3);
    RenderSettings settings;
    settings.width = 64;
    settings.height = 48;
    settings.localLights.lightCount = 300;
    const FrameData frame = makeFrameData(s, settings, 2.5f);
    ASSERT_TRUE(frame.localLights);
    const std::vector<PointLight> expected = localLightsForFrame(s, settings.localLights, 2.5f);
    ASSERT_EQ(frame.localLights->size(), expected.size());
    for (size_t i = 0; i < expected.size(); ++i) {
        EXPECT_EQ((*frame.localLights)[i].position, expected[i].position) << i;
        EXPECT_EQ((*frame.localLights)[i].range, expected[i].range) << i;
    }
    EXPECT_EQ(frameLocalLights(frame), frame.localLights);  // the same list, not a new one
    FrameData byHand = frame;
    byHand.localLights = nullptr;  // a frame made without them: made on demand, the same lights
    ASSERT_EQ(frameLocalLights(byHand)->size(), expected.size());
    EXPECT_EQ((*frameLocalLights(byHand))[299].position, expected[299].position);
}

std::vector<std::string> order(const Scene& s, RenderSettings settings) {
    settings.width = 64;
    settings.height = 48;
    FrameData frame = makeFrameData(s, settings, 0.0f);
    fg::FrameGraph g;
    PassStates passes;
    buildFrameGraph(g, passes, frame);
    g.compile();
    return g.executionOrder();
}
bool has(const std::vector<std::string>& v, const std::string& x) { return std::find(v.begin(), v.end(), x) != v.end(); }

TEST(LocalLightGraph, NoLocalLightPassWithoutLights) {
    RenderSettings r;
    EXPECT_FALSE(has(order(sceneWithLights(0), r), "local_lights"));  // the scene has none
    r.localLights.enabled = false;
    EXPECT_FALSE(has(order(sceneWithLights(3), r), "local_lights"));  // --no-local-lights
    r.localLights.enabled = true;
    r.localLights.lightCount = 0;
    EXPECT_FALSE(has(order(sceneWithLights(3), r), "local_lights"));  // --light-count 0
    r.localLights.globes = true;
    EXPECT_FALSE(has(order(sceneWithLights(3), r), "light_globes"));
}

TEST(LocalLightGraph, LocalLightsAddIntoHdrBetweenGlobalLightsAndSky) {
    RenderSettings r;
    auto o = order(sceneWithLights(3), r);
    auto pos = [&](const std::string& n) { return std::find(o.begin(), o.end(), n) - o.begin(); };
    ASSERT_TRUE(has(o, "local_lights"));
    EXPECT_LT(pos("global_lights"), pos("local_lights"));
    EXPECT_LT(pos("local_lights"), pos("sky"));
    // The lighting view keeps them (white albedo); a G-buffer view culls them.
    r.view = DebugView::Lighting;
    EXPECT_TRUE(has(order(sceneWithLights(3), r), "local_lights"));
    r.view = DebugView::Normals;
    EXPECT_FALSE(has(order(sceneWithLights(3), r), "local_lights"));
}

TEST(LocalLightGraph, OverlayViewsDrawOverTheFinalImage) {
    RenderSettings r;
    r.view = DebugView::LightRanges;
    auto o = order(sceneWithLights(3), r);
    EXPECT_TRUE(has(o, "light_ranges"));
    EXPECT_TRUE(has(o, "tonemap"));
    EXPECT_FALSE(has(o, "debug_view"));
    r.view = DebugView::LightsPerTile;
    r.localLights.globes = true;
    o = order(sceneWithLights(3), r);
    EXPECT_TRUE(has(o, "lights_per_tile"));
    EXPECT_TRUE(has(o, "light_globes"));
    auto pos = [&](const std::string& n) { return std::find(o.begin(), o.end(), n) - o.begin(); };
    EXPECT_LT(pos("sky"), pos("light_globes"));  // globes show against the background too
    EXPECT_EQ(parseView("light-ranges"), DebugView::LightRanges);
    EXPECT_EQ(parseView("lights-per-tile"), DebugView::LightsPerTile);
    EXPECT_EQ(parseView("lights-per-cluster"), DebugView::LightsPerCluster);
    r.view = DebugView::LightsPerCluster;
    EXPECT_TRUE(has(order(sceneWithLights(3), r), "lights_per_cluster"));
    EXPECT_EQ(parseLocalLightMethod("clustered"), LocalLightMethod::Clustered);
    for (LocalLightMethod m : allLocalLightMethods()) EXPECT_EQ(parseLocalLightMethod(localLightMethodName(m)), m);
    EXPECT_FALSE(parseLocalLightMethod("deferred"));
}

}  // namespace

namespace {
// Every point of a spot's spherical sector (within the range, within the outer angle of the axis)
// lies in localLightBounds, and the bound is no larger than the range sphere.
TEST(LocalLightBounds, SpotBoundingSphereHoldsTheWholeCone) {
    for (float outer : {1.0f, 20.0f, 44.9f, 45.0f, 45.1f, 60.0f, 89.0f}) {
        PointLight l;
        l.position = {0.5f, 2.0f, -1.0f};
        l.range = 3.0f;
        l.spot = SpotCone{glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f)), 0.0f, outer};
        const BoundingSphere b = localLightBounds(l);
        EXPECT_LE(b.radius, l.range * (1.0f + 1e-6f)) << outer;
        const glm::dvec3 axis(l.spot->direction);
        const glm::dvec3 u = glm::normalize(glm::cross(axis, glm::dvec3(1, 0, 0))), v = glm::cross(axis, u);
        double worst = 0.0;
        for (int i = 0; i <= 40; ++i)          // distance from the apex, 0..R
            for (int j = 0; j <= 20; ++j)      // angle from the axis, 0..outer
                for (int k = 0; k < 16; ++k) {  // around the axis
                    const double d = l.range * i / 40.0, a = glm::radians(double(outer)) * j / 20.0, t = M_PI * k / 8.0;
                    const glm::dvec3 p = glm::dvec3(l.position) +
                                         d * (std::cos(a) * axis + std::sin(a) * (std::cos(t) * u + std::sin(t) * v));
                    worst = std::max(worst, glm::length(p - glm::dvec3(b.center)) - b.radius);
                }
        EXPECT_LE(worst, 1e-5 * l.range) << "outer " << outer;
    }
    PointLight point;
    point.range = 2.0f;
    EXPECT_EQ(localLightBounds(point).radius, 2.0f);
}

// The GPU record: a point light's cone encoding gives no falloff; a spot's axis in eye space.
TEST(LocalLightSelection, GpuRecordEncodesTheCone) {
    PointLight p;
    p.range = 2.0f;
    GpuLocalLight g = gpuLocalLight(p, glm::mat4(1.0f), -1);
    EXPECT_LT(g.directionCos.w, -1.0f);
    EXPECT_LT(g.intensity.w, -1.0f);
    EXPECT_EQ(g.bound, glm::vec4(0.0f, 0.0f, 0.0f, 2.0f));
    EXPECT_EQ(g.shadow.x, -1.0f);
    p.spot = SpotCone{{1.0f, 0.0f, 0.0f}, 30.0f, 60.0f};
    p.castsShadow = true;
    const glm::mat4 view = glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(0, 1, 0));
    g = gpuLocalLight(p, view, 2);
    EXPECT_NEAR(g.directionCos.z, -1.0f, 1e-6f);  // +X world is -Z after this rotation
    EXPECT_NEAR(g.directionCos.w, 0.5f, 1e-6f);
    EXPECT_NEAR(g.intensity.w, std::sqrt(3.0f) / 2.0f, 1e-6f);
    EXPECT_EQ(g.shadow.x, 2.0f);
}
}  // namespace
