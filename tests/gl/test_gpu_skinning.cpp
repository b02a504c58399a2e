// Skinning and morphing on the GPU (--skinning gpu, passes/skinning_pass): the skinning pass's
// posed vertices against poseVertices (the CPU reference, engine/scene/animation.cpp) within 1e-5
// for a two-joint skin bent 90 degrees, a morph target at weight 0.5, both together, and the
// animated test models; the previous positions it keeps or poses for motion vectors; bounds that
// contain every posed vertex; and the pass's place in the frame graph.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/graph/texture_pool.hpp"
#include "engine/render/scene_gpu.hpp"
#include "engine/scene/animation.hpp"
#include "engine/scene/scene_loader.hpp"
#include "frame/frame_builder.hpp"
#include "passes/skinning_pass.hpp"
#include "tests/gl/gl_fixture.hpp"

namespace lp {
namespace {

constexpr float kTolerance = 1e-5f;

// What the vertex buffer and the previous positions of mesh `mesh` hold.
struct PosedBuffers {
    std::vector<GpuVertex> vertices;
    std::vector<glm::vec4> previous;
};
PosedBuffers readBack(const SceneGpu& gpu, size_t mesh) {
    const GpuMesh& m = gpu.meshes[mesh];
    GLint bytes = 0;
    glGetNamedBufferParameteriv(m.vertices.id(), GL_BUFFER_SIZE, &bytes);
    PosedBuffers out;
    out.vertices.resize(size_t(bytes) / sizeof(GpuVertex));
    glGetNamedBufferSubData(m.vertices.id(), 0, bytes, out.vertices.data());
    out.previous.resize(out.vertices.size());
    glGetNamedBufferSubData(m.previousPositions.id(), 0, GLsizeiptr(out.previous.size() * sizeof(glm::vec4)), out.previous.data());
    return out;
}

// Poses `scene` at `time` after `previousTime` as the Renderer does with --skinning gpu: SceneGpu::pose,
// then a graph of the skinning pass and a pass that reads its vertices (as the G-buffer would).
// Returns whether the skinning pass ran.
bool poseOnGpu(const Scene& scene, SceneGpu& gpu, SkinningPass& state, double time, double previousTime) {
    gpu.pose(scene, time, previousTime, SkinningMode::Gpu);
    RenderSettings settings;
    settings.skinning = SkinningMode::Gpu;
    gl::ShaderLibrary shaders;
    FrameData frame = makeFrameData(scene, settings, float(time));
    frame.gpu = &gpu;
    frame.shaders = &shaders;
    fg::FrameGraph graph;
    if (!skinningSkipReason(frame).empty()) return false;
    addSkinningPass(graph, state, frame);
    frame.posedVerticesOnGpu = true;
    fg::ResourceId out;
    graph.addPass(
        "reader", fg::PassKind::Compute,
        [&](fg::PassBuilder& b) {
            readPosedVertices(b, frame);
            out = b.create("out", {1, 1, GL_RGBA8}, fg::Usage::Transfer);
        },
        [](const fg::PassResources&) {});
    graph.markOutput(out);
    graph.compile();
    fg::TexturePool pool;
    graph.execute(pool);
    EXPECT_TRUE(graph.isLive("skinning"));
    EXPECT_NE(graph.barriersBefore("reader") & GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT, 0u);  // the draws see the posed vertices
    return true;
}

// The CPU reference: the model's vertices as loaded, posed by poseVertices at `time`.
std::vector<Vertex> posedOnCpu(const ModelInstance& model, double time) {
    std::vector<Vertex> v = model.mesh.vertices;
    poseVertices(*model.animation, animatedPose(*model.animation, model.playingClips, time), v);
    return v;
}

// Every vertex of every moving range: position, normal, tangent (and handedness) within kTolerance.
void expectPosedLike(const std::vector<GpuVertex>& gpu, const std::vector<Vertex>& cpu, const NodeAnimation& animation) {
    ASSERT_EQ(gpu.size(), cpu.size());
    float worst = 0.0f;
    size_t checked = 0;
    for (const NodeVertexRange& r : animation.ranges)
        for (uint32_t k = r.firstVertex; k < r.firstVertex + r.vertexCount; ++k) {
            const float d = std::max({glm::length(gpu[k].position - cpu[k].position), glm::length(gpu[k].normal - cpu[k].normal),
                                      glm::length(glm::vec3(gpu[k].tangent) - glm::vec3(cpu[k].tangent))});
            EXPECT_LT(d, kTolerance) << "vertex " << k << ": position (" << gpu[k].position.x << ", " << gpu[k].position.y << ", "
                                     << gpu[k].position.z << ") against (" << cpu[k].position.x << ", " << cpu[k].position.y << ", "
                                     << cpu[k].position.z << ")";
            EXPECT_EQ(gpu[k].tangent.w, cpu[k].tangent.w) << "vertex " << k;
            worst = std::max(worst, d);
            ++checked;
        }
    EXPECT_GT(checked, 0u);
    ::testing::Test::RecordProperty("worst_difference", std::to_string(worst));
}

// A strip of 2 x 9 vertices along +x from 0 to 2 (normals +y, tangents +x): joint 0 at the origin,
// joint 1 at x = 1, rotated 90 degrees about +z over the clip's second; vertices blend from joint 0
// to joint 1 between x = 0.75 and 1.25. With `morph`, one target lifts the strip, tilts its normals
// and tangents: skinned, weight 0.5 at rest, animated to 1 with the bend; unskinned, 0 at rest and
// held at 0.5 by the clip. Without `skin` the node itself places the strip.
ModelInstance strip(bool skin, bool morph) {
    auto a = std::make_shared<NodeAnimation>();
    MeshData mesh;
    for (int i = 0; i < 9; ++i)
        for (int side = 0; side < 2; ++side) {
            Vertex v;
            v.position = glm::vec3(0.25f * float(i), 0.0f, side ? 0.2f : -0.2f);
            v.normal = glm::vec3(0.0f, 1.0f, 0.0f);
            v.tangent = glm::vec4(1.0f, 0.0f, 0.0f, side ? 1.0f : -1.0f);
            mesh.vertices.push_back(v);
        }
    for (uint32_t i = 0; i + 1 < 9; ++i) {
        const uint32_t q[4] = {2 * i, 2 * i + 1, 2 * i + 2, 2 * i + 3};
        for (uint32_t k : {q[0], q[1], q[2], q[2], q[1], q[3]}) mesh.indices.push_back(k);
    }
    mesh.subMeshes.push_back({0, uint32_t(mesh.indices.size()), 0});
    mesh.materials.emplace_back();
    mesh.boundsMin = glm::vec3(0.0f, 0.0f, -0.2f);
    mesh.boundsMax = glm::vec3(2.0f, 0.0f, 0.2f);
    const uint32_t count = uint32_t(mesh.vertices.size());
    AnimationClip clip;
    clip.name = "bend";
    clip.duration = 1.0f;
    AnimationSampler rotate;
    rotate.times = {0.0f, 1.0f};
    const glm::quat bent = glm::angleAxis(glm::radians(90.0f), glm::vec3(0.0f, 0.0f, 1.0f));
    rotate.values = {glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), glm::vec4(bent.x, bent.y, bent.z, bent.w)};
    a->restLocal = mesh.vertices;
    NodeVertexRange range;
    range.vertexCount = count;
    if (skin) {
        AnimatedNode root, elbow, meshNode;
        elbow.parent = 0;
        elbow.translation = glm::vec3(1.0f, 0.0f, 0.0f);
        meshNode.translation = glm::vec3(0.0f, 5.0f, 0.0f);  // a skin ignores it
        if (morph) meshNode.weights = {0.5f};
        a->nodes = {root, elbow, meshNode};
        a->order = {0, 1, 2};
        Skin s;
        s.joints = {0, 1};
        s.inverseBind = {glm::mat4(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(-1.0f, 0.0f, 0.0f))};
        a->skins.push_back(s);
        range.node = 2;
        range.skin = 0;
        for (const Vertex& v : mesh.vertices) {
            VertexJoints j;
            const float t = glm::clamp((v.position.x - 0.75f) / 0.5f, 0.0f, 1.0f);
            j.joint[0] = 0;
            j.weight[0] = 1.0f - t;
            j.joint[1] = 1;
            j.weight[1] = t;
            a->vertexJoints.push_back(j);
        }
        clip.samplers.push_back(rotate);
        clip.channels.push_back({1, AnimationPath::Rotation, 0});
    } else {
        AnimatedNode node;
        node.translation = glm::vec3(0.0f, 0.5f, 0.0f);
        node.weights = {0.0f};  // at rest unmorphed: the buffers start without the target
        a->nodes = {node};
        a->order = {0};
    }
    if (morph) {
        range.morphTargets = 1;
        for (const Vertex& v : mesh.vertices) {
            MorphDelta d;
            d.position = glm::vec3(0.0f, 0.3f * v.position.x, 0.1f);
            d.normal = glm::vec3(-0.4f, 0.0f, 0.2f);
            d.tangent = glm::vec3(0.0f, 0.5f, -0.1f);
            a->morphDeltas.push_back(d);
        }
        if (skin) {  // the weight runs 0.5 -> 1 with the bend
            AnimationSampler w;
            w.times = {0.0f, 1.0f};
            w.weights = {0.5f, 1.0f};
            w.weightCount = 1;
            clip.channels.push_back({2, AnimationPath::Weights, int(clip.samplers.size())});
            clip.samplers.push_back(w);
        } else {  // held at 0.5 (STEP) by the node's weights channel
            AnimationSampler w;
            w.interpolation = AnimationInterpolation::Step;
            w.times = {0.0f, 1.0f};
            w.weights = {0.5f, 0.5f};
            w.weightCount = 1;
            clip.channels.push_back({0, AnimationPath::Weights, 0});
            clip.samplers.push_back(w);
        }
    }
    a->ranges.push_back(range);
    a->clips.push_back(clip);
    // The rest pose, as the loader places it.
    poseVertices(*a, animatedNodeWorlds(*a, {}, 0.0), mesh.vertices);
    ModelInstance m;
    m.name = skin ? (morph ? "skin_morph" : "skin") : "morph";
    m.mesh = std::move(mesh);
    m.animation = a;
    m.playingClips = {0};
    return m;
}

Scene sceneOf(ModelInstance model) {
    Scene s;
    s.models.push_back(std::move(model));
    s.camera.position = {1.0f, 1.0f, 4.0f};
    s.camera.target = {1.0f, 0.0f, 0.0f};
    return s;
}

// Posed on the GPU at `time` (after `previous`) equals the CPU reference; the previous positions
// equal the reference's at `previous`.
void expectGpuPoseMatchesCpu(const Scene& scene, double time, double previous) {
    SceneGpu gpu(scene);
    SkinningPass state;
    ASSERT_TRUE(poseOnGpu(scene, gpu, state, time, previous));
    const ModelInstance& model = scene.models[0];
    const PosedBuffers b = readBack(gpu, 0);
    expectPosedLike(b.vertices, posedOnCpu(model, time), *model.animation);
    const std::vector<Vertex> before = posedOnCpu(model, previous);
    for (const NodeVertexRange& r : model.animation->ranges)
        for (uint32_t k = r.firstVertex; k < r.firstVertex + r.vertexCount; ++k)
            EXPECT_LT(glm::length(glm::vec3(b.previous[k]) - before[k].position), kTolerance) << "previous position of vertex " << k;
}

}  // namespace

