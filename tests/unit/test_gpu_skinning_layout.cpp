// What the skinning pass reads, laid out on the CPU (engine/render/gpu_skinning.hpp): the packed
// pose puts each skin's joint matrices, an unskinned node's world and normal matrix and the morph
// weights where the ranges' records point, and the joint-transformed bounds are exact for a rigid
// range and follow a morph weight of either sign.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "engine/render/gpu_skinning.hpp"

namespace lp {
namespace {

// Two ranges: vertices 0-1 skinned to a two-joint skin, vertices 2-4 placed by node 2, which has
// two morph targets (only the second moves: +1 in y at vertex 3).
NodeAnimation twoRanges() {
    NodeAnimation a;
    AnimatedNode root, joint, rigid;
    joint.parent = 0;
    joint.translation = glm::vec3(1.0f, 0.0f, 0.0f);
    rigid.translation = glm::vec3(0.0f, 0.0f, 3.0f);
    rigid.scale = glm::vec3(2.0f, 1.0f, 1.0f);
    rigid.weights = {0.0f, 0.0f};
    a.nodes = {root, joint, rigid};
    a.order = {0, 1, 2};
    Skin s;
    s.joints = {0, 1};
    s.inverseBind = {glm::mat4(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(-1.0f, 0.0f, 0.0f))};
    a.skins.push_back(s);
    for (int i = 0; i < 5; ++i) {
        Vertex v;
        v.position = glm::vec3(float(i), 0.0f, 0.0f);
        a.restLocal.push_back(v);
    }
    NodeVertexRange skinned;
    skinned.node = 1;
    skinned.vertexCount = 2;
    skinned.skin = 0;
    a.ranges.push_back(skinned);
    VertexJoints j0, j1;
    j0.weight[0] = 1.0f;
    j1.joint[0] = 1;
    j1.weight[0] = 1.0f;
    a.vertexJoints = {j0, j1};
    NodeVertexRange placed;
    placed.node = 2;
    placed.firstVertex = 2;
    placed.vertexCount = 3;
    placed.firstLocal = 2;
    placed.morphTargets = 2;
    a.ranges.push_back(placed);
    a.morphDeltas.assign(6, MorphDelta{});
    a.morphDeltas[3 + 1].position = glm::vec3(0.0f, 1.0f, 0.0f);  // target 1, vertex 1 of the range
    return a;
}

}  // namespace

TEST(GpuSkinningLayout, PackedPoseIsWhereTheRangesPoint) {
    const NodeAnimation a = twoRanges();
    const SkinningLayout layout = makeSkinningLayout(a);
    ASSERT_EQ(layout.ranges.size(), 2u);
    EXPECT_EQ(layout.workCount(), 5u);
    EXPECT_EQ(layout.matrixCount, 4u);  // 2 joints + the rigid node's world and normal matrix
    EXPECT_EQ(layout.weightCount, 2u);
    EXPECT_EQ(layout.ranges[1].firstWork, 2u);
    EXPECT_EQ(layout.ranges[0].flags, kSkinningRangeSkinned);
    EXPECT_EQ(layout.workRange, (std::vector<uint32_t>{0, 0, 1, 1, 1}));
    EXPECT_EQ(layout.joints[1].joint0.x, 1u);
    EXPECT_EQ(layout.joints[1].weight0.x, 1.0f);

    NodePose pose = animatedPose(a, {}, 0.0);
    pose.weights[2] = {0.25f, -0.5f};
    const std::vector<glm::vec4> packed = packSkinningPose(a, layout, pose, usedJointMatrices(a, pose));
    auto matrix = [&](uint32_t m) { return glm::mat4(packed[4 * m], packed[4 * m + 1], packed[4 * m + 2], packed[4 * m + 3]); };
    const std::vector<glm::mat4> joints = jointMatrices(a.skins[0], pose.worlds);
    EXPECT_EQ(matrix(layout.skinFirstMatrix[0] + 1), joints[1]);
    EXPECT_EQ(matrix(layout.ranges[1].firstMatrix), pose.worlds[2]);
    EXPECT_EQ(glm::mat3(matrix(layout.ranges[1].firstMatrix + 1)), glm::inverseTranspose(glm::mat3(pose.worlds[2])));
    const float* weights = &packed[0].x + skinningWeightBase(layout);
    EXPECT_EQ(weights[layout.ranges[1].firstWeight], 0.25f);
    EXPECT_EQ(weights[layout.ranges[1].firstWeight + 1], -0.5f);
}

TEST(GpuSkinningLayout, BoundsAreExactForARigidRangeAndFollowAMorphWeight) {
    const NodeAnimation a = twoRanges();
    std::vector<Vertex> vertices = a.restLocal;
    const std::vector<uint32_t> indices = {2, 3, 4};  // the rigid range alone
    const PoseBounds bounds = makePoseBounds(a, vertices, vertexRanges(a, vertices.size()), indices, 0, 3);
    NodePose pose = animatedPose(a, {}, 0.0);
    for (float w : {0.0f, 0.5f, -0.5f}) {
        SCOPED_TRACE(w);
        pose.weights[2] = {0.0f, w};
        glm::vec3 lo, hi;
        poseBoundsBox(bounds, a, pose, usedJointMatrices(a, pose), lo, hi);
        std::vector<Vertex> posed = vertices;
        poseVertices(a, pose, posed);
        glm::vec3 exactLo(1e30f), exactHi(-1e30f);
        for (uint32_t v : indices) {
            exactLo = glm::min(exactLo, posed[v].position);
            exactHi = glm::max(exactHi, posed[v].position);
        }
        EXPECT_EQ(lo, exactLo);
        EXPECT_EQ(hi, exactHi);
    }
}

}  // namespace lp
