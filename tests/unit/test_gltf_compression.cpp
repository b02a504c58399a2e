// glTF's compressed geometry: KHR_draco_mesh_compression and EXT_meshopt_compression files, made here
// with the libraries' own encoders from a small mesh, load as that mesh within the quantisation's
// bound; corrupt streams and inconsistent declarations are one error line naming the element.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include <draco/compression/encode.h>
#include <draco/compression/expert_encode.h>
#include <draco/mesh/mesh.h>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include "engine/io/gltf_loader.hpp"
#include "engine/io/obj_loader.hpp"
#include "tests/unit/gltf_test_files.hpp"

using namespace lp;
namespace fs = std::filesystem;
using lp::test::loadError;
using lp::test::TempDir;

namespace {

// A 6 x 6 grid over [0, 2]^2 lifted to z = 0.3 sin(x) cos(y): 36 vertices, 50 triangles, analytic
// unit normals, uvs (x, y) / 2.
struct Grid {
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec2> uvs;
    std::vector<uint32_t> indices;
};
Grid makeGrid() {
    Grid g;
    constexpr int n = 6;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const float x = 2.0f * float(i) / float(n - 1), y = 2.0f * float(j) / float(n - 1);
            g.positions.emplace_back(x, y, 0.3f * std::sin(x) * std::cos(y));
            g.normals.push_back(glm::normalize(glm::vec3(-0.3f * std::cos(x) * std::cos(y), 0.3f * std::sin(x) * std::sin(y), 1.0f)));
            g.uvs.emplace_back(x / 2.0f, y / 2.0f);
        }
    for (int j = 0; j + 1 < n; ++j)
        for (int i = 0; i + 1 < n; ++i) {
            const uint32_t a = uint32_t(j * n + i), b = a + 1, c = a + n, d = c + 1;
            g.indices.insert(g.indices.end(), {a, b, d, a, d, c});
        }
    return g;
}

