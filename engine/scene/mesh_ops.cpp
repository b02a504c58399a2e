#include "engine/scene/mesh_ops.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lp {

glm::vec3 anyPerpendicular(glm::vec3 n) {
    float sign = std::copysign(1.0f, n.z);
    float a = -1.0f / (sign + n.z);
    float b = n.x * n.y * a;
    return glm::vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
}

void computeNormals(MeshData& mesh) {
    std::vector<glm::vec3> acc(mesh.vertices.size(), glm::vec3(0.0f));
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        const uint32_t a = mesh.indices[i], b = mesh.indices[i + 1], c = mesh.indices[i + 2];
        const glm::vec3 n = glm::cross(mesh.vertices[b].position - mesh.vertices[a].position,
                                       mesh.vertices[c].position - mesh.vertices[a].position);
        acc[a] += n;
        acc[b] += n;
        acc[c] += n;
    }
    for (size_t v = 0; v < acc.size(); ++v) {
        float len = glm::length(acc[v]);
        mesh.vertices[v].normal = (len > 0.0f && std::isfinite(len)) ? acc[v] / len : glm::vec3(0.0f, 1.0f, 0.0f);
    }
}

void computeTangents(MeshData& mesh) {
    std::vector<glm::vec3> tan(mesh.vertices.size(), glm::vec3(0.0f)), bit(mesh.vertices.size(), glm::vec3(0.0f));
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        const uint32_t idx[3] = {mesh.indices[i], mesh.indices[i + 1], mesh.indices[i + 2]};
        const Vertex &v0 = mesh.vertices[idx[0]], &v1 = mesh.vertices[idx[1]], &v2 = mesh.vertices[idx[2]];
        const glm::vec3 e1 = v1.position - v0.position, e2 = v2.position - v0.position;
        const glm::vec2 d1 = v1.uv - v0.uv, d2 = v2.uv - v0.uv;
        const float det = d1.x * d2.y - d2.x * d1.y;
        if (std::abs(det) < 1e-20f || !std::isfinite(det)) continue;  // no usable UV mapping here
        const float r = 1.0f / det;
        const glm::vec3 t = (e1 * d2.y - e2 * d1.y) * r, b = (e2 * d1.x - e1 * d2.x) * r;
        if (!std::isfinite(t.x + t.y + t.z + b.x + b.y + b.z)) continue;
        for (uint32_t k : idx) {
            tan[k] += t;
            bit[k] += b;
        }
    }
    for (size_t v = 0; v < mesh.vertices.size(); ++v) {
        Vertex& vert = mesh.vertices[v];
        const glm::vec3 n = vert.normal;
        glm::vec3 t = tan[v] - n * glm::dot(n, tan[v]);
        float len = glm::length(t);
        if (len > 1e-12f && std::isfinite(len)) {
            t /= len;
            float w = glm::dot(glm::cross(n, t), bit[v]) < 0.0f ? -1.0f : 1.0f;
            vert.tangent = glm::vec4(t, w);
        } else {
            vert.tangent = glm::vec4(glm::normalize(anyPerpendicular(n)), 1.0f);
        }
    }
}

void computeBounds(MeshData& mesh) {
    if (mesh.vertices.empty()) {
        mesh.boundsMin = mesh.boundsMax = glm::vec3(0.0f);
        return;
    }
    mesh.boundsMin = glm::vec3(std::numeric_limits<float>::max());
    mesh.boundsMax = glm::vec3(std::numeric_limits<float>::lowest());
    for (const auto& v : mesh.vertices) {
        // A NaN/Inf vertex draws nothing; in the bounds it would make the scene infinite for the
        // camera framing, the generated demo lights and the shadow cascade fit.
        if (!std::isfinite(v.position.x) || !std::isfinite(v.position.y) || !std::isfinite(v.position.z)) continue;
        mesh.boundsMin = glm::min(mesh.boundsMin, v.position);
        mesh.boundsMax = glm::max(mesh.boundsMax, v.position);
    }
    if (mesh.boundsMin.x > mesh.boundsMax.x) mesh.boundsMin = mesh.boundsMax = glm::vec3(0.0f);  // none finite
}

}  // namespace lp

namespace lp {

float shininessFromRoughness(float roughness) {
    const double r = std::clamp(double(roughness), double(kMinRoughness), 1.0);
    return float(2.0 / (r * r * r * r) - 2.0);  // alpha = r^2
}

float roughnessFromShininess(float shininess) {
    const double n = std::clamp(double(shininess), 0.0, double(shininessFromRoughness(kMinRoughness)));
    return float(std::sqrt(std::sqrt(2.0 / (n + 2.0))));
}

bool degenerateTriangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    const glm::dvec3 da(a), db(b), dc(c);
    const glm::dvec3 e0 = db - da, e1 = dc - da, e2 = dc - db;
    const double area2 = glm::length(glm::cross(e0, e1));
    const double longest2 = std::max({glm::dot(e0, e0), glm::dot(e1, e1), glm::dot(e2, e2)});
    return !(area2 > 1e-10 * longest2) || !std::isfinite(area2);
}

}  // namespace lp
