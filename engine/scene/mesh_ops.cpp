#include "engine/scene/mesh_ops.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <unordered_map>
#include <utility>

#include "engine/core/error.hpp"

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

namespace {

// A vertex as MikkTSpace identifies it: position, normal and uv, compared bit for bit (so that two
// index-buffer entries of one corner share a tangent, and NaNs compare as themselves).
struct WeldKey {
    uint32_t bits[8];
    bool operator==(const WeldKey& o) const { return std::memcmp(bits, o.bits, sizeof bits) == 0; }
};
struct WeldKeyHash {
    size_t operator()(const WeldKey& k) const {
        uint64_t h = 1469598103934665603ull;
        for (uint32_t b : k.bits) h = (h ^ b) * 1099511628211ull;
        return size_t(h);
    }
};

WeldKey weldKey(const Vertex& v) {
    const float f[8] = {v.position.x, v.position.y, v.position.z, v.normal.x, v.normal.y, v.normal.z, v.uv.x, v.uv.y};
    WeldKey k;
    std::memcpy(k.bits, f, sizeof k.bits);
    return k;
}

glm::vec3 projectedUnit(glm::vec3 v, glm::vec3 n) {
    v -= n * glm::dot(n, v);
    const float len = glm::length(v);
    return (len > 0.0f && std::isfinite(len)) ? v / len : glm::vec3(0.0f);
}

}  // namespace