std::string base64(const std::string& bytes) {
    static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 1])) << 8;
        if (i + 2 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 2]));
        out += k[(v >> 18) & 63];
        out += k[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? k[(v >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? k[v & 63] : '=';
    }
    return out;
}
std::string dataUri(const std::string& bytes) { return "data:application/octet-stream;base64," + base64(bytes); }

// Appends `bytes` to `buffer` at a 4-byte boundary; returns where they start.
size_t append(std::string& buffer, const void* bytes, size_t size) {
    buffer.resize((buffer.size() + 3) / 4 * 4, '\0');
    const size_t at = buffer.size();
    buffer.append(static_cast<const char*>(bytes), size);
    return at;
}

struct Bounds {
    float position, normal, uv;
};

// The loaded mesh is the grid within `b`: each loaded vertex is matched to the grid vertex nearest
// its position (the grid's spacing, 0.4, is far above any bound), its normal and uv compared; then
// the triangles, mapped to grid vertices and each rotated to start at its smallest index (the
// winding kept), must be the grid's. Names the first mismatch.
void expectGrid(const MeshData& m, const Grid& g, const Bounds& b) {
    std::vector<uint32_t> gridOf(m.vertices.size());
    for (size_t v = 0; v < m.vertices.size(); ++v) {
        const Vertex& x = m.vertices[v];
        size_t best = 0;
        for (size_t k = 1; k < g.positions.size(); ++k)
            if (glm::distance(x.position, g.positions[k]) < glm::distance(x.position, g.positions[best])) best = k;
        gridOf[v] = uint32_t(best);
        const float dp = glm::distance(x.position, g.positions[best]);
        ASSERT_LE(dp, b.position) << "vertex " << v << " position (" << x.position.x << ", " << x.position.y << ", " << x.position.z
                                  << ") is " << dp << " from grid vertex " << best;
        const float dn = glm::distance(x.normal, g.normals[best]);
        ASSERT_LE(dn, b.normal) << "vertex " << v << " (grid " << best << ") normal off by " << dn;
        const glm::vec2 uv(g.uvs[best].x, 1.0f - g.uvs[best].y);  // the loader flips v
        const float du = glm::distance(x.uv, uv);
        ASSERT_LE(du, b.uv) << "vertex " << v << " (grid " << best << ") uv (" << x.uv.x << ", " << x.uv.y << ") off by " << du;
    }
    auto canonical = [](std::array<uint32_t, 3> t) {
        while (t[0] > t[1] || t[0] > t[2]) t = {t[1], t[2], t[0]};
        return t;
    };
    std::vector<std::array<uint32_t, 3>> loaded, expected;
    for (size_t i = 0; i + 2 < m.indices.size(); i += 3)
        loaded.push_back(canonical({gridOf[m.indices[i]], gridOf[m.indices[i + 1]], gridOf[m.indices[i + 2]]}));
    for (size_t i = 0; i + 2 < g.indices.size(); i += 3) expected.push_back(canonical({g.indices[i], g.indices[i + 1], g.indices[i + 2]}));
    std::sort(loaded.begin(), loaded.end());
    std::sort(expected.begin(), expected.end());
    ASSERT_EQ(loaded.size(), expected.size()) << "triangles";
    for (size_t t = 0; t < loaded.size(); ++t)
        ASSERT_EQ(loaded[t], expected[t]) << "sorted triangle " << t << ": loaded (" << loaded[t][0] << ", " << loaded[t][1] << ", "
                                          << loaded[t][2] << "), grid (" << expected[t][0] << ", " << expected[t][1] << ", " << expected[t][2] << ")";
}

// ---- Draco ----

struct DracoFile {
    std::string stream;
    int positionId = -1, normalId = -1, uvId = -1;
};
constexpr int kDracoPositionBits = 14, kDracoNormalBits = 10, kDracoUvBits = 12;

// The grid as a Draco mesh, encoded by draco::Encoder (edgebreaker, which reorders the points) or
// draco::ExpertEncoder (sequential), positions, normals and uvs quantised.
DracoFile encodeDraco(const Grid& g, bool expert) {
    draco::Mesh mesh;
    mesh.set_num_points(uint32_t(g.positions.size()));
    auto add = [&](draco::GeometryAttribute::Type type, int components, const float* data) {
        draco::GeometryAttribute ga;
        ga.Init(type, nullptr, uint8_t(components), draco::DT_FLOAT32, false, int64_t(sizeof(float)) * components, 0);
        const int id = mesh.AddAttribute(ga, true, uint32_t(g.positions.size()));
        for (size_t i = 0; i < g.positions.size(); ++i)
            mesh.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(uint32_t(i)), data + i * size_t(components));
        return id;
    };
    const int pos = add(draco::GeometryAttribute::POSITION, 3, &g.positions[0].x);
    const int nrm = add(draco::GeometryAttribute::NORMAL, 3, &g.normals[0].x);
    const int uv = add(draco::GeometryAttribute::TEX_COORD, 2, &g.uvs[0].x);
    for (size_t i = 0; i < g.indices.size(); i += 3)
        mesh.AddFace({draco::PointIndex(g.indices[i]), draco::PointIndex(g.indices[i + 1]), draco::PointIndex(g.indices[i + 2])});
    draco::EncoderBuffer out;
    if (expert) {
        draco::ExpertEncoder encoder(mesh);
        encoder.SetAttributeQuantization(pos, kDracoPositionBits);
        encoder.SetAttributeQuantization(nrm, kDracoNormalBits);
        encoder.SetAttributeQuantization(uv, kDracoUvBits);
        encoder.SetEncodingMethod(draco::MESH_SEQUENTIAL_ENCODING);
        EXPECT_TRUE(encoder.EncodeToBuffer(&out).ok());
    } else {
        draco::Encoder encoder;
        encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, kDracoPositionBits);
        encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, kDracoNormalBits);
        encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, kDracoUvBits);
        EXPECT_TRUE(encoder.EncodeMeshToBuffer(mesh, &out).ok());
    }
    return {std::string(out.data(), out.size()), int(mesh.attribute(pos)->unique_id()), int(mesh.attribute(nrm)->unique_id()),
            int(mesh.attribute(uv)->unique_id())};
}

