// Scene-file "instances": a model stored once and drawn at each placement renders what the same
// scene written as separate copies renders, in every path that draws meshes (deferred with both
// G-buffer modes, forward+, the transparent pass, sun cascades, spot and point shadows, the path
// tracer), while its vertices are uploaded once.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <string>
#include <vector>

#include "engine/graph/texture_pool.hpp"
#include "engine/render/motion.hpp"
#include "engine/render/scene_gpu.hpp"
#include "engine/scene/placements.hpp"
#include "engine/scene/scene_loader.hpp"
#include "frame/renderer.hpp"
#include "passes/gbuffer_pass.hpp"
#include "tests/gl/render_fixture.hpp"
#include "gl_fixture.hpp"

using namespace lp;
using lp::test::renderHdr;

namespace {

// Where the copies go: turned, scaled and moved, so that a placement read wrongly moves pixels.
const std::vector<std::string> kCubePlacements = {
    R"("translate": [-1.2, 0.3, 0], "rotate": [0, 30, 0], "scale": 0.6)",
    R"("translate": [0.1, 0.25, -0.8], "rotate": [10, -20, 5], "scale": [0.5, 0.5, 0.8])",
    R"("translate": [1.3, 0.4, 0.4], "rotate": [0, 75, 0], "scale": 0.8)",
};
const std::vector<std::string> kGlassPlacements = {
    R"("translate": [-0.5, 0.9, 0.9], "scale": 0.5)",
    R"("translate": [0.7, 0.8, 1.1], "scale": 0.4)",
};

std::string lightsAndCamera() {
    return R"(
      "camera": {"position": [0, 2.6, 4.2], "target": [0, 0.3, 0], "fov": 50, "near": 0.1, "far": 30},
      "lights": [{"type": "directional", "direction": [-0.4, -1, -0.3], "intensity": 2, "shadows": true},
                 {"type": "spot", "position": [-1.5, 2.5, 1.5], "direction": [0.5, -1, -0.5], "intensity": 6, "range": 6,
                  "innerAngle": 25, "outerAngle": 40, "castsShadow": true},
                 {"type": "point", "position": [1.2, 1.6, -0.6], "intensity": 2, "range": 4, "castsShadow": true}],
      "ambient": 0.05)";
}

const char* kCube = R"("primitive": "cube", "material": {"diffuse": [0.7, 0.4, 0.2], "specular": [0.04, 0.04, 0.04], "roughness": 0.4})";
const char* kGlass = R"("primitive": "sphere", "material": {"diffuse": [0.2, 0.5, 0.8], "opacity": 0.5})";
const char* kFloor = R"({"primitive": "plane", "scale": 6})";

// The scene with each model once and its placements under "instances".
Scene instancedScene() {
    auto list = [](const std::vector<std::string>& placements) {
        std::string s;
        for (const std::string& p : placements) s += (s.empty() ? "{" : ", {") + p + "}";
        return "[" + s + "]";
    };
    const std::string json = std::string("{") + lightsAndCamera() + R"(, "models": [)" + kFloor + ", {" + kCube +
                             R"(, "instances": )" + list(kCubePlacements) + "}, {" + kGlass + R"(, "instances": )" +
                             list(kGlassPlacements) + "}]}";
    return parseScene(json, "instanced.json", true);
}

// The same scene written out: one model entry per placement.
Scene expandedScene() {
    std::string models = kFloor;
    for (const std::string& p : kCubePlacements) models += std::string(", {") + kCube + ", " + p + "}";
    for (const std::string& p : kGlassPlacements) models += std::string(", {") + kGlass + ", " + p + "}";
    return parseScene(std::string("{") + lightsAndCamera() + R"(, "models": [)" + models + "]}", "expanded.json", true);
}

