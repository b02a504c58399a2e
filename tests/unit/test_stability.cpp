// Stability suite, CPU side: degenerate meshes (zero-area, collinear, non-finite and only-degenerate
// faces) through the OBJ loader and the mesh operations, and the SH projection of a synthetic map
// with a 1e5 sun against the brute-force double integral. The GPU side is tests/gl/test_stability.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include <unistd.h>

#include "engine/core/error.hpp"
#include "engine/io/obj_loader.hpp"
#include "engine/render/ibl_sh.hpp"
#include "engine/scene/mesh_ops.hpp"

using namespace lp;

namespace {
constexpr double kPi = 3.14159265358979323846;

std::filesystem::path writeTempObj(const std::string& name, const std::string& text) {
    const auto path = std::filesystem::temp_directory_path() / ("lp_stability_" + std::to_string(getpid()) + "_" + name);
    std::ofstream(path) << text;
    return path;
}

bool unitAndFinite(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::abs(glm::length(v) - 1.0f) < 1e-5f;
}
}  // namespace

// Two good triangles among a repeated-index face, a zero-area face of distinct vertices, a collinear
// face, a face 1e-13 wide on a 2 m mesh and a face with an overflowing (Inf) coordinate. Bound: exactly
// the two good faces survive (4 degenerate, 1 non-finite counted), and every normal and tangent is a
// finite unit vector.
TEST(StabilityMesh, ObjDropsZeroAreaCollinearAndNonFiniteFaces) {
    const auto path = writeTempObj("mixed.obj",
                                   "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"  // 1..4: a unit quad
                                   "v 0.5 0.5 0\nv 2 0 0\n"                  // 5, 6: collinear with 1, 2
                                   "v 0 0 1e-13\nv 0 1e39 0\n"               // 7: a hair off 1; 8: Inf
                                   "f 1 2 3\nf 2 4 3\n"                      // good
                                   "f 1 1 2\n"                               // repeated index
                                   "f 1 4 5\n"                               // zero area (5 on the diagonal)
                                   "f 1 2 6\n"                               // collinear
                                   "f 1 7 2\n"                               // 1e-13 wide: below 1e-12 of scale^2
                                   "f 1 2 8\n");                             // non-finite
    MeshLoadReport report;
    MeshData mesh = loadObj(path, &report);
    std::filesystem::remove(path);
    EXPECT_EQ(mesh.indices.size(), 6u) << "only the two good triangles are kept";
    EXPECT_EQ(report.droppedDegenerate, 4u);
    EXPECT_EQ(report.droppedNonFinite, 1u);
    ASSERT_FALSE(report.warnings.empty());
    EXPECT_NE(report.warnings.back().find("dropped 4 degenerate and 1 non-finite"), std::string::npos)
        << report.warnings.back();
    for (const auto& v : mesh.vertices) {
        EXPECT_TRUE(unitAndFinite(v.normal));
        EXPECT_TRUE(unitAndFinite(glm::vec3(v.tangent)));
        EXPECT_NEAR(v.normal.z, 1.0f, 1e-6f) << "the quad faces +Z";
    }
}

// A model made only of degenerate faces is a one-line error naming the file, not an empty draw.
TEST(StabilityMesh, ObjOfOnlyDegenerateFacesIsAClearError) {
    const auto path = writeTempObj("degenerate.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 0 0\nf 1 2 3\nf 1 4 2\nf 2 2 2\n");
    try {
        loadObj(path);
        ADD_FAILURE() << "expected an error";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(path.string()), std::string::npos) << what;
        EXPECT_NE(what.find("no triangles"), std::string::npos) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << "one line";
    }
    std::filesystem::remove(path);
}

// Meshes made in code bypass the loader's filter: computeNormals / computeTangents on zero-area,
// collinear and NaN-positioned triangles, and on UVs that are all equal. Bound: every normal and
// tangent is a finite unit vector; a vertex with no area around it gets +Y; the good triangle's
// vertices get its true normal (exact to 1e-6); the bounds are those of the finite positions.
TEST(StabilityMesh, NormalsAndTangentsOfDegenerateTrianglesAreFiniteUnitVectors) {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    MeshData mesh;
    const glm::vec3 positions[] = {{0, 0, 0}, {1, 0, 0}, {0, 0, -1},            // good, normal +Y
                                   {5, 5, 5}, {5, 5, 5}, {5, 5, 5},             // a point
                                   {0, 2, 0}, {1, 2, 0}, {3, 2, 0},             // collinear
                                   {nan, 0, 0}, {0, nan, 1}, {1, 1, 1},         // NaN
                                   {inf, 0, 0}, {0, -inf, 0}, {0, 0, 1e38f}};   // Inf / overflow
    for (const auto& p : positions) {
        Vertex v;
        v.position = p;
        v.uv = glm::vec2(0.25f);  // equal UVs: no tangent from the UV mapping anywhere
        mesh.vertices.push_back(v);
    }
    for (uint32_t i = 0; i < mesh.vertices.size(); ++i) mesh.indices.push_back(i);
    computeNormals(mesh);
    computeTangents(mesh);
    computeBounds(mesh);
    for (size_t i = 0; i < mesh.vertices.size(); ++i) {
        const Vertex& v = mesh.vertices[i];
        EXPECT_TRUE(unitAndFinite(v.normal)) << "vertex " << i;
        EXPECT_TRUE(unitAndFinite(glm::vec3(v.tangent))) << "vertex " << i;
        EXPECT_NEAR(glm::dot(v.normal, glm::vec3(v.tangent)), 0.0f, 1e-5f) << "vertex " << i;
        EXPECT_TRUE(v.tangent.w == 1.0f || v.tangent.w == -1.0f);
        if (i < 3) EXPECT_NEAR(v.normal.y, 1.0f, 1e-6f) << "good triangle";
        if (i >= 3 && i < 9) EXPECT_EQ(v.normal, glm::vec3(0, 1, 0)) << "no area: +Y";
    }
    // Bounds skip non-finite positions (an Inf vertex would stretch the shadow cascades over an
    // infinite scene).
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(std::isfinite(mesh.boundsMin[c]) && std::isfinite(mesh.boundsMax[c]));
    EXPECT_EQ(mesh.boundsMax, glm::vec3(5.0f, 5.0f, 1e38f));
    EXPECT_EQ(mesh.boundsMin, glm::vec3(0.0f, 0.0f, -1.0f));
}

