// Caster culling for the sun cascades (engine/render/shadow_casters): clusters, the per-cascade
// box test and the counts 'lightpass graph --explain' shows. No GL.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/graph/frame_graph.hpp"
#include "engine/io/obj_loader.hpp"
#include "engine/render/shadow_casters.hpp"
#include "frame/frame_builder.hpp"

using namespace lp;

namespace {

// A model of `triangles` small triangles in a row along +x from `origin` (`spacing` apart), one sub-mesh.
ModelInstance rowOfTriangles(const std::string& name, glm::vec3 origin, int triangles, float spacing = 0.1f) {
    ModelInstance m;
    m.name = name;
    for (int t = 0; t < triangles; ++t) {
        const glm::vec3 p = origin + glm::vec3(spacing * float(t), 0.0f, 0.0f);
        for (glm::vec3 d : {glm::vec3(0.0f), glm::vec3(0.05f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, 0.05f)}) {
            Vertex v;
            v.position = p + d;
            m.mesh.indices.push_back(uint32_t(m.mesh.vertices.size()));
            m.mesh.vertices.push_back(v);
        }
    }
    m.mesh.subMeshes.push_back({0, uint32_t(m.mesh.indices.size()), 0});
    m.mesh.materials.emplace_back();
    return m;
}

// A sun straight down onto a 2 m cascade box: x and z in [-1, 1], y in [-1, 1] (near plane at y = 1,
// the light above it).
glm::mat4 downwardCascade() {
    const glm::mat4 view = glm::lookAt(glm::vec3(0, 10, 0), glm::vec3(0), glm::vec3(0, 0, -1));
    return glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, 9.0f, 11.0f) * view;
}

}  // namespace

TEST(ShadowCasters, ClustersCoverEverySubMeshTriangleOnceWithTheirBounds) {
    Scene s;
    s.models.push_back(rowOfTriangles("a", glm::vec3(0.0f), 10));
    ModelInstance b = rowOfTriangles("b", glm::vec3(0.0f, 1.0f, 0.0f), 5);
    b.mesh.subMeshes = {{0, 6, 0}, {6, 9, 0}};  // 2 + 3 triangles: clusters never span sub-meshes
    s.models.push_back(b);
    const std::vector<CasterCluster> c = buildCasterClusters(s, 4);
    ASSERT_EQ(c.size(), 3u + 1u + 1u);
    EXPECT_EQ(c[0].indexCount, 12u);
    EXPECT_EQ(c[2].firstIndex, 24u);
    EXPECT_EQ(c[2].indexCount, 6u);
    EXPECT_EQ(c[3].model, 1);
    EXPECT_EQ(c[3].indexCount, 6u);
    EXPECT_EQ(c[4].firstIndex, 6u);
    EXPECT_EQ(c[4].indexCount, 9u);
    // Cluster 1 holds triangles 4..7: x from 0.4 to 0.75.
    EXPECT_FLOAT_EQ(c[1].boundsMin.x, 0.4f);
    EXPECT_FLOAT_EQ(c[1].boundsMax.x, 0.75f);
    EXPECT_FLOAT_EQ(c[1].boundsMax.z, 0.05f);
}

TEST(ShadowCasters, OutsideTheTileIsCulledBetweenLightAndBoxIsKept) {
    const glm::mat4 toClip = downwardCascade();
    const float margin = 2.0f / 256.0f;
    // Inside the box.
    EXPECT_TRUE(casterBoxMayCast(toClip, glm::vec3(-0.2f), glm::vec3(0.2f), margin));
    // Beside the tile (x past 1): cannot cover any of its texels.
    EXPECT_FALSE(casterBoxMayCast(toClip, glm::vec3(3, -0.2f, -0.2f), glm::vec3(4, 0.2f, 0.2f), margin));
    EXPECT_FALSE(casterBoxMayCast(toClip, glm::vec3(-0.2f, -0.2f, 2), glm::vec3(0.2f, 0.2f, 3), margin));
    // Above the box, between it and the light (past the near plane): it shadows the box, kept.
    EXPECT_TRUE(casterBoxMayCast(toClip, glm::vec3(-0.2f, 4, -0.2f), glm::vec3(0.2f, 5, 0.2f), margin));
    // Below the box (past the far plane): behind every receiver, culled.
    EXPECT_FALSE(casterBoxMayCast(toClip, glm::vec3(-0.2f, -5, -0.2f), glm::vec3(0.2f, -4, 0.2f), margin));
    // Within the margin of the tile's edge: the conservative raster's half-texel growth reaches it.
    EXPECT_TRUE(casterBoxMayCast(toClip, glm::vec3(1.003f, -0.2f, -0.2f), glm::vec3(1.2f, 0.2f, 0.2f), margin));
    EXPECT_FALSE(casterBoxMayCast(toClip, glm::vec3(1.003f, -0.2f, -0.2f), glm::vec3(1.2f, 0.2f, 0.2f), 0.0f));
}