RenderSettings small(RenderPath path, GBufferMode mode) {
    RenderSettings s;
    s.aa.method = AntiAliasing::Off;
    s.aa.dither = false;
    s.autoExposure = false;
    s.width = 64;
    s.height = 48;
    s.keepHdr = true;
    s.renderPath = path;
    s.gbuffer.mode = mode;
    return s;
}

}  // namespace

TEST(Instancing, StoresTheMeshOnceAndDrawsEachPlacement) {
    const Scene instanced = instancedScene(), expanded = expandedScene();
    ASSERT_EQ(instanced.models.size(), 3u);
    ASSERT_EQ(expanded.models.size(), 6u);
    const SceneGpu one(instanced), copies(expanded);
    // Drawn: the floor, three cubes and two spheres either way, with the same matrices.
    ASSERT_EQ(one.meshes.size(), 6u);
    ASSERT_EQ(copies.meshes.size(), 6u);
    for (size_t i = 0; i < 6; ++i) EXPECT_EQ(one.meshes[i].model, copies.meshes[i].model) << "mesh " << i;
    EXPECT_EQ(one.triangleCount, copies.triangleCount);
    // Stored: the cube's and the sphere's vertices once instead of three and two times, whether
    // the copies are instances of one model or model entries of one primitive (their geometry key).
    const size_t plane = instanced.models[0].mesh.vertices.size(), cube = instanced.models[1].mesh.vertices.size(),
                 sphere = instanced.models[2].mesh.vertices.size();
    EXPECT_EQ(one.storedVertices, plane + cube + sphere);
    EXPECT_EQ(copies.storedVertices, plane + cube + sphere);
    EXPECT_EQ(sceneCounts(instanced).storedVertices, one.storedVertices);
    EXPECT_EQ(sceneCounts(expanded).storedVertices, one.storedVertices);
    Scene own = expanded;  // each entry its own vertices, as every scene was stored before
    for (ModelInstance& m : own.models) m.geometryKey.clear();
    const SceneGpu owned(own);
    EXPECT_EQ(owned.storedVertices, plane + 3 * cube + 2 * sphere);
    EXPECT_EQ(sceneCounts(own).storedVertices, owned.storedVertices);
    EXPECT_LT(one.geometryBytes, owned.geometryBytes);
    EXPECT_EQ(one.geometryBytes, copies.geometryBytes);
    for (size_t i : {2u, 3u}) {
        EXPECT_EQ(one.meshes[i].vertices.id(), one.meshes[1].vertices.id()) << "instance " << i;
        EXPECT_EQ(one.meshes[i].vao.id(), one.meshes[1].vao.id()) << "instance " << i;
        EXPECT_EQ(copies.meshes[i].vertices.id(), copies.meshes[1].vertices.id()) << "entry " << i;
        EXPECT_NE(owned.meshes[i].vertices.id(), owned.meshes[1].vertices.id()) << "entry " << i;
    }
    EXPECT_EQ(one.meshes[5].indices.id(), one.meshes[4].indices.id());
    // The materials are the model's, once: every cube instance draws the same one; model entries
    // keep their own (their overrides may differ).
    EXPECT_EQ(one.meshes[2].draws[0].material, one.meshes[1].draws[0].material);
    EXPECT_EQ(one.materials.size(), 3u);
    EXPECT_EQ(copies.materials.size(), 6u);
    // Shadow caster clusters per drawn copy, in the same order.
    ASSERT_EQ(one.casterClusters.size(), copies.casterClusters.size());
    for (size_t i = 0; i < one.casterClusters.size(); ++i) {
        EXPECT_EQ(one.casterClusters[i].model, copies.casterClusters[i].model) << i;
        EXPECT_EQ(one.casterClusters[i].indexCount, copies.casterClusters[i].indexCount) << i;
    }
    glm::vec3 lo1, hi1, lo2, hi2;
    one.bounds(instanced, lo1, hi1);
    copies.bounds(expanded, lo2, hi2);
    EXPECT_EQ(lo1, lo2);
    EXPECT_EQ(hi1, hi2);
}

