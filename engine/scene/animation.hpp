#pragma once
// glTF animation (docs/models-and-materials.md, "Animation"): keyframe clips on node translation,
// rotation, scale and morph weights, the node hierarchy they move, skins and morph targets, and the
// vertices each moving, skinned or morphed node draws, kept in their own space so that any pose can
// be placed. CPU math, no GL: the renderer
// poses vertices with it (SceneGpu::pose) and the tests check it against the specification.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/scene/mesh.hpp"

namespace lp {

// A sampler's interpolation, as glTF spells it (one table: kAnimationInterpolationNames).
enum class AnimationInterpolation { Linear, Step, CubicSpline };
// What a channel moves.
enum class AnimationPath { Translation, Rotation, Scale, Weights };

struct AnimationInterpolationName {
    AnimationInterpolation interpolation;
    const char* name;
};
inline constexpr AnimationInterpolationName kAnimationInterpolationNames[] = {
    {AnimationInterpolation::Linear, "LINEAR"}, {AnimationInterpolation::Step, "STEP"}, {AnimationInterpolation::CubicSpline, "CUBICSPLINE"}};

struct AnimationSampler {
    AnimationInterpolation interpolation = AnimationInterpolation::Linear;
    std::vector<float> times;  // seconds, finite, strictly increasing, at least one
    // One value a key (LINEAR, STEP) or three (CUBICSPLINE: in-tangent, value, out-tangent, the
    // spec's order). xyz for translation and scale; a rotation's quaternion as (x, y, z, w).
    std::vector<glm::vec4> values;
    // A `weights` channel's values instead: `weightCount` floats a value, the values in the order
    // above (CUBICSPLINE: the in-tangents of all weights, their values, their out-tangents, a key).
    std::vector<float> weights;
    uint32_t weightCount = 0;
};

struct AnimationChannel {
    int node = 0;  // into NodeAnimation::nodes
    AnimationPath path = AnimationPath::Translation;
    int sampler = 0;  // into the clip's samplers
};

struct AnimationClip {
    std::string name;  // the file's, "" when it has none
    std::vector<AnimationSampler> samplers;
    std::vector<AnimationChannel> channels;
    float duration = 0.0f;  // the last key time of any sampler: the clip loops over [0, duration)
};

// A node's rest transform: translation x rotation x scale, or a matrix (which no channel may target).
struct AnimatedNode {
    int parent = -1;
    glm::vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
    glm::vec3 scale{1.0f};
    bool hasMatrix = false;
    glm::mat4 matrix{1.0f};
    // The morph weights of the node's mesh at rest: the node's `weights`, else the mesh's, else 0
    // (one a morph target; empty for a node without morph targets).
    std::vector<float> weights;
};

// A glTF skin: joint j's matrix is world(joints[j]) x inverseBind[j].
struct Skin {
    std::vector<int> joints;  // into NodeAnimation::nodes
    std::vector<glm::mat4> inverseBind;
};

// A skinned vertex's joints (indices into its skin's joints) and weights: JOINTS_0/WEIGHTS_0 in the
// first four, JOINTS_1/WEIGHTS_1 (or weight 0) in the last four; the weights sum to 1, or all are 0
// (the vertex then stays where the mesh places it).
struct VertexJoints {
    uint32_t joint[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    float weight[8] = {0, 0, 0, 0, 0, 0, 0, 0};
};

// One morph target's difference at a vertex (glTF's POSITION, NORMAL and TANGENT targets; 0 where
// the target or the vertex's attribute from the file is absent).
struct MorphDelta {
    glm::vec3 position{0.0f}, normal{0.0f}, tangent{0.0f};
};

// Mesh vertices [firstVertex, firstVertex + vertexCount) are drawn by `node`; restLocal holds them,
// from firstLocal on, in the node's own space (a skinned node's: its mesh's, since a skin ignores the
// node's transform). `mirrored`: the rest pose's world transform mirrors, so the loader reversed the
// triangles' winding and the tangents' handedness (kept in every pose). Posing a vertex morphs it
// first (the node's weights times the deltas), then skins it (the weighted sum of its joints'
// matrices) or places it by the node's world matrix, the order the specification gives.
struct NodeVertexRange {
    int node = 0;
    uint32_t firstVertex = 0;
    uint32_t vertexCount = 0;
    uint32_t firstLocal = 0;
    bool mirrored = false;
    int skin = -1;                // into NodeAnimation::skins; -1: placed by the node's world matrix
    uint32_t firstJoints = 0;     // into NodeAnimation::vertexJoints, one a vertex (skinned ranges)
    uint32_t morphTargets = 0;    // how many morph targets the range's primitive has
    uint32_t firstDelta = 0;      // into NodeAnimation::morphDeltas: target t's at vertex i is firstDelta + t * vertexCount + i
};

struct NodeAnimation {
    std::vector<AnimatedNode> nodes;  // every node of the file, at rest
    std::vector<int> order;           // the drawn scene's nodes, each after its parent
    std::vector<AnimationClip> clips;
    std::vector<NodeVertexRange> ranges;  // the vertices of nodes that a channel moves (or an ancestor's), skinned or morphed
    std::vector<Vertex> restLocal;
    std::vector<Skin> skins;
    std::vector<VertexJoints> vertexJoints;
    std::vector<MorphDelta> morphDeltas;
};

// A pose: every node's world matrix and morph weights.
struct NodePose {
    std::vector<glm::mat4> worlds;
    std::vector<std::vector<float>> weights;  // AnimatedNode::weights, or what a weights channel sets
    bool operator==(const NodePose& o) const { return worlds == o.worlds && weights == o.weights; }
    bool operator!=(const NodePose& o) const { return !(*this == o); }
};

// The sampler's value at `time` (seconds): held at the first key before it and at the last after
// it; STEP holds each key's value until the next key; LINEAR interpolates translation and scale
// linearly and rotation by spherical linear interpolation on the shorter arc; CUBICSPLINE is the
// spec's Hermite spline, v = (2s^3 - 3s^2 + 1) v_k + (s^3 - 2s^2 + s) d b_k + (-2s^3 + 3s^2) v_k+1 +
// (s^3 - s^2) d a_k+1, d = t_k+1 - t_k, s = (t - t_k) / d, b the out- and a the in-tangents. A
// rotation comes back normalised.
glm::vec4 sampleAnimation(const AnimationSampler& sampler, AnimationPath path, float time);

// A weights sampler's value at `time` (weightCount floats), by the rules of sampleAnimation (LINEAR
// linear per weight; CUBICSPLINE the Hermite form per weight with the spec's layout).
std::vector<float> sampleWeights(const AnimationSampler& sampler, float time);

// Spherical linear interpolation from a to b (unit quaternions as x, y, z, w) on the shorter arc;
// unit length.
glm::vec4 slerpUnit(glm::vec4 a, glm::vec4 b, float s);

// The time inside a clip that loops over [0, duration): `time` modulo the duration (a clip of
// duration 0 stays at 0).
float clipTime(const AnimationClip& clip, double time);

// Every node's world matrix (parent x T x R x S, or the node's matrix) with the channels of the clips
// `playing` (indices into animation.clips, later clips winning where two move the same property)
// evaluated at `time`, each clip looping over its duration. Nodes outside `order` keep identity.
std::vector<glm::mat4> animatedNodeWorlds(const NodeAnimation& animation, const std::vector<int>& playing, double time);
// The same worlds, and every node's morph weights (weights channels of the clips `playing` at `time`).
NodePose animatedPose(const NodeAnimation& animation, const std::vector<int>& playing, double time);

// `vertices` (the mesh's, as loaded) with the ranges' positions, normals and tangents placed by
// `pose` (animatedPose): morphed, then skinned or placed by their node. Skinned normals go through
// the inverse transpose of the vertex's blended joint matrix (its cofactor matrix, which the
// renormalisation makes the same), tangents through the matrix itself, both renormalised.
void poseVertices(const NodeAnimation& animation, const NodePose& pose, std::vector<Vertex>& vertices);
// The same with the nodes at `worlds` and every morph weight at rest.
void poseVertices(const NodeAnimation& animation, const std::vector<glm::mat4>& worlds, std::vector<Vertex>& vertices);

// Skin s's joint matrices for `worlds`: world(joint) x inverse bind matrix.
std::vector<glm::mat4> jointMatrices(const Skin& skin, const std::vector<glm::mat4>& worlds);

// Which clips `choice` plays: "" (the default) the first clip; "none" none; "all" every clip; a
// whole number the clip of that index; anything else the clips of that name. Indices into
// animation.clips; empty when the model has no such clip.
std::vector<int> chooseClips(const NodeAnimation& animation, const std::string& choice);

}  // namespace lp
