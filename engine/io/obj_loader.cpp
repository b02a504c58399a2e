#include "engine/io/obj_loader.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <tuple>

#include <tiny_obj_loader.h>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/io/file_check.hpp"
#include "engine/io/obj_text.hpp"
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

// A map's file, relative to the MTL's folder; `-clamp on` samples it clamped to its edge (the MTL
// option's texture coordinates clamped to [0, 1]) instead of repeating.
TextureRef texturePath(const fs::path& dir, const std::string& name, const tinyobj::texture_option_t& option) {
    if (name.empty()) return {};
    fs::path p(name);
    TextureRef t = TextureRef::file(p.is_absolute() ? p : (dir / p).lexically_normal());
    if (option.clamp) t.sampler.wrapS = t.sampler.wrapT = 33071;  // GL_CLAMP_TO_EDGE
    return t;
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
    out.roughness = roughnessFromShininess(out.shininess);
    out.diffuseMap = texturePath(dir, m.diffuse_texname, m.diffuse_texopt);
    out.emissiveMap = texturePath(dir, m.emissive_texname, m.emissive_texopt);
    // "norm" is a tangent-space normal map; "bump" / "map_Bump" a height map (the MTL conversion in
    // the README). tinyobjloader keeps them apart: normal_texname and bump_texname.
    out.normalMap = texturePath(dir, m.normal_texname, m.normal_texopt);
    if (!m.normal_texname.empty() && std::isfinite(m.normal_texopt.bump_multiplier))
        out.normalScale = m.normal_texopt.bump_multiplier;
    out.bumpMap = texturePath(dir, m.bump_texname, m.bump_texopt);
    if (!m.bump_texname.empty() && std::isfinite(m.bump_texopt.bump_multiplier)) out.bumpScale = m.bump_texopt.bump_multiplier;
    // d (tinyobjloader turns Tr into d = 1 - Tr): below 1 the material is see-through, drawn
    // alpha-blended by the transparent pass.
    if (std::isfinite(m.dissolve)) out.opacity = std::clamp(float(m.dissolve), 0.0f, 1.0f);
    else bad.push_back("d");
    // The refraction/glass illumination models (the MTL specification's illum 4, 6 and 7) map onto
    // KHR_materials_transmission with the index Ni: 6 and 7 add the refracted light filtered by Tf
    // ("(1 - Ks) Tf It"): transmission 1 and base colour Tf (Kd has no share left); 4 is glass whose
    // dissolve d refracts: transmission 1 - d, base Kd. A transmissive material is not also blended.
    // Its volume's thickness (MTL has none) is set by loadObj from the material's triangles.
    const bool glass = m.illum == 4 || m.illum == 6 || m.illum == 7;
    if (glass) {
        const float transmission = m.illum == 4 ? 1.0f - out.opacity : 1.0f;
        if (transmission > 0.0f) {
            out.transmission = transmission;
            if (m.illum != 4) out.diffuse = glm::min(colorOr(m.transmittance, glm::vec3(1.0f), "Tf", bad), glm::vec3(1.0f));
            if (std::isfinite(m.ior) && m.ior >= 1.0f) {
                out.ior = float(m.ior);
            } else {
                out.ior = 1.0f;
                std::ostringstream ni;
                ni << m.ior;
                std::string msg = file + ": material " + quoteUserText(m.name) + ": Ni " + ni.str() +
                                  " is below 1 (or not finite); its refraction bends no ray (Ni 1)";
                report.warnings.push_back(msg);
                logWarn(msg);
            }
            out.opacity = 1.0f;
        }
    }
    if (out.opacity < 1.0f) out.alphaMode = AlphaMode::Blend;
    if (!bad.empty()) {
        std::string list;
        for (const auto& b : bad) list += (list.empty() ? "" : ", ") + b;
        std::string msg = file + ": material " + quoteUserText(m.name) + ": non-finite " + list + "; using defaults";
        report.warnings.push_back(msg);
        logWarn(msg);
    }
    return out;
}

// Reads each "mtllib" through the regular-file check, so a FIFO or folder named there is an error
// naming it instead of a read that blocks, and sanitises its numbers (sanitizeMtlText).
class CheckedMaterialReader : public tinyobj::MaterialReader {
public:
    CheckedMaterialReader(fs::path folder, std::string objFile, std::vector<std::string>& warnings)
        : folder_(std::move(folder)), objFile_(std::move(objFile)), warnings_(warnings) {}

    bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* matMap, std::string* warn, std::string* err) override {
        const fs::path path = fs::path(name).is_absolute() ? fs::path(name) : (folder_ / name).lexically_normal();
        std::error_code ec;
        if (!fs::exists(path, ec)) {  // a missing MTL is common in exported models: defaults, one warning
            warnings_.push_back(objFile_ + ": mtllib " + path.string() + ": file not found; using default materials");
            return false;
        }
        std::string text;
        try {
            text = readFileChecked(path, kMaxTextFileBytes, "an MTL file", true);
        } catch (const Error& e) {
            throw Error(objFile_ + ": mtllib " + e.what());
        }
        std::istringstream in(sanitizeMtlText(text, path.string(), warnings_));
        tinyobj::LoadMtl(matMap, materials, &in, warn, err);
        return true;
    }

private:
    fs::path folder_;
    std::string objFile_;
    std::vector<std::string>& warnings_;
};

}  // namespace

