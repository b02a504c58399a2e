// MikkTSpace-compatible tangent generation (engine/scene/mesh_ops.cpp computeTangents): the frame
// of a plain and a mirrored UV mapping, vertex splitting where the handedness changes, the corner-angle
// weighting, welding of identical vertices, independence of triangle and corner order, and the
// analytic dp/du of a UV sphere.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <tuple>

#include "engine/scene/mesh_ops.hpp"
#include "engine/scene/primitives.hpp"

using namespace lp;

namespace {

Vertex vertex(glm::vec3 p, glm::vec2 uv, glm::vec3 n = {0, 0, 1}) {
    Vertex v;
    v.position = p;
    v.uv = uv;
    v.normal = n;
    v.tangent = glm::vec4(0.0f);
    return v;
}

// The bitangent cross(N, T) w of every corner of triangle t.
glm::vec3 bitangent(const Vertex& v) { return glm::cross(v.normal, glm::vec3(v.tangent)) * v.tangent.w; }

}  // namespace

// A quad in z = 0 facing +Z with u along +X and v along +Y: T = +X, w = +1. With u mirrored
// (u = 1 - x) T = -X and w = -1; in both the bitangent points along +v (+Y).
TEST(MikkTangents, PlaneFrameAndMirroredUvHandedness) {
    for (bool mirrored : {false, true}) {
        MeshData m;
        for (glm::vec3 p : {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(1, 1, 0), glm::vec3(0, 1, 0)})
            m.vertices.push_back(vertex(p, glm::vec2(mirrored ? 1.0f - p.x : p.x, p.y)));
        m.indices = {0, 1, 2, 0, 2, 3};
        computeTangents(m);
        ASSERT_EQ(m.vertices.size(), 4u) << "one frame per vertex: nothing to split";
        for (const Vertex& v : m.vertices) {
            EXPECT_NEAR(v.tangent.x, mirrored ? -1.0f : 1.0f, 1e-6f);
            EXPECT_EQ(v.tangent.w, mirrored ? -1.0f : 1.0f);
            EXPECT_NEAR(bitangent(v).y, 1.0f, 1e-6f);
        }
    }
}

// Two quads sharing their middle edge's vertices (same index, same uv u = 1), the right one's u
// mirrored (u = 2 - x): the shared vertices get one copy per handedness (6 -> 8 vertices), and
// every corner carries its own triangle's frame.
TEST(MikkTangents, SplitsVerticesWhereTheUvMappingMirrors) {
    MeshData m;
    for (float x : {0.0f, 1.0f, 2.0f})
        for (float y : {0.0f, 1.0f}) m.vertices.push_back(vertex({x, y, 0}, {x <= 1.0f ? x : 2.0f - x, y}));
    // vertex (x, y) is number 2 x + y
    m.indices = {0, 2, 3, 0, 3, 1, 2, 4, 5, 2, 5, 3};
    computeTangents(m);
    EXPECT_EQ(m.vertices.size(), 8u);
    for (size_t c = 0; c < m.indices.size(); ++c) {
        const bool right = c >= 6;
        const Vertex& v = m.vertices[m.indices[c]];
        EXPECT_NEAR(v.tangent.x, right ? -1.0f : 1.0f, 1e-6f) << "corner " << c;
        EXPECT_EQ(v.tangent.w, right ? -1.0f : 1.0f) << "corner " << c;
        EXPECT_NEAR(bitangent(v).y, 1.0f, 1e-6f) << "corner " << c;
    }
}

