#include "engine/io/obj_loader.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include <tiny_obj_loader.h>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/scene/mesh_ops.hpp"

namespace lp {
namespace fs = std::filesystem;

namespace {

bool finite3(const float* v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

glm::vec3 colorOr(const tinyobj::real_t c[3], glm::vec3 fallback, const std::string& what, std::vector<std::string>& bad) {
    if (!finite3(c)) {
        bad.push_back(what);
        return fallback;
    }
    return glm::max(glm::vec3(c[0], c[1], c[2]), glm::vec3(0.0f));
}

fs::path texturePath(const fs::path& dir, const std::string& name) {
    if (name.empty()) return {};
    fs::path p(name);
    return p.is_absolute() ? p : (dir / p).lexically_normal();
}

Material convertMaterial(const tinyobj::material_t& m, const fs::path& dir, const std::string& file,
                         MeshLoadReport& report) {
    Material out;
    std::vector<std::string> bad;
    out.name = m.name;
    out.diffuse = colorOr(m.diffuse, out.diffuse, "Kd", bad);
    out.specular = colorOr(m.specular, out.specular, "Ks", bad);
    out.emission = colorOr(m.emission, out.emission, "Ke", bad);
    if (std::isfinite(m.shininess)) out.shininess = std::clamp(float(m.shininess), 0.0f, 10000.0f);
    else bad.push_back("Ns");
    out.diffuseMap = texturePath(dir, m.diffuse_texname);
    std::string bump = !m.bump_texname.empty() ? m.bump_texname : m.normal_texname;
    out.bumpMap = texturePath(dir, bump);
    const auto& opt = !m.bump_texname.empty() ? m.bump_texopt : m.normal_texopt;
    if (!bump.empty() && std::isfinite(opt.bump_multiplier)) out.bumpScale = opt.bump_multiplier;
    if (!bad.empty()) {
        std::string list;
        for (const auto& b : bad) list += (list.empty() ? "" : ", ") + b;
        std::string msg = file + ": material '" + m.name + "': non-finite " + list + "; using defaults";
        report.warnings.push_back(msg);
        logWarn(msg);
    }
    return out;
}

// Twice the triangle's area relative to the mesh scale: below this a face is degenerate.
bool degenerate(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, float scale) {
    glm::vec3 n = glm::cross(b - a, c - a);
    float area2 = glm::length(n);
    return !(area2 > 1e-12f * scale * scale);
}

}  // namespace

MeshData loadObj(const fs::path& path, MeshLoadReport* reportOut) {
    MeshLoadReport report;
    const std::string file = path.string();
    if (!fs::exists(path)) throw Error(file + ": file not found");
    if (fs::is_directory(path)) throw Error(file + ": is a folder, not an OBJ file");

    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    config.mtl_search_path = path.parent_path().string();
    tinyobj::ObjReader reader;
    const bool ok = reader.ParseFromFile(file, config);
    auto warnLines = [&](const std::string& text) {
        size_t start = 0;
        while (start < text.size()) {
            size_t end = text.find('\n', start);
            std::string line = text.substr(start, end == std::string::npos ? std::string::npos : end - start);
            if (!line.empty()) {
                std::string msg = file + ": " + line;
                report.warnings.push_back(msg);
                logWarn(msg);
            }
            if (end == std::string::npos) break;
            start = end + 1;
        }
    };
    if (!ok) {
        std::string err = reader.Error();
        while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
        for (char& c : err)
            if (c == '\n') c = ' ';
        throw Error(file + ": " + (err.empty() ? "could not be parsed" : err));
    }
    warnLines(reader.Warning());

    const auto& attrib = reader.GetAttrib();
    const auto& shapes = reader.GetShapes();
    const auto& materials = reader.GetMaterials();

    MeshData mesh;
    mesh.name = path.stem().string();
    for (const auto& m : materials) mesh.materials.push_back(convertMaterial(m, path.parent_path(), file, report));
    const int defaultMaterial = int(mesh.materials.size());
    mesh.materials.push_back(Material{});  // for faces without (or with a bad) material id

    const size_t positionCount = attrib.vertices.size() / 3;
    const size_t normalCount = attrib.normals.size() / 3;
    const size_t uvCount = attrib.texcoords.size() / 2;
    // Mesh scale for the degeneracy threshold.
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    for (size_t i = 0; i < positionCount; ++i) {
        const float* p = &attrib.vertices[3 * i];
        if (!finite3(p)) continue;
        lo = glm::min(lo, glm::vec3(p[0], p[1], p[2]));
        hi = glm::max(hi, glm::vec3(p[0], p[1], p[2]));
    }
    const float scale = positionCount ? std::max(glm::length(hi - lo), 1e-30f) : 1.0f;

    std::map<std::tuple<int, int, int>, uint32_t> dedup;
    std::map<int, std::vector<uint32_t>> byMaterial;  // triangles grouped by material
    std::vector<int> positionOf;  // OBJ position index of each output vertex
    bool missingNormals = false;
    size_t badIndex = 0;
    auto vertexFor = [&](const tinyobj::index_t& idx) -> int64_t {
        if (idx.vertex_index < 0 || size_t(idx.vertex_index) >= positionCount) return -1;
        int n = (idx.normal_index >= 0 && size_t(idx.normal_index) < normalCount) ? idx.normal_index : -1;
        int t = (idx.texcoord_index >= 0 && size_t(idx.texcoord_index) < uvCount) ? idx.texcoord_index : -1;
        if (n < 0) missingNormals = true;
        auto key = std::make_tuple(idx.vertex_index, n, t);
        auto it = dedup.find(key);
        if (it != dedup.end()) return it->second;
        Vertex v;
        const float* p = &attrib.vertices[3 * size_t(idx.vertex_index)];
        v.position = glm::vec3(p[0], p[1], p[2]);
        if (n >= 0) {
            const float* nn = &attrib.normals[3 * size_t(n)];
            glm::vec3 nv(nn[0], nn[1], nn[2]);
            float len = glm::length(nv);
            if (len > 0.0f && std::isfinite(len)) v.normal = nv / len;
            else missingNormals = true;
        }
        if (t >= 0) {
            const float* tt = &attrib.texcoords[2 * size_t(t)];
            if (std::isfinite(tt[0]) && std::isfinite(tt[1])) v.uv = glm::vec2(tt[0], tt[1]);
        }
        uint32_t id = uint32_t(mesh.vertices.size());
        mesh.vertices.push_back(v);
        positionOf.push_back(idx.vertex_index);
        dedup.emplace(key, id);
        return id;
    };

    for (const auto& shape : shapes) {
        const auto& ids = shape.mesh.indices;
        for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
            if (shape.mesh.num_face_vertices[f] != 3 || 3 * f + 2 >= ids.size()) continue;
            const tinyobj::index_t tri[3] = {ids[3 * f], ids[3 * f + 1], ids[3 * f + 2]};
            bool inRange = true, finite = true;
            for (const auto& t : tri) {
                if (t.vertex_index < 0 || size_t(t.vertex_index) >= positionCount) inRange = false;
                else if (!finite3(&attrib.vertices[3 * size_t(t.vertex_index)])) finite = false;
            }
            if (!inRange) {
                ++badIndex;
                continue;
            }
            if (!finite) {
                ++report.droppedNonFinite;
                continue;
            }
            auto pos = [&](int i) {
                const float* p = &attrib.vertices[3 * size_t(tri[i].vertex_index)];
                return glm::vec3(p[0], p[1], p[2]);
            };
            if (tri[0].vertex_index == tri[1].vertex_index || tri[1].vertex_index == tri[2].vertex_index ||
                tri[0].vertex_index == tri[2].vertex_index || degenerate(pos(0), pos(1), pos(2), scale)) {
                ++report.droppedDegenerate;
                continue;
            }
            int mat = f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1;
            if (mat < 0 || mat >= defaultMaterial) mat = defaultMaterial;
            auto& list = byMaterial[mat];
            for (const auto& t : tri) list.push_back(uint32_t(vertexFor(t)));
        }
    }
    if (badIndex) {
        std::string msg = file + ": " + std::to_string(badIndex) + " faces with out-of-range vertex indices dropped";
        report.warnings.push_back(msg);
        logWarn(msg);
    }
    if (report.droppedDegenerate || report.droppedNonFinite) {
        std::string msg = file + ": dropped " + std::to_string(report.droppedDegenerate) + " degenerate and " +
                          std::to_string(report.droppedNonFinite) + " non-finite triangles";
        report.warnings.push_back(msg);
        logWarn(msg);
    }
    if (byMaterial.empty()) throw Error(file + ": no triangles");

