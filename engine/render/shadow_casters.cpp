#include "engine/render/shadow_casters.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/scene/placements.hpp"

namespace lp {

CasterAlpha casterAlpha(const MeshData& mesh, const SubMesh& sm) {
    if (sm.material < 0 || size_t(sm.material) >= mesh.materials.size()) return CasterAlpha::Opaque;
    const Material& m = mesh.materials[size_t(sm.material)];
    if (m.alphaMode == AlphaMode::Opaque) return CasterAlpha::Opaque;
    const bool mask = m.alphaMode == AlphaMode::Mask;
    if (!m.diffuseMap.empty()) return mask ? CasterAlpha::Mask : CasterAlpha::Hashed;
    // The base colour's alpha (common/material.glsl's materialBaseColor): opacity x vertex alpha,
    // interpolated linearly between the vertices, so it stays within their range.
    float lo = std::numeric_limits<float>::max(), hi = -std::numeric_limits<float>::max();
    const uint32_t end = std::min<uint32_t>(sm.firstIndex + sm.indexCount, uint32_t(mesh.indices.size()));
    for (uint32_t i = sm.firstIndex; i < end; ++i) {
        const uint32_t v = mesh.indices[i];
        if (v >= mesh.vertices.size()) continue;
        const float a = m.opacity * mesh.vertices[v].color.w;
        lo = std::min(lo, a);
        hi = std::max(hi, a);
    }
    if (lo > hi) return CasterAlpha::Opaque;  // no vertex: nothing is drawn either way
    if (mask) return lo >= m.alphaCutoff ? CasterAlpha::Opaque : hi < m.alphaCutoff ? CasterAlpha::None : CasterAlpha::Mask;
    return lo >= 1.0f ? CasterAlpha::Opaque : hi <= 0.0f ? CasterAlpha::None : CasterAlpha::Hashed;
}

std::vector<CasterCluster> buildCasterClusters(const Scene& scene, uint32_t trianglesPerCluster) {
    std::vector<CasterCluster> clusters;
    const uint32_t perCluster = std::max<uint32_t>(trianglesPerCluster, 1u) * 3u;
    int materialBase = 0;  // SceneGpu::materials holds every model's materials in model order
    int placement = 0;     // the first instance of model m (placements order)
    for (size_t m = 0; m < scene.models.size(); ++m) {
        const MeshData& mesh = scene.models[m].mesh;
        const size_t firstCluster = clusters.size();
        for (const SubMesh& sm : mesh.subMeshes) {
            const CasterAlpha alpha = casterAlpha(mesh, sm);
            if (alpha == CasterAlpha::None) continue;  // casts nothing
            const uint32_t end = std::min<uint32_t>(sm.firstIndex + sm.indexCount, uint32_t(mesh.indices.size()));
            for (uint32_t first = sm.firstIndex; first < end; first += perCluster) {
                CasterCluster c;
                c.model = placement;
                c.firstIndex = first;
                c.indexCount = std::min(perCluster, end - first);
                c.alpha = alpha;
                c.material = alpha == CasterAlpha::Opaque ? -1 : materialBase + sm.material;
                glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
                for (uint32_t i = first; i < first + c.indexCount; ++i) {
                    const uint32_t v = mesh.indices[i];
                    if (v >= mesh.vertices.size()) continue;
                    const glm::vec3 p = mesh.vertices[v].position;
                    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
                    lo = glm::min(lo, p);
                    hi = glm::max(hi, p);
                }
                if (lo.x > hi.x) lo = hi = glm::vec3(0.0f);  // nothing finite: a point, culled like one
                c.boundsMin = lo;
                c.boundsMax = hi;
                clusters.push_back(c);
            }
        }
        materialBase += int(mesh.materials.size());
        // Every further instance casts the same clusters (object-space bounds) from its own placement.
        const size_t lastCluster = clusters.size();
        for (size_t k = 1; k < scene.models[m].instanceCount(); ++k)
            for (size_t i = firstCluster; i < lastCluster; ++i) {
                CasterCluster c = clusters[i];
                c.model = placement + int(k);
                clusters.push_back(c);
            }
        placement += int(scene.models[m].instanceCount());
    }
    return clusters;
}

bool hasAlphaTestedCasters(const std::vector<CasterCluster>& clusters) {
    return std::any_of(clusters.begin(), clusters.end(), [](const CasterCluster& c) { return c.alpha != CasterAlpha::Opaque; });
}

bool casterBoxMayCast(const glm::mat4& objectToClip, glm::vec3 lo, glm::vec3 hi, float margin) {
    glm::vec3 cmin(std::numeric_limits<float>::max()), cmax(-std::numeric_limits<float>::max());
    for (int c = 0; c < 8; ++c) {
        const glm::vec4 p(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z, 1.0f);
        const glm::vec4 q = objectToClip * p;
        const glm::vec3 ndc = glm::vec3(q) / q.w;  // orthographic: w = 1
        cmin = glm::min(cmin, ndc);
        cmax = glm::max(cmax, ndc);
    }
    const float edge = 1.0f + margin;
    if (cmax.x < -edge || cmin.x > edge || cmax.y < -edge || cmin.y > edge) return false;
    return cmin.z <= 1.0f;  // a box wholly past the far plane is behind every receiver of the tile
}

namespace {
// Appends cluster c to `list`, merged into the last draw of its kind where it continues it.
void addCluster(CasterList& list, const CasterCluster& c) {
    ++list.clusters;
    list.triangles += c.indexCount / 3;
    const bool tested = c.alpha != CasterAlpha::Opaque;
    if (tested) list.alphaTriangles += c.indexCount / 3;
    std::vector<CasterDraw>& draws = tested ? list.alphaDraws : list.draws;
    const int material = tested ? c.material : -1;
    if (!draws.empty() && draws.back().model == c.model && draws.back().material == material &&
        draws.back().firstIndex + draws.back().indexCount == c.firstIndex)
        draws.back().indexCount += c.indexCount;
    else
        draws.push_back({c.model, c.firstIndex, c.indexCount, material});
}
}  // namespace

CasterList cullCasters(const std::vector<CasterCluster>& clusters, const Scene& scene, const glm::mat4& worldToClip,
                       float margin, bool cull) {
    CasterList list;
    int lastModel = -1;
    glm::mat4 objectToClip(1.0f);
    const std::vector<Placement> placed = placements(scene);
    for (const CasterCluster& c : clusters) {
        if (c.model < 0 || size_t(c.model) >= placed.size()) continue;
        if (c.model != lastModel) {
            objectToClip = worldToClip * placed[size_t(c.model)].transform;
            lastModel = c.model;
        }
        if (cull && !casterBoxMayCast(objectToClip, c.boundsMin, c.boundsMax, margin)) continue;
        addCluster(list, c);
    }
    return list;
}

bool casterBoxReachesSphere(const glm::mat4& objectToWorld, glm::vec3 lo, glm::vec3 hi, glm::vec3 centre, float radius) {
    glm::vec3 wmin(std::numeric_limits<float>::max()), wmax(-std::numeric_limits<float>::max());
    for (int c = 0; c < 8; ++c) {
        const glm::vec3 p = glm::vec3(objectToWorld * glm::vec4(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z, 1.0f));
        wmin = glm::min(wmin, p);
        wmax = glm::max(wmax, p);
    }
    const glm::vec3 nearest = glm::clamp(centre, wmin, wmax);
    const glm::vec3 d = nearest - centre;
    return glm::dot(d, d) <= radius * radius;
}

bool casterBoxInPerspectiveView(const glm::mat4& objectToClip, glm::vec3 lo, glm::vec3 hi) {
    bool right = true, left = true, top = true, bottom = true;
    for (int c = 0; c < 8; ++c) {
        const glm::vec4 q = objectToClip * glm::vec4(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z, 1.0f);
        if (!(q.w > 0.0f)) return true;
        right = right && q.x > q.w;
        left = left && q.x < -q.w;
        top = top && q.y > q.w;
        bottom = bottom && q.y < -q.w;
    }
    return !(right || left || top || bottom);
}

CasterList castersInSphereAndView(const std::vector<CasterCluster>& clusters, const Scene& scene, glm::vec3 centre,
                                  float radius, const glm::mat4& worldToClip) {
    CasterList list;
    const std::vector<Placement> placed = placements(scene);
    for (const CasterCluster& c : clusters) {
        if (c.model < 0 || size_t(c.model) >= placed.size()) continue;
        const glm::mat4& transform = placed[size_t(c.model)].transform;
        if (!casterBoxReachesSphere(transform, c.boundsMin, c.boundsMax, centre, radius)) continue;
        if (!casterBoxInPerspectiveView(worldToClip * transform, c.boundsMin, c.boundsMax)) continue;
        addCluster(list, c);
    }
    return list;
}

CasterList castersInSphere(const std::vector<CasterCluster>& clusters, const Scene& scene, glm::vec3 centre, float radius) {
    CasterList list;
    const std::vector<Placement> placed = placements(scene);
    for (const CasterCluster& c : clusters) {
        if (c.model < 0 || size_t(c.model) >= placed.size()) continue;
        if (!casterBoxReachesSphere(placed[size_t(c.model)].transform, c.boundsMin, c.boundsMax, centre, radius)) continue;
        addCluster(list, c);
    }
    return list;
}

}  // namespace lp