TEST(ShadowCasters, CullingKeepsOnlyClustersReachingTheCascadeAndMergesNeighbours) {
    Scene s;
    // 40 triangles from x = -3 to x = 0.95: clusters of 4 triangles span 0.4 m; those with x >= -1 reach the tile.
    s.models.push_back(rowOfTriangles("row", glm::vec3(-3.0f, 0.0f, 0.0f), 40));
    // A caster above the box (between it and the light) and one to the side of it, moved by the transform.
    s.models.push_back(rowOfTriangles("above", glm::vec3(0.0f), 4));
    s.models.back().transform = glm::translate(glm::mat4(1.0f), glm::vec3(0, 5, 0));
    s.models.push_back(rowOfTriangles("beside", glm::vec3(0.0f), 4));
    s.models.back().transform = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 5));
    const std::vector<CasterCluster> clusters = buildCasterClusters(s, 4);
    ASSERT_EQ(clusters.size(), 12u);

    const CasterList all = cullCasters(clusters, s, downwardCascade(), 0.0f, false);
    EXPECT_EQ(all.clusters, 12u);
    EXPECT_EQ(all.triangles, 48u);
    EXPECT_EQ(all.draws.size(), 3u);  // one per model: its clusters are contiguous

    const CasterList kept = cullCasters(clusters, s, downwardCascade(), 0.0f, true);
    // Row: triangles 20..39 (x >= -1.0) are clusters 5..9; the first of them starts at x = -1.0.
    // Plus "above"; "beside" is culled.
    EXPECT_EQ(kept.clusters, 5u + 1u);
    EXPECT_EQ(kept.triangles, 24u);
    ASSERT_EQ(kept.draws.size(), 2u);
    EXPECT_EQ(kept.draws[0].model, 0);
    EXPECT_EQ(kept.draws[0].firstIndex, 20u * 3u);
    EXPECT_EQ(kept.draws[0].indexCount, 20u * 3u);  // five neighbours merged into one draw
    EXPECT_EQ(kept.draws[1].model, 1);
}

// 'lightpass graph --explain' lists what each cascade draws; culling off draws every triangle.
TEST(ShadowCasters, ExplainListsEachCascadesDrawsAndTriangles) {
    Scene s;
    s.models.push_back(rowOfTriangles("row", glm::vec3(-30.0f, 0.0f, 0.0f), 20000, 0.003f));  // x from -30 to 30
    DirectionalLight sun;
    sun.direction = glm::vec3(0.2f, -1.0f, 0.1f);
    s.directionalLights.push_back(sun);
    s.camera.position = glm::vec3(-29, 2, 0);
    s.camera.target = glm::vec3(-25, 0, 0);
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 100.0f;
    for (bool cull : {true, false}) {
        RenderSettings settings;
        settings.width = 64;
        settings.height = 48;
        settings.shadows.cascades = 4;
        settings.shadows.cullCasters = cull;
        FrameData frame = makeFrameData(s, settings, 0.0f);
        fg::FrameGraph g;
        PassStates passes;
        buildFrameGraph(g, passes, frame);
        g.compile();
        std::vector<std::string> notes;
        for (const auto& d : g.explain())
            if (d.name == "shadow_map_0") notes = d.notes;
        ASSERT_GE(notes.size(), 1u) << g.explainText();
        EXPECT_NE(notes[0].find("cascade 0: "), std::string::npos) << notes[0];
        EXPECT_NE(g.explainText().find(notes[0]), std::string::npos);
        // The nearest cascade covers a few metres of the 60 m row: culling leaves most of it out.
        const bool drawsAll = notes[0].find(" 20000 of 20000 triangles") != std::string::npos;
        EXPECT_EQ(drawsAll, !cull) << notes[0];
    }
}

