// --shadow-raster compute against the hardware plain raster: the same casters give the same depth
// atlas (shadow_raster.comp follows the plain path's fill rule, sample positions, slope bias and
// depth clamp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/graph/texture_pool.hpp"
#include "engine/render/scene_gpu.hpp"
#include "engine/scene/primitives.hpp"
#include "frame/renderer.hpp"
#include "passes/shadow_map_pass.hpp"
#include "tests/gl/gl_fixture.hpp"

using namespace lp;

namespace {

// Spheres and boxes at random rotations (fixed seed) under a tilted sun; with `floor`, a 12 m plane
// of two triangles per 3 m square, which the compute path hands to the hardware (too large).
Scene randomCasters(bool floor) {
    Scene s;
    std::mt19937 rng(1234);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    if (floor) {
        ModelInstance plane;
        plane.name = "floor";
        plane.mesh = makePlane(12.0f, 4);
        s.models.push_back(std::move(plane));
    }
    for (int i = 0; i < 6; ++i) {
        ModelInstance m;
        m.name = "caster" + std::to_string(i);
        m.mesh = i % 2 == 0 ? makeSphere(0.4f + 0.1f * float(i), 14, 9) : makeCube(0.7f);
        const glm::vec3 axis = glm::normalize(glm::vec3(unit(rng), unit(rng), unit(rng)) + glm::vec3(0.0f, 0.0f, 1e-3f));
        m.transform = glm::translate(glm::mat4(1.0f), glm::vec3(1.6f * float(i % 3) - 1.6f, 0.8f + 0.3f * unit(rng),
                                                                 1.4f * float(i / 3) - 0.7f)) *
                      glm::rotate(glm::mat4(1.0f), 3.14159265f * unit(rng), axis);
        s.models.push_back(std::move(m));
    }
    DirectionalLight sun;
    sun.direction = glm::normalize(glm::vec3(0.35f, -1.0f, 0.25f));
    s.directionalLights.push_back(sun);
    s.camera.position = glm::vec3(0.0f, 3.0f, 5.0f);
    s.camera.target = glm::vec3(0.0f, 0.5f, 0.0f);
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 30.0f;
    return s;
}

std::vector<float> shadowAtlas(const Scene& scene, const RenderSettings& settings) {
    SceneGpu gpu(scene);
    gl::ShaderLibrary shaders;
    FrameData frame = makeFrameData(scene, settings, 0.0f);
    frame.gpu = &gpu;
    frame.shaders = &shaders;
    ShadowMapPass state;
    fg::FrameGraph graph;
    fg::TexturePool pool;
    const ShadowMaps maps = addShadowMapPasses(graph, state, frame);
    EXPECT_EQ(maps.size(), 1u);
    if (maps.empty()) return {};
    graph.markOutput(maps[0].depth);
    graph.compile();
    graph.execute(pool);
    const int side = maps[0].frustum.tileSize;
    const size_t n = size_t(side * maps[0].frustum.columns) * size_t(side * maps[0].frustum.rows);
    std::vector<float> depth(n);
    glGetTextureImage(graph.outputTexture(maps[0].depth), 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(n * sizeof(float)),
                      depth.data());
    return depth;
}

uint32_t bitsOf(float f) {
    uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}

struct AtlasComparison {
    size_t both = 0;           // texels where both rasters hold a caster
    size_t onlyOne = 0;        // texels where one does and the other doesn't
    uint32_t maxUlps = 0;      // over `both`
    size_t withinOneUlp = 0;   // of `both`
    float maxDifference = 0.0f;
    size_t casters = 0;        // texels with a caster in the plain atlas
};

AtlasComparison compareAtlases(const std::vector<float>& plain, const std::vector<float>& compute) {
    AtlasComparison r;
    EXPECT_EQ(plain.size(), compute.size());
    for (size_t i = 0; i < plain.size() && i < compute.size(); ++i) {
        EXPECT_TRUE(std::isfinite(compute[i]) && compute[i] >= 0.0f && compute[i] <= 1.0f);
        const bool a = plain[i] < 1.0f, b = compute[i] < 1.0f;
        r.casters += a ? 1 : 0;
        if (a != b) ++r.onlyOne;
        if (!a || !b) continue;
        ++r.both;
        const uint32_t x = bitsOf(plain[i]), y = bitsOf(compute[i]);
        r.maxUlps = std::max(r.maxUlps, x > y ? x - y : y - x);
        r.withinOneUlp += (x > y ? x - y : y - x) <= 1 ? 1 : 0;
        r.maxDifference = std::max(r.maxDifference, std::abs(plain[i] - compute[i]));
    }
    return r;
}

void expectSameAtlas(const Scene& s, RenderSettings settings, const char* what) {
    RenderSettings plain = settings, compute = settings;
    plain.shadows.raster = ShadowSettings::Raster::Plain;
    compute.shadows.raster = ShadowSettings::Raster::Compute;
    const AtlasComparison r = compareAtlases(shadowAtlas(s, plain), shadowAtlas(s, compute));
    // The driver's numbers, for the benchmark log (bench/shadow_cost.sh runs this test on the GPU).
    std::printf("%s: %zu texels in both, %zu within one ulp, max %u ulps (%.3g), %zu covered by one only\n", what, r.both,
                r.withinOneUlp, r.maxUlps, double(r.maxDifference), r.onlyOne);
    EXPECT_GT(r.casters, size_t(500)) << what << ": the test needs casters in the map";
    // GL leaves the interpolation's arithmetic to the implementation: the depth agrees with the
    // plane at the texel centre to a few float roundings, more on steep triangles (large dz/dx).
    EXPECT_LE(r.maxDifference, 1e-5f) << what << " (" << r.maxUlps << " ulps)";
    EXPECT_GE(r.withinOneUlp * 2, r.both) << what << ": " << r.withinOneUlp << " of " << r.both << " within one ulp";
    EXPECT_EQ(r.onlyOne, 0u) << what << " (" << r.both << " texels with a caster in both)";
}

}  // namespace

// Only casters a few texels wide (every one on the compute path), one cascade, with and without
// slope bias.
TEST(ShadowComputeRaster, DepthEqualsThePlainHardwareRaster) {
    const Scene s = randomCasters(false);
    RenderSettings settings;
    settings.width = 64;
    settings.height = 48;
    settings.shadows.size = 128;
    settings.shadows.cascades = 1;
    for (float slope : {0.0f, 1.0f, 3.0f}) {
        settings.shadows.slopeBias = slope;
        expectSameAtlas(s, settings, slope == 0.0f ? "slope 0" : slope == 1.0f ? "slope 1" : "slope 3");
    }
}

// With a floor of large triangles (the hardware part of the compute path) and 4 cascades of a
// 2x2 atlas (tile origins), culled.
TEST(ShadowComputeRaster, LargeTrianglesAndCascadeTilesMatchThePlainRaster) {
    const Scene s = randomCasters(true);
    RenderSettings settings;
    settings.width = 64;
    settings.height = 48;
    settings.shadows.size = 96;
    settings.shadows.cascades = 4;
    expectSameAtlas(s, settings, "floor, 4 cascades");
}
