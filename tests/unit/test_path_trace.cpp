// The path tracer's CPU side: the scene it traces (engine/render/path_trace_scene.hpp) and its noise
// estimate (passes/path_trace_pass.hpp).
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/scene/primitives.hpp"
#include "engine/render/path_trace_scene.hpp"
#include "passes/path_trace_pass.hpp"

namespace lp {
namespace {

TEST(PathTraceScene, TrianglesAreInWorldSpaceInLeafOrderWithTheirMaterials) {
    Scene scene;
    ModelInstance plane;
    plane.mesh = makePlane(1.0f);
    plane.mesh.materials[0].diffuse = glm::vec3(0.2f, 0.4f, 0.6f);
    plane.mesh.materials[0].metallic = 0.5f;
    plane.mesh.materials[0].shininess = 1e9f;  // clamped to the roughness floor's exponent, as material.glsl
    plane.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 2.0f, 0.0f)) *
                      glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(1.0f, 0.0f, 0.0f));
    scene.models.push_back(plane);
    ModelInstance cube;
    cube.mesh = makeCube(1.0f);
    cube.mesh.materials[0].flat = true;
    scene.models.push_back(cube);
    const PathTraceScene traced = buildPathTraceScene(scene);
    const size_t triangles = plane.mesh.indices.size() / 3 + cube.mesh.indices.size() / 3;
    ASSERT_EQ(traced.triangles.size(), triangles);
    ASSERT_EQ(traced.materials.size(), 2u);
    EXPECT_FLOAT_EQ(traced.materials[0].specularMetallic.w, 0.5f);
    EXPECT_FLOAT_EQ(traced.materials[0].emissionShininess.w, shininessFromRoughness(kMinRoughness));
    EXPECT_EQ(traced.materials[1].flags.x, 1.0f);
    int planeTriangles = 0;
    for (size_t i = 0; i < traced.triangles.size(); ++i) {
        const PathTraceTriangle& t = traced.triangles[i];
        // Leaf order: triangle i is the input triangle triangleOrder[i].
        const bool fromPlane = traced.bvh.triangleOrder[i] < plane.mesh.indices.size() / 3;
        EXPECT_EQ(int(t.position[0].w), fromPlane ? 0 : 1);
        if (!fromPlane) continue;
        ++planeTriangles;
        for (int k = 0; k < 3; ++k) {
            // The XZ plane turned about +X by 90 degrees and lifted 2 m: z = 0, normal +Z.
            EXPECT_NEAR(t.position[k].z, 0.0f, 1e-6f);
            EXPECT_NEAR(t.normal[k].z, 1.0f, 1e-6f);
            EXPECT_GE(t.position[k].y, 1.5f - 1e-6f);
            EXPECT_LE(t.position[k].y, 2.5f + 1e-6f);
        }
    }
    EXPECT_EQ(planeTriangles, int(plane.mesh.indices.size() / 3));
}

TEST(PathTraceNoise, IsTheRelativeStandardErrorOfEachPixelsMeanAveraged) {
    // Pixel 0: samples of luminance 1 and 3 (grey): mean 2, sample variance 2, variance of the mean 1:
    // relative standard error 1 / 2. Pixel 1: every sample 4: none. Pixel 2: black: not counted.
    const int n = 2;
    std::vector<float> sums = {4.0f, 4.0f, 4.0f, 1.0f + 9.0f, 8.0f, 8.0f, 8.0f, 32.0f, 0.0f, 0.0f, 0.0f, 0.0f};
    const PathTraceNoise noise = pathTraceNoise(sums, n);
    EXPECT_EQ(noise.pixels, 2u);
    EXPECT_NEAR(noise.meanRelativeStandardError, (0.5 + 0.0) / 2.0, 1e-6);
    EXPECT_NEAR(noise.meanLuminance, (2.0 + 4.0 + 0.0) / 3.0, 1e-6);
}

}  // namespace
}  // namespace lp