// A glTF of one Draco primitive: accessors 0-3 (POSITION, NORMAL, TEXCOORD_0, indices) without buffer
// views, the stream in bufferViews[0]. `quantized`: normals as normalised bytes and uvs as normalised
// shorts under KHR_mesh_quantization.
nlohmann::json dracoGltf(const Grid& g, const DracoFile& d, bool quantized) {
    const size_t n = g.positions.size();
    nlohmann::json doc = {{"asset", {{"version", "2.0"}}}};
    doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    if (quantized) {
        doc["extensionsUsed"].push_back("KHR_mesh_quantization");
        doc["extensionsRequired"].push_back("KHR_mesh_quantization");
    }
    doc["buffers"] = {{{"byteLength", d.stream.size()}, {"uri", dataUri(d.stream)}}};
    doc["bufferViews"] = {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", d.stream.size()}}};
    doc["accessors"] = {{{"componentType", 5126}, {"count", n}, {"type", "VEC3"}},
                        {{"componentType", quantized ? 5120 : 5126}, {"normalized", quantized}, {"count", n}, {"type", "VEC3"}},
                        {{"componentType", quantized ? 5123 : 5126}, {"normalized", quantized}, {"count", n}, {"type", "VEC2"}},
                        {{"componentType", 5123}, {"count", g.indices.size()}, {"type", "SCALAR"}}};
    nlohmann::json prim = {{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}}, {"indices", 3}};
    prim["extensions"]["KHR_draco_mesh_compression"] = {
        {"bufferView", 0}, {"attributes", {{"POSITION", d.positionId}, {"NORMAL", d.normalId}, {"TEXCOORD_0", d.uvId}}}};
    doc["meshes"] = {{{"primitives", {prim}}}};
    doc["nodes"] = {{{"mesh", 0}}};
    doc["scenes"] = {{{"nodes", {0}}}};
    doc["scene"] = 0;
    return doc;
}

// An octahedral unit vector whose two coordinates are each rounded by at most `half`: the point on
// the octahedron moves by at most sqrt(6) half (the third coordinate takes both errors), and
// normalising it, at least 1/sqrt(3) from the centre, stretches that by at most sqrt(3).
float octahedralBound(float half) { return std::sqrt(18.0f) * half; }

// Draco's bounds: a quantised component is off by at most half a step of its range (2 for the
// positions, 1 for the uvs) over 2^bits - 1 steps; its octahedral normals' coordinates span [-1, 1]
// in 2^bits - 1 steps. Normalised bytes and shorts add half their step per component.
Bounds dracoBounds(bool quantized) {
    const float position = std::sqrt(3.0f) * 0.5f * 2.0f / float((1 << kDracoPositionBits) - 1);
    const float normal = octahedralBound(1.0f / float((1 << kDracoNormalBits) - 1)) * 1.001f +
                         (quantized ? std::sqrt(3.0f) * 0.5f / 127.0f : 0.0f);
    const float uv = std::sqrt(2.0f) * 0.5f / float((1 << kDracoUvBits) - 1) + (quantized ? std::sqrt(2.0f) * 0.5f / 65535.0f : 0.0f);
    return {position * 1.001f + 1e-6f, normal, uv * 1.001f + 1e-6f};
}

}  // namespace

// Both encoders' streams load as the grid, through float accessors and through KHR_mesh_quantization's
// normalised integer ones, with the extension required or only used.
TEST(GltfCompression, DracoMeshesLoadAsTheOriginalWithinTheQuantisationBound) {
    TempDir t;
    const Grid g = makeGrid();
    for (const bool expert : {false, true})
        for (const bool quantized : {false, true}) {
            SCOPED_TRACE(std::string(expert ? "ExpertEncoder (sequential)" : "Encoder (edgebreaker)") + (quantized ? ", quantized accessors" : ""));
            const DracoFile d = encodeDraco(g, expert);
            ASSERT_FALSE(d.stream.empty());
            MeshLoadReport report;
            const MeshData m = loadGltf(t.write("draco.gltf", dracoGltf(g, d, quantized).dump()), &report).mesh;
            expectGrid(m, g, dracoBounds(quantized));
            EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
        }
    // Only in extensionsUsed, with uncompressed fallback data that the decoded mesh replaces: the
    // fallback here is the grid moved by +10 in x, which must not be what loads.
    const DracoFile d = encodeDraco(g, false);
    nlohmann::json doc = dracoGltf(g, d, false);
    doc.erase("extensionsRequired");
    std::string fallback;
    std::vector<glm::vec3> moved = g.positions;
    for (glm::vec3& p : moved) p.x += 10.0f;
    std::vector<uint16_t> indices(g.indices.begin(), g.indices.end());
    const size_t p0 = append(fallback, moved.data(), moved.size() * sizeof(glm::vec3));
    const size_t n0 = append(fallback, g.normals.data(), g.normals.size() * sizeof(glm::vec3));
    const size_t u0 = append(fallback, g.uvs.data(), g.uvs.size() * sizeof(glm::vec2));
    const size_t i0 = append(fallback, indices.data(), indices.size() * 2);
    doc["buffers"].push_back({{"byteLength", fallback.size()}, {"uri", dataUri(fallback)}});
    for (const auto& [offset, bytes] : std::vector<std::pair<size_t, size_t>>{
             {p0, moved.size() * 12}, {n0, g.normals.size() * 12}, {u0, g.uvs.size() * 8}, {i0, indices.size() * 2}}) {
        doc["accessors"][doc["bufferViews"].size() - 1]["bufferView"] = doc["bufferViews"].size();
        doc["bufferViews"].push_back({{"buffer", 1}, {"byteOffset", offset}, {"byteLength", bytes}});
    }
    expectGrid(loadGltf(t.write("draco_fallback.gltf", doc.dump())).mesh, g, dracoBounds(false));
}

