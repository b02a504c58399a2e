// Caster culling on the driver: each sun cascade draws only the clusters that reach its tile, and
// its depth atlas is bit for bit the one drawn with every caster, for both caster rasters.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/graph/texture_pool.hpp"
#include "engine/render/scene_gpu.hpp"
#include "engine/render/shadow_casters.hpp"
#include "engine/scene/primitives.hpp"
#include "frame/renderer.hpp"
#include "passes/shadow_map_pass.hpp"
#include "tests/gl/gl_fixture.hpp"

using namespace lp;

namespace {

// A 40 m floor and a row of spheres going away from the camera: the near cascades see the first
// spheres only, the far ones all of them.
Scene rowOfSpheres() {
    Scene s;
    ModelInstance floor;
    floor.name = "floor";
    floor.mesh = makePlane(40.0f, 4);
    s.models.push_back(std::move(floor));
    for (int i = 0; i < 8; ++i) {
        ModelInstance ball;
        ball.name = "ball" + std::to_string(i);
        ball.mesh = makeSphere(0.5f, 16, 8);
        ball.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.6f * float(i % 2), 0.5f, -1.5f - 2.5f * float(i)));
        s.models.push_back(std::move(ball));
    }
    DirectionalLight sun;
    sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    s.directionalLights.push_back(sun);
    s.camera.position = glm::vec3(0.0f, 1.5f, 2.0f);
    s.camera.target = glm::vec3(0.0f, 0.5f, -6.0f);
    s.camera.nearPlane = 0.05f;
    s.camera.farPlane = 40.0f;
    return s;
}

using test::shadowAtlas;

// Two 128^2 cascades of rowOfSpheres at 64 x 48 with no slope bias: the rasters' depths compare
// directly (the tests that order them).
RenderSettings twoUnbiasedCascades() {
    RenderSettings settings;
    settings.width = 64;
    settings.height = 48;
    settings.shadows.size = 128;
    settings.shadows.cascades = 2;
    settings.shadows.slopeBias = 0.0f;
    return settings;
}

}  // namespace

TEST(ShadowCasterCulling, AtlasIsUnchangedWithCullingOnAndOff) {
    const Scene s = rowOfSpheres();
    RenderSettings settings;
    settings.width = 64;
    settings.height = 48;
    settings.shadows.size = 128;
    settings.shadows.cascades = 4;

    // The test means something only if the near cascade leaves spheres out.
    const FrameData frame = makeFrameData(s, settings, 0.0f);
    const ShadowFrustum fr = fitShadowFrustum(frame, s.directionalLights[0].direction);
    ASSERT_GE(fr.cascades.size(), 2u);
    const std::vector<CasterCluster> clusters = buildCasterClusters(s);
    const CasterList nearest = cullCasters(clusters, s, fr.cascades[0].worldToClip, 2.0f / float(fr.tileSize), true);
    EXPECT_LT(nearest.clusters + 2, clusters.size()) << "the near cascade should cull several spheres";

    for (auto raster : {ShadowSettings::Raster::Conservative, ShadowSettings::Raster::Plain, ShadowSettings::Raster::Split,
                        ShadowSettings::Raster::Compute}) {
        RenderSettings on = settings, off = settings;
        on.shadows.raster = off.shadows.raster = raster;
        off.shadows.cullCasters = false;
        const std::vector<float> culled = shadowAtlas(s, on), all = shadowAtlas(s, off);
        ASSERT_EQ(culled.size(), all.size());
        size_t differ = 0, casters = 0;
        for (size_t i = 0; i < all.size(); ++i) {
            differ += culled[i] != all[i] ? 1 : 0;
            casters += all[i] < 1.0f ? 1 : 0;
        }
        EXPECT_EQ(differ, 0u) << ShadowSettings::rasterName(raster);
        EXPECT_GT(casters, all.size() / 2) << "the floor covers every tile";
    }
}