void setObjTransmissionThickness(MeshData& mesh) {
    for (size_t mat = 0; mat < mesh.materials.size(); ++mat) {
        Material& material = mesh.materials[mat];
        if (!material.transmissive()) continue;
        glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
        for (const SubMesh& sm : mesh.subMeshes) {
            if (size_t(sm.material) != mat) continue;
            for (uint32_t i = sm.firstIndex; i < sm.firstIndex + sm.indexCount && i < mesh.indices.size(); ++i) {
                lo = glm::min(lo, mesh.vertices[mesh.indices[i]].position);
                hi = glm::max(hi, mesh.vertices[mesh.indices[i]].position);
            }
        }
        const glm::vec3 extent = hi - lo;
        material.thickness = lo.x <= hi.x ? std::max(std::min({extent.x, extent.y, extent.z}), 0.0f) : 0.0f;
    }
}

MeshData loadObj(const fs::path& path, MeshLoadReport* reportOut) {
    MeshLoadReport report;
    const std::string file = path.string();
    // Checked once (regular file, sane size), read without blocking, the UTF-8 BOM removed: tinyobjloader
    // would take "\xEF\xBB\xBFv" for an unknown statement and lose the first vertex.
    const std::string text = readFileChecked(path, kMaxTextFileBytes, "an OBJ file", true);
    const ObjTextScan scan = scanObjText(text, file);

    std::vector<std::string> parserWarnings;
    CheckedMaterialReader materialReader(path.parent_path(), file, parserWarnings);
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warning, error;
    std::istringstream objStream(text);
    const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warning, &error, &objStream, &materialReader,
                                     true, false);
    auto warn = [&](const std::string& msg) {
        report.warnings.push_back(msg);
        logWarn(msg);
    };
    // The parsers' warnings (a broken exporter repeats itself) are summarised after the first few.
    const size_t kWarningsShown = 5;
    size_t warningsSeen = 0;
    auto warnCapped = [&](const std::string& msg) {
        report.warnings.push_back(msg);
        if (++warningsSeen <= kWarningsShown) logWarn(msg);
    };
    auto warnLines = [&](const std::string& text) {
        size_t start = 0;
        while (start < text.size()) {
            size_t end = text.find('\n', start);
            std::string line = text.substr(start, end == std::string::npos ? std::string::npos : end - start);
            // tinyobjloader's own note on a missing MTL repeats CheckedMaterialReader's, which names the file.
            const bool repeatsMaterialWarning = line.rfind("Failed to load material file", 0) == 0 && !parserWarnings.empty();
            if (!line.empty() && !repeatsMaterialWarning) warnCapped(file + ": " + line);
            if (end == std::string::npos) break;
            start = end + 1;
        }
    };
    for (const auto& w : parserWarnings) warnCapped(w);
    if (!ok) {
        std::string err = error;
        while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
        for (char& c : err)
            if (c == '\n') c = ' ';
        throw Error(file + ": " + (err.empty() ? "could not be parsed" : err));
    }
    warnLines(warning);
    if (warningsSeen > kWarningsShown)
        logWarn(file + ": " + std::to_string(warningsSeen - kWarningsShown) + " more warnings like these");
    if (scan.nonFinitePositions)
        warn(file + ":" + std::to_string(scan.firstNonFinitePositionLine) + ": " +
                 std::to_string(scan.nonFinitePositions) + " vertices with NaN, Inf or beyond +-1e18 coordinates (first here); their triangles are dropped");
    if (scan.nonFiniteAttributes)
        warn(file + ":" + std::to_string(scan.firstNonFiniteAttributeLine) + ": " +
                 std::to_string(scan.nonFiniteAttributes) + " normals or texture coordinates with NaN or Inf (first here) ignored");

    // The positions as written: tinyobjloader turns "nan" into 0, which would keep a garbage triangle.
    if (scan.positions.size() == attrib.vertices.size()) attrib.vertices = scan.positions;

    MeshData mesh;
    mesh.name = path.stem().string();
    for (const auto& m : materials) mesh.materials.push_back(convertMaterial(m, path.parent_path(), file, report));
    const int defaultMaterial = int(mesh.materials.size());
    mesh.materials.push_back(Material{});  // for faces without (or with a bad) material id

    const size_t positionCount = attrib.vertices.size() / 3;
    const size_t normalCount = attrib.normals.size() / 3;
    // Vertex colours (the `v x y z r g b` extension), only when every `v` line has them (tinyobjloader
    // keeps none otherwise). OBJ does not say their colour space; MeshLab, scanners and most exporters
    // write display (sRGB) values, decoded here to the linear multipliers glTF's COLOR_0 gives.
    const bool hasColors = attrib.colors.size() == attrib.vertices.size() &&
                           std::any_of(attrib.colors.begin(), attrib.colors.end(), [](float c) { return c != 1.0f; });
    size_t colorsClamped = 0;
    const size_t uvCount = attrib.texcoords.size() / 2;
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
        if (hasColors) {
            const float* c = &attrib.colors[3 * size_t(idx.vertex_index)];
            for (int k = 0; k < 3; ++k) {
                const float x = std::isfinite(c[k]) ? std::clamp(c[k], 0.0f, 1.0f) : 1.0f;
                if (x != c[k]) ++colorsClamped;
                // sRGB to linear (IEC 61966-2-1)
                v.color[k] = x <= 0.04045f ? x / 12.92f : std::pow((x + 0.055f) / 1.055f, 2.4f);
            }
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
                tri[0].vertex_index == tri[2].vertex_index || degenerateTriangle(pos(0), pos(1), pos(2))) {
                ++report.droppedDegenerate;
                continue;
            }
            int mat = f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1;
            if (mat < 0 || mat >= defaultMaterial) mat = defaultMaterial;
            auto& list = byMaterial[mat];
            for (const auto& t : tri) list.push_back(uint32_t(vertexFor(t)));
        }
    }
    if (colorsClamped) warn(file + ": " + std::to_string(colorsClamped) + " vertex colour components outside [0, 1] clamped");
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
    setObjTransmissionThickness(mesh);
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