// A real scan: the Stanford bunny (low resolution) from ../shared/assets, as the OBJ loader reads it,
// through Draco's edgebreaker and back. Skipped where the shared assets are absent.
TEST(GltfCompression, DracoBunnyFromTheSharedAssets) {
    const fs::path obj = fs::path(LIGHTPASS_SHARED_ASSETS) / "stanford-bunny/bunny-lowres.obj";
    if (!fs::exists(obj)) GTEST_SKIP() << obj << " is not here";
    TempDir t;
    const MeshData source = loadObj(obj);
    Grid g;
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (const Vertex& v : source.vertices) lo = glm::min(lo, v.position), hi = glm::max(hi, v.position);
    for (const Vertex& v : source.vertices) {
        g.positions.push_back(v.position);
        g.normals.push_back(v.normal);
        g.uvs.push_back(glm::vec2((v.position - lo) / (hi - lo)));  // a planar projection in [0, 1]
    }
    g.indices = source.indices;
    ASSERT_GT(g.indices.size(), 3000u);
    const DracoFile d = encodeDraco(g, false);
    Bounds b = dracoBounds(false);
    b.position = std::sqrt(3.0f) * 0.5f * std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}) / float((1 << kDracoPositionBits) - 1) * 1.001f + 1e-6f;
    nlohmann::json doc = dracoGltf(g, d, false);
    doc["accessors"][3]["componentType"] = 5125;  // more than 255 vertices: 32-bit indices
    expectGrid(loadGltf(t.write("bunny.gltf", doc.dump())).mesh, g, b);
}

// A corrupt or truncated stream, or accessors that disagree with it: one line naming the extension.
TEST(GltfCompression, DracoFaultsAreOneLineNamingTheElement) {
    TempDir t;
    const Grid g = makeGrid();
    const DracoFile d = encodeDraco(g, false);
    const std::string where = "meshes[0].primitives[0].extensions.KHR_draco_mesh_compression";
    auto expectError = [&](const std::string& name, const nlohmann::json& doc, const std::string& fragment) {
        const fs::path p = t.write(name, doc.dump());
        const std::string err = loadError(p);
        EXPECT_EQ(err.rfind(p.string() + ": " + where, 0), 0u) << err;
        EXPECT_NE(err.find(fragment), std::string::npos) << err;
        EXPECT_EQ(err.find('\n'), std::string::npos) << err;
    };
    DracoFile broken = d;
    broken.stream.resize(broken.stream.size() / 2);
    expectError("truncated.gltf", dracoGltf(g, broken, false), ": Draco decoding failed: ");
    broken = d;
    broken.stream.replace(0, 5, "DRACX");
    expectError("header.gltf", dracoGltf(g, broken, false), ": Draco decoding failed: ");
    broken = d;
    for (size_t i = broken.stream.size() / 3; i < broken.stream.size(); ++i) broken.stream[i] = char(0xFF);
    expectError("garbage.gltf", dracoGltf(g, broken, false), ": Draco decoding failed: ");
    nlohmann::json doc = dracoGltf(g, d, false);
    doc["accessors"][0]["count"] = g.positions.size() + 1;
    expectError("count.gltf", doc, ".attributes.POSITION: the Draco mesh has 36 points, but accessors[0] has count 37");
    doc = dracoGltf(g, d, false);
    doc["accessors"][3]["count"] = 3;
    expectError("indices.gltf", doc, ": indices: the Draco mesh has 50 triangles (150 indices), but accessors[3] has count 3");
    doc = dracoGltf(g, d, false);
    doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["NORMAL"] = 99;
    expectError("id.gltf", doc, ".attributes.NORMAL: the Draco mesh has no attribute of id 99");
    doc = dracoGltf(g, d, false);
    doc["accessors"][2]["type"] = "VEC3";
    expectError("components.gltf", doc, ".attributes.TEXCOORD_0: the Draco attribute has 2 components, but accessors[2] has 3");
    doc = dracoGltf(g, d, false);
    doc["bufferViews"][0]["byteLength"] = 10;  // a buffer view shorter than the stream: the decoder reads 10 bytes only
    expectError("short_view.gltf", doc, ": Draco decoding failed: ");
}