// A vertex O where two coplanar triangles meet with different UV gradients: A (corner angle 90
// degrees, T = +X) and B (corner angle 135 degrees, T = (1, 1, 0)/sqrt 2). MikkTSpace weights by the
// corner angle: T(O) = normalise(pi/2 (1, 0, 0) + 3pi/4 (1, 1, 0)/sqrt 2). (Lengyel's sum of
// unnormalised per-triangle tangents gives a direction 0.6 degrees away.) The same mesh unwelded
// (each triangle its own three vertices) gives the same tangents: identical vertices are one.
TEST(MikkTangents, CornerAngleWeightingAndWelding) {
    const float pi = 3.14159265358979f;
    const glm::vec3 expected = glm::normalize(pi / 2 * glm::vec3(1, 0, 0) + 3 * pi / 4 * glm::vec3(1, 1, 0) / std::sqrt(2.0f));
    const Vertex o = vertex({0, 0, 0}, {0, 0}), p1 = vertex({1, 0, 0}, {1, 0}), p2 = vertex({0, 1, 0}, {0, 1}),
                 p3 = vertex({-1, -1, 0}, {-1, 0});
    MeshData indexed, unwelded;
    indexed.vertices = {o, p1, p2, p3};
    indexed.indices = {0, 1, 2, 0, 2, 3};
    unwelded.vertices = {o, p1, p2, o, p2, p3};
    unwelded.indices = {0, 1, 2, 3, 4, 5};
    for (MeshData* m : {&indexed, &unwelded}) {
        computeTangents(*m);
        for (size_t c : {size_t(0), size_t(3)}) {
            const glm::vec4 t = m->vertices[m->indices[c]].tangent;
            EXPECT_NEAR(t.x, expected.x, 1e-5f);
            EXPECT_NEAR(t.y, expected.y, 1e-5f);
            EXPECT_NEAR(t.z, 0.0f, 1e-6f);
            EXPECT_EQ(t.w, 1.0f);
        }
    }
    EXPECT_EQ(indexed.vertices.size(), 4u);
}

// MikkTSpace's result depends on the mesh, not on how it is listed: the UV sphere with its
// triangles reversed in order and each triangle's corners rotated gives every corner (identified
// by position and uv) the same tangent within float rounding (1e-5).
TEST(MikkTangents, IndependentOfTriangleAndCornerOrder) {
    MeshData a = makeSphere(1.0f, 24, 12);
    MeshData b = a;
    b.indices.clear();
    for (size_t t = a.indices.size() / 3; t-- > 0;)
        b.indices.insert(b.indices.end(), {a.indices[t * 3 + 1], a.indices[t * 3 + 2], a.indices[t * 3]});
    computeTangents(a);
    computeTangents(b);
    std::map<std::tuple<float, float, float, float, float>, glm::vec4> byCorner;
    for (uint32_t i : a.indices) {
        const Vertex& v = a.vertices[i];
        byCorner[{v.position.x, v.position.y, v.position.z, v.uv.x, v.uv.y}] = v.tangent;
    }
    for (uint32_t i : b.indices) {
        const Vertex& v = b.vertices[i];
        const auto it = byCorner.find({v.position.x, v.position.y, v.position.z, v.uv.x, v.uv.y});
        ASSERT_NE(it, byCorner.end());
        for (int k = 0; k < 4; ++k) EXPECT_NEAR(v.tangent[k], it->second[k], 1e-5f);
    }
}

// On a UV sphere (u = azimuth / 2pi, v up) the generated tangent follows dp/du, the analytic
// (-sin phi, 0, -cos phi) the generator stores, within 3 degrees (2.3 measured at 48 segments) within 45 degrees of the equator (a flat facet's u-gradient, angle weighted, tilts it towards the poles), w = +1
// everywhere, unit length and perpendicular to the normal; both sides of the UV seam (u = 0 and
// u = 1, separate vertices at one position) get the same tangent within 1e-4.
TEST(MikkTangents, UvSphereFollowsDpDuAndAgreesAcrossItsSeam) {
    MeshData m = makeSphere(1.0f, 48, 24);
    std::vector<glm::vec4> analytic;
    for (const Vertex& v : m.vertices) analytic.push_back(v.tangent);
    const size_t before = m.vertices.size();
    computeTangents(m);
    std::map<std::tuple<float, float, float>, std::vector<glm::vec4>> atPosition;
    for (uint32_t i : m.indices) {
        const Vertex& v = m.vertices[i];
        EXPECT_NEAR(glm::length(glm::vec3(v.tangent)), 1.0f, 1e-5f);
        EXPECT_NEAR(glm::dot(glm::vec3(v.tangent), v.normal), 0.0f, 1e-5f);
        EXPECT_EQ(v.tangent.w, 1.0f);
        if (std::abs(v.normal.y) < 0.7f) {
            const glm::vec3 want(analytic[i < before ? i : 0]);
            if (i < before) EXPECT_GT(glm::dot(glm::vec3(v.tangent), want), std::cos(3.0f * 3.14159265f / 180.0f)) << "vertex " << i;
            if (v.uv.x == 0.0f || v.uv.x == 1.0f) atPosition[{v.position.x, v.position.y, v.position.z}].push_back(v.tangent);
        }
    }
    EXPECT_GT(atPosition.size(), 10u);
    for (const auto& [p, ts] : atPosition)
        for (const glm::vec4& t : ts)
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(t[k], ts.front()[k], 1e-4f);
}
