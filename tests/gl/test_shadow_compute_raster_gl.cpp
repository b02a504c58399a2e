// --shadow-raster compute against the hardware plain raster: the same casters give the same depth
// atlas (shadow_raster.comp follows the plain path's fill rule, sample positions, slope bias and
// depth clamp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <random>

#include <unistd.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "engine/graph/texture_pool.hpp"
#include "engine/core/log.hpp"
#include "engine/core/measured_cache.hpp"
#include "engine/render/scene_gpu.hpp"
#include "engine/scene/mesh_ops.hpp"
#include "engine/scene/primitives.hpp"
#include "frame/renderer.hpp"
#include "passes/shadow_map_pass.hpp"
#include "tests/gl/gl_fixture.hpp"
#include "tests/gl/render_fixture.hpp"

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

using test::shadowAtlas;

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
    size_t worstTexel = 0;     // where maxUlps is (index into the atlas)
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
        if ((x > y ? x - y : y - x) > r.maxUlps) r.worstTexel = i;
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
    const int atlasWidth = settings.shadows.size * shadowAtlasGrid(settings.shadows.cascades).x;
    std::printf("%s: %zu texels in both, %zu within one ulp, max %u ulps (%.3g) at atlas texel (%zu, %zu), %zu covered by one only\n",
                what, r.both, r.withinOneUlp, r.maxUlps, double(r.maxDifference), r.worstTexel % size_t(atlasWidth),
                r.worstTexel / size_t(atlasWidth), r.onlyOne);
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

// Edges exactly through texel centres, where the fill rule decides: a tilted grid of 2x2-texel
// squares, each split along a diagonal, with every vertex on a texel centre of the cascade (placed
// through the inverse of the cascade's matrix; two cubes at the corners fix the scene's bounds, so
// the grid does not move the cascade). Both rasters cover the same texels, and the top-left rule
// (left and bottom edges in GL's window y) gives exactly the half-open square: 2n x 2n texels.
TEST(ShadowComputeRaster, EdgesThroughTexelCentresFollowTheFillRule) {
    Scene s;
    for (int i = 0; i < 2; ++i) {
        ModelInstance corner;
        corner.name = "corner" + std::to_string(i);
        corner.mesh = makeCube(0.2f);
        corner.transform = glm::translate(glm::mat4(1.0f), i == 0 ? glm::vec3(-2.0f, 0.0f, -2.0f) : glm::vec3(2.0f, 1.5f, 2.0f));
        s.models.push_back(std::move(corner));
    }
    DirectionalLight sun;
    sun.direction = glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f));
    s.directionalLights.push_back(sun);
    s.camera.position = glm::vec3(0.0f, 6.0f, 6.0f);
    s.camera.target = glm::vec3(0.0f);
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 30.0f;
    RenderSettings settings;
    settings.width = 64;
    settings.height = 48;
    settings.shadows.size = 128;
    settings.shadows.cascades = 1;
    settings.shadows.slopeBias = 1.0f;
    const ShadowFrustum before = fitShadowFrustum(makeFrameData(s, settings, 0.0f), sun.direction);
    ASSERT_EQ(before.cascades.size(), 1u);
    const int tile = before.tileSize;
    const glm::dmat4 clipToWorld = glm::inverse(glm::dmat4(before.cascades[0].worldToClip));

    const int n = 6, x0 = 40, y0 = 50;  // n x n squares of 2 texels from texel centre (x0, y0) + 0.5
    ModelInstance grid;
    grid.name = "grid";
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const double wx = x0 + 0.5 + 2.0 * i, wy = y0 + 0.5 + 2.0 * j;
            const double z = 0.1 * double(i) / n + 0.05 * double(j) / n - 0.2;  // tilted, inside the depth range
            const glm::dvec4 w = clipToWorld * glm::dvec4(2.0 * wx / tile - 1.0, 2.0 * wy / tile - 1.0, z, 1.0);
            Vertex v;
            v.position = glm::vec3(glm::dvec3(w) / w.w);
            grid.mesh.vertices.push_back(v);
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
            // Alternate the diagonal and the winding: every edge orientation occurs.
            if ((i + j) % 2 == 0) grid.mesh.indices.insert(grid.mesh.indices.end(), {a, b, d, a, d, c});
            else grid.mesh.indices.insert(grid.mesh.indices.end(), {a, c, b, b, c, d});
        }
    grid.mesh.materials = {Material{}};
    grid.mesh.subMeshes = {SubMesh{0, uint32_t(grid.mesh.indices.size()), 0}};
    computeBounds(grid.mesh);
    s.models.push_back(std::move(grid));
    const ShadowFrustum after = fitShadowFrustum(makeFrameData(s, settings, 0.0f), sun.direction);
    ASSERT_EQ(after.cascades.size(), 1u);
    ASSERT_EQ(after.tileSize, tile);
    for (int k = 0; k < 16; ++k)
        ASSERT_EQ(glm::value_ptr(after.cascades[0].worldToClip)[k], glm::value_ptr(before.cascades[0].worldToClip)[k]);

    RenderSettings plain = settings, compute = settings;
    plain.shadows.raster = ShadowSettings::Raster::Plain;
    compute.shadows.raster = ShadowSettings::Raster::Compute;
    const std::vector<float> a = shadowAtlas(s, plain), b = shadowAtlas(s, compute);
    ASSERT_EQ(a.size(), size_t(tile) * size_t(tile));
    ASSERT_EQ(b.size(), a.size());
    auto coveredInSquare = [&](const std::vector<float>& atlas) {
        size_t inside = 0, outside = 0;
        for (int y = y0 - 3; y < y0 + 2 * n + 3; ++y)
            for (int x = x0 - 3; x < x0 + 2 * n + 3; ++x) {
                const bool covered = atlas[size_t(y) * size_t(tile) + size_t(x)] < 1.0f;
                const bool expected = x >= x0 && x < x0 + 2 * n && y >= y0 && y < y0 + 2 * n;
                inside += covered && expected ? 1 : 0;
                outside += covered && !expected ? 1 : 0;
            }
        return std::make_pair(inside, outside);
    };
    const auto hardware = coveredInSquare(a), software = coveredInSquare(b);
    EXPECT_EQ(hardware.first, size_t(4 * n * n)) << "plain: texels of the half-open square covered";
    EXPECT_EQ(hardware.second, 0u) << "plain: texels outside it covered";
    EXPECT_EQ(software.first, size_t(4 * n * n)) << "compute";
    EXPECT_EQ(software.second, 0u) << "compute";
    size_t differ = 0;
    for (size_t i = 0; i < a.size(); ++i) differ += (a[i] < 1.0f) != (b[i] < 1.0f) ? 1 : 0;
    EXPECT_EQ(differ, 0u);
}