// ---- meshoptimizer ----

namespace {

// The grid as gltfpack stores it: positions quantised to unsigned shorts (the node's scale and
// translation bring them back) in an 8-byte stride, normals octahedral in normalised bytes
// (OCTAHEDRAL filter), uvs as floats through the EXPONENTIAL filter, indices as TRIANGLES or INDICES;
// each view compressed into buffers[0], decoded into the fallback buffers[1], which has no uri.
struct MeshoptFile {
    nlohmann::json doc;
    float positionStep = 0.0f;
    std::string compressed;  // buffers[0]'s bytes
};
// The document with buffers[0] holding `f.compressed` (changed by a test).
nlohmann::json withCompressed(const MeshoptFile& f) {
    nlohmann::json doc = f.doc;
    doc["buffers"][0] = {{"byteLength", f.compressed.size()}, {"uri", dataUri(f.compressed)}};
    return doc;
}
constexpr int kOctBits = 8, kExpBits = 15;
MeshoptFile meshoptGltf(const Grid& g, const std::string& indexMode, size_t indexSize) {
    const size_t n = g.positions.size();
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (const glm::vec3& p : g.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const float step = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}) / 65535.0f;
    std::vector<uint16_t> positions(n * 4, 0);
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) positions[i * 4 + size_t(c)] = uint16_t(std::lround((g.positions[i][c] - lo[c]) / step));
    std::vector<float> normal4(n * 4, 0.0f), uvs(n * 2);
    for (size_t i = 0; i < n; ++i) {
        for (int c = 0; c < 3; ++c) normal4[i * 4 + size_t(c)] = g.normals[i][c];
        uvs[i * 2] = g.uvs[i].x, uvs[i * 2 + 1] = g.uvs[i].y;
    }
    std::vector<int8_t> normals(n * 4);
    meshopt_encodeFilterOct(normals.data(), n, 4, kOctBits, normal4.data());
    std::vector<uint32_t> filteredUvs(n * 2);
    meshopt_encodeFilterExp(filteredUvs.data(), n, 8, kExpBits, uvs.data());

    std::string compressed;
    nlohmann::json views = nlohmann::json::array();
    size_t decodedOffset = 0;
    auto addView = [&](const std::vector<unsigned char>& stream, size_t count, size_t stride, const char* mode, const char* filter, bool vertexStride) {
        const size_t at = append(compressed, stream.data(), stream.size());
        nlohmann::json view = {{"buffer", 1}, {"byteOffset", decodedOffset}, {"byteLength", count * stride}};
        if (vertexStride) view["byteStride"] = stride;
        view["extensions"]["EXT_meshopt_compression"] = {{"buffer", 0},     {"byteOffset", at}, {"byteLength", stream.size()},
                                                         {"byteStride", stride}, {"count", count},   {"mode", mode}};
        if (filter) view["extensions"]["EXT_meshopt_compression"]["filter"] = filter;
        views.push_back(view);
        decodedOffset += (count * stride + 3) / 4 * 4;
    };
    auto vertexStream = [&](const void* data, size_t stride) {
        std::vector<unsigned char> out(meshopt_encodeVertexBufferBound(n, stride));
        out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), data, n, stride));
        return out;
    };
    addView(vertexStream(positions.data(), 8), n, 8, "ATTRIBUTES", nullptr, true);
    addView(vertexStream(normals.data(), 4), n, 4, "ATTRIBUTES", "OCTAHEDRAL", true);
    addView(vertexStream(filteredUvs.data(), 8), n, 8, "ATTRIBUTES", "EXPONENTIAL", true);
    std::vector<unsigned char> indexStream;
    if (indexMode == "TRIANGLES") {
        indexStream.resize(meshopt_encodeIndexBufferBound(g.indices.size(), n));
        indexStream.resize(meshopt_encodeIndexBuffer(indexStream.data(), indexStream.size(), g.indices.data(), g.indices.size()));
    } else {
        indexStream.resize(meshopt_encodeIndexSequenceBound(g.indices.size(), n));
        indexStream.resize(meshopt_encodeIndexSequence(indexStream.data(), indexStream.size(), g.indices.data(), g.indices.size()));
    }
    addView(indexStream, g.indices.size(), indexSize, indexMode.c_str(), nullptr, false);

    nlohmann::json doc = {{"asset", {{"version", "2.0"}}}};
    doc["extensionsUsed"] = doc["extensionsRequired"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
    doc["buffers"] = {{{"byteLength", compressed.size()}, {"uri", dataUri(compressed)}},
                      {{"byteLength", decodedOffset}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}};
    doc["bufferViews"] = views;
    doc["accessors"] = {{{"bufferView", 0}, {"componentType", 5123}, {"count", n}, {"type", "VEC3"}},
                        {{"bufferView", 1}, {"componentType", 5120}, {"normalized", true}, {"count", n}, {"type", "VEC3"}},
                        {{"bufferView", 2}, {"componentType", 5126}, {"count", n}, {"type", "VEC2"}},
                        {{"bufferView", 3}, {"componentType", indexSize == 2 ? 5123 : 5125}, {"count", g.indices.size()}, {"type", "SCALAR"}}};
    doc["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}}, {"indices", 3}}}}}};
    doc["nodes"] = {{{"mesh", 0}, {"translation", {lo.x, lo.y, lo.z}}, {"scale", {step, step, step}}}};
    doc["scenes"] = {{{"nodes", {0}}}};
    doc["scene"] = 0;
    return {doc, step, compressed};
}

// meshopt's codecs are lossless; the bounds are the quantisation's: half a step per position
// component; 8-bit octahedral normals (coordinates in steps of 1/127), then rounded to normalised
// bytes (half of 1/127 per component); EXPONENTIAL keeps 15-bit mantissas of uvs at most 1.
Bounds meshoptBounds(float positionStep) {
    const float octHalfStep = 0.5f / float((1 << (kOctBits - 1)) - 1);
    return {std::sqrt(3.0f) * 0.5f * positionStep * 1.01f + 1e-6f, octahedralBound(octHalfStep) * 1.001f + std::sqrt(3.0f) * 0.5f / 127.0f,
            std::sqrt(2.0f) * std::ldexp(1.0f, -(kExpBits - 1))};
}

}  // namespace