// Deferred (classic and visibility G-buffer) and forward+, with sun cascades, a spot's and a point
// light's shadows and the transparent pass: the instanced scene's image is the expanded one's, texel
// for texel (the same vertices, matrices and draw order; only where they are stored differs).
TEST(Instancing, RendersWhatTheExpandedSceneRendersInEveryRasterPath) {
    const Scene instanced = instancedScene(), expanded = expandedScene();
    struct Way {
        RenderPath path;
        GBufferMode mode;
        const char* name;
    };
    for (const Way& way : {Way{RenderPath::Deferred, GBufferMode::Classic, "deferred, classic G-buffer"},
                           Way{RenderPath::Deferred, GBufferMode::Visibility, "deferred, visibility buffer"},
                           Way{RenderPath::ForwardPlus, GBufferMode::Classic, "forward+"}}) {
        const RenderSettings s = small(way.path, way.mode);
        const ImageF a = renderHdr(instanced, s), b = renderHdr(expanded, s);
        EXPECT_TRUE(test::imagesNear(a, b, 0.0f, std::string("instanced vs expanded, ") + way.name));
        // Not a blank frame that matches anything: the lit cubes and their shadows are there.
        float lo = 1e30f, hi = 0.0f;
        for (size_t i = 0; i < a.rgba.size(); i += 4) {
            lo = std::min(lo, a.rgba[i + 1]);
            hi = std::max(hi, a.rgba[i + 1]);
        }
        EXPECT_GT(hi, 4.0f * lo + 0.01f) << way.name << ": the frame is flat (" << lo << " .. " << hi << ")";
    }
}

// Each instance casts its own shadow: without the cube's instances the image changes (the test
// above cannot pass on a frame that ignores them).
TEST(Instancing, EveryInstanceIsDrawn) {
    Scene fewer = instancedScene();
    fewer.models[1].instances.pop_back();
    const RenderSettings s = small(RenderPath::Deferred, GBufferMode::Classic);
    EXPECT_FALSE(test::imagesNear(renderHdr(instancedScene(), s), renderHdr(fewer, s), 1e-3f, "three cubes vs two"));
}

TEST(Instancing, PathTracerMatchesTheExpandedScene) {
    const Scene instanced = instancedScene(), expanded = expandedScene();
    RenderSettings s = small(RenderPath::PathTraced, GBufferMode::Classic);
    s.width = 24;
    s.height = 16;
    s.pathTrace.samples = 2;
    EXPECT_TRUE(test::imagesNear(renderHdr(instanced, s), renderHdr(expanded, s), 0.0f, "path traced, instanced vs expanded"));
}

namespace {
// The G-buffer pass alone for a frame whose camera moved since the previous one: its velocity
// target (RG16F), rows bottom first.
std::vector<glm::vec2> velocityAfterCameraStep(const Scene& scene) {
    RenderSettings settings = small(RenderPath::Deferred, GBufferMode::Classic);
    Scene moved = scene;
    const FrameData first = makeFrameData(moved, settings, 0.0f);
    moved.camera.position += glm::vec3(0.2f, 0.1f, -0.25f);
    FrameData frame = makeFrameData(moved, settings, 1.0f / 30.0f);
    applyMotion(frame, motionHistoryOf(first), glm::vec2(0.0f));
    return test::renderGBufferVelocity(moved, frame).velocity;
}
}  // namespace

// Motion vectors: each instance's previous position is its own placement through the previous
// frame's camera, as each copy's is in the expanded scene.
TEST(Instancing, MotionVectorsMatchTheExpandedScene) {
    const std::vector<glm::vec2> a = velocityAfterCameraStep(instancedScene()), b = velocityAfterCameraStep(expandedScene());
    std::vector<float> fa, fb;
    for (const glm::vec2& v : a) fa.insert(fa.end(), {v.x, v.y});
    for (const glm::vec2& v : b) fb.insert(fb.end(), {v.x, v.y});
    EXPECT_TRUE(test::valuesNear(fa, fb, 64, 2, 0.0f, "velocity, instanced vs expanded"));
    float largest = 0.0f;
    for (const glm::vec2& v : a) largest = std::max(largest, glm::length(v));
    EXPECT_GT(largest, 0.01f);  // the camera's step moves every surface
}

