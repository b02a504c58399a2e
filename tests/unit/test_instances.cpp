// Scene-file "instances": one mesh stored once, drawn at each placement (the instance's placement
// after the model's own); the counts, bounds and caster clusters follow; bad lists are one line
// naming the file, the place and what is wrong.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/error.hpp"
#include "engine/io/gltf_loader.hpp"
#include "engine/render/shadow_casters.hpp"
#include "engine/scene/placements.hpp"
#include "engine/scene/scene_loader.hpp"

using namespace lp;

namespace {
std::string errorFor(const std::string& json) {
    try {
        parseScene(json, "grid.json", false);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

std::string withInstances(const std::string& instances) {
    return R"({"models": [{"primitive": "cube", "instances": )" + instances + "}]}";
}

void expectMatrixNear(const glm::mat4& a, const glm::mat4& b, const std::string& what) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(a[c][r], b[c][r], 1e-5f) << what << ": column " << c << ", row " << r;
}
}  // namespace

TEST(SceneInstances, EachPlacementFollowsTheModelsOwn) {
    const Scene s = parseScene(R"({"models": [
        {"primitive": "cube", "scale": 0.5, "rotate": [0, 90, 0],
         "instances": [{"translate": [2, 0, 0]}, {"translate": [0, 0, -3], "rotate": [0, 0, 90], "scale": [1, 2, 1]}]},
        {"primitive": "plane"}]})",
                               "grid.json", true);
    ASSERT_EQ(s.models.size(), 2u);
    const ModelInstance& cube = s.models[0];
    ASSERT_EQ(cube.instanceCount(), 2u);
    EXPECT_EQ(s.models[1].instanceCount(), 1u);
    const glm::mat4 own = glm::scale(glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(0, 1, 0)), glm::vec3(0.5f));
    expectMatrixNear(cube.transform, own, "the model's own placement");
    expectMatrixNear(cube.instanceTransform(0), glm::translate(glm::mat4(1.0f), glm::vec3(2, 0, 0)) * own, "instances[0]");
    const glm::mat4 second = glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, -3)), glm::radians(90.0f),
                                                    glm::vec3(0, 0, 1)),
                                        glm::vec3(1, 2, 1));
    expectMatrixNear(cube.instanceTransform(1), second * own, "instances[1]");
    // The cube is +-0.25 after the model's scale: instances[0] reaches x = 2.25; instances[1] is
    // +-0.5 along its y, turned onto x, at z = -3 (to -3.25); the plane spans +-0.5 in x and z.
    glm::vec3 lo, hi;
    s.bounds(lo, hi);
    EXPECT_NEAR(hi.x, 2.25f, 1e-5f);
    EXPECT_NEAR(lo.x, -0.5f, 1e-5f);
    EXPECT_NEAR(lo.z, -3.25f, 1e-5f);
    EXPECT_NEAR(hi.y, 0.25f, 1e-5f);

    const std::vector<Placement> placed = placements(s);
    ASSERT_EQ(placed.size(), 3u);
    EXPECT_EQ(placed[1].model, 0u);
    EXPECT_EQ(placed[1].instance, 1u);
    EXPECT_EQ(placed[2].model, 1u);
    const SceneCounts counts = sceneCounts(s);
    EXPECT_EQ(counts.models, 2u);
    EXPECT_EQ(counts.instances, 3u);
    EXPECT_EQ(counts.storedVertices, cube.mesh.vertices.size() + s.models[1].mesh.vertices.size());
    EXPECT_EQ(counts.drawnTriangles, 2 * cube.mesh.indices.size() / 3 + s.models[1].mesh.indices.size() / 3);
    EXPECT_EQ(sceneCountsText(counts).find("2 models, 3 instances drawn"), 0u) << sceneCountsText(counts);
}