// anyPerpendicular at the poles, ±0, denormals and the z = 0 seam (its branch point is z = -1 with
// sign flips at z = ±0). Bound: |t| = 1 and |t.n| <= 1e-6 for every input.
TEST(StabilityMesh, AnyPerpendicularIsOrthonormalAtPolesSeamAndSignedZeros) {
    std::vector<glm::vec3> cases = {{0, 0, 1}, {0, 0, -1}, {-0.0f, -0.0f, 1}, {-0.0f, 0.0f, -1}, {1, 0, 0},
                                    {1, 0, -0.0f}, {0, 1, 0}, {0, -1, -0.0f}, {1e-40f, 1, 0}, {1, 1e-40f, -1e-40f},
                                    {1e-38f, 1e-38f, -1}, {1e-20f, 0, -1}};
    for (int i = 0; i < 720; ++i) {
        const double a = 2.0 * kPi * i / 720.0;
        for (float z : {0.0f, -0.0f, 1e-7f, -1e-7f, -0.999999f})
            cases.push_back(glm::vec3(float(std::cos(a) * std::sqrt(1.0 - double(z) * z)),
                                      float(std::sin(a) * std::sqrt(1.0 - double(z) * z)), z));
    }
    for (const auto& n : cases) {
        const glm::vec3 t = anyPerpendicular(n);
        ASSERT_TRUE(std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z)) << n.x << " " << n.y << " " << n.z;
        EXPECT_NEAR(glm::length(glm::dvec3(t)), 1.0, 1e-6) << n.x << " " << n.y << " " << n.z;
        EXPECT_NEAR(glm::dot(glm::dvec3(t), glm::dvec3(n)), 0.0, 1e-6) << n.x << " " << n.y << " " << n.z;
    }
}

// A 64 x 32 map of radiance 0.2 with one 1e5 texel (a sun brighter than quarry_01's 86,528), so the
// case runs without the shared assets. SH irradiance against the brute-force double integral at 64
// normals. Bound (addition theorem, as in IblSh): |E_sh - E| <= 0.0938 * 1.0001 * sum(L dOmega) per
// channel, with the sum dominated by the sun; and the coefficients are finite.
TEST(StabilityIbl, ShOfA1e5SunIsWithinTheKernelBound) {
    ImageF map;
    map.width = 64;
    map.height = 32;
    map.rgba.assign(size_t(64 * 32 * 4), 0.2f);
    for (size_t i = 3; i < map.rgba.size(); i += 4) map.rgba[i] = 1.0f;
    const size_t sunTexel = size_t(9) * 64 + 40;  // 9 rows from the top: elevation ~39 degrees
    for (int c = 0; c < 3; ++c) map.rgba[sunTexel * 4 + c] = 1e5f;
    const ShCoefficients sh = projectEquirectSh(map, 0.0);
    for (const auto& c : sh) ASSERT_TRUE(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z));
    double total = 0.0;
    for (int y = 0; y < map.height; ++y) {
        const double dOmega = (2.0 * kPi / map.width) * (kPi / map.height) * std::sin((y + 0.5) / map.height * kPi);
        for (int x = 0; x < map.width; ++x) total += map.rgba[(size_t(y) * 64 + size_t(x)) * 4] * dOmega;
    }
    const double bound = 0.0938 * 1.0001 * total;
    const double golden = kPi * (3.0 - std::sqrt(5.0));
    double worst = 0.0;
    for (int i = 0; i < 64; ++i) {
        const double z = 1.0 - 2.0 * (i + 0.5) / 64.0, r = std::sqrt(1.0 - z * z);
        const glm::dvec3 n(r * std::cos(golden * i), z, r * std::sin(golden * i));
        const glm::dvec3 esh = shIrradiance(sh, n), ref = bruteForceIrradiance(map, 0.0, n);
        ASSERT_TRUE(std::isfinite(esh.x));
        EXPECT_GE(esh.x, 0.0) << "clamped at 0";
        worst = std::max(worst, std::abs(esh.x - ref.x));
        EXPECT_LE(std::abs(esh.x - ref.x), bound) << "normal " << i << ": SH " << esh.x << " vs " << ref.x;
    }
    std::printf("  1e5 sun: worst |E_sh - E| = %.4g of bound %.4g\n", worst, bound);
}
