// The path tracer's CPU side: the scene it traces (engine/render/path_trace_scene.hpp) and its noise
// estimate (passes/path_trace_pass.hpp).
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/scene/primitives.hpp"
#include "engine/render/path_trace_scene.hpp"
#include "passes/path_trace_environment.hpp"
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

// KHR_materials_clearcoat reaches the tracer's material records: factor and roughness where a material
// has a coat, zeros for a coat of 0 and for a flat-lit material (which takes none).
TEST(PathTraceScene, MaterialsCarryTheirClearcoat) {
    Scene scene;
    for (const float clearcoat : {1.0f, 0.0f, 0.3f, 1.0f}) {
        ModelInstance plane;
        plane.mesh = makePlane(1.0f);
        plane.mesh.materials[0].clearcoat = clearcoat;
        plane.mesh.materials[0].clearcoatRoughness = 0.25f;
        plane.mesh.materials[0].flat = scene.models.size() == 3;
        scene.models.push_back(plane);
    }
    const PathTraceScene traced = buildPathTraceScene(scene);
    ASSERT_EQ(traced.materials.size(), 4u);
    EXPECT_EQ(traced.materials[0].clearcoat, glm::vec4(1.0f, 0.25f, 0.0f, 0.0f));
    EXPECT_EQ(traced.materials[1].clearcoat, glm::vec4(0.0f));
    EXPECT_EQ(traced.materials[2].clearcoat, glm::vec4(0.3f, 0.25f, 0.0f, 0.0f));
    EXPECT_EQ(traced.materials[3].clearcoat, glm::vec4(0.0f)) << "flat-lit: no coat";
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
    // Variances of the means 1, 0 and 0 over three pixels: RMS standard error sqrt(1 / 3).
    EXPECT_NEAR(noise.rmsStandardError, std::sqrt(1.0 / 3.0), 1e-6);
}


// A black map with one bright texel and a dim grey elsewhere (width x height).
ImageF lampMap(int width, int height, int lampX, int lampY, float lamp, float rest) {
    ImageF map;
    map.width = width;
    map.height = height;
    map.rgba.assign(size_t(width) * size_t(height) * 4, rest);
    for (size_t i = 3; i < map.rgba.size(); i += 4) map.rgba[i] = 1.0f;
    float* t = &map.rgba[(size_t(lampY) * size_t(width) + size_t(lampX)) * 4];
    t[0] = t[1] = t[2] = lamp;
    return map;
}

TEST(EnvironmentSampling, DensityIntegratesToOneOverTheSphere) {
    const EnvironmentDistribution d = buildEnvironmentDistribution(lampMap(64, 32, 40, 9, 5000.0f, 0.2f));
    ASSERT_FALSE(d.empty());
    // Midpoint rule in (u, v) at 8x the cells' resolution: dω = 2π² sin θ du dv.
    const int nu = 512, nv = 256;
    double integral = 0.0;
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            const glm::vec2 uv((float(i) + 0.5f) / float(nu), (float(j) + 0.5f) / float(nv));
            const double sinTheta = std::sin(double(uv.y) * M_PI);
            integral += double(environmentPdf(d, equirectDirectionOf(uv))) * 2.0 * M_PI * M_PI * sinTheta / (double(nu) * double(nv));
        }
    EXPECT_NEAR(integral, 1.0, 2e-3);
}

TEST(EnvironmentSampling, SamplesFollowTheLampAndTheirDensityIsTheLookupsDensity) {
    const int w = 64, h = 32, lx = 40, ly = 9;
    const float lamp = 5000.0f, rest = 0.2f;
    const EnvironmentDistribution d = buildEnvironmentDistribution(lampMap(w, h, lx, ly, lamp, rest));
    // A cell's weight is the mean luminance over the 3x3 texels of its bilinear support times sin θ:
    // the nine cells around the lamp hold (lamp + 8 rest) / 9 each. Their share of the weight:
    double lampWeight = 0.0, total = 0.0;
    for (int y = 0; y < h; ++y) {
        const double s = std::sin((y + 0.5) / h * M_PI);
        for (int x = 0; x < w; ++x) {
            const bool near = std::abs(x - lx) <= 1 && std::abs(y - ly) <= 1;
            const double wgt = (near ? (lamp + 8.0 * rest) / 9.0 : rest) * s;
            total += wgt;
            if (near) lampWeight += wgt;
        }
    }
    int inLamp = 0;
    const int n = 64 * 64;
    for (int j = 0; j < 64; ++j)
        for (int i = 0; i < 64; ++i) {
            const EnvironmentSample s = sampleEnvironment(d, glm::vec2((i + 0.5f) / 64.0f, (j + 0.5f) / 64.0f));
            ASSERT_GT(s.pdf, 0.0f);
            EXPECT_NEAR(glm::length(s.direction), 1.0f, 1e-5f);
            EXPECT_NEAR(s.pdf, environmentPdf(d, s.direction), 1e-3f * s.pdf) << "sample " << i << "," << j;
            const glm::vec2 uv = equirectUvOf(s.direction);
            if (std::abs(int(uv.x * w) - lx) <= 1 && std::abs(int(uv.y * h) - ly) <= 1) ++inLamp;
        }
    // Stratified numbers: the share of samples near the lamp within a stratum's worth of its weight.
    EXPECT_NEAR(double(inLamp) / n, lampWeight / total, 2.0 / 64.0);
}

TEST(EnvironmentSampling, ABlackMapHasNoTablesAndLargeMapsAreAveragedIntoCells) {
    EXPECT_TRUE(buildEnvironmentDistribution(lampMap(16, 8, 3, 3, 0.0f, 0.0f)).empty());
    const EnvironmentDistribution big = buildEnvironmentDistribution(lampMap(2048, 1024, 1500, 300, 1e4f, 0.1f), 512);
    EXPECT_EQ(big.width, 512);
    EXPECT_EQ(big.height, 256);
    // The lamp's cell (texel / 4) is far denser than a cell of the dim rest, and so are the cells
    // whose bilinear support holds the lamp's texel (it is the first texel of its cell in x and y).
    auto pdfAt = [&](int x, int y) { return big.cellPdf[size_t(y) * 512 + size_t(x)]; };
    const float dim = pdfAt(100, 128);
    EXPECT_GT(pdfAt(1500 / 4, 300 / 4), 100.0f * dim);
    EXPECT_GT(pdfAt(1500 / 4 - 1, 300 / 4 - 1), 100.0f * dim);
    EXPECT_LT(pdfAt(1500 / 4 + 1, 300 / 4 + 1), 2.0f * dim);
}

TEST(EnvironmentSampling, EquirectMappingRoundTrips) {
    for (glm::vec2 uv : {glm::vec2(0.1f, 0.2f), glm::vec2(0.75f, 0.5f), glm::vec2(0.5f, 0.9f)}) {
        const glm::vec2 back = equirectUvOf(equirectDirectionOf(uv));
        EXPECT_NEAR(back.x, uv.x, 1e-5f);
        EXPECT_NEAR(back.y, uv.y, 1e-5f);
    }
    // v = 0 is +Y (the map's top row), u = 0.5 looks along -Z.
    EXPECT_NEAR(equirectDirectionOf(glm::vec2(0.3f, 0.0f)).y, 1.0f, 1e-6f);
    EXPECT_NEAR(equirectDirectionOf(glm::vec2(0.5f, 0.5f)).z, -1.0f, 1e-6f);
}

}  // namespace
}  // namespace lp