    for (auto& [mat, list] : byMaterial) {
        mesh.subMeshes.push_back(SubMesh{uint32_t(mesh.indices.size()), uint32_t(list.size()), mat});
        mesh.indices.insert(mesh.indices.end(), list.begin(), list.end());
    }
    if (missingNormals) {
        // Area-weighted, accumulated per OBJ position so that vertices split by UV seams share one
        // smooth normal.
        std::vector<glm::vec3> acc(positionCount, glm::vec3(0.0f));
        for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
            const uint32_t a = mesh.indices[i], b = mesh.indices[i + 1], c = mesh.indices[i + 2];
            glm::vec3 n = glm::cross(mesh.vertices[b].position - mesh.vertices[a].position,
                                     mesh.vertices[c].position - mesh.vertices[a].position);
            for (uint32_t v : {a, b, c}) acc[size_t(positionOf[v])] += n;
        }
        for (size_t v = 0; v < mesh.vertices.size(); ++v) {
            glm::vec3 n = acc[size_t(positionOf[v])];
            float len = glm::length(n);
            mesh.vertices[v].normal = (len > 0.0f && std::isfinite(len)) ? n / len : glm::vec3(0.0f, 1.0f, 0.0f);
        }
        report.generatedNormals = true;
    }
    computeTangents(mesh);
    report.generatedTangents = true;
    computeBounds(mesh);
    if (reportOut) *reportOut = report;
    return mesh;
}

}  // namespace lp