TEST(GpuSkinning, TwoJointSkinBentNinetyDegreesMatchesTheCpu) {
    const Scene scene = sceneOf(strip(true, false));
    expectGpuPoseMatchesCpu(scene, 0.999, 0.5);  // nearly 90 degrees; the previous frame halfway
    // The bend is real: the far end has swung up to about (1, 1, z).
    SceneGpu gpu(scene);
    SkinningPass state;
    ASSERT_TRUE(poseOnGpu(scene, gpu, state, 0.999, 0.999));
    const PosedBuffers b = readBack(gpu, 0);
    EXPECT_NEAR(b.vertices[16].position.x, 1.0f, 0.01f);
    EXPECT_NEAR(b.vertices[16].position.y, 1.0f, 0.01f);
    EXPECT_NEAR(b.vertices[16].tangent.y, 1.0f, 0.01f);  // the tangent turned with the joint
}

TEST(GpuSkinning, MorphAtHalfWeightMatchesTheCpu) {
    const Scene scene = sceneOf(strip(false, true));
    expectGpuPoseMatchesCpu(scene, 0.25, 0.25);
    // Morphed by the pass: the far end is lifted by half its 0.6 m delta above the node's 0.5 m.
    SceneGpu gpu(scene);
    SkinningPass state;
    ASSERT_TRUE(poseOnGpu(scene, gpu, state, 0.25, 0.25));
    EXPECT_NEAR(readBack(gpu, 0).vertices[16].position.y, 0.5f + 0.5f * 0.6f, 1e-5f);
}

