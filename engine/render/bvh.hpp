#pragma once
// A bounding volume hierarchy over triangles for the path tracer: binned SAH (Wald 2007), built on
// the CPU and flattened for a GPU storage buffer. The ray queries here are the CPU reference the
// tests compare the tracer's traversal (shaders/common/bvh.glsl) against.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace lp {

// One node, two vec4s in std430 (shaders/common/bvh.glsl's LpBvhNode). Interior: count == 0, its
// children are nodes `first` and `first + 1`. Leaf: count > 0 triangles, Bvh::triangleOrder[first ..
// first + count) (the GPU's triangles are stored in that order, so a leaf reads them directly).
struct BvhNode {
    glm::vec3 lo{0.0f};
    int32_t first = 0;
    glm::vec3 hi{0.0f};
    int32_t count = 0;
};
static_assert(sizeof(BvhNode) == 32, "BvhNode is two vec4s on the GPU");

struct Bvh {
    std::vector<BvhNode> nodes;           // nodes[0] is the root; empty for no triangles
    std::vector<uint32_t> triangleOrder;  // leaf order -> input triangle index
    int depth = 0;                        // longest root-to-leaf path (nodes), for the GPU's stack
};

struct BvhBuildOptions {
    int bins = 16;         // SAH candidate planes per axis
    int maxLeafSize = 4;   // a node above this is always split
    float traversalCost = 1.0f;  // relative to one triangle test
};

// `positions`: three per triangle (triangle i is positions[3i .. 3i+2]).
Bvh buildBvh(const std::vector<glm::vec3>& positions, const BvhBuildOptions& options = {});

struct RayHit {
    float t = -1.0f;   // < 0: no hit
    int triangle = -1; // input triangle index
    float u = 0.0f, v = 0.0f;  // barycentrics of positions[3i + 1] and [3i + 2]
    bool hit() const { return triangle >= 0; }
};

// Moller-Trumbore, both faces; a hit in (tMin, tMax) returns true with t, u, v.
bool intersectTriangle(glm::vec3 origin, glm::vec3 dir, glm::vec3 a, glm::vec3 b, glm::vec3 c, float tMin, float tMax,
                       float& t, float& u, float& v);
// The nearest hit with t in (tMin, tMax), through the BVH and by testing every triangle.
RayHit intersectBvh(const Bvh& bvh, const std::vector<glm::vec3>& positions, glm::vec3 origin, glm::vec3 dir,
                    float tMin, float tMax);
RayHit intersectBruteForce(const std::vector<glm::vec3>& positions, glm::vec3 origin, glm::vec3 dir, float tMin,
                           float tMax);

}  // namespace lp