TEST(SceneInstances, CasterClustersRepeatPerInstance) {
    const Scene s = parseScene(R"({"models": [{"primitive": "cube", "instances": [{"translate": [-2, 0, 0]}, {"translate": [2, 0, 0]}]},
                                              {"primitive": "sphere"}]})",
                               "grid.json", true);
    const std::vector<CasterCluster> clusters = buildCasterClusters(s, 4);
    // A cube is 12 triangles: 3 clusters of 4 per instance; the sphere's follow as placement 2.
    ASSERT_GE(clusters.size(), 7u);
    for (size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(clusters[i].model, 0) << i;
        EXPECT_EQ(clusters[i + 3].model, 1) << i;
        EXPECT_EQ(clusters[i + 3].firstIndex, clusters[i].firstIndex) << i;
        EXPECT_EQ(clusters[i + 3].boundsMin, clusters[i].boundsMin) << i;  // object space: the same
    }
    EXPECT_EQ(clusters[6].model, 2);
    // Culled against a light looking down on x in [-1, 1] (clip = world x, z): the instances at
    // x = -2 and 2 (each +-0.5) lie outside it; only the sphere at the origin casts.
    glm::mat4 worldToClip(0.0f);
    worldToClip[0][0] = 1.0f;   // clip x = world x
    worldToClip[2][1] = 1.0f;   // clip y = world z
    worldToClip[1][2] = -0.1f;  // clip z: depth along -y, within [-1, 1]
    worldToClip[3][3] = 1.0f;
    const CasterList kept = cullCasters(clusters, s, worldToClip, 0.0f, true);
    for (const CasterDraw& d : kept.draws) EXPECT_EQ(d.model, 2) << "an instance outside the tile was kept";
    EXPECT_FALSE(kept.draws.empty());
    EXPECT_EQ(cullCasters(clusters, s, worldToClip, 0.0f, false).triangles, 2 * 12 + s.models[1].mesh.indices.size() / 3);
}

TEST(SceneInstances, GltfLightsComeWithEachInstance) {
    // A glTF's KHR_lights_punctual lights are placed by each instance.
    const std::string file = std::string(LIGHTPASS_SOURCE_DIR) + "/tests/data/gltf/lights.gltf";
    const Scene one = parseScene(R"({"models": [{"gltf": ")" + file + R"("}]})", "grid.json", true);
    const Scene two = parseScene(R"({"models": [{"gltf": ")" + file + R"(", "instances": [{"translate": [0, 0, 0]}, {"translate": [5, 0, 0]}]}]})",
                                 "grid.json", true);
    ASSERT_FALSE(one.pointLights.empty());
    ASSERT_EQ(two.pointLights.size(), 2 * one.pointLights.size());
    const size_t n = one.pointLights.size();
    for (size_t i = 0; i < n; ++i) {
        EXPECT_EQ(two.pointLights[i].position, one.pointLights[i].position) << i;
        EXPECT_NEAR(two.pointLights[n + i].position.x, one.pointLights[i].position.x + 5.0f, 1e-5f) << i;
    }
}

TEST(SceneInstances, BadListsAreOneLineNamingThePlace) {
    struct Case {
        std::string instances, expected;
    };
    const Case cases[] = {
        {R"({"translate": [1, 0, 0]})", "grid.json: models[0].instances: expected an array of placements"},
        {"[]", "grid.json: models[0].instances: is empty"},
        {"[{\"translate\": [1, 0, 0]}, 3]", "grid.json: models[0].instances[1]: expected an object"},
        {"[{\"translate\": [1, 0, 0]}, {\"tranlate\": [1, 0, 0]}]",
         "grid.json: models[0].instances[1].tranlate: unknown field (known: rotate, scale, translate)"},
        {"[{\"translate\": [1, 1e39, 0]}]", "grid.json: models[0].instances[0].translate[1]: not a finite number"},
        {"[{\"translate\": [1e8, 0, 0]}]", "grid.json: models[0].instances[0].translate: 1e+08 is too far from the origin"},
        {"[{\"scale\": 0}]", "grid.json: models[0].instances[0].scale: must not be zero"},
        {"[{\"rotate\": [0, \"a\", 0]}]", "grid.json: models[0].instances[0].rotate[1]: expected a number"},
        {"[{\"translate\": [1, 0]}]", "grid.json: models[0].instances[0].translate: expected an array of 3 numbers"},
    };
    for (const Case& c : cases) {
        const std::string error = errorFor(withInstances(c.instances));
        EXPECT_EQ(error.find(c.expected), 0u) << c.instances << " gave: " << error;
        EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    }
}