TEST(GpuSkinning, SkinAndMorphTogetherMatchTheCpu) { expectGpuPoseMatchesCpu(sceneOf(strip(true, true)), 0.7, 0.6); }

// The animated test models, loaded as --model loads them: node animation (animated_grid: every
// range placed by its node's world matrix, done on the GPU too) and skin + morph (skinned_grid).
TEST(GpuSkinning, AnimatedTestModelsMatchTheCpu) {
    for (const char* file : {"tests/data/gltf/animated_grid.gltf", "tests/data/gltf/skinned_grid.gltf"}) {
        SCOPED_TRACE(file);
        const Scene scene = sceneForModel(test::repoPath(file));
        ASSERT_EQ(scene.models.size(), 1u);
        ASSERT_TRUE(scene.models[0].animation);
        expectGpuPoseMatchesCpu(scene, 0.8, 0.8 - 1.0 / 30.0);
    }
}

// Playing on, the dispatch that poses a frame keeps the vertex buffer's positions as the previous
// ones (no second pose); a frame whose pose the buffers hold runs no pass; a jump poses both.
TEST(GpuSkinning, PlayingOnKeepsTheLastPoseAsThePreviousOne) {
    const Scene scene = sceneForModel(test::repoPath("tests/data/gltf/skinned_grid.gltf"));
    const ModelInstance& model = scene.models[0];
    SceneGpu gpu(scene);
    SkinningPass state;
    ASSERT_TRUE(poseOnGpu(scene, gpu, state, 0.3, 0.2));
    EXPECT_EQ(gpu.skinningWork().size(), 2u);  // the first frame poses both times
    ASSERT_TRUE(poseOnGpu(scene, gpu, state, 0.4, 0.3));
    ASSERT_EQ(gpu.skinningWork().size(), 1u);
    EXPECT_EQ(gpu.skinningWork()[0].mode, kSkinningPoseVertices | kSkinningKeepPrevious);
    PosedBuffers b = readBack(gpu, 0);
    expectPosedLike(b.vertices, posedOnCpu(model, 0.4), *model.animation);
    const std::vector<Vertex> at03 = posedOnCpu(model, 0.3);
    for (const NodeVertexRange& r : model.animation->ranges)
        for (uint32_t k = r.firstVertex; k < r.firstVertex + r.vertexCount; ++k)
            ASSERT_LT(glm::length(glm::vec3(b.previous[k]) - at03[k].position), kTolerance) << k;
    EXPECT_FALSE(poseOnGpu(scene, gpu, state, 0.4, 0.3));  // held: nothing to do
    ASSERT_TRUE(poseOnGpu(scene, gpu, state, 0.9, 0.85));   // a jump
    EXPECT_EQ(gpu.skinningWork().size(), 2u);
    expectPosedLike(readBack(gpu, 0).vertices, posedOnCpu(model, 0.9), *model.animation);
}