// The plain and split rasters (--shadow-raster plain|split) draw the same casters: with no slope
// bias, away from silhouettes they hold the same nearest surface as the conservative one (1e-3 of
// the depth range), and split never holds a farther one than plain (its faces away from the light
// are only grown and pulled nearer).
TEST(ShadowCasterCulling, PlainAndSplitRastersSeeTheSameCasters) {
    const Scene s = rowOfSpheres();
    const RenderSettings settings = twoUnbiasedCascades();
    RenderSettings plain = settings, split = settings;
    plain.shadows.raster = ShadowSettings::Raster::Plain;
    split.shadows.raster = ShadowSettings::Raster::Split;
    const std::vector<float> a = shadowAtlas(s, settings), b = shadowAtlas(s, plain), c = shadowAtlas(s, split);
    ASSERT_EQ(a.size(), b.size());
    ASSERT_EQ(a.size(), c.size());
    size_t closePlain = 0, closeSplit = 0, splitFarther = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        ASSERT_TRUE(std::isfinite(b[i]) && std::isfinite(c[i]));
        closePlain += std::abs(a[i] - b[i]) < 1e-3f ? 1 : 0;
        closeSplit += std::abs(a[i] - c[i]) < 1e-3f ? 1 : 0;
        splitFarther += c[i] > b[i] + 1e-5f ? 1 : 0;
    }
    EXPECT_GT(closePlain, a.size() * 9 / 10);
    EXPECT_GT(closeSplit, a.size() * 9 / 10);
    EXPECT_EQ(splitFarther, 0u);
}

// The hardware conservative raster (GL_NV_conservative_raster; skipped with the reason where the GPU
// lacks it) against the geometry-shader one and the plain raster, slope bias 0: the hardware covers
// exactly the texels a triangle touches, which is every texel whose centre it covers (plain's) and
// within the geometry shader's triangle grown by half a texel (clipped to its box, which reaches a
// little past the touched texels at sharp corners). Per triangle and texel it writes the same depth
// as the geometry shader (faces towards the light: never nearer than the centre's), so where all
// hold a caster: geometry shader <= hardware <= plain (1e-5; 1e-4 against the geometry shader,
// whose grown vertices carry the plane in float). Coverage: plain's texels all in the hardware's;
// the hardware's touches all in the geometry shader's but for 0.1% (fill-rule ties on the grown
// edges). A touch the geometry shader misses shows either as a texel only the hardware covers or,
// where another caster covers the texel in both, as a hardware depth nearer than the geometry
// shader's (on an H100: 4 of 26178 texels, up to 0.039 nearer, with the cache's stable cascades), so
// both count against that 0.1%.
TEST(ShadowConservativeRaster, HardwareLiesBetweenTheGeometryShaderAndThePlainRaster) {
    const ConservativeRasterSupport support = queryConservativeRasterSupport();
    if (!support.hardware) GTEST_SKIP() << "no hardware conservative raster on this GPU: " << support.reason;
    const Scene s = rowOfSpheres();
    const RenderSettings settings = twoUnbiasedCascades();
    RenderSettings hardware = settings, geometry = settings, plain = settings;
    hardware.shadows.conservativeRaster = ShadowSettings::ConservativeRaster::Hardware;
    geometry.shadows.conservativeRaster = ShadowSettings::ConservativeRaster::GeometryShader;
    plain.shadows.raster = ShadowSettings::Raster::Plain;
    const std::vector<float> hw = shadowAtlas(s, hardware), gs = shadowAtlas(s, geometry), pl = shadowAtlas(s, plain);
    ASSERT_EQ(hw.size(), gs.size());
    ASSERT_EQ(hw.size(), pl.size());
    size_t plainOnly = 0, hardwareOnly = 0, nearerThanGs = 0, fartherThanPlain = 0, equalToGs = 0, covered = 0;
    float worstGs = 0.0f, worstPlain = 0.0f;
    for (size_t i = 0; i < hw.size(); ++i) {
        ASSERT_TRUE(std::isfinite(hw[i])) << i;
        const bool h = hw[i] < 1.0f, g = gs[i] < 1.0f, p = pl[i] < 1.0f;
        plainOnly += p && !h ? 1 : 0;
        hardwareOnly += h && !g ? 1 : 0;
        if (!h) continue;
        ++covered;
        if (g) {
            if (hw[i] < gs[i] - 1e-4f && ++nearerThanGs <= 8)  // the texels that break the order, to tell why
                std::printf("atlas texel %zu: hardware %.6f, geometry shader %.6f, plain %.6f\n", i, double(hw[i]),
                            double(gs[i]), double(pl[i]));
            worstGs = std::max(worstGs, gs[i] - hw[i]);
            equalToGs += std::abs(hw[i] - gs[i]) <= 1e-5f ? 1 : 0;
        }
        if (p) {
            fartherThanPlain += hw[i] > pl[i] + 1e-5f ? 1 : 0;
            worstPlain = std::max(worstPlain, hw[i] - pl[i]);
        }
    }
    std::printf("hardware conservative raster: %zu texels hold a caster, %zu equal to the geometry shader's (1e-5); "
                "worst nearer than it %g, worst farther than plain %g; touches the geometry shader misses: %zu "
                "texels only the hardware covers, %zu nearer than the geometry shader's\n",
                covered, equalToGs, double(worstGs), double(worstPlain), hardwareOnly, nearerThanGs);
    EXPECT_GT(covered, hw.size() / 2);
    EXPECT_EQ(plainOnly, 0u);
    EXPECT_LE(hardwareOnly + nearerThanGs, covered / 1000);
    EXPECT_EQ(fartherThanPlain, 0u);
}

