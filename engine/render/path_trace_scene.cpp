#include "engine/render/path_trace_scene.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "engine/scene/posed_vertices.hpp"

namespace lp {

namespace {
// The shininess material.glsl uses where no roughness map is sampled: up to the IBL's roughness
// floor (LP_IBL_MAX_SHININESS, kMinRoughness).
float materialShininess(const Material& m) {
    return std::clamp(m.shininess, 0.0f, shininessFromRoughness(kMinRoughness));
}
int wrapCode(int glWrap) { return glWrap == 33071 ? 1 : glWrap == 33648 ? 2 : 0; }  // clamp, mirrored, else repeat

// The layer of `ref` in `layers`, added when new (one layer per image and sampler).
float layerOf(const TextureRef& ref, std::vector<TextureRef>& layers, std::map<std::string, int>& index) {
    if (ref.empty()) return -1.0f;
    const std::string key = ref.key + "#" + std::to_string(ref.sampler.wrapS) + "," + std::to_string(ref.sampler.wrapT);
    auto [it, added] = index.emplace(key, int(layers.size()));
    if (added) layers.push_back(ref);
    return float(it->second);
}
}  // namespace

int pathTraceMapBits(const TextureRef* const maps[kPtMapCount]) {
    int bits = 0;
    for (int i = 0; i < kPtMapCount; ++i) {
        if (!maps[i] || maps[i]->empty()) continue;
        bits |= (maps[i]->uvSet == 1 ? 1 : 0) << (4 * i);
        bits |= wrapCode(maps[i]->sampler.wrapS) << (4 * i + 1);
        bits |= wrapCode(maps[i]->sampler.wrapT) << (16 + 2 * i);
    }
    return bits;
}

PathTraceScene buildPathTraceScene(const Scene& scene, double time) {
    PathTraceScene out;
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec4> uvs, tangents;
    std::vector<int> materialOfTriangle;
    std::map<std::string, int> srgbIndex, linearIndex;
    for (const ModelInstance& model : scene.models) {
        const MeshData& mesh = model.mesh;
        const int firstMaterial = int(out.materials.size());
        for (const Material& m : mesh.materials) {
            PathTraceMaterial g;
            g.baseOpacity = glm::vec4(glm::clamp(m.diffuse, 0.0f, 1.0f), m.opacity);
            g.specularMetallic = glm::vec4(m.dielectricF0Of(), std::clamp(m.metallic, 0.0f, 1.0f));
            g.emissionShininess = glm::vec4(m.emission, materialShininess(m));
            const float alphaMode = m.alphaMode == AlphaMode::Mask ? 1.0f : m.alphaMode == AlphaMode::Blend ? 2.0f : 0.0f;
            g.flags = glm::vec4(m.flat ? 1.0f : 0.0f, m.doubleSided ? 1.0f : 0.0f, alphaMode, m.alphaCutoff);
            g.maps = glm::vec4(layerOf(m.diffuseMap, out.srgbMaps, srgbIndex),
                               layerOf(m.metallicRoughnessMap, out.linearMaps, linearIndex),
                               layerOf(m.normalMap, out.linearMaps, linearIndex),
                               layerOf(m.emissiveMap, out.srgbMaps, srgbIndex));
            const TextureRef* const maps[kPtMapCount] = {&m.diffuseMap, &m.metallicRoughnessMap, &m.normalMap, &m.emissiveMap};
            // w: KHR_materials_specular's dielectric f90 where the material gives one, else -1 (derived).
            g.mapParams = glm::vec4(m.normalScale, m.roughness, float(pathTraceMapBits(maps)),
                                    m.dielectricF90 ? std::clamp(*m.dielectricF90, 0.0f, 1.0f) : -1.0f);
            if (m.hasClearcoat()) g.clearcoat = glm::vec4(m.clearcoat, m.clearcoatRoughness, 0.0f, 0.0f);
            if (m.transmissive()) {
                g.transmission = glm::vec4(std::clamp(m.transmission, 0.0f, 1.0f), std::max(m.ior, 1.0f), std::max(m.thickness, 0.0f),
                                           std::isfinite(m.attenuationDistance) ? m.attenuationDistance : 0.0f);
                g.attenuation = glm::vec4(glm::clamp(m.attenuationColor, 0.0f, 1.0f), 1.0f);
            }
            out.materials.push_back(g);
            const bool coatMaps = m.hasClearcoat() && (!m.clearcoatMap.empty() || !m.clearcoatRoughnessMap.empty() ||
                                                       !m.clearcoatNormalMap.empty());
            out.unsampledMapMaterials +=
                (!m.bumpMap.empty() || !m.specularMap.empty() || !m.specularColorMap.empty() || coatMaps ||
                 (m.transmissive() && (!m.transmissionMap.empty() || !m.thicknessMap.empty())))
                    ? 1
                    : 0;
            out.hasMaskedMaterials = out.hasMaskedMaterials || alphaMode != 0.0f;
        }
        // An animated model's vertices where its clips put them at `time` (the rest pose otherwise).
        std::vector<Vertex> posed;
        const std::vector<Vertex>& vertices = posedVertices(model, time, posed);
        // Each instance is its own world-space triangles: the BVH is one level.
        for (size_t instance = 0; instance < model.instanceCount(); ++instance) {
            const glm::mat4& toWorld = model.instanceTransform(instance);
            const glm::mat3 normalToWorld = glm::transpose(glm::inverse(glm::mat3(toWorld)));
            for (const SubMesh& sub : mesh.subMeshes) {
                const int material = firstMaterial + std::clamp(sub.material, 0, int(mesh.materials.size()) - 1);
                const size_t end = std::min<size_t>(size_t(sub.firstIndex) + sub.indexCount, mesh.indices.size());
                for (size_t i = sub.firstIndex; i + 2 < end; i += 3) {
                    for (int k = 0; k < 3; ++k) {
                        const Vertex& v = vertices[mesh.indices[i + size_t(k)]];
                        positions.push_back(glm::vec3(toWorld * glm::vec4(v.position, 1.0f)));
                        const glm::vec3 n = normalToWorld * v.normal;
                        const float len = glm::length(n);
                        normals.push_back(len > 0.0f ? n / len : glm::vec3(0.0f, 1.0f, 0.0f));
                        uvs.push_back(glm::vec4(v.uv, v.uv1));
                        // A tangent is a direction on the surface: it goes with the model matrix itself.
                        const glm::vec3 t = glm::mat3(toWorld) * glm::vec3(v.tangent);
                        const float tl = glm::length(t);
                        tangents.push_back(glm::vec4(tl > 0.0f ? t / tl : glm::vec3(1.0f, 0.0f, 0.0f), v.tangent.w < 0.0f ? -1.0f : 1.0f));
                    }
                    materialOfTriangle.push_back(material);
                }
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
            g.uv[k] = uvs[3 * t + k];
            g.tangent[k] = tangents[3 * t + k];
        }
        g.position[0].w = float(materialOfTriangle[t]);
        out.triangles.push_back(g);
    }
    return out;
}

}  // namespace lp