// The bounds the GPU mode keeps without the posed vertices (joint-transformed rest boxes) contain
// every posed vertex, for the casters (shadow culling) and the whole mesh (the cascades' fit).
TEST(GpuSkinning, JointTransformedBoundsContainThePose) {
    for (const Scene& scene : {sceneOf(strip(true, true)), sceneForModel(test::repoPath("tests/data/gltf/skinned_grid.gltf"))}) {
        SceneGpu gpu(scene);
        SkinningPass state;
        ASSERT_TRUE(poseOnGpu(scene, gpu, state, 0.999, 0.999));
        const std::vector<Vertex> posed = posedOnCpu(scene.models[0], 0.999);
        const MeshData& mesh = scene.models[0].mesh;
        const float slack = 1e-4f;
        auto inside = [&](glm::vec3 p, glm::vec3 lo, glm::vec3 hi) {
            return glm::all(glm::greaterThanEqual(p, lo - slack)) && glm::all(glm::lessThanEqual(p, hi + slack));
        };
        ASSERT_FALSE(gpu.casterClusters.empty());
        for (const CasterCluster& c : gpu.casterClusters)
            for (uint32_t k = c.firstIndex; k < c.firstIndex + c.indexCount; ++k)
                ASSERT_TRUE(inside(posed[mesh.indices[k]].position, c.boundsMin, c.boundsMax)) << "index " << k;
        for (uint32_t v : mesh.indices) ASSERT_TRUE(inside(posed[v].position, gpu.meshes[0].boundsMin, gpu.meshes[0].boundsMax)) << v;
    }
    // The bent strip's bounds followed the pose: its far end is now about 1 m up.
    const Scene bent = sceneOf(strip(true, false));
    SceneGpu gpu(bent);
    SkinningPass state;
    ASSERT_TRUE(poseOnGpu(bent, gpu, state, 0.999, 0.999));
    glm::vec3 lo, hi;
    gpu.bounds(bent, lo, hi);
    EXPECT_GT(hi.y, 0.95f);
    EXPECT_LT(hi.x, 1.3f);
}

