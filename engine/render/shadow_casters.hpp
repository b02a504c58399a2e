#pragma once
// Caster culling for the sun cascades (CPU math, no GL, so unit tests and 'lightpass graph' can use
// it). Each model's triangles are split once, at load, into clusters of at most
// kCasterClusterTriangles consecutive triangles of one sub-mesh with their own object-space bounds:
// the Stanford models are one mesh each, so whole-mesh bounds would overlap every cascade. Per
// cascade, a cluster is drawn when its bounds, in the cascade's light clip space, overlap the tile
// (grown by a margin for the conservative rasteriser's half-texel growth) and do not lie entirely
// beyond its far plane. Clusters between the light and the near plane are kept: depth clamping
// makes them cast.
// Clusters also say how their fragments occlude (CasterAlpha): opaque ones are drawn without a
// texture fetch or discard, as before; MASK and BLEND ones test the base colour's alpha in draws of
// their own (CasterList::alphaDraws), so a scene's opaque casters cost what they did.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "engine/scene/scene.hpp"

namespace lp {

constexpr uint32_t kCasterClusterTriangles = 4096;

// How a sub-mesh's fragments occlude in the shadow maps (docs/shadows.md, "Alpha in shadows").
enum class CasterAlpha {
    Opaque,  // every fragment: no texture fetch, no discard (OPAQUE, or an alpha that never cuts)
    Mask,    // glTF MASK: where the base colour's alpha is at least alphaCutoff
    Hashed,  // BLEND, MTL d < 1: where the alpha is at least a hashed threshold (coverage = opacity)
    None,    // nothing: BLEND of opacity 0, or MASK whose constant alpha is below the cutoff
};

// The caster kind of sub-mesh `sm` of `mesh`. Without a base colour texture the alpha is the
// opacity times the vertex colours' alpha, interpolated linearly, so its range over the sub-mesh's
// vertices decides: MASK with every vertex at or above the cutoff, or BLEND with every vertex at 1,
// is Opaque; MASK with all below the cutoff, or BLEND with all at 0, is None. A texture makes MASK
// Mask and BLEND Hashed (its alpha is known only on the GPU).
CasterAlpha casterAlpha(const MeshData& mesh, const SubMesh& sm);

struct CasterCluster {
    int model = 0;            // the drawn copy: index into placements(scene) (and SceneGpu::meshes)
    uint32_t firstIndex = 0;  // into the model's index buffer
    uint32_t indexCount = 0;
    glm::vec3 boundsMin{0.0f};  // object space
    glm::vec3 boundsMax{0.0f};
    CasterAlpha alpha = CasterAlpha::Opaque;  // never None: those sub-meshes have no cluster
    // Mask and Hashed: the material's index in SceneGpu::materials (every model's materials in
    // model order); -1 for Opaque.
    int material = -1;
};

// One glDrawElements of a model's index range.
struct CasterDraw {
    int model = 0;
    uint32_t firstIndex = 0;
    uint32_t indexCount = 0;
    int material = -1;  // alpha-tested draws: SceneGpu::materials index; -1 in CasterList::draws
};

struct CasterList {
    // Opaque casters: adjacent kept clusters of one model merged into one draw.
    std::vector<CasterDraw> draws;
    // Alpha-tested casters (Mask, Hashed): adjacent kept clusters of one model and material merged.
    std::vector<CasterDraw> alphaDraws;
    size_t clusters = 0;        // clusters kept
    size_t triangles = 0;       // triangles drawn, both lists
    size_t alphaTriangles = 0;  // of which alpha-tested
};

// Clusters of every model, in model then index order, repeated for each of its instances; every
// triangle of every sub-mesh that casts (casterAlpha not None) is in exactly one cluster per
// instance, and a cluster holds one sub-mesh. Non-finite vertex
// positions are left out of the bounds.
std::vector<CasterCluster> buildCasterClusters(const Scene& scene, uint32_t trianglesPerCluster = kCasterClusterTriangles);

// Whether some cluster is alpha-tested (Mask or Hashed): the passes then make their alpha-tested programs.
bool hasAlphaTestedCasters(const std::vector<CasterCluster>& clusters);

// Whether object-space box [lo, hi] under `objectToClip` (an orthographic light's clip space,
// w = 1) may draw into the tile: its clip-space bounds overlap [-1 - margin, 1 + margin] in x and y,
// and not all of it lies past the far plane (z > 1). Nearer than the near plane (z < -1) is kept.
bool casterBoxMayCast(const glm::mat4& objectToClip, glm::vec3 lo, glm::vec3 hi, float margin);

// The draws of one cascade: every cluster when `cull` is false, else those casterBoxMayCast keeps
// (margin: one texel of the tile, 2 / tileSize in clip units).
CasterList cullCasters(const std::vector<CasterCluster>& clusters, const Scene& scene, const glm::mat4& worldToClip,
                       float margin, bool cull);

// Whether object-space box [lo, hi] under `objectToWorld` may reach the sphere (world-space `centre`,
// `radius`): the world-space box of its eight corners does. A point light's casters: what lies
// outside its range cannot come between it and a point it lights (the segment stays inside).
bool casterBoxReachesSphere(const glm::mat4& objectToWorld, glm::vec3 lo, glm::vec3 hi, glm::vec3 centre, float radius);

// The draws of the clusters casterBoxReachesSphere keeps (each model placed by its transform).
CasterList castersInSphere(const std::vector<CasterCluster>& clusters, const Scene& scene, glm::vec3 centre, float radius);

// Whether object-space box [lo, hi] under `objectToClip` (a perspective projection's clip space) may
// draw into the viewport: false only when all eight corners lie in front of the eye (w > 0) and
// beyond one side plane (x > w, x < -w, y > w or y < -w); a box reaching behind the eye is kept.
// Exact for the depth drawn: the rasteriser clips what lies outside those planes (depth clamp lifts
// only the near and far planes).
bool casterBoxInPerspectiveView(const glm::mat4& objectToClip, glm::vec3 lo, glm::vec3 hi);

// The draws of one face of a point light's cube: the clusters that reach the light's range sphere
// and may draw into the face's view (casterBoxInPerspectiveView under worldToClip).
CasterList castersInSphereAndView(const std::vector<CasterCluster>& clusters, const Scene& scene, glm::vec3 centre,
                                  float radius, const glm::mat4& worldToClip);

}  // namespace lp