void computeTangents(MeshData& mesh, std::vector<uint32_t>* copiedFrom) {
    if (copiedFrom) copiedFrom->clear();
    const size_t triCount = mesh.indices.size() / 3;
    // Weld identical vertices.
    std::vector<uint32_t> weld(mesh.vertices.size());
    {
        std::unordered_map<WeldKey, uint32_t, WeldKeyHash> first;
        first.reserve(mesh.vertices.size());
        for (size_t v = 0; v < mesh.vertices.size(); ++v)
            weld[v] = first.emplace(weldKey(mesh.vertices[v]), uint32_t(first.size())).first->second;
    }
    auto welded = [&](size_t tri, int k) { return weld[mesh.indices[tri * 3 + size_t(k)]]; };

    // Per triangle: the unit direction of increasing u (MikkTSpace's vOs, signed by the UV area so
    // that it is dp/du's direction) and whether the UV mapping keeps the winding (w = +1).
    std::vector<glm::vec3> triTangent(triCount, glm::vec3(0.0f));
    std::vector<int8_t> orientation(triCount, 0);  // +1 / -1, 0: no UV area (takes a neighbour's)
    for (size_t t = 0; t < triCount; ++t) {
        const Vertex &v0 = mesh.vertices[mesh.indices[t * 3]], &v1 = mesh.vertices[mesh.indices[t * 3 + 1]],
                     &v2 = mesh.vertices[mesh.indices[t * 3 + 2]];
        const glm::vec3 d1 = v1.position - v0.position, d2 = v2.position - v0.position;
        const glm::vec2 t21 = v1.uv - v0.uv, t31 = v2.uv - v0.uv;
        const float area = t21.x * t31.y - t21.y * t31.x;
        if (!(area != 0.0f) || !std::isfinite(area)) continue;
        const float sign = area > 0.0f ? 1.0f : -1.0f;
        const glm::vec3 os = d1 * t31.y - d2 * t21.y;
        const float len = glm::length(os);
        orientation[t] = int8_t(sign);
        if (len > 0.0f && std::isfinite(len)) triTangent[t] = os * (sign / len);
    }

    // The triangles around each welded vertex, and edge neighbours for the UV-degenerate ones.
    const size_t weldCount = weld.empty() ? 0 : size_t(*std::max_element(weld.begin(), weld.end())) + 1;
    std::vector<std::vector<uint32_t>> around(weldCount);  // corner numbers (tri * 3 + k)
    for (size_t t = 0; t < triCount; ++t)
        for (int k = 0; k < 3; ++k) around[welded(t, k)].push_back(uint32_t(t * 3 + size_t(k)));
    auto sharesEdge = [&](size_t a, size_t b, uint32_t at) {  // another welded vertex besides `at`
        for (int i = 0; i < 3; ++i) {
            const uint32_t wa = welded(a, i);
            if (wa == at) continue;
            for (int j = 0; j < 3; ++j)
                if (welded(b, j) == wa) return true;
        }
        return false;
    };
    // A triangle with no UV area joins any group: it takes the orientation of an edge neighbour
    // that has one (propagated across runs of such triangles), else +1.
    for (bool changed = true; changed;) {
        changed = false;
        for (size_t t = 0; t < triCount; ++t) {
            if (orientation[t] != 0) continue;
            for (int k = 0; k < 3 && orientation[t] == 0; ++k)
                for (uint32_t c : around[welded(t, k)]) {
                    const size_t o = c / 3;
                    if (o != t && orientation[o] != 0 && sharesEdge(t, o, welded(t, k))) {
                        orientation[t] = orientation[o];
                        changed = true;
                        break;
                    }
                }
        }
    }
    for (auto& o : orientation)
        if (o == 0) o = 1;

    // Per welded vertex: groups of its triangles connected through edges at the vertex and of one
    // orientation (MikkTSpace's default 180-degree threshold never splits a group further). A
    // group's tangent: the sum over its corners of the triangle's tangent projected into the
    // vertex's tangent plane, weighted by the corner's angle in that plane; normalised.
    std::vector<glm::vec4> cornerTangent(triCount * 3, glm::vec4(0.0f));
    std::vector<int> group;
    std::vector<size_t> queue;
    for (size_t w = 0; w < weldCount; ++w) {
        const std::vector<uint32_t>& corners = around[w];
        const size_t n = corners.size();
        group.assign(n, -1);
        int groups = 0;
        for (size_t i = 0; i < n; ++i) {
            if (group[i] >= 0) continue;
            group[i] = groups;
            queue.assign(1, i);
            while (!queue.empty()) {  // flood fill over edge-sharing triangles of one orientation
                const size_t m = queue.back();
                queue.pop_back();
                for (size_t j = 0; j < n; ++j)
                    if (group[j] < 0 && orientation[corners[j] / 3] == orientation[corners[m] / 3] &&
                        sharesEdge(corners[j] / 3, corners[m] / 3, uint32_t(w))) {
                        group[j] = groups;
                        queue.push_back(j);
                    }
            }
            ++groups;
        }
        for (int g = 0; g < groups; ++g) {
            glm::vec3 sum(0.0f), normal(0.0f, 1.0f, 0.0f);
            for (size_t i = 0; i < n; ++i) {
                if (group[i] != g) continue;
                const size_t t = corners[i] / 3;
                const int k = int(corners[i] % 3);
                const Vertex& v = mesh.vertices[mesh.indices[corners[i]]];
                normal = v.normal;
                const glm::vec3 e1 = projectedUnit(mesh.vertices[mesh.indices[t * 3 + size_t((k + 1) % 3)]].position - v.position, v.normal);
                const glm::vec3 e2 = projectedUnit(mesh.vertices[mesh.indices[t * 3 + size_t((k + 2) % 3)]].position - v.position, v.normal);
                const float angle = std::acos(std::clamp(glm::dot(e1, e2), -1.0f, 1.0f));
                const glm::vec3 tangent = projectedUnit(triTangent[t], v.normal);
                if (std::isfinite(angle)) sum += angle * tangent;
            }
            const float len = glm::length(sum);
            glm::vec3 tangent = (len > 1e-20f && std::isfinite(len)) ? sum / len : glm::normalize(anyPerpendicular(normal));
            if (!std::isfinite(tangent.x + tangent.y + tangent.z)) tangent = glm::vec3(1.0f, 0.0f, 0.0f);
            for (size_t i = 0; i < n; ++i)
                if (group[i] == g) cornerTangent[corners[i]] = glm::vec4(tangent, float(orientation[corners[i] / 3]));
        }
    }

    // Back to vertices: a vertex whose corners got different frames (a handedness change or a
    // break in its fan) is split, one copy per frame.
    std::vector<std::vector<std::pair<glm::vec4, uint32_t>>> copies(mesh.vertices.size());
    for (size_t c = 0; c < triCount * 3; ++c) {
        const uint32_t v = mesh.indices[c];
        const glm::vec4 t = cornerTangent[c];
        auto& list = copies[v];
        auto same = std::find_if(list.begin(), list.end(), [&](const auto& e) { return std::memcmp(&e.first, &t, sizeof t) == 0; });
        if (same != list.end()) {
            mesh.indices[c] = same->second;
            continue;
        }
        uint32_t target = v;
        if (!list.empty()) {
            target = uint32_t(mesh.vertices.size());
            mesh.vertices.push_back(mesh.vertices[v]);
            if (copiedFrom) copiedFrom->push_back(v);
        }
        mesh.vertices[target].tangent = t;
        list.emplace_back(t, target);
        mesh.indices[c] = target;
    }
    // Vertices no triangle uses.
    for (size_t v = 0; v < copies.size(); ++v)
        if (copies[v].empty()) {
            const glm::vec3 p = anyPerpendicular(mesh.vertices[v].normal);
            mesh.vertices[v].tangent = glm::vec4(std::isfinite(p.x + p.y + p.z) ? glm::normalize(p) : glm::vec3(1, 0, 0), 1.0f);
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

bool selectMaterialVariant(MeshData& mesh, const std::string& variant) {
    if (mesh.materialVariants.empty()) return variant.empty();  // nothing to switch (an OBJ, a primitive)
    int index = -1;
    if (!variant.empty()) {
        const auto it = std::find(mesh.materialVariants.begin(), mesh.materialVariants.end(), variant);
        if (it == mesh.materialVariants.end()) return false;
        index = int(it - mesh.materialVariants.begin());
    }
    for (SubMesh& sub : mesh.subMeshes)
        sub.material = index >= 0 && size_t(index) < sub.variantMaterials.size() ? sub.variantMaterials[size_t(index)]
                                                                                  : sub.defaultMaterial;
    return true;
}

std::string materialVariantList(const MeshData& mesh) {
    std::string list;
    for (const std::string& v : mesh.materialVariants) list += (list.empty() ? "" : ", ") + quoteUserText(v);
    return list;
}

}  // namespace lp