// Two model entries naming one OBJ: parsed once, its vertices stored once on the GPU, each entry
// drawn with its own material override, and the image is the one with each entry's own copy.
TEST(Instancing, ModelEntriesOfOneFileShareItsVerticesAndKeepTheirMaterials) {
    const std::string box = test::repoPath("models/cornell_box.obj");
    const Scene scene = parseScene(R"({
      "camera": {"position": [0.2, 0.9, 2.2], "target": [0.2, 0.25, 0], "fov": 50, "near": 0.1, "far": 20},
      "lights": [{"type": "directional", "direction": [-0.3, -1, -0.4], "intensity": 2, "shadows": true}],
      "ambient": 0.05,
      "models": [{"obj": ")" + box + R"(", "translate": [-0.5, 0, 0]},
                 {"obj": ")" + box + R"(", "translate": [0.4, 0, -0.3], "rotate": [0, 40, 0], "material": {"diffuse": [0.1, 0.6, 0.2]}}]})",
                                   "two-boxes.json", true);
    ASSERT_EQ(scene.models.size(), 2u);
    EXPECT_EQ(scene.models[0].geometryKey, scene.models[1].geometryKey);
    Scene own = scene;
    for (ModelInstance& m : own.models) m.geometryKey.clear();
    const SceneGpu shared(scene), separate(own);
    EXPECT_EQ(shared.meshes[1].vertices.id(), shared.meshes[0].vertices.id());
    EXPECT_EQ(shared.storedVertices, scene.models[0].mesh.vertices.size());
    EXPECT_EQ(separate.storedVertices, 2 * scene.models[0].mesh.vertices.size());
    EXPECT_NE(shared.materials[shared.meshes[1].draws[0].material].diffuse,
              shared.materials[shared.meshes[0].draws[0].material].diffuse);  // the override is the second entry's alone
    for (GBufferMode mode : {GBufferMode::Classic, GBufferMode::Visibility}) {
        const RenderSettings s = small(RenderPath::Deferred, mode);
        EXPECT_TRUE(test::imagesNear(renderHdr(scene, s), renderHdr(own, s), 0.0f, std::string("one stored box vs two, ") +
                                                                                   gbufferModeName(mode)));
    }
}

namespace {
// Texels of `a` and `b` that differ by more than `tolerance` x max(1, |value|): at most `allowed`
// of them (a triangle's edge may cover a texel centre in one and not the other when its vertices are
// placed by the CPU in one and by the GPU in the other). On failure: the count and the first one.
testing::AssertionResult nearlyEveryTexelNear(const ImageF& a, const ImageF& b, float tolerance, size_t allowed, const std::string& what) {
    if (a.width != b.width || a.height != b.height) return testing::AssertionFailure() << what << ": sizes differ";
    size_t differing = 0;
    std::string first;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            for (int c = 0; c < 4; ++c) {
                const size_t i = (size_t(y) * size_t(a.width) + size_t(x)) * 4 + size_t(c);
                const float va = a.rgba[i], vb = b.rgba[i];
                if (!(std::abs(va - vb) <= tolerance * std::max({1.0f, std::abs(va), std::abs(vb)}))) {
                    if (differing++ == 0)
                        first = "texel (" + std::to_string(x) + ", " + std::to_string(y) + ") channel " + std::to_string(c) + ": " +
                                std::to_string(va) + " vs " + std::to_string(vb);
                    break;
                }
            }
    if (differing <= allowed) return testing::AssertionSuccess();
    return testing::AssertionFailure() << what << ": " << differing << " texels differ by more than " << tolerance << " (allowed "
                                       << allowed << "); the first: " << first;
}

Scene gltfScene(const std::string& file) {
    return parseScene(R"({
      "camera": {"position": [0.5, 2.8, 4.5], "target": [0, 0.3, 0], "fov": 45, "near": 0.1, "far": 30},
      "lights": [{"type": "directional", "direction": [-0.4, -1, -0.3], "intensity": 2, "shadows": true},
                 {"type": "spot", "position": [-1.5, 2.5, 1.5], "direction": [0.5, -1, -0.5], "intensity": 6, "range": 6,
                  "innerAngle": 25, "outerAngle": 40, "castsShadow": true}],
      "ambient": 0.05,
      "models": [{"gltf": ")" + test::repoPath("tests/data/gltf/" + file) + R"("}]})",
                      file + ".json", true);
}
}  // namespace

