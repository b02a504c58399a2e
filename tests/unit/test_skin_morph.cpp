// glTF skins and morph targets (docs/models-and-materials.md, "Animation"): posed vertices of small
// generated files against the joint matrices and the morph sum worked out by hand, the spec's
// CUBICSPLINE layout for weights, the morph-then-skin order, and bad skins and targets as one line.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/error.hpp"
#include "engine/io/gltf_loader.hpp"
#include "engine/scene/animation.hpp"
#include "tests/unit/gltf_test_files.hpp"

using namespace lp;
using lp::test::bytesOf;
using lp::test::Doc;
using lp::test::loadError;
using lp::test::TempDir;

namespace {

// A strip of six vertices up +Y, x = +-0.5 at y = 0, 1, 2 (normal +Z, tangent +X), skinned to two
// joints: node 0 at the origin and its child node 1 at (0, 1, 0). The y = 0 row follows joint 0, the
// y = 2 row joint 1, the y = 1 row both, half and half. Node 2 draws it with skin 0 and a translation
// of (100, 0, 0), which a skin ignores. One clip turns joint 1 from 0 to 90 degrees about +Z over 1 s,
// then holds it there to 2 s.
struct SkinnedStrip {
    Doc doc;
    int joints = -1, weights = -1;
    explicit SkinnedStrip(bool u16Joints = false, bool normalisedWeights = false, std::vector<float> weightValues = {}) {
        const int pos = doc.floats({-0.5f, 0, 0, 0.5f, 0, 0, -0.5f, 1, 0, 0.5f, 1, 0, -0.5f, 2, 0, 0.5f, 2, 0}, "VEC3", 6);
        std::vector<float> n, t;
        for (int v = 0; v < 6; ++v) {
            n.insert(n.end(), {0, 0, 1});
            t.insert(t.end(), {1, 0, 0, 1});
        }
        const int normals = doc.floatArray(n, "VEC3", 6);
        const int tangents = doc.floatArray(t, "VEC4", 6);
        const std::vector<int> jointIndex = {0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
        if (u16Joints) {
            std::string bytes;
            for (int j : jointIndex) bytes += bytesOf<uint16_t>({uint16_t(j)});
            joints = doc.accessor({{"bufferView", doc.view(bytes)}, {"componentType", 5123}, {"type", "VEC4"}, {"count", 6}});
        } else {
            std::string bytes;
            for (int j : jointIndex) bytes += char(j);
            joints = doc.accessor({{"bufferView", doc.view(bytes)}, {"componentType", 5121}, {"type", "VEC4"}, {"count", 6}});
        }
        if (weightValues.empty()) weightValues = {1, 0, 0, 0, 1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 0.5f, 0.5f, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
        if (normalisedWeights) {
            // Normalised unsigned shorts; a half is 32767 + 32768 (sum 65535, exactly 1).
            std::string bytes;
            for (size_t i = 0; i < weightValues.size(); ++i) {
                uint16_t u = uint16_t(std::lround(weightValues[i] * 65535.0f));
                if (weightValues[i] == 0.5f) u = (i % 4 == 0) ? 32767 : 32768;
                bytes += bytesOf<uint16_t>({u});
            }
            weights = doc.accessor({{"bufferView", doc.view(bytes)}, {"componentType", 5123}, {"normalized", true}, {"type", "VEC4"}, {"count", 6}});
        } else {
            weights = doc.floatArray(weightValues, "VEC4", 6);
        }
        const int idx = doc.accessor({{"bufferView", doc.view(bytesOf<uint16_t>({0, 1, 3, 0, 3, 2, 2, 3, 5, 2, 5, 4}))},
                                      {"componentType", 5123}, {"type", "SCALAR"}, {"count", 12}});
        doc.j["meshes"].push_back({{"primitives", {{{"attributes", {{"POSITION", pos}, {"NORMAL", normals}, {"TANGENT", tangents},
                                                                    {"JOINTS_0", joints}, {"WEIGHTS_0", weights}}},
                                                    {"indices", idx}}}}});
        const glm::mat4 inverseBind1 = glm::translate(glm::mat4(1.0f), glm::vec3(0, -1, 0));
        std::vector<float> ibm(16, 0.0f);
        ibm[0] = ibm[5] = ibm[10] = ibm[15] = 1.0f;
        for (int c = 0; c < 16; ++c) ibm.push_back(inverseBind1[c / 4][c % 4]);
        const int ibmAccessor = doc.floatArray(ibm, "MAT4", 2);
        doc.node({{"children", {1}}});
        doc.node({{"translation", {0, 1, 0}}}, false);
        doc.node({{"mesh", 0}, {"skin", 0}, {"translation", {100, 0, 0}}});
        doc.j["skins"] = {{{"joints", {0, 1}}, {"inverseBindMatrices", ibmAccessor}}};
        const float h = std::sqrt(0.5f);
        // Keys at 0, 1 and 2 s (0, 90 and 90 degrees): at 1 s, inside the 2 s loop, joint 1 is at 90 degrees.
        const int in = doc.floatArray({0, 1, 2}, "SCALAR", 3);
        const int out = doc.floatArray({0, 0, 0, 1, 0, 0, h, h, 0, 0, h, h}, "VEC4", 3);
        doc.j["animations"] = {{{"channels", {{{"sampler", 0}, {"target", {{"node", 1}, {"path", "rotation"}}}}}},
                                {"samplers", {{{"input", in}, {"output", out}}}}}};
    }
};

// The vertex at file position p (its first copy) in `vertices`, posed from the rest `loaded`.
size_t vertexAt(const std::vector<Vertex>& loaded, glm::vec3 p) {
    for (size_t i = 0; i < loaded.size(); ++i)
        if (glm::length(loaded[i].position - p) < 1e-6f) return i;
    ADD_FAILURE() << "no vertex at " << p.x << " " << p.y << " " << p.z;
    return 0;
}

std::vector<Vertex> posedAt(const GltfContent& g, double time) {
    std::vector<Vertex> v = g.mesh.vertices;
    poseVertices(*g.animation, animatedPose(*g.animation, {0}, time), v);
    return v;
}

void expectNear(glm::vec3 a, glm::vec3 b, float tolerance, const std::string& what) {
    EXPECT_NEAR(glm::length(a - b), 0.0f, tolerance) << what << ": (" << a.x << ", " << a.y << ", " << a.z << ") expected (" << b.x << ", "
                                                     << b.y << ", " << b.z << ")";
}

}  // namespace

// Bent 90 degrees, each vertex is where the joint matrices world(joint) x inverseBind put it: the
// y = 2 row turned about (0, 1, 0), the y = 1 row at the blend of both joints' placements, the
// y = 0 row still, the node's own translation ignored; normals and tangents turned with them.
TEST(SkinMorph, TwoJointSkinBentNinetyDegrees) {
    for (int variant = 0; variant < 2; ++variant) {
        SCOPED_TRACE(variant ? "u16 joints, normalised u16 weights" : "u8 joints, float weights");
        TempDir dir;
        SkinnedStrip strip(variant == 1, variant == 1);
        MeshLoadReport report;
        const GltfContent g = loadGltf(dir.write("skin.gltf", strip.doc.text()), &report);
        EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
        ASSERT_TRUE(g.animation);
        ASSERT_EQ(g.animation->skins.size(), 1u);
        // At rest the joint matrices are identity: the file's positions, not moved by (100, 0, 0).
        for (glm::vec3 p : {glm::vec3(0.5f, 0, 0), glm::vec3(0.5f, 1, 0), glm::vec3(0.5f, 2, 0)}) (void)vertexAt(g.mesh.vertices, p);
        const std::vector<Vertex> bent = posedAt(g, 1.0);
        const float tol = variant ? 2e-5f : 1e-6f;
        // Joint 1's matrix: T(0, 1, 0) Rz(90) T(0, -1, 0), which takes (x, y) to (1 - y, x + 1).
        expectNear(bent[vertexAt(g.mesh.vertices, {0.5f, 2, 0})].position, {-1.0f, 1.5f, 0}, tol, "tip right");
        expectNear(bent[vertexAt(g.mesh.vertices, {-0.5f, 2, 0})].position, {-1.0f, 0.5f, 0}, tol, "tip left");
        expectNear(bent[vertexAt(g.mesh.vertices, {0.5f, 0, 0})].position, {0.5f, 0, 0}, tol, "root");
        // Half and half: joint 0 leaves (0.5, 1) there, joint 1 takes it to (0, 1.5); the blend (0.25, 1.25).
        expectNear(bent[vertexAt(g.mesh.vertices, {0.5f, 1, 0})].position, {0.25f, 1.25f, 0}, 1e-4f, "middle right");
        expectNear(bent[vertexAt(g.mesh.vertices, {-0.5f, 1, 0})].position, {-0.25f, 0.75f, 0}, 1e-4f, "middle left");
        const size_t tip = vertexAt(g.mesh.vertices, {0.5f, 2, 0});
        expectNear(bent[tip].normal, {0, 0, 1}, 1e-5f, "normal");
        expectNear(glm::vec3(bent[tip].tangent), {0, 1, 0}, 1e-5f, "tangent");  // +X turned to +Y
        // Half way through the clip, 45 degrees: the tip's right corner turned by 45 degrees about (0, 1, 0).
        const float c = std::sqrt(0.5f);
        expectNear(posedAt(g, 0.5)[tip].position, {0.5f * c - c, 1.0f + 0.5f * c + c, 0}, 1e-5f, "45 degrees");
    }
}

// JOINTS_1/WEIGHTS_1 carry influences 5 to 8: the tip row's joint 1 given there (its WEIGHTS_0 all 0),
// the middle row's half split over both sets, bends as before.
TEST(SkinMorph, SecondJointSetCounts) {
    TempDir dir;
    SkinnedStrip strip(false, false, {1, 0, 0, 0, 1, 0, 0, 0, 0.5f, 0, 0, 0, 0.5f, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
    std::string joints1;
    for (int v = 0; v < 6; ++v) joints1 += std::string{char(1), char(0), char(0), char(0)};
    const int j1 = strip.doc.accessor({{"bufferView", strip.doc.view(joints1)}, {"componentType", 5121}, {"type", "VEC4"}, {"count", 6}});
    const int w1 = strip.doc.floatArray({0, 0, 0, 0, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0.5f, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4", 6);
    strip.doc.j["meshes"][0]["primitives"][0]["attributes"]["JOINTS_1"] = j1;
    strip.doc.j["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_1"] = w1;
    MeshLoadReport report;
    const GltfContent g = loadGltf(dir.write("j1.gltf", strip.doc.text()), &report);
    EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
    const std::vector<Vertex> bent = posedAt(g, 1.0);
    expectNear(bent[vertexAt(g.mesh.vertices, {0.5f, 2, 0})].position, {-1.0f, 1.5f, 0}, 1e-6f, "tip right");
    expectNear(bent[vertexAt(g.mesh.vertices, {0.5f, 1, 0})].position, {0.25f, 1.25f, 0}, 1e-6f, "middle right");
    // Only one of the two sets: one line naming what is missing.
    strip.doc.j["meshes"][0]["primitives"][0]["attributes"].erase("WEIGHTS_1");
    const auto path = dir.write("half.gltf", strip.doc.text());
    EXPECT_EQ(loadError(path), path.string() + ": meshes[0].primitives[0].attributes: has JOINTS_1 and no WEIGHTS_1, but its node has "
                                               "skins[0] (a skinned primitive needs both)");
}

// Weights that do not sum to 1 are normalised, said in one line with the count.
TEST(SkinMorph, UnnormalisedWeightsAreNormalisedWithOneWarning) {
    TempDir dir;
    SkinnedStrip strip(false, false, {2, 0, 0, 0, 2, 0, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0});
    MeshLoadReport report;
    const GltfContent g = loadGltf(dir.write("w.gltf", strip.doc.text()), &report);
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_NE(report.warnings[0].find("meshes[0].primitives[0].attributes.WEIGHTS_0 (accessors[" + std::to_string(strip.weights) +
                                      "]): 4 vertices whose joint weights do not sum to 1; normalized"),
              std::string::npos)
        << report.warnings[0];
    expectNear(posedAt(g, 1.0)[vertexAt(g.mesh.vertices, {0.5f, 1, 0})].position, {0.25f, 1.25f, 0}, 1e-5f, "normalised blend");
}

// A joint outside the scene's node trees has no world transform: identity, with one warning.
TEST(SkinMorph, JointOutsideTheSceneIsWarnedOnce) {
    TempDir dir;
    SkinnedStrip strip;
    strip.doc.j["nodes"][0].erase("children");  // node 1, joint 1, is now in no tree of the scene
    MeshLoadReport report;
    const GltfContent g = loadGltf(dir.write("j.gltf", strip.doc.text()), &report);
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_NE(report.warnings[0].find("skins[0].joints[1]: 1 joints outside the scene's node trees; placed as if at the origin"),
              std::string::npos)
        << report.warnings[0];
    // Joint 1's matrix is its inverse bind matrix alone, T(0, -1, 0): the half-and-half vertex at
    // (0.5, 1) rests at the blend of (0.5, 1) and (0.5, 0).
    (void)vertexAt(g.mesh.vertices, {0.5f, 0.5f, 0});
}

namespace {
// The unit quad (z = 0, normal +Z) with morph targets whose POSITION deltas are `deltas` (one vec3 a
// target, the same at every vertex), mesh weights `meshWeights`, drawn by node 0.
int morphQuad(Doc& doc, const std::vector<glm::vec3>& deltas, const std::vector<float>& meshWeights) {
    const int m = doc.quad({{"NORMAL", doc.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 4)}});
    nlohmann::json targets = nlohmann::json::array();
    for (glm::vec3 d : deltas) {
        std::vector<float> v;
        for (int i = 0; i < 4; ++i) v.insert(v.end(), {d.x, d.y, d.z});
        targets.push_back({{"POSITION", doc.floatArray(v, "VEC3", 4)}});
    }
    doc.j["meshes"][size_t(m)]["primitives"][0]["targets"] = targets;
    if (!meshWeights.empty()) doc.j["meshes"][size_t(m)]["weights"] = meshWeights;
    return m;
}
}  // namespace

// A morph weight of 0.5 puts every vertex half way along its delta; node.weights override the
// mesh's; a LINEAR weights channel moves them.
TEST(SkinMorph, MorphWeightHalfLandsHalfway) {
    TempDir dir;
    {
        Doc doc;
        doc.node({{"mesh", morphQuad(doc, {{0, 0, 2}}, {0.5f})}});
        const GltfContent g = loadGltf(dir.write("half.gltf", doc.text()));
        for (const Vertex& v : g.mesh.vertices) EXPECT_NEAR(v.position.z, 1.0f, 1e-6f);
    }
    {
        Doc doc;
        doc.node({{"mesh", morphQuad(doc, {{0, 0, 2}}, {0.5f})}, {"weights", {0.25}}});
        const GltfContent g = loadGltf(dir.write("node.gltf", doc.text()));
        for (const Vertex& v : g.mesh.vertices) EXPECT_NEAR(v.position.z, 0.5f, 1e-6f);  // the node's 0.25 wins
    }
    {
        Doc doc;
        doc.node({{"mesh", morphQuad(doc, {{0, 0, 2}}, {})}});
        const int in = doc.floatArray({0, 1}, "SCALAR", 2), out = doc.floatArray({0, 1}, "SCALAR", 2);
        doc.j["animations"] = {{{"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}}}},
                                {"samplers", {{{"input", in}, {"output", out}}}}}};
        const GltfContent g = loadGltf(dir.write("anim.gltf", doc.text()));
        ASSERT_TRUE(g.animation);
        for (const Vertex& v : g.mesh.vertices) EXPECT_EQ(v.position.z, 0.0f);  // rest: no weights, 0
        for (const Vertex& v : posedAt(g, 0.5)) EXPECT_NEAR(v.position.z, 1.0f, 1e-6f);
        EXPECT_NE(animatedPose(*g.animation, {0}, 0.2), animatedPose(*g.animation, {0}, 0.3));  // a pose differs by its weights
    }
}

// NORMAL and TANGENT deltas are added with the weights, then renormalised: (0, 0, 1) + 0.5 (1, 0, -1)
// is (1, 0, 1) / sqrt 2; the tangent (1, 0, 0) + 0.5 (0, 2, 0) is (1, 1, 0) / sqrt 2.
TEST(SkinMorph, NormalAndTangentDeltas) {
    TempDir dir;
    Doc doc;
    const int m = doc.quad({{"NORMAL", doc.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 4)},
                            {"TANGENT", doc.floats({1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1}, "VEC4", 4)}});
    doc.j["meshes"][size_t(m)]["primitives"][0]["targets"] = {
        {{"NORMAL", doc.floats({1, 0, -1, 1, 0, -1, 1, 0, -1, 1, 0, -1}, "VEC3", 4)},
         {"TANGENT", doc.floats({0, 2, 0, 0, 2, 0, 0, 2, 0, 0, 2, 0}, "VEC3", 4)}}};
    doc.j["meshes"][size_t(m)]["weights"] = {0.5};
    doc.node({{"mesh", m}});
    MeshLoadReport report;
    const GltfContent g = loadGltf(dir.write("nt.gltf", doc.text()), &report);
    EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
    const float h = std::sqrt(0.5f);
    for (const Vertex& v : g.mesh.vertices) {
        expectNear(v.normal, {h, 0, h}, 1e-6f, "normal");
        expectNear(glm::vec3(v.tangent), {h, h, 0}, 1e-6f, "tangent");
        EXPECT_EQ(v.tangent.w, 1.0f);
        EXPECT_EQ(v.position.z, 0.0f);  // no POSITION target: the shape stays
    }
}

// CUBICSPLINE weights: per key the in-tangents of every weight, then their values, then their
// out-tangents; at a mid time the spec's Hermite form, v = h00 v_k + h10 d b_k + h01 v_k+1 + h11 d a_k+1.
TEST(SkinMorph, CubicSplineWeightsFollowTheHermiteForm) {
    TempDir dir;
    Doc doc;
    doc.node({{"mesh", morphQuad(doc, {{0, 0, 1}, {1, 0, 0}}, {})}});
    // Keys at 0 and 2; two weights. [a0 a0'] [v0 v0'] [b0 b0'] [a1 a1'] [v1 v1'] [b1 b1'].
    const std::vector<float> values = {9, 9, 0.2f, 0.8f, 1.5f, -0.5f, -1.0f, 2.0f, 0.6f, 0.1f, 9, 9};
    const int in = doc.floatArray({0, 2}, "SCALAR", 2), out = doc.floatArray(values, "SCALAR", values.size());
    doc.j["animations"] = {{{"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}}}},
                            {"samplers", {{{"input", in}, {"output", out}, {"interpolation", "CUBICSPLINE"}}}}}};
    const GltfContent g = loadGltf(dir.write("cubic.gltf", doc.text()));
    ASSERT_TRUE(g.animation);
    const double d = 2.0, s = 0.25;  // t = 0.5
    const double h00 = 2 * s * s * s - 3 * s * s + 1, h10 = s * s * s - 2 * s * s + s, h01 = -2 * s * s * s + 3 * s * s, h11 = s * s * s - s * s;
    const double w0 = h00 * 0.2 + h10 * d * 1.5 + h01 * 0.6 + h11 * d * -1.0;
    const double w1 = h00 * 0.8 + h10 * d * -0.5 + h01 * 0.1 + h11 * d * 2.0;
    const std::vector<float> w = sampleWeights(g.animation->clips[0].samplers[0], 0.5f);
    ASSERT_EQ(w.size(), 2u);
    EXPECT_NEAR(w[0], w0, 1e-6);
    EXPECT_NEAR(w[1], w1, 1e-6);
    for (size_t i = 0; i < g.mesh.vertices.size(); ++i) {
        const glm::vec3 expected = g.mesh.vertices[i].position + glm::vec3(float(w1), 0.0f, float(w0));
        expectNear(posedAt(g, 0.5)[i].position, expected, 1e-5f, "posed");
    }
    // At the keys, the keys' values.
    EXPECT_NEAR(sampleWeights(g.animation->clips[0].samplers[0], 2.0f)[1], 0.1f, 1e-7f);
}

// Morph first, then skin (the spec's order): a delta of +X at the bent joint's tip turns with it.
TEST(SkinMorph, MorphThenSkin) {
    TempDir dir;
    SkinnedStrip strip;
    std::vector<float> delta;
    for (int v = 0; v < 6; ++v) delta.insert(delta.end(), {1, 0, 0});
    strip.doc.j["meshes"][0]["primitives"][0]["targets"] = {{{"POSITION", strip.doc.floatArray(delta, "VEC3", 6)}}};
    strip.doc.j["meshes"][0]["weights"] = {1.0};
    const GltfContent g = loadGltf(dir.write("ms.gltf", strip.doc.text()));
    // The rest pose is morphed: the tip's right corner from (0.5, 2) to (1.5, 2).
    const size_t tip = vertexAt(g.mesh.vertices, {1.5f, 2, 0});
    // Bent: (1.5, 2) about (0, 1) by 90 degrees is (-1, 2.5); skinned first, then morphed, it would be (0, 1.5).
    expectNear(posedAt(g, 1.0)[tip].position, {-1.0f, 2.5f, 0}, 1e-5f, "morphed tip");
}

// Bad skins and targets: one line naming the file, the element and what is wrong.
TEST(SkinMorph, BadSkinsAndTargetsNameThePlace) {
    TempDir dir;
    auto error = [&](const Doc& doc) {
        const auto path = dir.write("bad.gltf", doc.text());
        const std::string e = loadError(path);
        EXPECT_EQ(e.rfind(path.string() + ": ", 0), 0u) << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
        return e.substr(std::min(e.size(), path.string().size() + 2));
    };
    {
        SkinnedStrip s;
        s.doc.j["skins"][0]["joints"] = {0};  // joint 1 named by the vertices no longer exists
        EXPECT_EQ(error(s.doc), "meshes[0].primitives[0].attributes.JOINTS_0 (accessors[" + std::to_string(s.joints) +
                                    "]): joint 1 of vertex 2 is beyond skins[0]'s 1 joints");
    }
    {
        SkinnedStrip s;
        s.doc.j["accessors"][size_t(s.weights)]["count"] = 5;
        EXPECT_EQ(error(s.doc), "meshes[0].primitives[0].attributes.WEIGHTS_0: 5 elements, but POSITION has 6");
    }
    {
        SkinnedStrip s;
        std::vector<float> ibm(32, 0.0f);
        ibm[0] = ibm[5] = ibm[10] = ibm[15] = 1.0f;
        ibm[16 + 3] = std::nanf("");
        const int a = s.doc.floatArray(ibm, "MAT4", 2);
        s.doc.j["skins"][0]["inverseBindMatrices"] = a;
        EXPECT_EQ(error(s.doc), "skins[0].inverseBindMatrices (accessors[" + std::to_string(a) + "]): matrix 1 (for joint 1) is not finite");
    }
    {
        Doc doc;
        const int m = morphQuad(doc, {{0, 0, 1}}, {});
        doc.node({{"mesh", m}});
        const int shortTarget = doc.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
        doc.j["meshes"][0]["primitives"][0]["targets"][0]["POSITION"] = shortTarget;
        EXPECT_EQ(error(doc), "meshes[0].primitives[0].targets[0].POSITION: 3 elements, but POSITION has 4");
    }
    {
        Doc doc;
        doc.node({{"mesh", morphQuad(doc, {{0, 0, 1}}, {0.5f, 0.5f})}});
        EXPECT_EQ(error(doc), "meshes[0].weights: 2 weights for 1 morph targets (one a target)");
    }
    {
        Doc doc;
        doc.node({{"mesh", doc.quad()}});
        const int in = doc.floatArray({0, 1}, "SCALAR", 2), out = doc.floatArray({0, 1}, "SCALAR", 2);
        doc.j["animations"] = {{{"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}}}},
                                {"samplers", {{{"input", in}, {"output", out}}}}}};
        EXPECT_EQ(error(doc), "animations[0].channels[0].target.node: nodes[0] has no mesh with morph targets for its weights to move");
    }
    {
        Doc doc;
        doc.node({{"mesh", morphQuad(doc, {{0, 0, 1}, {1, 0, 0}}, {})}});
        const int in = doc.floatArray({0, 1}, "SCALAR", 2), out = doc.floatArray({0, 1, 0}, "SCALAR", 3);
        doc.j["animations"] = {{{"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}}}},
                                {"samplers", {{{"input", in}, {"output", out}}}}}};
        EXPECT_EQ(error(doc), "animations[0].samplers[0].output (accessors[" + std::to_string(out) +
                                  "]): 3 values for 2 key times of 2 morph weights: LINEAR needs 4 (every weight, a key)");
    }
}
