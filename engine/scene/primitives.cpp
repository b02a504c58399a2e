#include "engine/scene/primitives.hpp"

#include <algorithm>
#include <cmath>

#include "engine/scene/mesh_ops.hpp"

namespace lp {
namespace {
void finish(MeshData& m, const char* name) {
    m.name = name;
    m.materials = {Material{}};
    m.subMeshes = {SubMesh{0, uint32_t(m.indices.size()), 0}};
    computeBounds(m);
}
}  // namespace

MeshData makePlane(float size, int subdivisions) {
    MeshData m;
    const int n = std::max(1, subdivisions);
    for (int z = 0; z <= n; ++z) {
        for (int x = 0; x <= n; ++x) {
            Vertex v;
            float u = float(x) / n, w = float(z) / n;
            v.position = glm::vec3((u - 0.5f) * size, 0.0f, (w - 0.5f) * size);
            v.normal = glm::vec3(0, 1, 0);
            v.uv = glm::vec2(u, 1.0f - w);
            v.tangent = glm::vec4(1, 0, 0, 1);
            m.vertices.push_back(v);
        }
    }
    for (int z = 0; z < n; ++z) {
        for (int x = 0; x < n; ++x) {
            uint32_t a = uint32_t(z * (n + 1) + x), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
            // Seen from +Y: a(x,z) -> c(x,z+1) -> b(x+1,z) is counter-clockwise.
            m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
        }
    }
    finish(m, "plane");
    return m;
}

MeshData makeSphere(float radius, int segments, int rings) {
    MeshData m;
    segments = std::max(3, segments);
    rings = std::max(2, rings);
    const float pi = 3.14159265358979f;
    for (int r = 0; r <= rings; ++r) {
        float theta = pi * float(r) / rings;  // 0 at +Y
        for (int s = 0; s <= segments; ++s) {
            float phi = 2.0f * pi * float(s) / segments;
            glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
            Vertex v;
            v.normal = n;
            v.position = n * radius;
            v.uv = glm::vec2(float(s) / segments, 1.0f - float(r) / rings);
            // d(position)/d(phi) direction; at the poles use the same azimuthal direction.
            v.tangent = glm::vec4(-std::sin(phi), 0.0f, -std::cos(phi), 1.0f);
            m.vertices.push_back(v);
        }
    }
    const uint32_t row = uint32_t(segments + 1);
    for (int r = 0; r < rings; ++r) {
        for (int s = 0; s < segments; ++s) {
            uint32_t a = uint32_t(r) * row + uint32_t(s), b = a + 1, c = a + row, d = c + 1;
            if (r != 0) m.indices.insert(m.indices.end(), {a, c, b});
            if (r != rings - 1) m.indices.insert(m.indices.end(), {b, c, d});
        }
    }
    finish(m, "sphere");
    return m;
}

MeshData makeCube(float size) {
    MeshData m;
    const float h = 0.5f * size;
    const glm::vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const glm::vec3& n : normals) {
        glm::vec3 t = std::abs(n.y) > 0.5f ? glm::vec3(1, 0, 0) : glm::vec3(-n.z, 0, n.x);  // tangent in the face
        glm::vec3 b = glm::cross(n, t);
        uint32_t base = uint32_t(m.vertices.size());
        const glm::vec2 corners[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
        for (const glm::vec2& c : corners) {
            Vertex v;
            v.position = (n + c.x * t + c.y * b) * h;
            v.normal = n;
            v.uv = (c + glm::vec2(1.0f)) * 0.5f;
            v.tangent = glm::vec4(t, 1.0f);
            m.vertices.push_back(v);
        }
        m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    finish(m, "cube");
    return m;
}

}  // namespace lp