namespace {
bool markedFrontAtCentre(float depth) {  // shaders/common/shadow_caster_depth.glsl's shadowDepthFrontAtCentre
    uint32_t bits;
    std::memcpy(&bits, &depth, sizeof bits);
    return (bits & 1u) == 0u;
}
}  // namespace

// The conservative raster's marks (shaders/common/shadow_caster_depth.glsl), against the plain raster
// at slope bias 0 on rowOfSpheres (a floor of 32 triangles, spheres of 16 x 8 segments): a texel no caster
// covers at its centre (plain holds none there) is marked "no face towards the light at the centre";
// a texel where both hold the same depth (1e-5: the same surface at the centre, which faces the
// light: faces away write a nearer depth, or lie behind) is marked "face towards the light", also
// where two triangles of one surface meet (their edges: a face grown past its edge yields to the
// face that covers the centre). Texel-centre ties on an edge may fall either way: 0.1% allowed.
TEST(ShadowConservativeRaster, MarksTellWhetherAFaceTowardsTheLightCoversTheCentre) {
    const Scene s = rowOfSpheres();
    RenderSettings conservative = twoUnbiasedCascades(), plain = twoUnbiasedCascades();
    conservative.shadows.raster = ShadowSettings::Raster::Conservative;
    plain.shadows.raster = ShadowSettings::Raster::Plain;
    const std::vector<float> c = shadowAtlas(s, conservative), p = shadowAtlas(s, plain);
    ASSERT_EQ(c.size(), p.size());
    size_t grown = 0, grownMarkedFront = 0, same = 0, sameMarkedNotFront = 0;
    for (size_t i = 0; i < c.size(); ++i) {
        if (c[i] >= 1.0f) continue;
        if (p[i] >= 1.0f) {
            ++grown;
            grownMarkedFront += markedFrontAtCentre(c[i]) ? 1 : 0;
        } else if (std::abs(c[i] - p[i]) <= 1e-5f) {
            ++same;
            sameMarkedNotFront += markedFrontAtCentre(c[i]) ? 0 : 1;
        }
    }
    std::printf("conservative raster marks: %zu texels grown past every caster (%zu marked front), %zu holding plain's "
                "depth (%zu marked not front)\n",
                grown, grownMarkedFront, same, sameMarkedNotFront);
    EXPECT_GE(grown, 150u);  // the H100's hardware conservative raster grows 200 texels here
    EXPECT_GT(same, c.size() / 2);
    EXPECT_LE(grownMarkedFront, grown / 1000);
    EXPECT_LE(sameMarkedNotFront, same / 1000);
}