namespace {
std::string gltfTestFile(const std::string& name) { return std::string(LIGHTPASS_SOURCE_DIR) + "/tests/data/gltf/" + name; }
}  // namespace

// glTF node reuse (tests/data/gltf/node_reuse.gltf, scripts/make_gltf_assets.py): the box that five
// nodes draw is read once, in its own space, with the four non-mirroring nodes' world transforms;
// the mirroring node and the floor stay baked. Without the option every node is baked, as before.
TEST(GltfNodeReuse, AMeshSeveralStillNodesDrawIsReadOnce) {
    const GltfContent baked = loadGltf(gltfTestFile("node_reuse.gltf"));
    EXPECT_TRUE(baked.instancedMeshes.empty());
    EXPECT_EQ(baked.mesh.indices.size() / 3, 2u + 5u * 12u);
    const GltfContent g = loadGltf(gltfTestFile("node_reuse.gltf"), nullptr, true);
    ASSERT_EQ(g.instancedMeshes.size(), 1u);
    const GltfInstancedMesh& box = g.instancedMeshes[0];
    EXPECT_EQ(box.meshIndex, 0);
    EXPECT_EQ(box.mesh.indices.size() / 3, 12u);
    EXPECT_EQ(box.mesh.vertices.size(), 24u);
    EXPECT_EQ(g.mesh.indices.size() / 3, 2u + 12u);  // the floor and the mirrored box
    ASSERT_EQ(box.transforms.size(), 4u);
    EXPECT_NEAR(box.mesh.boundsMax.x, 0.25f, 1e-6f);  // its own space
    // Node order; the third under a parent turned 90 degrees about +Y at (0.5, 0.3, 0.75): its
    // (0.75, 0, 0) lands at (0.5, 0.3, 0).
    const glm::vec3 t0(box.transforms[0][3]), t2(box.transforms[2][3]);
    EXPECT_NEAR(glm::length(t0 - glm::vec3(-1.0f, 0.25f, 0.0f)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(t2 - glm::vec3(0.5f, 0.3f, 0.0f)), 0.0f, 1e-6f);
    ASSERT_EQ(box.mesh.materials.size(), g.mesh.materials.size());
    EXPECT_EQ(box.mesh.materials[size_t(box.mesh.subMeshes[0].material)].name, "box");
    // The expanded file (a mesh entry per node) has nothing to reuse.
    EXPECT_TRUE(loadGltf(gltfTestFile("node_reuse_expanded.gltf"), nullptr, true).instancedMeshes.empty());
}

TEST(GltfNodeReuse, SceneModelsDrawTheReusedMeshAtEveryNodeUnderEveryInstance) {
    const Scene s = parseScene(R"({"models": [{"name": "boxes", "gltf": ")" + gltfTestFile("node_reuse.gltf") +
                                   R"(", "material": {"diffuse": [0.1, 0.2, 0.3]},
                                   "instances": [{"translate": [0, 0, 0]}, {"translate": [10, 0, 0]}]}]})",
                               "grid.json", true);
    ASSERT_EQ(s.models.size(), 2u);
    EXPECT_EQ(s.models[0].name, "boxes");
    EXPECT_EQ(s.models[1].name, "boxes/meshes[0]");
    EXPECT_EQ(s.models[1].instanceCount(), 8u);  // 4 nodes x 2 placements
    EXPECT_NEAR(s.models[1].instanceTransform(4)[3].x, 10.0f - 1.0f, 1e-5f);
    EXPECT_EQ(s.models[1].mesh.materials[0].diffuse, glm::vec3(0.1f, 0.2f, 0.3f));  // the entry's override
    const SceneCounts counts = sceneCounts(s);
    EXPECT_EQ(counts.storedVertices, 4u + 24u + 24u);
    EXPECT_EQ(counts.drawnTriangles, 2u * (2u + 12u) + 8u * 12u);
    // Loaded as a bare model (lightpass view): the same split.
    const Scene bare = sceneForModel(gltfTestFile("node_reuse.gltf"));
    ASSERT_EQ(bare.models.size(), 2u);
    EXPECT_EQ(bare.models[1].instanceCount(), 4u);
}

