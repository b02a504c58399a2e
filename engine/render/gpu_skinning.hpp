#pragma once
// Skinning and morphing on the GPU (--skinning gpu, docs/motion.md "Skinning on the GPU"): what an
// animated model's skinning compute pass (shaders/skinning.comp) reads, laid out on the CPU. At load
// the rest vertices, joints and weights, morph deltas and one record a NodeVertexRange go to storage
// buffers once; each frame only a pose's matrices (skin joint matrices; an unskinned range's world
// and normal matrix) and morph weights are packed (packSkinningPose) and uploaded. The shader then
// does poseVertices' arithmetic, vertex by vertex. Also the bounds of posed vertices without the
// posed vertices: each joint's rest box of the vertices it moves, morphed by interval arithmetic and
// carried through the joint matrix (a skinned vertex is a convex combination of its joints'
// transforms of it, so it lies in the union of those boxes).
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "engine/scene/animation.hpp"

namespace lp {

// Bindings of shaders/skinning.comp's storage blocks (passed as LP_SKINNING_*_BINDING defines).
constexpr unsigned kSkinningRestBinding = 0;
constexpr unsigned kSkinningJointsBinding = 1;
constexpr unsigned kSkinningDeltasBinding = 2;
constexpr unsigned kSkinningRangesBinding = 3;
constexpr unsigned kSkinningWorkRangeBinding = 4;
constexpr unsigned kSkinningPoseBinding = 5;
constexpr unsigned kSkinningVerticesBinding = 6;
constexpr unsigned kSkinningPreviousBinding = 7;

// What one dispatch writes (its uMode, LP_SKINNING_* defines): the pose into the vertex buffer
// (positions, normals, tangents), the pose's positions into the previous positions, and before
// posing into the vertex buffer, the positions it held into the previous positions (playing on,
// the last frame's pose is this frame's previous one: kept, not posed again).
constexpr unsigned kSkinningPoseVertices = 1u;
constexpr unsigned kSkinningPosePrevious = 2u;
constexpr unsigned kSkinningKeepPrevious = 4u;

// One record a NodeVertexRange, std430 (shaders/skinning.comp's Range).
struct SkinningRange {
    uint32_t firstVertex = 0;   // into the mesh's vertex buffer
    uint32_t vertexCount = 0;
    uint32_t firstWork = 0;     // into the rest / joints arrays (the ranges' vertices back to back)
    uint32_t firstDelta = 0;    // NodeVertexRange::firstDelta
    uint32_t morphTargets = 0;  // targets with a weight (min of the primitive's and the node's)
    uint32_t firstWeight = 0;   // into the pose's weights
    uint32_t firstMatrix = 0;   // into the pose's matrices: the skin's joint 0, or the node's world (its normal matrix next)
    uint32_t flags = 0;         // kSkinningRangeSkinned, kSkinningRangeMirrored
};
constexpr uint32_t kSkinningRangeSkinned = 1u;
constexpr uint32_t kSkinningRangeMirrored = 2u;

struct SkinningRestVertex {  // std430 (RestVertex): the morph base, in the node's (or the skin's) space
    glm::vec4 position, normal, tangent;
};
struct SkinningVertexJoints {  // std430 (VertexJoints): VertexJoints' eight, zero for an unskinned range
    glm::uvec4 joint0, joint1;
    glm::vec4 weight0, weight1;
};
struct SkinningDelta {  // std430 (MorphDelta)
    glm::vec4 position, normal, tangent;
};

// Everything the shader reads that never changes, and where each pose's values go.
struct SkinningLayout {
    std::vector<SkinningRange> ranges;
    std::vector<uint32_t> workRange;  // a work item's range (index into ranges)
    std::vector<SkinningRestVertex> rest;
    std::vector<SkinningVertexJoints> joints;
    std::vector<SkinningDelta> deltas;
    std::vector<uint32_t> skinFirstMatrix;  // a skin's joint 0 in the pose's matrices (used skins only)
    uint32_t matrixCount = 0;               // mat4s a pose holds
    uint32_t weightCount = 0;               // floats a pose holds
    uint32_t workCount() const { return uint32_t(workRange.size()); }
};
SkinningLayout makeSkinningLayout(const NodeAnimation& animation);

// A pose as the shader reads it, in vec4s: the matrices (four columns each), then the weights
// (four a vec4), padded.
// jointMatrices: every skin's for the pose (jointMatrices(skin, pose.worlds)); empty for a skin no range uses.
std::vector<glm::vec4> packSkinningPose(const NodeAnimation& animation, const SkinningLayout& layout, const NodePose& pose,
                                        const std::vector<std::vector<glm::mat4>>& jointMatrices);
// Every skin's joint matrices in `pose` that some range of `animation` uses (poseVertices' first step).
std::vector<std::vector<glm::mat4>> usedJointMatrices(const NodeAnimation& animation, const NodePose& pose);
// Where in a packed pose the weights begin, in floats.
inline uint32_t skinningWeightBase(const SkinningLayout& layout) { return layout.matrixCount * 16u; }

// Conservative bounds of a set of a mesh's vertices in any pose (see the header's comment): one part
// a (range, joint) the vertices touch with a nonzero weight, plus their vertices outside every range.
struct PoseBoundsPart {
    int range = -1;          // -1: vertices no range moves (fixed in the mesh's space)
    int joint = -1;          // the skin's joint; -1: the node's world matrix (unskinned), or identity (skinned, all weights 0)
    glm::vec3 lo{0.0f}, hi{0.0f};  // rest positions
    std::vector<glm::vec3> deltaLo, deltaHi;  // per morph target, the box of the vertices' position deltas
};
struct PoseBounds {
    std::vector<PoseBoundsPart> parts;
    bool empty() const { return parts.empty(); }
};
// Which range moves each of a mesh's `vertexCount` vertices (index into animation.ranges; -1: none).
std::vector<int> vertexRanges(const NodeAnimation& animation, size_t vertexCount);
// The bounds of mesh vertices `indices[first, first + count)` refer to (`vertices`: the mesh's, as
// loaded; `ranges`: vertexRanges of them).
PoseBounds makePoseBounds(const NodeAnimation& animation, const std::vector<Vertex>& vertices, const std::vector<int>& ranges,
                          const std::vector<uint32_t>& indices, uint32_t first, uint32_t count);
// The box in `pose` (mesh space); jointMatrices: every skin's (jointMatrices(skin, pose.worlds)). lo > hi when empty.
void poseBoundsBox(const PoseBounds& bounds, const NodeAnimation& animation, const NodePose& pose,
                   const std::vector<std::vector<glm::mat4>>& jointMatrices, glm::vec3& lo, glm::vec3& hi);

}  // namespace lp