namespace {

std::string readFile(const std::filesystem::path& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// LIGHTPASS_CACHE_DIR set to a fresh directory for one test, restored after it.
struct ScopedCacheDir {
    std::filesystem::path dir;
    std::string previous;
    bool had = false;
    explicit ScopedCacheDir(const std::string& name) {
        dir = std::filesystem::temp_directory_path() / ("lightpass_test_" + name + "_" + std::to_string(::getpid()));
        std::filesystem::remove_all(dir);
        std::filesystem::create_directories(dir);
        if (const char* p = std::getenv("LIGHTPASS_CACHE_DIR")) {
            had = true;
            previous = p;
        }
        ::setenv("LIGHTPASS_CACHE_DIR", dir.c_str(), 1);
    }
    ~ScopedCacheDir() {
        had ? void(::setenv("LIGHTPASS_CACHE_DIR", previous.c_str(), 1)) : void(::unsetenv("LIGHTPASS_CACHE_DIR"));
        std::filesystem::remove_all(dir);
    }
};

RenderSettings autoTestSettings(ShadowSettings::Raster raster) {
    RenderSettings settings;
    settings.width = 64;
    settings.height = 48;
    settings.shadows.size = 64;
    settings.shadows.cascades = 2;
    settings.shadows.raster = raster;
    return settings;
}

}  // namespace

// --shadow-raster auto without a cache: measures the four rasters once, draws with the fastest
// (its atlas is that raster's), and caches the choice under this GPU's key.
TEST(ShadowRasterAuto, MeasuresOnceAndCachesTheChoicePerGpu) {
    ScopedCacheDir cache("auto_measure");
    const Scene s = randomCasters(true);
    ShadowMapPass state;
    const std::vector<float> autoAtlas = shadowAtlas(s, autoTestSettings(ShadowSettings::Raster::Auto), &state);
    ASSERT_TRUE(state.autoResolved);
    ASSERT_NE(state.autoRaster, ShadowSettings::Raster::Auto);
    EXPECT_NE(state.autoReport.find("measured: conservative"), std::string::npos) << state.autoReport;
    EXPECT_NE(state.autoReport.find("compute"), std::string::npos) << state.autoReport;
    EXPECT_EQ(measuredCachePath(), cache.dir / "measured_choices.json");
    const MeasuredSection cached = readMeasuredSection(measuredCachePath(), "shadow_raster");
    EXPECT_EQ(cached.warning, "");
    EXPECT_EQ(cached.entries, nlohmann::json({{shadowRasterCacheKey(), ShadowSettings::rasterName(state.autoRaster)}}));
    EXPECT_TRUE(test::valuesNear(autoAtlas, shadowAtlas(s, autoTestSettings(state.autoRaster)), int(autoAtlas.size()), 1, 0.0f,
                                 "the auto atlas against its raster's"));
    // A second frame of the same pass does not measure again.
    const std::string report = state.autoReport;
    shadowAtlas(s, autoTestSettings(ShadowSettings::Raster::Auto), &state);
    EXPECT_EQ(state.autoReport, report);
}

// A cached choice for this GPU is used as is (no measurement), other GPUs' entries are left alone.
TEST(ShadowRasterAuto, UsesTheCachedChoiceForThisGpu) {
    ScopedCacheDir cache("auto_cached");
    const std::filesystem::path file = cache.dir / "measured_choices.json";
    ASSERT_EQ(writeMeasuredSection(file, "shadow_raster",
                                   {{"Some Other GPU / 1.0", "plain"}, {shadowRasterCacheKey(), "split"}}), "");
    const std::string contents = readFile(file);
    const Scene s = randomCasters(true);
    ShadowMapPass state;
    const std::vector<float> autoAtlas = shadowAtlas(s, autoTestSettings(ShadowSettings::Raster::Auto), &state);
    EXPECT_EQ(state.autoRaster, ShadowSettings::Raster::Split);
    EXPECT_NE(state.autoReport.find("cached in"), std::string::npos) << state.autoReport;
    EXPECT_EQ(state.autoReport.find("(measured:"), std::string::npos) << state.autoReport;
    EXPECT_EQ(readFile(file), contents);
    EXPECT_TRUE(test::valuesNear(autoAtlas, shadowAtlas(s, autoTestSettings(ShadowSettings::Raster::Split)),
                                 int(autoAtlas.size()), 1, 0.0f, "the auto atlas against split's"));
}

// An unknown raster name in this GPU's entry: a warning, a new measurement, the entry replaced;
// other GPUs' entries and the other choices' sections are kept.
TEST(ShadowRasterAuto, BadCacheEntryIsMeasuredAgainAndReplaced) {
    ScopedCacheDir cache("auto_bad");
    const std::filesystem::path file = cache.dir / "measured_choices.json";
    const nlohmann::json postBackend = {{"gpu|driver|64x48|kernel 9|separable|shared|bloom", {{"cuda_ms", 1.0}, {"glsl_ms", 2.0}}}};
    ASSERT_EQ(writeMeasuredSection(file, "post_backend", postBackend), "");
    ASSERT_EQ(writeMeasuredSection(file, "shadow_raster", {{"Some Other GPU / 1.0", "plain"}, {shadowRasterCacheKey(), "bogus"}}), "");
    const int warnings = warningCount();
    ShadowMapPass state;
    shadowAtlas(randomCasters(true), autoTestSettings(ShadowSettings::Raster::Auto), &state);
    EXPECT_GT(warningCount(), warnings);
    EXPECT_NE(state.autoReport.find("(measured:"), std::string::npos) << state.autoReport;
    EXPECT_EQ(readMeasuredSection(file, "shadow_raster").entries,
              nlohmann::json({{"Some Other GPU / 1.0", "plain"}, {shadowRasterCacheKey(), ShadowSettings::rasterName(state.autoRaster)}}));
    EXPECT_EQ(readMeasuredSection(file, "post_backend").entries, postBackend);
}
