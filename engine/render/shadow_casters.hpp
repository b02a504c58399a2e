#pragma once
// Caster culling for the sun cascades (CPU math, no GL, so unit tests and 'lightpass graph' can use
// it). Each model's triangles are split once, at load, into clusters of at most
// kCasterClusterTriangles consecutive triangles of one sub-mesh with their own object-space bounds:
// the Stanford models are one mesh each, so whole-mesh bounds would overlap every cascade. Per
// cascade, a cluster is drawn when its bounds, in the cascade's light clip space, overlap the tile
// (grown by a margin for the conservative rasteriser's half-texel growth) and do not lie entirely
// beyond its far plane. Clusters between the light and the near plane are kept: depth clamping
// makes them cast.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "engine/scene/scene.hpp"

namespace lp {

constexpr uint32_t kCasterClusterTriangles = 4096;

struct CasterCluster {
    int model = 0;            // index into scene.models (and SceneGpu::meshes)
    uint32_t firstIndex = 0;  // into the model's index buffer
    uint32_t indexCount = 0;
    glm::vec3 boundsMin{0.0f};  // object space
    glm::vec3 boundsMax{0.0f};
};

// One glDrawElements of a model's index range.
struct CasterDraw {
    int model = 0;
    uint32_t firstIndex = 0;
    uint32_t indexCount = 0;
};

struct CasterList {
    std::vector<CasterDraw> draws;  // adjacent kept clusters of one model merged into one draw
    size_t clusters = 0;            // clusters kept
    size_t triangles = 0;           // triangles drawn
};

// Clusters of every model, in model then index order; every triangle of every sub-mesh is in
// exactly one. Non-finite vertex positions are left out of the bounds.
std::vector<CasterCluster> buildCasterClusters(const Scene& scene, uint32_t trianglesPerCluster = kCasterClusterTriangles);

// Whether object-space box [lo, hi] under `objectToClip` (an orthographic light's clip space,
// w = 1) may draw into the tile: its clip-space bounds overlap [-1 - margin, 1 + margin] in x and y,
// and not all of it lies past the far plane (z > 1). Nearer than the near plane (z < -1) is kept.
bool casterBoxMayCast(const glm::mat4& objectToClip, glm::vec3 lo, glm::vec3 hi, float margin);

// The draws of one cascade: every cluster when `cull` is false, else those casterBoxMayCast keeps
// (margin: one texel of the tile, 2 / tileSize in clip units).
CasterList cullCasters(const std::vector<CasterCluster>& clusters, const Scene& scene, const glm::mat4& worldToClip,
                       float margin, bool cull);

}  // namespace lp