TEST(GltfCompression, MeshoptBuffersLoadAsTheOriginalWithinTheQuantisationBound) {
    TempDir t;
    const Grid g = makeGrid();
    for (const auto& [mode, size] : std::vector<std::pair<std::string, size_t>>{{"TRIANGLES", 2}, {"TRIANGLES", 4}, {"INDICES", 2}, {"INDICES", 4}}) {
        SCOPED_TRACE(mode + " of " + std::to_string(size) + "-byte indices");
        const MeshoptFile f = meshoptGltf(g, mode, size);
        MeshLoadReport report;
        expectGrid(loadGltf(t.write("meshopt.gltf", f.doc.dump()), &report).mesh, g, meshoptBounds(f.positionStep));
        EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
    }
    // The fallback buffer without the `fallback` mark (it has no uri, and only compressed views read it).
    MeshoptFile f = meshoptGltf(g, "TRIANGLES", 2);
    f.doc["buffers"][1].erase("extensions");
    expectGrid(loadGltf(t.write("unmarked.gltf", f.doc.dump())).mesh, g, meshoptBounds(f.positionStep));
    // Only used, with a fallback that has data (zeros here): the compressed data is what loads.
    f = meshoptGltf(g, "TRIANGLES", 2);
    f.doc.erase("extensionsRequired");
    f.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
    f.doc["buffers"][1] = {{"byteLength", f.doc["buffers"][1]["byteLength"]},
                           {"uri", dataUri(std::string(f.doc["buffers"][1]["byteLength"].get<size_t>(), '\0'))}};
    expectGrid(loadGltf(t.write("used.gltf", f.doc.dump())).mesh, g, meshoptBounds(f.positionStep));
}

