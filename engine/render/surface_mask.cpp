#include "engine/render/surface_mask.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include "engine/render/bvh.hpp"
#include "engine/scene/posed_vertices.hpp"

namespace lp {

std::vector<uint8_t> surfaceMask(const Scene& scene, const Camera& camera, int width, int height, double time) {
    std::vector<uint8_t> mask(size_t(width) * size_t(height), 0);
    std::vector<glm::vec3> positions;
    for (const ModelInstance& model : scene.models) {
        const MeshData& mesh = model.mesh;
        std::vector<Vertex> posed;
        const std::vector<Vertex>& vertices = posedVertices(model, time, posed);
        for (size_t instance = 0; instance < model.instanceCount(); ++instance) {
            const glm::mat4& toWorld = model.instanceTransform(instance);
            for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
                for (size_t k = 0; k < 3; ++k) {
                    const uint32_t index = mesh.indices[i + k];
                    if (index >= vertices.size()) return mask;  // the loader never leaves one; nothing to cast against
                    positions.push_back(glm::vec3(toWorld * glm::vec4(vertices[index].position, 1.0f)));
                }
        }
    }
    if (positions.empty() || width <= 0 || height <= 0) return mask;
    const Bvh bvh = buildBvh(positions);
    const glm::mat4 inverse = glm::inverse(camera.projection(float(width) / float(height)) * camera.view());
    auto unproject = [&](float x, float y, float z) {
        const glm::vec4 p = inverse * glm::vec4(x, y, z, 1.0f);
        return glm::vec3(p) / p.w;
    };
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float nx = (float(x) + 0.5f) / float(width) * 2.0f - 1.0f;
            const float ny = 1.0f - (float(y) + 0.5f) / float(height) * 2.0f;  // row 0 is the top
            const glm::vec3 nearPoint = unproject(nx, ny, -1.0f), farPoint = unproject(nx, ny, 1.0f);
            const glm::vec3 d = farPoint - nearPoint;
            const float length = glm::length(d);
            if (!(length > 0.0f)) continue;
            const RayHit hit = intersectBvh(bvh, positions, nearPoint, d / length, 0.0f, length);
            mask[size_t(y) * size_t(width) + size_t(x)] = hit.hit() ? 1 : 0;
        }
    return mask;
}

}  // namespace lp
