#include "engine/scene/placements.hpp"

#include <set>

namespace lp {

std::vector<Placement> placements(const Scene& scene) {
    std::vector<Placement> out;
    for (size_t m = 0; m < scene.models.size(); ++m)
        for (size_t k = 0; k < scene.models[m].instanceCount(); ++k) out.push_back({m, k, scene.models[m].instanceTransform(k)});
    return out;
}

SceneCounts sceneCounts(const Scene& scene) {
    SceneCounts c;
    c.models = scene.models.size();
    std::set<std::string> stored;  // geometry keys counted
    for (const ModelInstance& m : scene.models) {
        c.instances += m.instanceCount();
        // An animated model's copies each hold their pose (SceneGpu); a file's or primitive's still
        // vertices are stored once, whichever models name it.
        const bool animated = m.animation && !m.playingClips.empty() && !m.animation->ranges.empty();
        const size_t copies = animated ? m.instanceCount() : 1;
        if (animated || m.geometryKey.empty() || stored.insert(m.geometryKey).second) {
            c.storedVertices += copies * m.mesh.vertices.size();
            c.storedTriangles += copies * (m.mesh.indices.size() / 3);
        }
        c.drawnTriangles += m.instanceCount() * (m.mesh.indices.size() / 3);
    }
    return c;
}

std::string sceneCountsText(const SceneCounts& c) {
    return std::to_string(c.models) + " models, " + std::to_string(c.instances) + " instances drawn; " +
           std::to_string(c.storedVertices) + " vertices and " + std::to_string(c.storedTriangles) + " triangles stored, " +
           std::to_string(c.drawnTriangles) + " triangles drawn";
}

}  // namespace lp