TEST(GltfCompression, MeshoptFaultsAreOneLineNamingTheElement) {
    TempDir t;
    const Grid g = makeGrid();
    auto expectError = [&](const std::string& name, const nlohmann::json& doc, const std::string& fragment) {
        const fs::path p = t.write(name, doc.dump());
        const std::string err = loadError(p);
        EXPECT_EQ(err.rfind(p.string() + ": ", 0), 0u) << err;
        EXPECT_NE(err.find(fragment), std::string::npos) << err;
        EXPECT_EQ(err.find('\n'), std::string::npos) << err;
    };
    const nlohmann::json base = meshoptGltf(g, "TRIANGLES", 2).doc;
    const std::string ext = "bufferViews[0].extensions.EXT_meshopt_compression";
    const std::string idx = "bufferViews[3].extensions.EXT_meshopt_compression";
    nlohmann::json d = base;
    d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteLength"] = 20;  // truncated stream
    expectError("truncated.gltf", d, ext + ": meshopt decoding failed (ATTRIBUTES, 36 elements of 8 bytes from 20 bytes)");
    d = base;
    d["bufferViews"][3]["extensions"]["EXT_meshopt_compression"]["byteLength"] = 8;
    expectError("truncated_indices.gltf", d, idx + ": meshopt decoding failed (TRIANGLES, 150 elements of 2 bytes from 8 bytes)");
    // A stream of another codec version: its header byte (0xA0 | version) says version 1, which
    // meshoptimizer 0.18 does not know.
    MeshoptFile f = meshoptGltf(g, "TRIANGLES", 2);
    f.compressed[f.doc["bufferViews"][1]["extensions"]["EXT_meshopt_compression"]["byteOffset"].get<size_t>()] = char(0xA1);
    d = withCompressed(f);
    expectError("version.gltf", d, "bufferViews[1].extensions.EXT_meshopt_compression: meshopt decoding failed (ATTRIBUTES, 36 elements of 4 bytes");
    f = meshoptGltf(g, "TRIANGLES", 2);
    f.compressed[f.doc["bufferViews"][3]["extensions"]["EXT_meshopt_compression"]["byteOffset"].get<size_t>()] = char(0x00);
    expectError("index_header.gltf", withCompressed(f), idx + ": meshopt decoding failed (TRIANGLES");
    d = base;
    d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["mode"] = "STRIPS";
    expectError("mode.gltf", d, ext + ".mode: 'STRIPS' is not ATTRIBUTES, TRIANGLES or INDICES");
    d = base;
    d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["filter"] = "COLOR";
    expectError("filter.gltf", d, ext + ".filter: 'COLOR' is not NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL");
    d = base;
    d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["filter"] = "QUATERNION";
    d["bufferViews"][1]["extensions"]["EXT_meshopt_compression"]["filter"] = "QUATERNION";
    expectError("quaternion.gltf", d, "bufferViews[1].extensions.EXT_meshopt_compression.byteStride: 4 does not suit filter QUATERNION (8)");
    d = base;
    d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = 35;
    expectError("count.gltf", d, ext + ": count 35 x byteStride 8 = 280 bytes, but the buffer view's byteLength is 288");
    d = base;
    d["bufferViews"][3]["extensions"]["EXT_meshopt_compression"]["count"] = 149;
    expectError("triangles.gltf", d, idx + ".count: 149 is not a multiple of 3 (mode TRIANGLES)");
    d = base;
    d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteStride"] = 6;
    expectError("stride.gltf", d, ext + ".byteStride: 6 is not a multiple of 4 from 4 to 256 (mode ATTRIBUTES)");
    d = base;
    d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteOffset"] = 1u << 30;
    expectError("offset.gltf", d, ext + ": bytes 1073741824+");
    d = base;
    d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["buffer"] = 1;
    expectError("from_fallback.gltf", d, ext + ".buffer: buffers[1] is a fallback buffer, which holds no data");
    d = base;
    d["bufferViews"][2].erase("extensions");  // a plain view into the fallback buffer
    expectError("plain_view.gltf", d, "bufferViews[2]: reads buffers[1], a EXT_meshopt_compression fallback buffer, which holds no data");
    // A large declared count and a tiny stream: refused before anything is allocated for it.
    d = base;
    d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = 1u << 29;
    expectError("huge.gltf", d, ext + ".count: 536870912 is over the limit");
}
