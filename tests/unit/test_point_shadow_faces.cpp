// The point-shadow cube's geometry (passes/point_shadow_pass): every direction from the light falls
// in exactly the face pointShadowFace names, inside its tile at least kPointShadowFaceMargin texels
// from the edge, and that face's clip w (what the shaders compare to pick it) is the largest; the
// casters a cube draws are those whose bounds reach its range sphere, each face those of them that
// may reach its view.
#include <gtest/gtest.h>

#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/render/shadow_casters.hpp"
#include "passes/point_shadow_pass.hpp"

using namespace lp;

TEST(PointShadowFaces, EveryDirectionLandsInsideItsFaceWithTheMargin) {
    const glm::vec3 light(0.5f, 2.0f, -1.0f);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    for (int tileSize : {64, 128, 1024}) {
        const float faceTan = pointShadowFaceTan(tileSize);
        const auto faces = pointShadowFaceMatrices(light, 0.01f, 10.0f, faceTan);
        const float limit = 1.0f - 2.0f * float(kPointShadowFaceMargin) / float(tileSize) + 1e-5f;
        for (int i = 0; i < 2000; ++i) {
            glm::vec3 d(unit(rng), unit(rng), unit(rng));
            if (i < 8) d = glm::vec3(i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 1.0f : -1.0f);  // the cube's corners
            if (glm::length(d) < 1e-3f) continue;
            const glm::vec3 p = light + 3.0f * glm::normalize(d);
            const int face = pointShadowFace(d);
            int largest = 0;
            for (int f = 1; f < kPointShadowFaces; ++f)
                if ((faces[size_t(f)] * glm::vec4(p, 1.0f)).w > (faces[size_t(largest)] * glm::vec4(p, 1.0f)).w) largest = f;
            const glm::vec4 q = faces[size_t(face)] * glm::vec4(p, 1.0f);
            EXPECT_NEAR(q.w, (faces[size_t(largest)] * glm::vec4(p, 1.0f)).w, 1e-5f) << "face " << face << " vs " << largest;
            ASSERT_GT(q.w, 0.0f);
            EXPECT_LE(std::abs(q.x / q.w), limit) << "tile " << tileSize << " direction " << d.x << " " << d.y << " " << d.z;
            EXPECT_LE(std::abs(q.y / q.w), limit) << "tile " << tileSize << " direction " << d.x << " " << d.y << " " << d.z;
            EXPECT_NEAR(q.w, std::abs(glm::normalize(d)[face / 2]) * 3.0f, 1e-4f);  // clip w: distance along the axis
        }
    }
}

TEST(PointShadowFaces, TileSizeFollowsTheShadowSizeWithinTheAtlas) {
    EXPECT_EQ(pointShadowTileSize(2048, 1), 1024);  // the spots' half of --shadow-size
    EXPECT_EQ(pointShadowTileSize(4096, 1), kPointShadowAtlasMaxSide / kPointShadowFaces);
    EXPECT_EQ(pointShadowTileSize(4096, kMaxPointShadows), kPointShadowAtlasMaxSide / kMaxPointShadows);
    EXPECT_EQ(pointShadowTileSize(16, 1), 64);
}

TEST(PointShadowFaces, CastersAreTheClustersReachingTheRange) {
    const glm::mat4 moved = glm::translate(glm::mat4(1.0f), glm::vec3(3.0f, 0.0f, 0.0f));
    // A unit box at x in [2.5, 3.5]: 2.5 m from a light at the origin.
    EXPECT_TRUE(casterBoxReachesSphere(moved, glm::vec3(-0.5f), glm::vec3(0.5f), glm::vec3(0.0f), 2.6f));
    EXPECT_FALSE(casterBoxReachesSphere(moved, glm::vec3(-0.5f), glm::vec3(0.5f), glm::vec3(0.0f), 2.4f));
    // The corner (2.5, 0.5, 0.5) is sqrt(6.75) away from a light beside the box's edge.
    const float corner = std::sqrt(2.5f * 2.5f + 0.5f);
    EXPECT_TRUE(casterBoxReachesSphere(moved, glm::vec3(-0.5f), glm::vec3(0.5f), glm::vec3(0.0f, 1.0f, 1.0f), corner + 1e-3f));
    EXPECT_FALSE(casterBoxReachesSphere(moved, glm::vec3(-0.5f), glm::vec3(0.5f), glm::vec3(0.0f, 1.0f, 1.0f), corner - 1e-3f));
}

// A cube face draws only the clusters that may reach its view: a box wholly beyond one side plane
// is dropped, one inside, straddling a side or reaching behind the light is kept.
TEST(PointShadowFaces, FaceDrawsOnlyCastersThatMayReachItsView) {
    const glm::vec3 light(0.0f);
    const auto faces = pointShadowFaceMatrices(light, 0.01f, 10.0f, pointShadowFaceTan(256));
    const glm::mat4& plusX = faces[0];
    auto box = [&](glm::vec3 centre, float half) {
        return casterBoxInPerspectiveView(plusX * glm::translate(glm::mat4(1.0f), centre), glm::vec3(-half), glm::vec3(half));
    };
    EXPECT_TRUE(box({2.0f, 0.0f, 0.0f}, 0.2f));    // on the +X axis
    EXPECT_FALSE(box({1.0f, 3.0f, 0.0f}, 0.2f));   // above the face's top plane: the +Y face's
    EXPECT_FALSE(box({1.0f, 0.0f, -3.0f}, 0.2f));  // beyond a side plane: the -Z face's
    EXPECT_TRUE(box({-2.0f, 0.0f, 0.0f}, 0.2f));   // behind the light (w < 0): kept, the test is conservative there
    EXPECT_TRUE(box({2.0f, 2.1f, 0.0f}, 0.2f));    // straddling the 45-degree edge
    EXPECT_TRUE(box({0.0f, 0.0f, 0.0f}, 0.5f));    // around the light
}
