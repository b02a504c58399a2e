#pragma once
// glTF node animation (docs/models-and-materials.md, "Animation"): keyframe clips on node
// translation, rotation and scale, the node hierarchy they move, and the vertices each moving node
// draws, kept in the node's own space so that any pose can be placed. CPU math, no GL: the renderer
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
enum class AnimationPath { Translation, Rotation, Scale };

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
};

// Mesh vertices [firstVertex, firstVertex + vertexCount) are drawn by `node`; restLocal holds them,
// from firstLocal on, in the node's own space. `mirrored`: the rest pose's world transform mirrors,
// so the loader reversed the triangles' winding and the tangents' handedness (kept in every pose).
struct NodeVertexRange {
    int node = 0;
    uint32_t firstVertex = 0;
    uint32_t vertexCount = 0;
    uint32_t firstLocal = 0;
    bool mirrored = false;
};

struct NodeAnimation {
    std::vector<AnimatedNode> nodes;  // every node of the file, at rest
    std::vector<int> order;           // the drawn scene's nodes, each after its parent
    std::vector<AnimationClip> clips;
    std::vector<NodeVertexRange> ranges;  // the vertices of nodes that a channel moves (or an ancestor's)
    std::vector<Vertex> restLocal;
};

// The sampler's value at `time` (seconds): held at the first key before it and at the last after
// it; STEP holds each key's value until the next key; LINEAR interpolates translation and scale
// linearly and rotation by spherical linear interpolation on the shorter arc; CUBICSPLINE is the
// spec's Hermite spline, v = (2s^3 - 3s^2 + 1) v_k + (s^3 - 2s^2 + s) d b_k + (-2s^3 + 3s^2) v_k+1 +
// (s^3 - s^2) d a_k+1, d = t_k+1 - t_k, s = (t - t_k) / d, b the out- and a the in-tangents. A
// rotation comes back normalised.
glm::vec4 sampleAnimation(const AnimationSampler& sampler, AnimationPath path, float time);

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

// `vertices` (the mesh's, as loaded) with the ranges' positions, normals and tangents placed by
// `worlds` (animatedNodeWorlds).
void poseVertices(const NodeAnimation& animation, const std::vector<glm::mat4>& worlds, std::vector<Vertex>& vertices);

// Which clips `choice` plays: "" (the default) the first clip; "none" none; "all" every clip; a
// whole number the clip of that index; anything else the clips of that name. Indices into
// animation.clips; empty when the model has no such clip.
std::vector<int> chooseClips(const NodeAnimation& animation, const std::string& choice);

}  // namespace lp