// The frame's graph: the skinning pass runs before the passes that draw the meshes when a model
// animates its vertices; for a static scene (or --skinning cpu, or nothing to pose) it is skipped with why.
TEST(GpuSkinning, PassIsInTheGraphOnlyWhenSomethingIsAnimated) {
    auto explainSkinning = [](const Scene& scene, SkinningMode mode, bool poseFirst) {
        RenderSettings settings;
        settings.width = 32;
        settings.height = 24;
        settings.skinning = mode;
        SceneGpu gpu(scene);
        if (poseFirst) gpu.pose(scene, 0.5, 0.5, mode);
        gl::ShaderLibrary shaders;
        FrameData frame = makeFrameData(scene, settings, 0.5f);
        frame.gpu = &gpu;
        frame.shaders = &shaders;
        fg::FrameGraph graph;
        PassStates passes;
        buildFrameGraph(graph, passes, frame);
        graph.compile();
        for (const fg::PassDecision& d : graph.explain())
            if (d.name == "skinning") return std::make_pair(d.runs, d.reason);
        return std::make_pair(false, std::string("absent"));
    };
    Scene still = sceneOf(strip(true, true));
    still.models[0].playingClips.clear();
    const auto [stillRuns, stillWhy] = explainSkinning(still, SkinningMode::Gpu, true);
    EXPECT_FALSE(stillRuns);
    EXPECT_NE(stillWhy.find("nothing is animated"), std::string::npos) << stillWhy;
    const Scene moving = sceneOf(strip(true, true));
    EXPECT_TRUE(explainSkinning(moving, SkinningMode::Gpu, true).first);
    const auto [cpuRuns, cpuWhy] = explainSkinning(moving, SkinningMode::Cpu, true);
    EXPECT_FALSE(cpuRuns);
    EXPECT_NE(cpuWhy.find("--skinning cpu"), std::string::npos) << cpuWhy;
}

}  // namespace lp