// Alpha in shadows: which sub-meshes test their alpha (CasterAlpha), from the material and, without
// a base colour texture, from the range of opacity x vertex alpha over the sub-mesh.
TEST(ShadowCasterAlpha, KindFollowsTheMaterialsAlphaModeTextureAndConstantAlpha) {
    ModelInstance m = rowOfTriangles("card", glm::vec3(0.0f), 2);
    const SubMesh sm = m.mesh.subMeshes[0];
    Material& mat = m.mesh.materials[0];
    EXPECT_EQ(casterAlpha(m.mesh, sm), CasterAlpha::Opaque);  // OPAQUE
    mat.alphaMode = AlphaMode::Mask;
    mat.alphaCutoff = 0.5f;
    mat.opacity = 0.7f;
    EXPECT_EQ(casterAlpha(m.mesh, sm), CasterAlpha::Opaque);  // constant 0.7 >= 0.5: never cut
    mat.opacity = 0.3f;
    EXPECT_EQ(casterAlpha(m.mesh, sm), CasterAlpha::None);  // constant 0.3 < 0.5: always cut
    m.mesh.vertices[1].color.w = 2.0f;  // 0.3 .. 0.6 across the first triangle: tested per fragment
    EXPECT_EQ(casterAlpha(m.mesh, sm), CasterAlpha::Mask);
    m.mesh.vertices[1].color.w = 1.0f;
    mat.diffuseMap.path = "leaf.png";  // a texture: only the GPU knows its alpha
    EXPECT_EQ(casterAlpha(m.mesh, sm), CasterAlpha::Mask);
    mat.alphaMode = AlphaMode::Blend;
    EXPECT_EQ(casterAlpha(m.mesh, sm), CasterAlpha::Hashed);
    mat.diffuseMap.clear();
    mat.opacity = 1.0f;
    EXPECT_EQ(casterAlpha(m.mesh, sm), CasterAlpha::Opaque);  // BLEND at opacity 1 everywhere shadows as opaque
    mat.opacity = 0.0f;
    EXPECT_EQ(casterAlpha(m.mesh, sm), CasterAlpha::None);  // opacity 0 casts nothing
    mat.opacity = 0.5f;  // MTL d = 0.5
    EXPECT_EQ(casterAlpha(m.mesh, sm), CasterAlpha::Hashed);
    SubMesh noMaterial = sm;
    noMaterial.material = 7;  // out of range: the default material, opaque
    EXPECT_EQ(casterAlpha(m.mesh, noMaterial), CasterAlpha::Opaque);
}