// glTF node reuse: the box five nodes draw, stored once and drawn per node, renders what the file
// with a mesh entry per node (every node baked) renders, in both G-buffer modes and forward+.
TEST(Instancing, GltfNodeReuseRendersTheExpandedFile) {
    const Scene reused = gltfScene("node_reuse.gltf"), expanded = gltfScene("node_reuse_expanded.gltf");
    ASSERT_EQ(reused.models.size(), 2u);
    ASSERT_EQ(expanded.models.size(), 1u);
    const SceneGpu one(reused), baked(expanded);
    EXPECT_EQ(one.storedVertices, 4u + 24u + 24u);   // the floor, the mirrored box, the reused box once
    EXPECT_EQ(baked.storedVertices, 4u + 5u * 24u);  // the floor and five boxes
    EXPECT_EQ(one.triangleCount, baked.triangleCount);
    for (const auto& [path, mode, name] : {std::tuple{RenderPath::Deferred, GBufferMode::Classic, "deferred, classic"},
                                           std::tuple{RenderPath::Deferred, GBufferMode::Visibility, "deferred, visibility"},
                                           std::tuple{RenderPath::ForwardPlus, GBufferMode::Classic, "forward+"}}) {
        RenderSettings s = small(path, mode);
        s.width = 96;
        s.height = 72;
        // 1e-3 relative: the box's vertices placed by the GPU's matrix instead of baked on the CPU
        // differ in the last bits; 1% of the texels: edges that cover a texel centre in one only.
        EXPECT_TRUE(nearlyEveryTexelNear(renderHdr(reused, s), renderHdr(expanded, s), 1e-3f, size_t(s.width * s.height / 100),
                                         std::string("node reuse vs expanded, ") + name));
    }
}

// EXT_mesh_gpu_instancing: the box's five instances, stored once, render what the same placements
// written as child nodes (baked) render.
TEST(Instancing, GltfGpuInstancingRendersTheExpandedFile) {
    const Scene instanced = gltfScene("gpu_instancing.gltf"), expanded = gltfScene("gpu_instancing_expanded.gltf");
    ASSERT_EQ(instanced.models.size(), 2u);
    EXPECT_EQ(instanced.models[1].instanceCount(), 5u);
    const SceneGpu one(instanced), baked(expanded);
    EXPECT_EQ(one.storedVertices, 4u + 24u);
    EXPECT_EQ(baked.storedVertices, 4u + 5u * 24u);
    for (GBufferMode mode : {GBufferMode::Classic, GBufferMode::Visibility}) {
        RenderSettings s = small(RenderPath::Deferred, mode);
        s.width = 96;
        s.height = 72;
        EXPECT_TRUE(nearlyEveryTexelNear(renderHdr(instanced, s), renderHdr(expanded, s), 1e-3f, size_t(s.width * s.height / 100),
                                         std::string("EXT_mesh_gpu_instancing vs child nodes, ") + gbufferModeName(mode)));
    }
}
