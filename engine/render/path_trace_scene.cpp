#include "engine/render/path_trace_scene.hpp"

#include <algorithm>

namespace lp {

namespace {
// The shininess material.glsl uses where no roughness map is sampled: up to the IBL's roughness
// floor (LP_IBL_MAX_SHININESS, kMinRoughness).
float materialShininess(const Material& m) {
    return std::clamp(m.shininess, 0.0f, shininessFromRoughness(kMinRoughness));
}
}  // namespace

PathTraceScene buildPathTraceScene(const Scene& scene) {
    PathTraceScene out;
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<int> materialOfTriangle;
    for (const ModelInstance& model : scene.models) {
        const MeshData& mesh = model.mesh;
        const int firstMaterial = int(out.materials.size());
        for (const Material& m : mesh.materials) {
            PathTraceMaterial g;
            g.baseOpacity = glm::vec4(glm::clamp(m.diffuse, 0.0f, 1.0f), m.opacity);
            g.specularMetallic = glm::vec4(glm::clamp(m.specular, 0.0f, 1.0f), std::clamp(m.metallic, 0.0f, 1.0f));
            g.emissionShininess = glm::vec4(m.emission, materialShininess(m));
            g.flags = glm::vec4(m.flat ? 1.0f : 0.0f, m.doubleSided ? 1.0f : 0.0f, 0.0f, 0.0f);
            out.materials.push_back(g);
            const bool textured = !m.diffuseMap.empty() || !m.metallicRoughnessMap.empty() || !m.normalMap.empty() ||
                                  !m.bumpMap.empty() || !m.emissiveMap.empty() || !m.occlusionMap.empty();
            out.texturedMaterials += textured ? 1 : 0;
            out.blendedMaterials += (m.alphaMode == AlphaMode::Blend || m.opacity < 1.0f) ? 1 : 0;
        }
        const glm::mat4 toWorld = model.transform;
        const glm::mat3 normalToWorld = glm::transpose(glm::inverse(glm::mat3(toWorld)));
        for (const SubMesh& sub : mesh.subMeshes) {
            const int material = firstMaterial + std::clamp(sub.material, 0, int(mesh.materials.size()) - 1);
            const size_t end = std::min<size_t>(size_t(sub.firstIndex) + sub.indexCount, mesh.indices.size());
            for (size_t i = sub.firstIndex; i + 2 < end; i += 3) {
                for (int k = 0; k < 3; ++k) {
                    const Vertex& v = mesh.vertices[mesh.indices[i + size_t(k)]];
                    positions.push_back(glm::vec3(toWorld * glm::vec4(v.position, 1.0f)));
                    const glm::vec3 n = normalToWorld * v.normal;
                    const float len = glm::length(n);
                    normals.push_back(len > 0.0f ? n / len : glm::vec3(0.0f, 1.0f, 0.0f));
                }
                materialOfTriangle.push_back(material);
            }
        }
    }
    out.bvh = buildBvh(positions);
    out.triangles.reserve(out.bvh.triangleOrder.size());
    for (uint32_t t : out.bvh.triangleOrder) {
        PathTraceTriangle g;
        for (int k = 0; k < 3; ++k) {
            g.position[k] = glm::vec4(positions[3 * t + k], 0.0f);
            g.normal[k] = glm::vec4(normals[3 * t + k], 0.0f);
        }
        g.position[0].w = float(materialOfTriangle[t]);
        out.triangles.push_back(g);
    }
    return out;
}

}  // namespace lp