// The opaque and alpha-tested casters are separate draws: the opaque ones merge as before (the
// alpha-tested sub-mesh between them splits them), the alpha-tested ones carry their material's
// index in SceneGpu::materials (every model's materials in model order), and casters of no
// occlusion have no cluster.
TEST(ShadowCasterAlpha, CullingSplitsOpaqueAndAlphaTestedDrawsWithTheirMaterials) {
    Scene s;
    s.models.push_back(rowOfTriangles("first", glm::vec3(0.0f, 0.0f, -0.5f), 3));  // one material: index 0
    ModelInstance m = rowOfTriangles("tree", glm::vec3(-0.9f, 0.0f, 0.0f), 12);
    // Sub-meshes: trunk (opaque) 0..2, leaves (MASK, textured) 3..5, trunk again 6..8, glass (BLEND
    // d 0.5) 9..10, invisible (BLEND d 0) 11.
    m.mesh.materials.resize(4);
    m.mesh.materials[1].alphaMode = AlphaMode::Mask;
    m.mesh.materials[1].diffuseMap.path = "leaves.png";
    m.mesh.materials[2].alphaMode = AlphaMode::Blend;
    m.mesh.materials[2].opacity = 0.5f;
    m.mesh.materials[3].alphaMode = AlphaMode::Blend;
    m.mesh.materials[3].opacity = 0.0f;
    m.mesh.subMeshes = {{0, 9, 0}, {9, 9, 1}, {18, 9, 0}, {27, 6, 2}, {33, 3, 3}};
    s.models.push_back(m);
    const std::vector<CasterCluster> clusters = buildCasterClusters(s, 4);
    ASSERT_EQ(clusters.size(), 1u + 4u);  // the invisible sub-mesh has none
    EXPECT_EQ(clusters[2].alpha, CasterAlpha::Mask);
    EXPECT_EQ(clusters[2].material, 1 + 1);  // after "first"'s one material
    EXPECT_EQ(clusters[4].alpha, CasterAlpha::Hashed);
    EXPECT_EQ(clusters[4].material, 1 + 2);
    EXPECT_EQ(clusters[1].material, -1);
    EXPECT_TRUE(hasAlphaTestedCasters(clusters));

    const CasterList all = cullCasters(clusters, s, downwardCascade(), 0.0f, false);
    EXPECT_EQ(all.triangles, 3u + 11u);
    EXPECT_EQ(all.alphaTriangles, 3u + 2u);
    ASSERT_EQ(all.draws.size(), 3u);  // "first"; the trunk's two parts (the leaves between them)
    EXPECT_EQ(all.draws[1].model, 1);
    EXPECT_EQ(all.draws[1].firstIndex, 0u);
    EXPECT_EQ(all.draws[1].indexCount, 9u);
    EXPECT_EQ(all.draws[2].firstIndex, 18u);
    for (const CasterDraw& d : all.draws) EXPECT_EQ(d.material, -1);
    ASSERT_EQ(all.alphaDraws.size(), 2u);
    EXPECT_EQ(all.alphaDraws[0].firstIndex, 9u);
    EXPECT_EQ(all.alphaDraws[0].indexCount, 9u);
    EXPECT_EQ(all.alphaDraws[0].material, 2);
    EXPECT_EQ(all.alphaDraws[1].firstIndex, 27u);
    EXPECT_EQ(all.alphaDraws[1].material, 3);

    // A scene of opaque casters only has no alpha-tested draw (its cost stays what it was).
    Scene opaque;
    opaque.models.push_back(rowOfTriangles("row", glm::vec3(0.0f), 10));
    const std::vector<CasterCluster> plain = buildCasterClusters(opaque, 4);
    EXPECT_FALSE(hasAlphaTestedCasters(plain));
    EXPECT_TRUE(cullCasters(plain, opaque, downwardCascade(), 0.0f, false).alphaDraws.empty());
}

// OBJ transparency follows the BLEND rule: an MTL material with d < 1 (or Tr > 0) is hashed by its
// opacity, d 0 (Tr 1) casts nothing, d 1 is opaque.
TEST(ShadowCasterAlpha, MtlTransparencyIsHashedByItsOpacity) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / ("lightpass-caster-alpha-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "m.mtl") << "newmtl glass\nKd 0.8 0.8 0.8\nd 0.5\nnewmtl ghost\nKd 1 1 1\nTr 1\n"
                                    "newmtl wall\nKd 0.5 0.5 0.5\nd 1\n";
    std::ofstream(dir / "a.obj") << "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl glass\nf 1 2 3\nusemtl ghost\nf 1 3 2\n"
                                    "usemtl wall\nf 2 3 1\n";
    const MeshData mesh = loadObj(dir / "a.obj");
    fs::remove_all(dir);
    ASSERT_EQ(mesh.subMeshes.size(), 3u);
    std::vector<CasterAlpha> kinds;
    for (const SubMesh& sm : mesh.subMeshes) kinds.push_back(casterAlpha(mesh, sm));
    EXPECT_EQ(kinds[0], CasterAlpha::Hashed);  // glass, d 0.5
    EXPECT_EQ(kinds[1], CasterAlpha::None);    // ghost, Tr 1 = d 0
    EXPECT_EQ(kinds[2], CasterAlpha::Opaque);  // wall
}