// EXT_mesh_gpu_instancing (tests/data/gltf/gpu_instancing.gltf): five TRANSLATION / ROTATION / SCALE
// instances of a box under a moved and turned node, as gpu_instancing_expanded.gltf writes them as
// child nodes: the same world transforms; baked by default, stored once when asked.
TEST(GltfGpuInstancing, InstancesAreTheNodesPlacements) {
    const GltfContent baked = loadGltf(gltfTestFile("gpu_instancing.gltf"));
    EXPECT_TRUE(baked.instancedMeshes.empty());
    EXPECT_EQ(baked.mesh.indices.size() / 3, 2u + 5u * 12u);
    const GltfContent g = loadGltf(gltfTestFile("gpu_instancing.gltf"), nullptr, true);
    ASSERT_EQ(g.instancedMeshes.size(), 1u);
    ASSERT_EQ(g.instancedMeshes[0].transforms.size(), 5u);
    EXPECT_EQ(g.mesh.indices.size() / 3, 2u);  // the floor
    // The expanded file's boxes, baked: each instance's box through its transform lands where the
    // baked copy is (same vertex order: box k is vertices 4 + 24k .. of the expanded mesh).
    const GltfContent expanded = loadGltf(gltfTestFile("gpu_instancing_expanded.gltf"));
    const MeshData& box = g.instancedMeshes[0].mesh;
    ASSERT_EQ(expanded.mesh.vertices.size(), 4u + 5u * box.vertices.size());
    for (size_t k = 0; k < 5; ++k)
        for (size_t v = 0; v < box.vertices.size(); ++v) {
            const glm::vec3 placed(g.instancedMeshes[0].transforms[k] * glm::vec4(box.vertices[v].position, 1.0f));
            EXPECT_NEAR(glm::length(placed - expanded.mesh.vertices[4 + k * box.vertices.size() + v].position), 0.0f, 1e-5f)
                << "instance " << k << ", vertex " << v;
        }
}

TEST(GltfGpuInstancing, BadAttributesAreOneLineNamingThem) {
    const std::string text = [] {
        std::ifstream f(gltfTestFile("gpu_instancing.gltf"));
        std::stringstream s;
        s << f.rdbuf();
        return s.str();
    }();
    const auto dir = std::filesystem::temp_directory_path() / ("lp_gpu_instancing_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    struct Case {
        std::string from, to, expected;
    };
    const std::string attributes = "nodes[1].extensions.EXT_mesh_gpu_instancing.attributes";
    // The generated file names accessors 6, 7 and 8 (TRANSLATION, ROTATION, SCALE; 3 is the floor's
    // 4 positions).
    const size_t extension = text.find("\"EXT_mesh_gpu_instancing\": {");
    ASSERT_NE(text.find("\"TRANSLATION\": 6", extension), std::string::npos) << "the asset changed; update the cases";
    const Case cases[] = {
        {"\"TRANSLATION\": 6", "\"TRANSLATION\": 99", attributes + ".TRANSLATION: accessor 99 does not exist"},
        {"\"TRANSLATION\": 6", "\"TRANSLATION\": 7", attributes + ".TRANSLATION (accessors[7]): unexpected type"},
        {"\"SCALE\": 8", "\"SCALE\": 3", attributes + ".SCALE: 4 instances, but the other attributes have 5"},
        {"\"attributes\"", "\"attributez\"", attributes + ": missing"},
    };
    for (const Case& c : cases) {
        std::string doc = text;
        const size_t at = doc.find(c.from, extension);
        ASSERT_NE(at, std::string::npos) << c.from;
        doc.replace(at, c.from.size(), c.to);
        const auto file = dir / "bad.gltf";
        std::ofstream(file) << doc;
        std::string error;
        try {
            loadGltf(file, nullptr, true);
        } catch (const Error& e) {
            error = e.what();
        }
        EXPECT_NE(error.find(c.expected), std::string::npos) << c.to << " gave: " << error;
        EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    }
    std::filesystem::remove_all(dir);
}
