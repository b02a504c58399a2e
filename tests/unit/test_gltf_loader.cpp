// glTF 2.0 loading: every primitive form, node transforms, materials, lights and cameras, and bad
// input (each error names the file and the element). Assets: tests/data/gltf (scripts/make_gltf_assets.py).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "engine/core/error.hpp"
#include "engine/io/gltf_loader.hpp"
#include "tests/unit/gltf_test_files.hpp"
#include "engine/io/gltf_schema.hpp"
#include "engine/io/obj_loader.hpp"
#include "engine/scene/mesh_ops.hpp"
#include "engine/scene/scene_loader.hpp"

using namespace lp;
namespace fs = std::filesystem;

using lp::test::TempDir;
using lp::test::loadError;

namespace {

const fs::path kData = fs::path(LIGHTPASS_SOURCE_DIR) / "tests/data/gltf";

// Temporary folder of hand-written files, removed at the end of the test.
// A one-triangle glTF around a buffer given as a data: URI of `bytes` and the accessor JSON given.
std::string triangleGltf(const std::string& accessors, const std::string& bufferViews, size_t bufferBytes,
                         const std::string& extra = "", const std::string& primitive = "\"attributes\": {\"POSITION\": 0}") {
    // 36 bytes of float positions (0,0,0) (1,0,0) (0,1,0), then 6 bytes of u16 indices 0 1 2.
    static const char* kB64 = "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIA";
    return std::string("{\"asset\": {\"version\": \"2.0\"}, ") + extra +
           "\"buffers\": [{\"byteLength\": " + std::to_string(bufferBytes) + ", \"uri\": \"data:application/octet-stream;base64," + kB64 + "\"}]," +
           "\"bufferViews\": " + bufferViews + ", \"accessors\": " + accessors +
           ", \"meshes\": [{\"primitives\": [{" + primitive + "}]}], \"nodes\": [{\"mesh\": 0}], \"scenes\": [{\"nodes\": [0]}], \"scene\": 0}";
}
const std::string kViews = R"([{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}])";
const std::string kPositions = R"({"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"})";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

}  // namespace

// Seven primitive forms (u8, u16, u32 indices, none, interleaved, strip, fan), each a unit quad of
// two triangles at x = 3 i: all load, from .gltf + .bin and from .glb alike.
TEST(GltfLoader, EveryPrimitiveFormLoads) {
    for (const char* name : {"forms.gltf", "forms.glb"}) {
        SCOPED_TRACE(name);
        const GltfContent g = loadGltf(kData / name);
        const MeshData& m = g.mesh;
        ASSERT_EQ(m.subMeshes.size(), 7u);
        EXPECT_EQ(m.indices.size(), 7u * 6u);
        for (size_t i = 0; i < m.subMeshes.size(); ++i) {
            const SubMesh& s = m.subMeshes[i];
            EXPECT_EQ(s.indexCount, 6u) << "primitive " << i;
            double area = 0.0;
            glm::vec3 lo(1e9f), hi(-1e9f);
            for (uint32_t k = s.firstIndex; k < s.firstIndex + s.indexCount; k += 3) {
                const glm::vec3 a = m.vertices[m.indices[k]].position, b = m.vertices[m.indices[k + 1]].position,
                                c = m.vertices[m.indices[k + 2]].position;
                const glm::vec3 n = glm::cross(b - a, c - a);
                area += 0.5 * glm::length(n);
                EXPECT_GT(n.z, 0.0f) << "primitive " << i << " triangle faces away from +Z";  // winding kept
                for (const glm::vec3& p : {a, b, c}) lo = glm::min(lo, p), hi = glm::max(hi, p);
            }
            EXPECT_NEAR(area, 1.0, 1e-6) << "primitive " << i;
            EXPECT_NEAR(lo.x, 3.0f * float(i), 1e-6f);
            EXPECT_NEAR(hi.x, 3.0f * float(i) + 1.0f, 1e-6f);
            for (uint32_t k = s.firstIndex; k < s.firstIndex + s.indexCount; ++k)
                EXPECT_NEAR(m.vertices[m.indices[k]].normal.z, 1.0f, 1e-6f);
        }
        EXPECT_NEAR(m.boundsMax.x, 19.0f, 1e-6f);
        // glTF v runs down the image; the loader flips it to the OBJ convention (v = 0 at the bottom):
        // the quad's top corner (y = 1) has glTF v 0, so v = 1 here.
        for (const Vertex& v : m.vertices)
            if (v.position.y == 1.0f && v.position.x == 0.0f) EXPECT_NEAR(v.uv.y, 1.0f, 1e-6f);
        ASSERT_EQ(m.materials.size(), 1u);
        EXPECT_NEAR(m.materials[0].diffuse.x, 0.8f, 1e-6f);
        EXPECT_FALSE(m.materials[0].doubleSided);
    }
}

// parent T (10,0,0) R (90 deg about +Y) S 2 > child T (1,0,0): the child's origin lands at
// T_p R_p S_p T_c 0 = (10, 0, -2); any other order puts it elsewhere.
TEST(GltfLoader, NodeTransformsComposeParentTimesTRS) {
    const GltfContent g = loadGltf(kData / "hierarchy.gltf");
    ASSERT_EQ(g.mesh.vertices.size(), 3u);  // no normals: flat normals, 3 vertices for 1 triangle
    const glm::mat4 expected = glm::translate(glm::mat4(1.0f), glm::vec3(10, 0, 0)) *
                               glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(0, 1, 0)) *
                               glm::scale(glm::mat4(1.0f), glm::vec3(2.0f)) * glm::translate(glm::mat4(1.0f), glm::vec3(1, 0, 0));
    const glm::vec3 local[3] = {{0, 0, 0}, {0.5f, 0, 0}, {0, 0.5f, 0}};
    bool foundOrigin = false;
    for (const Vertex& v : g.mesh.vertices) {
        bool matched = false;
        for (const glm::vec3& p : local) matched |= glm::length(v.position - glm::vec3(expected * glm::vec4(p, 1.0f))) < 1e-5f;
        EXPECT_TRUE(matched) << v.position.x << " " << v.position.y << " " << v.position.z;
        foundOrigin |= glm::length(v.position - glm::vec3(10, 0, -2)) < 1e-5f;
        EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-5f);
    }
    EXPECT_TRUE(foundOrigin);
}

// Lights and cameras: the directional light points down its node's -Z, the point light keeps its range,
// the spot light (under a rotated parent) keeps its world position, its node's -Z and its cone.
TEST(GltfLoader, LightsAndCameras) {
    MeshLoadReport report;
    const GltfContent g = loadGltf(kData / "lights.gltf", &report);
    ASSERT_EQ(g.directionalLights.size(), 1u);
    EXPECT_NEAR(g.directionalLights[0].direction.y, -1.0f, 1e-5f);
    EXPECT_NEAR(g.directionalLights[0].intensity, 2.0f, 1e-6f);
    ASSERT_EQ(g.pointLights.size(), 2u);
    EXPECT_NEAR(g.pointLights[0].range, 5.0f, 1e-6f);
    EXPECT_NEAR(g.pointLights[0].position.y, 2.0f, 1e-6f);
    EXPECT_FALSE(g.pointLights[0].spot.has_value());
    // The spot: parent T (1, 0, 0) R 90 deg about +Y > child T (0, 3, 1) R -45 deg about +X.
    const PointLight& spot = g.pointLights[1];
    EXPECT_NEAR(spot.intensity, 20.0f, 1e-6f);  // candela on the axis, as for points
    EXPECT_NEAR(glm::distance(spot.position, glm::vec3(2, 3, 0)), 0.0f, 1e-5f);
    ASSERT_TRUE(spot.spot.has_value());
    const glm::vec3 expectedAxis = glm::normalize(glm::vec3(-1, -1, 0));
    EXPECT_NEAR(glm::distance(spot.spot->direction, expectedAxis), 0.0f, 1e-5f);
    EXPECT_NEAR(spot.spot->innerDegrees, glm::degrees(0.2f), 1e-4f);
    EXPECT_NEAR(spot.spot->outerDegrees, glm::degrees(0.5f), 1e-4f);
    EXPECT_FALSE(spot.castsShadow);
    for (const auto& w : report.warnings) EXPECT_EQ(w.find("spot"), std::string::npos) << w;
    ASSERT_EQ(g.cameras.size(), 1u);
    EXPECT_NEAR(g.cameras[0].fovYDegrees, glm::degrees(0.8f), 1e-3f);
    EXPECT_NEAR(g.cameras[0].position.z, 6.0f, 1e-6f);
    EXPECT_LT(g.cameras[0].target.z, 6.0f);  // looks down -Z

    // As a model: its lights replace the key and fill light, its camera the framed one.
    const Scene s = sceneForModel(kData / "lights.gltf");
    EXPECT_EQ(s.directionalLights.size(), 1u);
    EXPECT_EQ(s.pointLights.size(), 2u);
    EXPECT_NEAR(s.camera.position.z, 6.0f, 1e-6f);
}

// Materials: emission with KHR_materials_emissive_strength, alpha MASK, the normal texture.
TEST(GltfLoader, Materials) {
    const MeshData e = loadGltf(kData / "emissive.gltf").mesh;
    ASSERT_EQ(e.materials.size(), 1u);
    EXPECT_NEAR(e.materials[0].emission.x, 4.0f, 1e-6f);
    EXPECT_NEAR(e.materials[0].emission.y, 2.0f, 1e-6f);
    EXPECT_NEAR(e.materials[0].emission.z, 1.0f, 1e-6f);
    const MeshData a = loadGltf(kData / "alpha_mask.gltf").mesh;
    ASSERT_EQ(a.materials.size(), 3u);
    for (const Material& m : a.materials) EXPECT_EQ(m.alphaMode, AlphaMode::Mask);
    EXPECT_NEAR(a.materials[0].opacity, 0.3f, 1e-6f);
    EXPECT_FALSE(a.materials[2].diffuseMap.empty());
    EXPECT_TRUE(a.materials[2].diffuseMap.encoded != nullptr);  // embedded in the buffer
    const MeshData n = loadGltf(kData / "normal_plane.glb").mesh;
    ASSERT_FALSE(n.materials[0].normalMap.empty());
    // The file's tangent (+X, w +1): with v flipped, the bitangent cross(N, T) w is -Z, up the image.
    for (const Vertex& v : n.vertices) {
        EXPECT_NEAR(v.tangent.x, 1.0f, 1e-6f);
        EXPECT_GT(glm::dot(glm::cross(v.normal, glm::vec3(v.tangent)) * v.tangent.w, glm::vec3(0, 0, -1)), 0.99f);
    }
    // Generated tangents give the same frame.
    const MeshData g = loadGltf(kData / "normal_plane_notangent.glb").mesh;
    for (const Vertex& v : g.vertices) {
        EXPECT_NEAR(v.tangent.x, 1.0f, 1e-5f);
        EXPECT_GT(glm::dot(glm::cross(v.normal, glm::vec3(v.tangent)) * v.tangent.w, glm::vec3(0, 0, -1)), 0.99f);
    }
}

namespace {

std::string base64(const std::string& bytes) {
    static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t n = uint32_t(uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) n |= uint32_t(uint8_t(bytes[i + 1])) << 8;
        if (i + 2 < bytes.size()) n |= uint32_t(uint8_t(bytes[i + 2]));
        out += k[(n >> 18) & 63];
        out += k[(n >> 12) & 63];
        out += i + 1 < bytes.size() ? k[(n >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? k[n & 63] : '=';
    }
    return out;
}

// A unit quad in z = 0 facing +Z, glTF uvs (0, 1) (1, 1) (0, 0) (1, 0) at (0, 0) (1, 0) (0, 1) (1, 1)
// (v down the image), file tangents +X, base colour and normal textures, with `baseTransform` and
// `normalTransform` as their KHR_texture_transform (null: none).
nlohmann::json texturedQuad(const nlohmann::json& baseTransform, const nlohmann::json& normalTransform) {
    const float pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    const float nrm[] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    const float uv[] = {0, 1, 1, 1, 0, 0, 1, 0};
    const float tan[] = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
    const uint16_t idx[] = {0, 1, 2, 2, 1, 3};
    std::string bytes;
    for (const auto& [data, size] : std::vector<std::pair<const void*, size_t>>{
             {pos, sizeof pos}, {nrm, sizeof nrm}, {uv, sizeof uv}, {tan, sizeof tan}, {idx, sizeof idx}})
        bytes.append(static_cast<const char*>(data), size);
    nlohmann::json d = {{"asset", {{"version", "2.0"}}}, {"extensionsUsed", {"KHR_texture_transform"}}};
    d["buffers"] = {{{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + base64(bytes)}}};
    d["bufferViews"] = {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},   {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 48}},
                        {{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 32}},  {{"buffer", 0}, {"byteOffset", 128}, {"byteLength", 64}},
                        {{"buffer", 0}, {"byteOffset", 192}, {"byteLength", 12}}};
    d["accessors"] = {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
                      {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
                      {{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
                      {{"bufferView", 3}, {"componentType", 5126}, {"count", 4}, {"type", "VEC4"}},
                      {{"bufferView", 4}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}};
    d["images"] = {{{"uri", "missing.png"}}};
    d["textures"] = {{{"source", 0}}};
    nlohmann::json base = {{"index", 0}}, normal = {{"index", 0}};
    if (!baseTransform.is_null()) base["extensions"]["KHR_texture_transform"] = baseTransform;
    if (!normalTransform.is_null()) normal["extensions"]["KHR_texture_transform"] = normalTransform;
    d["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", base}}}, {"normalTexture", normal}}};
    d["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}, {"TANGENT", 3}}},
                                     {"indices", 4}, {"material", 0}}}}}};
    d["nodes"] = {{{"mesh", 0}}};
    d["scenes"] = {{{"nodes", {0}}}};
    d["scene"] = 0;
    return d;
}

}  // namespace

static void expectOneLineError(const fs::path& p, const std::string& fragment);  // below

// KHR_texture_transform, applied to the uvs on load. The extension's example (offset (0, 1), rotation
// pi/2, scale 0.5: "the lower left quadrant of the source image, rotated clockwise 90 degrees") maps
// glTF uv (u, v) to (v / 2, 1 - u / 2), i.e. (v / 2, u / 2) once v is flipped to lightpass's v up;
// turning the uv axes replaces the file's tangents by generated ones (here dP/du = -Y). A scale and
// offset keep them. Textures of one material with different transforms get the first's, warned.
TEST(GltfLoader, TextureTransformIsAppliedToTheUvs) {
    TempDir t;
    const float glTFuv[4][2] = {{0, 1}, {1, 1}, {0, 0}, {1, 0}};
    const nlohmann::json example = {{"offset", {0, 1}}, {"rotation", 1.57079632679}, {"scale", {0.5, 0.5}}};
    MeshLoadReport turned;
    const MeshData a = loadGltf(t.write("turned.gltf", texturedQuad(example, example).dump()), &turned).mesh;
    ASSERT_EQ(a.vertices.size(), 4u);
    for (size_t i = 0; i < 4; ++i) {
        const float u = glTFuv[i][0], v = glTFuv[i][1];
        EXPECT_NEAR(a.vertices[i].uv.x, 0.5f * v, 1e-6f) << i;
        EXPECT_NEAR(a.vertices[i].uv.y, 0.5f * u, 1e-6f) << i;
        // Inside the image's lower left quadrant (glTF v in [0.5, 1] is lightpass v in [0, 0.5]).
        EXPECT_TRUE(a.vertices[i].uv.x >= -1e-6f && a.vertices[i].uv.x <= 0.5f + 1e-6f && a.vertices[i].uv.y <= 0.5f + 1e-6f);
        EXPECT_NEAR(glm::distance(glm::vec3(a.vertices[i].tangent), glm::vec3(0, -1, 0)), 0.0f, 1e-5f) << i;
    }
    EXPECT_TRUE(turned.generatedTangents);
    for (const auto& w : turned.warnings) EXPECT_EQ(w.find("not supported"), std::string::npos) << w;

    const nlohmann::json tiled = {{"offset", {0.25, 0}}, {"scale", {2, 3}}};
    MeshLoadReport scaled;
    const MeshData b = loadGltf(t.write("scaled.gltf", texturedQuad(tiled, tiled).dump()), &scaled).mesh;
    for (size_t i = 0; i < 4; ++i) {
        EXPECT_NEAR(b.vertices[i].uv.x, 2.0f * glTFuv[i][0] + 0.25f, 1e-6f) << i;
        EXPECT_NEAR(b.vertices[i].uv.y, 1.0f - 3.0f * glTFuv[i][1], 1e-6f) << i;
        EXPECT_EQ(glm::vec3(b.vertices[i].tangent), glm::vec3(1, 0, 0)) << i;
    }
    EXPECT_FALSE(scaled.generatedTangents);

    MeshLoadReport mixed;
    nlohmann::json twoPrimitives = texturedQuad(tiled, nlohmann::json{{"offset", {0.5, 0}}});
    twoPrimitives["meshes"][0]["primitives"].push_back(twoPrimitives["meshes"][0]["primitives"][0]);
    const MeshData c = loadGltf(t.write("mixed.gltf", twoPrimitives.dump()), &mixed).mesh;
    EXPECT_NEAR(c.vertices[1].uv.x, 2.25f, 1e-6f);  // the base colour's transform
    std::string all;
    int differs = 0;
    for (const auto& w : mixed.warnings) {
        all += w + "\n";
        differs += w.find("materials[0].normalTexture: its KHR_texture_transform differs from pbrMetallicRoughness.baseColorTexture's, "
                          "which is applied to every texture of the material on TEXCOORD_0") != std::string::npos;
    }
    EXPECT_EQ(differs, 1) << "once per material, not per primitive:\n" << all;
    nlohmann::json bad = texturedQuad(nlohmann::json{{"scale", 2}}, nullptr);
    expectOneLineError(t.write("bad.gltf", bad.dump()),
                       "materials[0].pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform.scale: expected an array of 2 numbers, got 2");
}

// A second uv set (TEXCOORD_1): read for the textures whose texCoord, or whose transform's texCoord
// (which overrides it), is 1, through that set's own transform; the tangents the loader makes follow
// the normal map's set (MikkTSpace on TEXCOORD_1: here u1 runs along +Y, so the tangent is +Y where
// TEXCOORD_0 would give +X). A primitive without TEXCOORD_1 whose material samples it reads
// TEXCOORD_0 there, warned; TEXCOORD_2 and up read TEXCOORD_0, warned.
TEST(GltfLoader, SecondUvSetIsReadByTheTexturesThatAskForIt) {
    TempDir t;
    const float glTFuv[4][2] = {{0, 1}, {1, 1}, {0, 0}, {1, 0}};
    const float glTFuv1[4][2] = {{0, 0}, {0, 1}, {1, 0}, {1, 1}};  // at (0,0) (1,0) (0,1) (1,1): u1 = y, v1 = x
    auto withSecondSet = [&](nlohmann::json d) {
        const std::string bytes(reinterpret_cast<const char*>(glTFuv1), sizeof glTFuv1);
        d["buffers"].push_back({{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + base64(bytes)}});
        d["bufferViews"].push_back({{"buffer", 1}, {"byteOffset", 0}, {"byteLength", bytes.size()}});
        d["accessors"].push_back({{"bufferView", d["bufferViews"].size() - 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}});
        d["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] = d["accessors"].size() - 1;
        d["meshes"][0]["primitives"][0]["attributes"].erase("TANGENT");
        return d;
    };
    // Base colour on set 0; normal map on set 1 (texCoord); emission on set 1 through its transform's
    // texCoord, scaled by 2; occlusion asks for TEXCOORD_2.
    nlohmann::json d = withSecondSet(texturedQuad(nullptr, nullptr));
    d["materials"][0]["normalTexture"]["texCoord"] = 1;
    d["materials"][0]["emissiveTexture"] = {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"texCoord", 1}}}}}};
    d["materials"][0]["occlusionTexture"] = {{"index", 0}, {"texCoord", 2}};
    MeshLoadReport report;
    const MeshData m = loadGltf(t.write("second.gltf", d.dump()), &report).mesh;
    ASSERT_EQ(m.vertices.size(), 4u);
    ASSERT_EQ(m.materials.size(), 1u);
    const Material& mat = m.materials[0];
    EXPECT_EQ(mat.diffuseMap.uvSet, 0);
    EXPECT_EQ(mat.normalMap.uvSet, 1);
    EXPECT_EQ(mat.emissiveMap.uvSet, 1);
    EXPECT_EQ(mat.occlusionMap.uvSet, 0);
    EXPECT_TRUE(mat.samplesUv1());
    for (size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(m.vertices[i].uv, glm::vec2(glTFuv[i][0], 1.0f - glTFuv[i][1])) << i;
        EXPECT_EQ(m.vertices[i].uv1, glm::vec2(glTFuv1[i][0], 1.0f - glTFuv1[i][1])) << i;
        EXPECT_NEAR(glm::distance(glm::vec3(m.vertices[i].tangent), glm::vec3(0, 1, 0)), 0.0f, 1e-5f) << "the tangent follows u1, " << i;
        // The bitangent cross(N, T) w points up set 1's image: +v1 (after the flip) is -X.
        EXPECT_GT(glm::dot(glm::cross(m.vertices[i].normal, glm::vec3(m.vertices[i].tangent)) * m.vertices[i].tangent.w, glm::vec3(-1, 0, 0)),
                  0.99f) << i;
    }
    // The warnings besides the one of the texture's image, which is not there.
    auto uvWarnings = [](const MeshLoadReport& r) {
        std::string all;
        for (const auto& w : r.warnings)
            if (w.find("missing.png") == std::string::npos) all += w + "\n";
        return all;
    };
    const std::string all = uvWarnings(report);
    EXPECT_NE(all.find("materials[0].occlusionTexture: uses TEXCOORD_2; only TEXCOORD_0 and TEXCOORD_1 are read, so it reads TEXCOORD_0"),
              std::string::npos) << all;
    EXPECT_EQ(std::count(all.begin(), all.end(), '\n'), 1) << all;

    // Set 1 has a transform of its own: the emission's scale 2 (with the normal map back on set 0, the
    // emission is set 1's only texture).
    d["materials"][0]["normalTexture"].erase("texCoord");
    d["materials"][0]["emissiveTexture"]["extensions"]["KHR_texture_transform"]["scale"] = {2, 2};
    d["materials"][0].erase("occlusionTexture");
    MeshLoadReport scaled;
    const MeshData s2 = loadGltf(t.write("scaled.gltf", d.dump()), &scaled).mesh;
    for (size_t i = 0; i < s2.vertices.size() && i < 4; ++i) {
        EXPECT_EQ(s2.vertices[i].uv1, glm::vec2(2.0f * glTFuv1[i][0], 1.0f - 2.0f * glTFuv1[i][1])) << i;
        EXPECT_EQ(s2.vertices[i].uv, glm::vec2(glTFuv[i][0], 1.0f - glTFuv[i][1])) << "set 0 keeps no transform, " << i;
        EXPECT_NEAR(glm::distance(glm::vec3(s2.vertices[i].tangent), glm::vec3(1, 0, 0)), 0.0f, 1e-5f) << "the normal map is on set 0, " << i;
    }
    EXPECT_EQ(uvWarnings(scaled), "");

    // No TEXCOORD_1 on the primitive: its textures on set 1 read TEXCOORD_0 (through set 1's
    // transform), said once for the material however many primitives lack it.
    d["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_1");
    d["meshes"][0]["primitives"].push_back(d["meshes"][0]["primitives"][0]);
    MeshLoadReport missing;
    const MeshData n = loadGltf(t.write("missing.gltf", d.dump()), &missing).mesh;
    for (size_t i = 0; i < n.vertices.size() && i < 4; ++i)
        EXPECT_EQ(n.vertices[i].uv1, glm::vec2(2.0f * glTFuv[i][0], 1.0f - 2.0f * glTFuv[i][1])) << i;
    const std::string missingWarnings = uvWarnings(missing);
    EXPECT_EQ(std::count(missingWarnings.begin(), missingWarnings.end(), '\n'), 1) << missingWarnings;
    EXPECT_NE(missingWarnings.find("meshes[0].primitives[0].attributes: has no TEXCOORD_1, which materials[0] samples; those "
                                   "textures read TEXCOORD_0"), std::string::npos) << missingWarnings;

    // Without a texture on set 1, TEXCOORD_1 is not read: every uv1 stays 0.
    const MeshData plain = loadGltf(t.write("plain.gltf", withSecondSet(texturedQuad(nullptr, nullptr)).dump())).mesh;
    EXPECT_FALSE(plain.materials[0].samplesUv1());
    for (const Vertex& v : plain.vertices) EXPECT_EQ(v.uv1, glm::vec2(0.0f));
}

// KHR_mesh_quantization (gltfpack's output): u16 positions scaled back by the node, i8 normalised
// normals and tangents, u16 normalised uvs, all read as their floats; without the extension declared
// the same file is refused, naming the attribute's component type.
TEST(GltfLoader, QuantizedAttributesWithKhrMeshQuantization) {
    TempDir t;
    const uint16_t pos[] = {0, 0, 0, 1000, 0, 0, 0, 1000, 0, 1000, 1000, 0};
    const int8_t nrm[] = {0, 0, 127, 0, 0, 0, 127, 0, 0, 0, 127, 0, 0, 0, 127, 0};  // VEC3 in 4-byte strides
    const int8_t tan[] = {127, 0, 0, 127, 127, 0, 0, 127, 127, 0, 0, 127, 127, 0, 0, 127};
    const uint16_t uv[] = {0, 65535, 65535, 65535, 0, 0, 65535, 0};
    const uint16_t idx[] = {0, 1, 2, 2, 1, 3};
    std::string bytes;
    for (const auto& [data, size] : std::vector<std::pair<const void*, size_t>>{
             {pos, sizeof pos}, {nrm, sizeof nrm}, {tan, sizeof tan}, {uv, sizeof uv}, {idx, sizeof idx}})
        bytes.append(static_cast<const char*>(data), size);
    nlohmann::json d = {{"asset", {{"version", "2.0"}}}, {"extensionsUsed", {"KHR_mesh_quantization"}},
                        {"extensionsRequired", {"KHR_mesh_quantization"}}};
    d["buffers"] = {{{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + base64(bytes)}}};
    d["bufferViews"] = {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 24}},
                        {{"buffer", 0}, {"byteOffset", 24}, {"byteLength", 16}, {"byteStride", 4}},
                        {{"buffer", 0}, {"byteOffset", 40}, {"byteLength", 16}},
                        {{"buffer", 0}, {"byteOffset", 56}, {"byteLength", 16}},
                        {{"buffer", 0}, {"byteOffset", 72}, {"byteLength", 12}}};
    d["accessors"] = {{{"bufferView", 0}, {"componentType", 5123}, {"count", 4}, {"type", "VEC3"}},
                      {{"bufferView", 1}, {"componentType", 5120}, {"normalized", true}, {"count", 4}, {"type", "VEC3"}},
                      {{"bufferView", 2}, {"componentType", 5120}, {"normalized", true}, {"count", 4}, {"type", "VEC4"}},
                      {{"bufferView", 3}, {"componentType", 5123}, {"normalized", true}, {"count", 4}, {"type", "VEC2"}},
                      {{"bufferView", 4}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}};
    d["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TANGENT", 2}, {"TEXCOORD_0", 3}}}, {"indices", 4}}}}}};
    d["nodes"] = {{{"mesh", 0}, {"scale", {0.001, 0.001, 0.001}}}};
    d["scenes"] = {{{"nodes", {0}}}};
    d["scene"] = 0;
    MeshLoadReport report;
    const MeshData m = loadGltf(t.write("quantized.gltf", d.dump()), &report).mesh;
    ASSERT_EQ(m.vertices.size(), 4u);
    const glm::vec3 expected[] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    const glm::vec2 expectedUv[] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};  // glTF v flipped
    for (size_t i = 0; i < 4; ++i) {
        EXPECT_NEAR(glm::distance(m.vertices[i].position, expected[i]), 0.0f, 1e-6f) << i;
        EXPECT_NEAR(glm::distance(m.vertices[i].normal, glm::vec3(0, 0, 1)), 0.0f, 1e-6f) << i;
        EXPECT_NEAR(glm::distance(glm::vec3(m.vertices[i].tangent), glm::vec3(1, 0, 0)), 0.0f, 1e-6f) << i;
        EXPECT_NEAR(glm::distance(m.vertices[i].uv, expectedUv[i]), 0.0f, 1e-6f) << i;
    }
    EXPECT_FALSE(report.generatedTangents);
    // Morph targets without weights (the spec's default: 0) leave the shape as loaded, without a warning.
    d["meshes"][0]["primitives"][0]["targets"] = {{{"POSITION", 1}}};
    d["meshes"][0]["primitives"].push_back(d["meshes"][0]["primitives"][0]);
    MeshLoadReport morphed;
    const MeshData withTargets = loadGltf(t.write("targets.gltf", d.dump()), &morphed).mesh;
    EXPECT_TRUE(morphed.warnings.empty()) << morphed.warnings.front();
    ASSERT_EQ(withTargets.vertices.size(), 8u);
    for (size_t i = 0; i < 8; ++i) EXPECT_NEAR(glm::distance(withTargets.vertices[i].position, expected[i % 4]), 0.0f, 1e-6f) << i;
    d["meshes"][0]["primitives"].erase(1);
    d["meshes"][0]["primitives"][0].erase("targets");
    d.erase("extensionsUsed");
    d.erase("extensionsRequired");
    expectOneLineError(t.write("undeclared.gltf", d.dump()), "meshes[0].primitives[0].attributes.POSITION (accessors[0]): unexpected componentType 5123");
}

// COLOR_0 multiplies the base colour: read from floats (VEC3 or VEC4) and from normalised unsigned
// bytes and shorts; integers without `normalized` are read as normalised with a warning; values outside
// [0, 1] are clamped with one warning per primitive (a NaN one read as 1); no COLOR_0 is white. A colour accessor of another
// type, or of another length than POSITION, is an error naming it.
TEST(GltfLoader, VertexColoursAreReadAsLinearMultipliers) {
    TempDir t;
    const float pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float rgba[] = {1, 0, 0, 1, 0, 1, 0, 0.5f, 0, 0, 1, 1, 2, -1, 0.25f, nan};  // the last one out of range, its alpha NaN
    const uint8_t rgb8[] = {255, 0, 0, 0, 0, 128, 0, 0, 0, 0, 255, 0, 51, 51, 51, 0};  // VEC3 in 4-byte strides
    const uint16_t rgba16[] = {65535, 0, 0, 65535, 0, 65535, 0, 32768, 0, 0, 65535, 65535, 13107, 13107, 13107, 0};
    const uint16_t idx[] = {0, 1, 2, 2, 1, 3};
    const float nrm[] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};  // with normals the 4 vertices stay 4
    std::string bytes;
    for (const auto& [data, size] : std::vector<std::pair<const void*, size_t>>{
             {pos, sizeof pos}, {rgba, sizeof rgba}, {rgb8, sizeof rgb8}, {rgba16, sizeof rgba16}, {idx, sizeof idx}, {nrm, sizeof nrm}})
        bytes.append(static_cast<const char*>(data), size);
    nlohmann::json d = {{"asset", {{"version", "2.0"}}}};
    d["buffers"] = {{{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + base64(bytes)}}};
    d["bufferViews"] = {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
                        {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 64}},
                        {{"buffer", 0}, {"byteOffset", 112}, {"byteLength", 16}, {"byteStride", 4}},
                        {{"buffer", 0}, {"byteOffset", 128}, {"byteLength", 32}},
                        {{"buffer", 0}, {"byteOffset", 160}, {"byteLength", 12}},
                        {{"buffer", 0}, {"byteOffset", 172}, {"byteLength", 48}}};
    d["accessors"] = {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
                      {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC4"}},
                      {{"bufferView", 2}, {"componentType", 5121}, {"normalized", true}, {"count", 4}, {"type", "VEC3"}},
                      {{"bufferView", 3}, {"componentType", 5123}, {"count", 4}, {"type", "VEC4"}},  // not normalized
                      {{"bufferView", 4}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}},
                      {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "SCALAR"}},
                      {{"bufferView", 1}, {"componentType", 5126}, {"count", 3}, {"type", "VEC4"}},
                      {{"bufferView", 5}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}}};
    d["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 7}}}, {"indices", 4}}}}}};
    d["nodes"] = {{{"mesh", 0}}};
    d["scenes"] = {{{"nodes", {0}}}};
    d["scene"] = 0;
    auto load = [&](int colours, MeshLoadReport* report) {
        nlohmann::json e = d;
        if (colours >= 0) e["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = colours;
        return loadGltf(t.write("colours" + std::to_string(colours) + ".gltf", e.dump()), report).mesh;
    };
    auto expectColours = [](const MeshData& m, const std::vector<glm::vec4>& expected, float tolerance, const char* what) {
        ASSERT_EQ(m.vertices.size(), expected.size()) << what;
        for (size_t i = 0; i < expected.size(); ++i)
            EXPECT_NEAR(glm::distance(m.vertices[i].color, expected[i]), 0.0f, tolerance) << what << ", vertex " << i;
    };
    MeshLoadReport none, floats, bytes8, shorts;
    expectColours(load(-1, &none), {glm::vec4(1), glm::vec4(1), glm::vec4(1), glm::vec4(1)}, 0.0f, "no COLOR_0");
    EXPECT_TRUE(none.warnings.empty());
    expectColours(load(1, &floats), {{1, 0, 0, 1}, {0, 1, 0, 0.5f}, {0, 0, 1, 1}, {1, 0, 0.25f, 1}}, 0.0f, "float RGBA");
    ASSERT_EQ(floats.warnings.size(), 1u);
    EXPECT_NE(floats.warnings[0].find("meshes[0].primitives[0].attributes.COLOR_0 (accessors[1]): 1 colours outside [0, 1]"), std::string::npos)
        << floats.warnings[0];
    expectColours(load(2, &bytes8), {{1, 0, 0, 1}, {0, 128 / 255.0f, 0, 1}, {0, 0, 1, 1}, {0.2f, 0.2f, 0.2f, 1}}, 1e-6f,
                  "normalised unsigned bytes, RGB");
    EXPECT_TRUE(bytes8.warnings.empty());
    expectColours(load(3, &shorts), {{1, 0, 0, 1}, {0, 1, 0, 32768 / 65535.0f}, {0, 0, 1, 1}, {0.2f, 0.2f, 0.2f, 0}}, 1e-6f,
                  "unsigned shorts without `normalized`");
    ASSERT_EQ(shorts.warnings.size(), 1u);
    EXPECT_NE(shorts.warnings[0].find("COLOR_0 (accessors[3]): integer colours without \"normalized\": true (the spec requires it); read as normalized"),
              std::string::npos)
        << shorts.warnings[0];
    nlohmann::json bad = d;
    bad["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = 5;
    expectOneLineError(t.write("scalar.gltf", bad.dump()), "meshes[0].primitives[0].attributes.COLOR_0 (accessors[5]): unexpected type");
    bad["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = 6;
    expectOneLineError(t.write("short.gltf", bad.dump()), "meshes[0].primitives[0].attributes.COLOR_0: 3 elements, but POSITION has 4");
}

// OBJ's `v x y z r g b` extension: display (sRGB) colours decoded to the linear multipliers COLOR_0
// gives; out of [0, 1] clamped with a warning. Without colours on every `v` line, none are read.
TEST(ObjLoader, VertexColoursAreReadAsSrgb) {
    TempDir t;
    MeshLoadReport report;
    const MeshData m = loadObj(t.write("coloured.obj", "v 0 0 0 1 0 0\nv 1 0 0 0 0.5 0\nv 0 1 0 0.02 0 2\nvn 0 0 1\n"
                                                       "f 1//1 2//1 3//1\n"),
                               &report);
    ASSERT_EQ(m.vertices.size(), 3u);
    auto at = [&](glm::vec3 p) {
        for (const Vertex& v : m.vertices)
            if (v.position == p) return v.color;
        return glm::vec4(-1.0f);
    };
    EXPECT_EQ(at({0, 0, 0}), glm::vec4(1, 0, 0, 1));
    EXPECT_NEAR(at({1, 0, 0}).y, 0.21404f, 1e-4f) << "sRGB 0.5";
    EXPECT_NEAR(at({0, 1, 0}).x, 0.02f / 12.92f, 1e-6f) << "the linear segment";
    EXPECT_EQ(at({0, 1, 0}).z, 1.0f) << "2 clamped to 1";
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_NE(report.warnings[0].find("coloured.obj: 1 vertex colour components outside [0, 1] clamped"), std::string::npos)
        << report.warnings[0];
    const MeshData partial = loadObj(t.write("partial.obj", "v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n"));
    for (const Vertex& v : partial.vertices) EXPECT_EQ(v.color, glm::vec4(1.0f)) << "not every v line has a colour";
}

// KHR_materials_unlit is lightpass's flat-lit material showing the base colour (metallic dropped);
// KHR_materials_ior gives the dielectric F0 ((n - 1) / (n + 1))^2, 0 meaning F0 = 1.
// Samplers: each texture carries its sampler's wraps and filters (OpenGL's codes, as glTF writes
// them); none means repeat and lightpass's trilinear default (0). A value outside the schema's
// enumeration keeps the default with a warning, and so does a sampler that does not exist.
TEST(GltfLoader, SamplersAreReadPerTexture) {
    TempDir t;
    nlohmann::json d = texturedQuad(nullptr, nullptr);
    d["samplers"] = {{{"wrapS", 33071}, {"wrapT", 33648}, {"magFilter", 9728}, {"minFilter", 9986}},
                     {{"wrapS", 12345}, {"wrapT", 33071}, {"minFilter", 9729}}};
    d["textures"] = {{{"source", 0}, {"sampler", 0}}, {{"source", 0}, {"sampler", 1}}};
    d["materials"][0]["normalTexture"]["index"] = 1;
    MeshLoadReport report;
    const MeshData a = loadGltf(t.write("samplers.gltf", d.dump()), &report).mesh;
    const TextureSampler& base = a.materials[0].diffuseMap.sampler;
    EXPECT_EQ(base.wrapS, 33071);
    EXPECT_EQ(base.wrapT, 33648);
    EXPECT_EQ(base.magFilter, 9728);
    EXPECT_EQ(base.minFilter, 9986);
    const TextureSampler& normal = a.materials[0].normalMap.sampler;
    EXPECT_EQ(normal.wrapS, 10497) << "invalid: the default";
    EXPECT_EQ(normal.wrapT, 33071);
    EXPECT_EQ(normal.magFilter, 0);
    EXPECT_EQ(normal.minFilter, 9729);
    std::string all;
    for (const auto& w : report.warnings) all += w + "\n";
    EXPECT_NE(all.find("samplers[1].wrapS"), std::string::npos) << all;
    EXPECT_NE(all.find("ignored (the default is used: repeat, trilinear)"), std::string::npos) << all;

    d["textures"] = {{{"source", 0}}, {{"source", 0}, {"sampler", 7}}};
    MeshLoadReport missing;
    const MeshData b = loadGltf(t.write("missing_sampler.gltf", d.dump()), &missing).mesh;
    EXPECT_TRUE(b.materials[0].diffuseMap.sampler.isDefault()) << "no sampler: the default";
    EXPECT_TRUE(b.materials[0].normalMap.sampler.isDefault());
    all.clear();
    for (const auto& w : missing.warnings) all += w + "\n";
    EXPECT_NE(all.find("textures[1]: sampler 7 does not exist; the default is used"), std::string::npos) << all;
}

TEST(GltfLoader, UnlitAndIorMaterials) {
    TempDir t;
    nlohmann::json d = texturedQuad(nullptr, nullptr);
    d["extensionsUsed"] = {"KHR_materials_unlit", "KHR_materials_ior"};
    nlohmann::json unlit = {{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.25, 1, 1}}, {"metallicFactor", 1}}},
                            {"extensions", {{"KHR_materials_unlit", nlohmann::json::object()}}}};
    nlohmann::json water = {{"extensions", {{"KHR_materials_ior", {{"ior", 1.33}}}}}};
    nlohmann::json mirror = {{"extensions", {{"KHR_materials_ior", {{"ior", 0}}}}}};
    d["materials"] = {unlit, water, mirror, nlohmann::json::object()};
    d["meshes"][0]["primitives"] = {d["meshes"][0]["primitives"][0], d["meshes"][0]["primitives"][0], d["meshes"][0]["primitives"][0],
                                    d["meshes"][0]["primitives"][0]};
    for (int i = 0; i < 4; ++i) d["meshes"][0]["primitives"][size_t(i)]["material"] = i;
    MeshLoadReport report;
    const MeshData m = loadGltf(t.write("materials.gltf", d.dump()), &report).mesh;
    ASSERT_EQ(m.materials.size(), 4u);
    EXPECT_TRUE(m.materials[0].flat);
    EXPECT_EQ(m.materials[0].metallic, 0.0f);
    EXPECT_EQ(m.materials[0].diffuse, glm::vec3(0.5f, 0.25f, 1.0f));
    EXPECT_NEAR(m.materials[1].specular.x, (0.33 / 2.33) * (0.33 / 2.33), 1e-7);
    EXPECT_FALSE(m.materials[1].flat);
    EXPECT_EQ(m.materials[2].specular, glm::vec3(1.0f));
    EXPECT_NEAR(m.materials[3].specular.x, 0.04f, 1e-7f);  // no extension: ior 1.5
    for (const auto& w : report.warnings) EXPECT_EQ(w.find("not supported"), std::string::npos) << w;
    d["materials"][1]["extensions"]["KHR_materials_ior"]["ior"] = 0.5;
    expectOneLineError(t.write("ior.gltf", d.dump()), "materials[1].extensions.KHR_materials_ior.ior: 0.5 must be >= 1 (or 0)");
}

// KHR_materials_specular: the dielectric's F0 = min(F0_ior x specularColorFactor, 1) x specularFactor
// and its f90 = specularFactor, given (with KHR_materials_ior's F0 when both are there): `specular` keeps
// F0_ior x colour (the shader clamps it after the colour map), dielectricF0Of() the factors' F0; a
// material without it keeps f90 derived (no dielectricF90). Its textures are read as maps; values
// outside the schema are one line naming the field.
TEST(GltfLoader, SpecularExtensionGivesF0AndF90) {
    TempDir t;
    nlohmann::json d = texturedQuad(nullptr, nullptr);
    d["extensionsUsed"] = {"KHR_materials_specular", "KHR_materials_ior"};
    nlohmann::json tinted = {{"extensions", {{"KHR_materials_specular", {{"specularFactor", 0.5}, {"specularColorFactor", {2.0, 1.0, 30.0}}}}}}};
    nlohmann::json withIor = {{"extensions",
                               {{"KHR_materials_specular", {{"specularColorFactor", {0.5, 0.5, 0.5}}, {"specularTexture", {{"index", 0}}}}},
                                {"KHR_materials_ior", {{"ior", 2.0}}}}}};
    d["materials"] = {tinted, withIor, nlohmann::json::object()};
    d["meshes"][0]["primitives"] = {d["meshes"][0]["primitives"][0], d["meshes"][0]["primitives"][0], d["meshes"][0]["primitives"][0]};
    for (int i = 0; i < 3; ++i) d["meshes"][0]["primitives"][size_t(i)]["material"] = i;
    MeshLoadReport report;
    const MeshData m = loadGltf(t.write("specular.gltf", d.dump()), &report).mesh;
    ASSERT_EQ(m.materials.size(), 3u);
    EXPECT_NEAR(m.materials[0].specular.z, 0.04 * 30.0, 1e-6);  // unclamped: the colour map comes first
    EXPECT_NEAR(m.materials[0].dielectricF0Of().x, 0.08 * 0.5, 1e-7);
    EXPECT_NEAR(m.materials[0].dielectricF0Of().y, 0.04 * 0.5, 1e-7);
    EXPECT_NEAR(m.materials[0].dielectricF0Of().z, 1.0 * 0.5, 1e-7);  // 1.2 clamped to 1 before the weight
    ASSERT_TRUE(m.materials[0].dielectricF90.has_value());
    EXPECT_EQ(*m.materials[0].dielectricF90, 0.5f);
    EXPECT_NEAR(m.materials[1].dielectricF0Of().x, 0.5 / 9.0, 1e-7);  // ((2 - 1) / (2 + 1))^2 x 0.5
    EXPECT_FALSE(m.materials[1].specularMap.empty()) << "specularTexture read";
    EXPECT_TRUE(m.materials[1].specularColorMap.empty());
    EXPECT_TRUE(m.materials[0].specularMap.empty());
    EXPECT_EQ(m.materials[1].dielectricF90, std::optional<float>(1.0f));
    EXPECT_FALSE(m.materials[2].dielectricF90.has_value()) << "no extension: f90 derived from F0";
    for (const auto& w : report.warnings) EXPECT_EQ(w.find("KHR_materials_specular"), std::string::npos) << w;
    d["materials"][0]["extensions"]["KHR_materials_specular"]["specularFactor"] = -0.5;
    expectOneLineError(t.write("weight.gltf", d.dump()),
                       "materials[0].extensions.KHR_materials_specular.specularFactor: -0.5 must be in [0, 1]");
    d["materials"][0]["extensions"]["KHR_materials_specular"]["specularFactor"] = 1;
    d["materials"][0]["extensions"]["KHR_materials_specular"]["specularColorFactor"] = {1, 1, -2};
    expectOneLineError(t.write("colour.gltf", d.dump()),
                       "materials[0].extensions.KHR_materials_specular.specularColorFactor[2]: -2 must be >= 0");
}

// KHR_materials_variants: every variant's materials are loaded; a sub-mesh draws its own material until
// a variant is chosen (--material-variant, a scene model's "materialVariant"), then its mapping's, or its
// own where the variant maps none. Bad mappings are one line naming the element.
TEST(GltfLoader, MaterialVariantsSwitchEachPrimitivesMaterial) {
    TempDir t;
    nlohmann::json d = texturedQuad(nullptr, nullptr);
    d["extensionsUsed"] = {"KHR_materials_variants"};
    auto colour = [](double r, double g, double b) {
        return nlohmann::json{{"pbrMetallicRoughness", {{"baseColorFactor", {r, g, b, 1.0}}}}};
    };
    d["materials"] = {colour(1, 1, 1), colour(1, 0, 0), colour(0, 0, 1)};
    d["extensions"]["KHR_materials_variants"]["variants"] = {{{"name", "red"}}, {{"name", "blue"}}, {{"name", "plain"}}};
    nlohmann::json first = d["meshes"][0]["primitives"][0];
    first["material"] = 0;
    nlohmann::json second = first;
    first["extensions"]["KHR_materials_variants"]["mappings"] = {{{"material", 1}, {"variants", {0}}},
                                                                 {{"material", 2}, {"variants", {1}}}};
    second["extensions"]["KHR_materials_variants"]["mappings"] = {{{"material", 2}, {"variants", {0, 1}}}};
    d["meshes"][0]["primitives"] = {first, second};
    const fs::path file = t.write("variants.gltf", d.dump());
    MeshData m = loadGltf(file).mesh;
    ASSERT_EQ(m.materialVariants, (std::vector<std::string>{"red", "blue", "plain"}));
    ASSERT_EQ(m.subMeshes.size(), 2u);
    auto base = [&](size_t sub) { return m.materials.at(size_t(m.subMeshes[sub].material)).diffuse; };
    EXPECT_EQ(base(0), glm::vec3(1, 1, 1));  // no variant: the file's materials
    EXPECT_EQ(base(1), glm::vec3(1, 1, 1));
    ASSERT_TRUE(selectMaterialVariant(m, "red"));
    EXPECT_EQ(base(0), glm::vec3(1, 0, 0));
    EXPECT_EQ(base(1), glm::vec3(0, 0, 1));
    ASSERT_TRUE(selectMaterialVariant(m, "blue"));
    EXPECT_EQ(base(0), glm::vec3(0, 0, 1));
    ASSERT_TRUE(selectMaterialVariant(m, "plain"));  // mapped by neither primitive: their own
    EXPECT_EQ(base(0), glm::vec3(1, 1, 1));
    EXPECT_EQ(base(1), glm::vec3(1, 1, 1));
    EXPECT_FALSE(selectMaterialVariant(m, "green"));
    EXPECT_EQ(base(0), glm::vec3(1, 1, 1)) << "an unknown variant changes nothing";
    ASSERT_TRUE(selectMaterialVariant(m, ""));

    // In a scene: per model, or for every model that has it.
    const std::string model = R"({"gltf": ")" + file.string() + R"(", "materialVariant": "blue"})";
    Scene s = parseScene(R"({"models": [)" + model + "]}", t.dir / "s.json");
    EXPECT_EQ(s.models[0].mesh.materials.at(size_t(s.models[0].mesh.subMeshes[0].material)).diffuse, glm::vec3(0, 0, 1));
    chooseMaterialVariant(s, "red");
    EXPECT_EQ(s.models[0].mesh.materials.at(size_t(s.models[0].mesh.subMeshes[0].material)).diffuse, glm::vec3(1, 0, 0));
    try {
        chooseMaterialVariant(s, "green");
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "--material-variant 'green': no model has a material variant of that name "
                                         "(variants: 'red', 'blue', 'plain')");
    }
    try {
        parseScene(R"({"models": [{"gltf": ")" + file.string() + R"(", "materialVariant": "green"}]})", t.dir / "s.json");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("models[0].materialVariant: 'green' is not a material variant of variants.gltf "
                                             "('red', 'blue', 'plain')"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_THROW(parseScene(R"({"models": [{"primitive": "plane", "materialVariant": "red"}]})", t.dir / "s.json"), Error);

    // Mappings that name what is not there.
    nlohmann::json bad = d;
    bad["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"][0]["material"] = 7;
    expectOneLineError(t.write("material.gltf", bad.dump()),
                       "meshes[0].primitives[0].extensions.KHR_materials_variants.mappings[0].material: material 7 does not exist");
    bad = d;
    bad["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"][1]["variants"] = {3};
    expectOneLineError(t.write("variant.gltf", bad.dump()),
                       "meshes[0].primitives[0].extensions.KHR_materials_variants.mappings[1].variants[0]: variant 3 does not exist");
    bad = d;
    bad["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"][1]["variants"] = {0};
    expectOneLineError(t.write("twice.gltf", bad.dump()), "variants[0]: variant 0 is mapped twice in this primitive");
    bad = d;
    bad["extensions"].erase("KHR_materials_variants");
    expectOneLineError(t.write("nolist.gltf", bad.dump()), "the file's extensions.KHR_materials_variants lists none");
    bad = d;
    bad["extensions"]["KHR_materials_variants"]["variants"][0] = {{"name", 3}};
    expectOneLineError(t.write("name.gltf", bad.dump()), "extensions.KHR_materials_variants.variants[0].name: expected a string");
    bad = d;
    bad["meshes"][0]["primitives"][1]["extensions"]["KHR_materials_variants"]["mappings"][0].erase("material");
    expectOneLineError(t.write("nomaterial.gltf", bad.dump()), "mappings[0].material: missing");
}

// KHR_materials_clearcoat: the factors (defaults 0 and 0: no coat), the three textures with their
// texCoord, the normal map's scale; a coat without a factor is none (its maps are not loaded); factors
// outside [0, 1] are one-line errors naming the field, a texture without its index too.
TEST(GltfLoader, ClearcoatFactorsAndTextures) {
    TempDir t;
    nlohmann::json d = texturedQuad(nullptr, nullptr);
    d["extensionsUsed"] = {"KHR_materials_clearcoat"};
    nlohmann::json factors = {{"extensions", {{"KHR_materials_clearcoat", {{"clearcoatFactor", 0.75}, {"clearcoatRoughnessFactor", 0.2}}}}}};
    nlohmann::json maps = {{"extensions",
                            {{"KHR_materials_clearcoat",
                              {{"clearcoatFactor", 1.0},
                               {"clearcoatTexture", {{"index", 0}}},
                               {"clearcoatRoughnessTexture", {{"index", 0}, {"texCoord", 0}}},
                               {"clearcoatNormalTexture", {{"index", 0}, {"scale", 0.5}}}}}}}};
    nlohmann::json zero = {{"extensions", {{"KHR_materials_clearcoat", {{"clearcoatTexture", {{"index", 0}}}}}}}};
    d["materials"] = {factors, maps, zero};
    d["meshes"][0]["primitives"] = {d["meshes"][0]["primitives"][0], d["meshes"][0]["primitives"][0], d["meshes"][0]["primitives"][0]};
    for (int i = 0; i < 3; ++i) d["meshes"][0]["primitives"][size_t(i)]["material"] = i;
    MeshLoadReport report;
    const MeshData m = loadGltf(t.write("clearcoat.gltf", d.dump()), &report).mesh;
    ASSERT_EQ(m.materials.size(), 3u);
    EXPECT_EQ(m.materials[0].clearcoat, 0.75f);
    EXPECT_EQ(m.materials[0].clearcoatRoughness, 0.2f);
    EXPECT_TRUE(m.materials[0].hasClearcoat());
    EXPECT_TRUE(m.materials[0].clearcoatMap.empty());
    EXPECT_EQ(m.materials[1].clearcoat, 1.0f);
    EXPECT_EQ(m.materials[1].clearcoatRoughness, 0.0f) << "the extension's default roughness";
    EXPECT_FALSE(m.materials[1].clearcoatMap.empty()) << "clearcoatTexture read";
    EXPECT_FALSE(m.materials[1].clearcoatRoughnessMap.empty()) << "clearcoatRoughnessTexture read";
    EXPECT_FALSE(m.materials[1].clearcoatNormalMap.empty()) << "clearcoatNormalTexture read";
    EXPECT_EQ(m.materials[1].clearcoatNormalScale, 0.5f);
    EXPECT_EQ(m.materials[1].secondUvMaps() & (kClearcoatMapBit | kClearcoatRoughnessMapBit | kClearcoatNormalMapBit), 0u);
    EXPECT_FALSE(m.materials[2].hasClearcoat()) << "clearcoatFactor defaults to 0: no coat";
    EXPECT_TRUE(m.materials[2].clearcoatMap.empty());
    for (const auto& w : report.warnings) EXPECT_EQ(w.find("KHR_materials_clearcoat"), std::string::npos) << w;
    d["materials"][0]["extensions"]["KHR_materials_clearcoat"]["clearcoatFactor"] = -0.5;
    expectOneLineError(t.write("factor.gltf", d.dump()),
                       "materials[0].extensions.KHR_materials_clearcoat.clearcoatFactor: -0.5 must be in [0, 1]");
    d["materials"][0]["extensions"]["KHR_materials_clearcoat"]["clearcoatFactor"] = 1;
    d["materials"][0]["extensions"]["KHR_materials_clearcoat"]["clearcoatRoughnessFactor"] = 2;
    expectOneLineError(t.write("roughness.gltf", d.dump()),
                       "materials[0].extensions.KHR_materials_clearcoat.clearcoatRoughnessFactor: 2 must be in [0, 1]");
    d["materials"][0]["extensions"]["KHR_materials_clearcoat"]["clearcoatRoughnessFactor"] = 0.5;
    d["materials"][0]["extensions"]["KHR_materials_clearcoat"]["clearcoatNormalTexture"] = {{"scale", 1.0}};
    expectOneLineError(t.write("index.gltf", d.dump()),
                       "materials[0].extensions.KHR_materials_clearcoat.clearcoatNormalTexture.index: missing (the glTF schema requires it)");
}

// KHR_materials_transmission + KHR_materials_volume: the factors and their textures (transmission .r,
// thickness .g), the defaults (no volume: thin-walled, attenuationDistance +inf: no absorption, colour
// white), KHR_materials_ior's index kept for the refraction; without a transmission factor the volume
// alone transmits nothing; both extensions load without the "not supported" warning; bad values are
// one-line errors naming the field.
TEST(GltfLoader, TransmissionAndVolume) {
    TempDir t;
    nlohmann::json d = texturedQuad(nullptr, nullptr);
    d["extensionsUsed"] = {"KHR_materials_transmission", "KHR_materials_volume", "KHR_materials_ior"};
    nlohmann::json glass = {{"extensions",
                             {{"KHR_materials_transmission", {{"transmissionFactor", 0.9}, {"transmissionTexture", {{"index", 0}}}}},
                              {"KHR_materials_volume",
                               {{"thicknessFactor", 0.25},
                                {"thicknessTexture", {{"index", 0}}},
                                {"attenuationDistance", 0.5},
                                {"attenuationColor", {0.5, 0.75, 1.0}}}},
                              {"KHR_materials_ior", {{"ior", 1.33}}}}}};
    nlohmann::json thin = {{"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}}}};
    nlohmann::json volumeOnly = {{"extensions", {{"KHR_materials_volume", {{"thicknessFactor", 1.0}}}}}};
    d["materials"] = {glass, thin, volumeOnly};
    d["meshes"][0]["primitives"] = {d["meshes"][0]["primitives"][0], d["meshes"][0]["primitives"][0], d["meshes"][0]["primitives"][0]};
    for (int i = 0; i < 3; ++i) d["meshes"][0]["primitives"][size_t(i)]["material"] = i;
    MeshLoadReport report;
    const MeshData m = loadGltf(t.write("transmission.gltf", d.dump()), &report).mesh;
    ASSERT_EQ(m.materials.size(), 3u);
    const Material& a = m.materials[0];
    EXPECT_TRUE(a.transmissive());
    EXPECT_FLOAT_EQ(a.transmission, 0.9f);
    EXPECT_FALSE(a.transmissionMap.empty()) << "transmissionTexture read";
    EXPECT_FLOAT_EQ(a.thickness, 0.25f);
    EXPECT_FALSE(a.thicknessMap.empty()) << "thicknessTexture read";
    EXPECT_FLOAT_EQ(a.attenuationDistance, 0.5f);
    EXPECT_EQ(a.attenuationColor, glm::vec3(0.5f, 0.75f, 1.0f));
    EXPECT_FLOAT_EQ(a.ior, 1.33f);
    EXPECT_NEAR(a.specular.x, (0.33f / 2.33f) * (0.33f / 2.33f), 1e-6f) << "F0 from the index, as before";
    const Material& b = m.materials[1];
    EXPECT_TRUE(b.transmissive());
    EXPECT_EQ(b.thickness, 0.0f) << "no KHR_materials_volume: thin-walled";
    EXPECT_TRUE(std::isinf(b.attenuationDistance)) << "the default distance: no absorption";
    EXPECT_EQ(b.attenuationColor, glm::vec3(1.0f));
    EXPECT_FLOAT_EQ(b.ior, 1.5f) << "KHR_materials_ior's default";
    EXPECT_FALSE(m.materials[2].transmissive()) << "a volume without transmission transmits nothing";
    for (const auto& w : report.warnings) {
        EXPECT_EQ(w.find("KHR_materials_transmission' is not supported"), std::string::npos) << w;
        EXPECT_EQ(w.find("KHR_materials_volume' is not supported"), std::string::npos) << w;
    }
    nlohmann::json bad = d;
    bad["materials"][0]["extensions"]["KHR_materials_transmission"]["transmissionFactor"] = 1.5;
    expectOneLineError(t.write("factor.gltf", bad.dump()),
                       "materials[0].extensions.KHR_materials_transmission.transmissionFactor: 1.5 must be in [0, 1]");
    bad = d;
    bad["materials"][0]["extensions"]["KHR_materials_volume"]["thicknessFactor"] = -1;
    expectOneLineError(t.write("thickness.gltf", bad.dump()),
                       "materials[0].extensions.KHR_materials_volume.thicknessFactor: -1 must be >= 0");
    bad = d;
    bad["materials"][0]["extensions"]["KHR_materials_volume"]["attenuationDistance"] = -2;
    expectOneLineError(t.write("distance.gltf", bad.dump()),
                       "materials[0].extensions.KHR_materials_volume.attenuationDistance: -2 must be > 0");
    bad = d;
    bad["materials"][0]["extensions"]["KHR_materials_volume"]["attenuationColor"] = {0.5, -0.5, 1.0};
    expectOneLineError(t.write("colour.gltf", bad.dump()),
                       "materials[0].extensions.KHR_materials_volume.attenuationColor[1]: -0.5 must be in [0, 1]");
}

TEST(GltfLoader, SceneFileModelsGltf) {
    TempDir t;
    const std::string scene = R"({"models": [{"gltf": ")" + (kData / "lights.gltf").string() +
                              R"(", "translate": [0, 10, 0]}], "lights": [{"type": "directional"}]})";
    const Scene s = parseScene(scene, t.dir / "s.json");
    ASSERT_EQ(s.models.size(), 1u);
    EXPECT_EQ(s.models[0].name, "lights");
    EXPECT_EQ(s.directionalLights.size(), 2u);  // the file's and the glTF's
    ASSERT_EQ(s.pointLights.size(), 2u);
    EXPECT_NEAR(s.pointLights[0].position.y, 12.0f, 1e-5f);  // placed by the model's transform
    // The model's rotation turns the spot's axis: 90 deg about +Y takes (-1, -1, 0)/sqrt 2 to (0, -1, 1)/sqrt 2.
    const std::string turned = R"({"models": [{"gltf": ")" + (kData / "lights.gltf").string() + R"(", "rotate": [0, 90, 0]}]})";
    const Scene r = parseScene(turned, t.dir / "s.json");
    ASSERT_EQ(r.pointLights.size(), 2u);
    ASSERT_TRUE(r.pointLights[1].spot.has_value());
    EXPECT_NEAR(glm::distance(r.pointLights[1].spot->direction, glm::normalize(glm::vec3(0, -1, 1))), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::distance(r.pointLights[1].position, glm::vec3(0, 3, -2)), 0.0f, 1e-5f);
    EXPECT_THROW(parseScene(R"({"models": [{"gltf": "a.glb", "obj": "b.obj"}]})", t.dir / "s.json"), Error);
    try {
        parseScene(R"({"models": [{"gltf": "a.txt"}]})", t.dir / "s.json");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("models[0].gltf: a.txt: expected a .gltf or .glb file"), std::string::npos) << e.what();
    }
}

// "lightShadows": the model's glTF point and spot lights cast shadows (a point's cube, a spot's map);
// without it they cast none (KHR_lights_punctual has no such flag); false says so explicitly; the
// field needs a glTF model and a boolean, and the scene's own lights keep their own castsShadow.
TEST(GltfLoader, SceneFileGivesAModelsLightsShadows) {
    TempDir t;
    const std::string gltf = (kData / "lights.gltf").string();
    auto scene = [&](const std::string& extra) {
        return parseScene(R"({"models": [{"gltf": ")" + gltf + "\"" + extra + R"(}],
                             "lights": [{"type": "point", "position": [0, 1, 0]}]})",
                          t.dir / "s.json");
    };
    const Scene on = scene(R"(, "lightShadows": true)");
    ASSERT_EQ(on.pointLights.size(), 3u);  // the file's point light, then the glTF's point and spot
    EXPECT_FALSE(on.pointLights[0].castsShadow);
    EXPECT_TRUE(on.pointLights[1].castsShadow);
    EXPECT_FALSE(on.pointLights[1].spot.has_value());
    EXPECT_TRUE(on.pointLights[2].castsShadow);
    EXPECT_TRUE(on.pointLights[2].spot.has_value());
    ASSERT_TRUE(on.models[0].lightShadows.has_value());
    for (const Scene& s : {scene(""), scene(R"(, "lightShadows": false)")}) {
        ASSERT_EQ(s.pointLights.size(), 3u);
        for (const PointLight& l : s.pointLights) EXPECT_FALSE(l.castsShadow);
    }
    auto error = [&](const std::string& model) {
        try {
            parseScene(R"({"models": [)" + model + "]}", t.dir / "s.json");
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(error(R"({"gltf": ")" + gltf + R"(", "lightShadows": 1})").find("models[0].lightShadows: expected true or false"),
              std::string::npos);
    EXPECT_NE(error(R"({"primitive": "cube", "lightShadows": true})")
                  .find("models[0].lightShadows: only a glTF model has lights (KHR_lights_punctual)"),
              std::string::npos);
    EXPECT_NE(error(R"({"gltf": ")" + gltf + R"(", "lightShadow": true})").find("models[0].lightShadow: unknown field"),
              std::string::npos);
}

// Bad input: one-line errors naming the file and the element.
TEST(GltfLoader, BadInputNamesFileAndElement) {
    TempDir t;
    auto expectError = [&](const std::string& name, const std::string& text, const std::string& fragment) {
        const fs::path p = t.write(name, text);
        const std::string err = loadError(p);
        EXPECT_EQ(err.rfind(p.string() + ":", 0), 0u) << name << ": " << err;  // ": " or, for JSON, ":line:column: "
        EXPECT_NE(err.find(fragment), std::string::npos) << name << ": " << err;
        EXPECT_EQ(err.find('\n'), std::string::npos) << err;
    };
    // The well-formed base loads.
    EXPECT_NO_THROW(loadGltf(t.write("ok.gltf", triangleGltf("[" + kPositions + "]", kViews, 42))));
    expectError("missing_buffer.gltf",
                R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 42, "uri": "nothere.bin"}], "bufferViews": )" + kViews +
                    R"(, "accessors": [)" + kPositions + R"(], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], "nodes": [{"mesh": 0}]})",
                "buffers[0].uri: 'nothere.bin': file not found");
    expectError("accessor_past_end.gltf", triangleGltf(R"([{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"}])", kViews, 42),
                "meshes[0].primitives[0].attributes.POSITION (accessors[0]): 4 elements from byte 0 run past the end of bufferViews[0]");
    expectError("view_past_buffer.gltf",
                triangleGltf("[" + kPositions + "]", R"([{"buffer": 0, "byteOffset": 8, "byteLength": 36}])", 42),
                "bufferViews[0]: bytes 8+36 run past the end of buffers[0]");
    expectError("no_accessor.gltf", triangleGltf("[" + kPositions + "]", kViews, 42, "", R"("attributes": {"POSITION": 7})"),
                "meshes[0].primitives[0].attributes.POSITION: accessor 7 does not exist");
    expectError("bad_index.gltf",
                replaced(triangleGltf("[" + kPositions + R"(, {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}])", kViews,
                                      42, "", R"("attributes": {"POSITION": 0}, "indices": 1)"),
                         "AAABAAIA", "AAABAAkA"),
                "meshes[0].primitives[0].indices: index 9 at position 2 is beyond the 3 vertices");
    expectError("required_ext.gltf", triangleGltf("[" + kPositions + "]", kViews, 42, R"("extensionsRequired": ["KHR_texture_basisu"],)"),
                "extensionsRequired[0]: 'KHR_texture_basisu' is not supported");
    expectError("wrong_type.gltf", triangleGltf(R"([{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC2"}])", kViews, 42),
                "unexpected type");
    expectError("cycle.gltf",
                replaced(triangleGltf("[" + kPositions + "]", kViews, 42), R"("nodes": [{"mesh": 0}])",
                         R"("nodes": [{"mesh": 0, "children": [1]}, {"children": [0]}])"),
                "the node hierarchy has a cycle");
    expectError("not_json.gltf", "{\"asset\": ", ":1:11: invalid JSON: syntax error while parsing value - unexpected end of input");
    // Spot cones: lights[2] of three, on the triangle's node.
    auto spotGltf = [&](const std::string& cone) {
        return replaced(triangleGltf("[" + kPositions + "]", kViews, 42,
                                     R"("extensionsUsed": ["KHR_lights_punctual"], "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point"}, {"type": "point"}, {"type": "spot", "spot": {)" +
                                         cone + "}}]}},"),
                        R"("nodes": [{"mesh": 0}])", R"("nodes": [{"mesh": 0, "extensions": {"KHR_lights_punctual": {"light": 2}}}])");
    };
    expectError("spot_outer_below_inner.gltf", spotGltf(R"("innerConeAngle": 0.5, "outerConeAngle": 0.3)"),
                "extensions.KHR_lights_punctual.lights[2].spot.outerConeAngle: 0.3 rad must be greater than innerConeAngle 0.5");
    expectError("spot_equal.gltf", spotGltf(R"("innerConeAngle": 0.4, "outerConeAngle": 0.4)"), "lights[2].spot.outerConeAngle");
    expectError("spot_negative_inner.gltf", spotGltf(R"("innerConeAngle": -0.1, "outerConeAngle": 0.4)"),
                "lights[2].spot.innerConeAngle: -0.1 rad: must be >= 0");
    // JSON has no NaN; an overflowing number is the way a file carries a non-finite angle.
    const std::string nanErr = loadError(t.write("spot_nan.gltf", spotGltf(R"("innerConeAngle": 0.1, "outerConeAngle": 1e999)")));
    EXPECT_EQ(nanErr.rfind((t.dir / "spot_nan.gltf").string() + ":1:", 0), 0u) << nanErr;
    EXPECT_NE(nanErr.find(": number '1e999' is beyond the range of a double"), std::string::npos) << nanErr;
    EXPECT_EQ(nanErr.find('\n'), std::string::npos) << nanErr;
    // Defaults (0 and pi/4), and glTF's widest cone pi/2 clamped below a hemisphere with a warning.
    const GltfContent d = loadGltf(t.write("spot_default.gltf", spotGltf("")));
    ASSERT_EQ(d.pointLights.size(), 1u);
    ASSERT_TRUE(d.pointLights[0].spot.has_value());
    EXPECT_NEAR(d.pointLights[0].spot->innerDegrees, 0.0f, 1e-6f);
    EXPECT_NEAR(d.pointLights[0].spot->outerDegrees, 45.0f, 1e-4f);
    EXPECT_NEAR(glm::distance(d.pointLights[0].spot->direction, glm::vec3(0, 0, -1)), 0.0f, 1e-6f);
    MeshLoadReport wide;
    const GltfContent w = loadGltf(t.write("spot_wide.gltf", spotGltf(R"("innerConeAngle": 1.5707963, "outerConeAngle": 1.5707964)")), &wide);
    ASSERT_TRUE(w.pointLights.at(0).spot.has_value());
    EXPECT_FLOAT_EQ(w.pointLights[0].spot->outerDegrees, 89.0f);
    EXPECT_FLOAT_EQ(w.pointLights[0].spot->innerDegrees, 89.0f);
    bool clampWarned = false;
    for (const auto& m : wide.warnings) clampWarned |= m.find("lights[2].spot.outerConeAngle: 90 degrees clamped to 89") != std::string::npos;
    EXPECT_TRUE(clampWarned);
    // A missing texture is the documented fallback: the file loads, the texture is a checker later.
    const std::string withTexture = triangleGltf("[" + kPositions + "]", kViews, 42,
                                                 R"("images": [{"uri": "missing.png"}], "textures": [{"source": 0}], "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],)",
                                                 R"("attributes": {"POSITION": 0}, "material": 0)");
    const GltfContent g = loadGltf(t.write("missing_texture.gltf", withTexture));
    ASSERT_EQ(g.mesh.materials.size(), 1u);
    EXPECT_EQ(g.mesh.materials[0].diffuseMap.path, t.dir / "missing.png");
}

// Malformed files found by mutating the project's own: each must be one error line naming the file
// (or a documented fallback), never a crash, a hang or an out-of-memory.
static void expectOneLineError(const fs::path& p, const std::string& fragment) {
    const std::string err = loadError(p);
    EXPECT_EQ(err.rfind(p.string() + ": ", 0), 0u) << p << ": " << err;
    EXPECT_NE(err.find(fragment), std::string::npos) << p << ": " << err;
    EXPECT_EQ(err.find('\n'), std::string::npos) << err;
}

// "material": -2 indexed the material table at -1 (a heap read before the array). The schema
// refuses every negative index; one past the table is the loader's to name.
TEST(GltfMalformed, MaterialIndexBelowMinusOne) {
    TempDir t;
    for (const char* m : {"-1", "-2", "-1000000"})
        expectOneLineError(t.write(std::string("material") + m + ".gltf",
                                   triangleGltf("[" + kPositions + "]", kViews, 42, "",
                                                std::string(R"("attributes": {"POSITION": 0}, "material": )") + m)),
                           std::string("meshes[0].primitives[0].material: expected an index (an integer >= 0), got ") + m);
    expectOneLineError(t.write("material1.gltf", triangleGltf("[" + kPositions + "]", kViews, 42, "",
                                                              R"("attributes": {"POSITION": 0}, "material": 1)")),
                       "materials: material 1 does not exist (0 materials)");
}

// Node structures that cost exponential time, the whole stack or gigabytes: refused up front.
TEST(GltfMalformed, NodeHierarchyIsCheckedBeforeItIsWalked) {
    TempDir t;
    const std::string base = triangleGltf("[" + kPositions + "]", kViews, 42);
    // Each of 40 nodes names the next one twice: 2^40 paths to the mesh.
    std::string dag = "\"nodes\": [";
    for (int i = 0; i < 40; ++i) dag += "{\"children\": [" + std::to_string(i + 1) + ", " + std::to_string(i + 1) + "]}, ";
    dag += "{\"mesh\": 0}]";
    expectOneLineError(t.write("dag.gltf", replaced(base, R"("nodes": [{"mesh": 0}])", dag)),
                       "nodes[40]: is reached twice (from nodes[39].children)");
    // A root listed twice would be drawn twice.
    expectOneLineError(t.write("root_twice.gltf", replaced(base, R"("scenes": [{"nodes": [0]}])", R"("scenes": [{"nodes": [0, 0]}])")),
                       "nodes[0]: is reached twice (from scenes[0].nodes)");
    // A chain 5000 nodes deep overflowed the stack of the recursive walk.
    std::string chain = "\"nodes\": [";
    for (int i = 0; i < 5000; ++i) chain += "{\"children\": [" + std::to_string(i + 1) + "]}, ";
    chain += "{\"mesh\": 0}]";
    expectOneLineError(t.write("chain.gltf", replaced(base, R"("nodes": [{"mesh": 0}])", chain)),
                       "nodes[1024]: is more than 1024 levels deep");
    // 2000 nodes drawing one mesh of 1000 primitives: 2M primitive instances.
    std::string prims;
    for (int i = 0; i < 1000; ++i) prims += std::string(i ? ", " : "") + R"({"attributes": {"POSITION": 0}})";
    std::string nodes = "\"nodes\": [", roots;
    for (int i = 0; i < 2000; ++i) {
        nodes += std::string(i ? ", " : "") + R"({"mesh": 0})";
        roots += std::string(i ? ", " : "") + std::to_string(i);
    }
    const std::string amplified = replaced(replaced(replaced(base, R"("nodes": [{"mesh": 0}])", nodes + "]"), R"("scenes": [{"nodes": [0]}])",
                                                    "\"scenes\": [{\"nodes\": [" + roots + "]}]"),
                                           R"("primitives": [{"attributes": {"POSITION": 0}}])", "\"primitives\": [" + prims + "]");
    expectOneLineError(t.write("amplified.gltf", amplified), "primitives or 67108864 vertices and indices in all");
    // The cycle keeps its own message.
    expectOneLineError(t.write("cycle.gltf", replaced(base, R"("nodes": [{"mesh": 0}])", R"("nodes": [{"mesh": 0, "children": [1]}, {"children": [0]}])")),
                       "nodes[0]: is its own ancestor");
    // A deep but legal chain (100 levels) still loads.
    std::string legal = "\"nodes\": [";
    for (int i = 0; i < 100; ++i) legal += "{\"children\": [" + std::to_string(i + 1) + "]}, ";
    legal += "{\"mesh\": 0}]";
    EXPECT_EQ(loadGltf(t.write("legal.gltf", replaced(base, R"("nodes": [{"mesh": 0}])", legal))).mesh.indices.size(), 3u);
}

// An accessor without a buffer view is all zeros and its count is bounded by no bytes of the file:
// a 300-byte file asked for 60M vertices (3 GiB).
TEST(GltfMalformed, PositionsOrIndicesWithoutABufferView) {
    TempDir t;
    expectOneLineError(t.write("positions.gltf", triangleGltf(R"([{"componentType": 5126, "count": 60000000, "type": "VEC3"}])", kViews, 42)),
                       "meshes[0].primitives[0].attributes.POSITION (accessors[0]): has no bufferView and is not sparse, so its 60000000 elements would all be zero");
}

// Values that parse but poison the frame once turned into floats: a directional light on a node
// scaled to zero shone in a NaN direction, a range of 1e300 or a colour of 1e30 became +Inf, and a
// node scale of 1e30 gave finite positions whose normals were NaN.
TEST(GltfMalformed, LightsAndPositionsThatOverflowAFloat) {
    TempDir t;
    auto lightGltf = [&](const std::string& light, const std::string& node) {
        return replaced(triangleGltf("[" + kPositions + "]", kViews, 42,
                                     R"("extensionsUsed": ["KHR_lights_punctual"], "extensions": {"KHR_lights_punctual": {"lights": [)" + light + "]}},"),
                        R"("nodes": [{"mesh": 0}])", R"("nodes": [{"mesh": 0}, {)" + node + R"("extensions": {"KHR_lights_punctual": {"light": 0}}}])");
    };
    auto withRoots = [](std::string text) { return replaced(text, R"("scenes": [{"nodes": [0]}])", R"("scenes": [{"nodes": [0, 1]}])"); };
    expectOneLineError(t.write("sun_zero_scale.gltf", withRoots(lightGltf(R"({"type": "directional"})", R"("scale": [0, 0, 0], )"))),
                       "extensions.KHR_lights_punctual.lights[0]: its node (nodes[1]) has no -Z direction (a zero scale)");
    expectOneLineError(t.write("range_1e300.gltf", withRoots(lightGltf(R"({"type": "point", "range": 1e300})", ""))),
                       "lights[0].range: 1e+300 is beyond a float's range");
    expectOneLineError(t.write("colour_1e30.gltf", withRoots(lightGltf(R"({"type": "point", "color": [1e30, 1, 1]})", ""))),
                       "lights[0]: colour and intensity must be finite, >= 0 and <= 1e9");
    // A point light needs no direction: a zero scale is fine for it.
    const GltfContent point = loadGltf(t.write("point_zero_scale.gltf", withRoots(lightGltf(R"({"type": "point"})", R"("scale": [0, 0, 0], )"))));
    ASSERT_EQ(point.pointLights.size(), 1u);
    EXPECT_TRUE(std::isfinite(point.pointLights[0].range));
    // Scaled by 1e30 the triangle's corners are finite floats but its normal is not: dropped, so no triangle.
    expectOneLineError(t.write("scale_1e30.gltf", replaced(triangleGltf("[" + kPositions + "]", kViews, 42), R"("nodes": [{"mesh": 0}])",
                                                           R"("nodes": [{"mesh": 0, "scale": [1e30, 1e30, 1e30]}])")),
                       "no triangles");
    MeshLoadReport report;
    const GltfContent big = loadGltf(t.write("scale_1e15.gltf", replaced(triangleGltf("[" + kPositions + "]", kViews, 42), R"("nodes": [{"mesh": 0}])",
                                                                        R"("nodes": [{"mesh": 0, "scale": [1e15, 1e15, 1e15]}])")), &report);
    ASSERT_EQ(big.mesh.vertices.size(), 3u);
    for (const Vertex& v : big.mesh.vertices) {
        EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-5f);  // the float cross product's squared length overflowed: a zero normal
        EXPECT_TRUE(std::isfinite(v.tangent.x + v.tangent.y + v.tangent.z));
    }
}

// tinygltf hands an image in a buffer view over as buffer + byteOffset, byteLength bytes unchecked:
// a byteLength past the buffer read the heap beyond it (found by mutating forms.gltf).
TEST(GltfMalformed, ImageBufferViewPastItsBuffer) {
    TempDir t;
    const std::string views = R"([{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}, )";
    const std::string image = R"("images": [{"mimeType": "image/png", "bufferView": 2}], "textures": [{"source": 0}], "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],)";
    expectOneLineError(t.write("long.gltf", triangleGltf("[" + kPositions + "]", views + R"({"buffer": 0, "byteOffset": 30, "byteLength": 782}])", 42, image,
                                                         R"("attributes": {"POSITION": 0}, "material": 0)")),
                       "images[0]: bufferViews[2]: bytes 30+782 run past the end of buffers[0] (42 bytes)");
    expectOneLineError(t.write("far.gltf", triangleGltf("[" + kPositions + "]", views + R"({"buffer": 0, "byteOffset": 1000000, "byteLength": 4}])", 42, image,
                                                        R"("attributes": {"POSITION": 0}, "material": 0)")),
                       "images[0]: bufferViews[2]: bytes 1000000+4 run past the end of buffers[0] (42 bytes)");
    // In range, the bytes are kept (and later decoded, or a checker with a warning: these 6 are no image).
    const GltfContent ok = loadGltf(t.write("in_range.gltf", triangleGltf("[" + kPositions + "]", views + R"({"buffer": 0, "byteOffset": 36, "byteLength": 6}])", 42,
                                                                          image, R"("attributes": {"POSITION": 0}, "material": 0)")));
    ASSERT_TRUE(ok.mesh.materials.at(0).diffuseMap.encoded);
    EXPECT_EQ(ok.mesh.materials[0].diffuseMap.encoded->size(), 6u);
}

// A property of the wrong JSON type, length or enumeration: tinygltf skipped these silently (the
// file then loaded as if the property were absent: no mesh, no emission, a default alpha mode).
// Each is one error line naming the element, from .gltf and from .glb alike.
namespace {

// The triangle document with a material, a texture, a sampler, a camera node and a light, all valid.
nlohmann::json schemaBase() {
    nlohmann::json d = nlohmann::json::parse(triangleGltf(
        "[" + kPositions + "]", kViews, 42,
        R"("materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1], "roughnessFactor": 0.5,
                          "baseColorTexture": {"index": 0}}, "emissiveFactor": [0, 0, 0], "alphaMode": "OPAQUE"}],
            "textures": [{"source": 0, "sampler": 0}], "samplers": [{"wrapS": 10497}], "images": [{"uri": "missing.png"}],
            "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
            "extensionsUsed": ["KHR_lights_punctual"],
            "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "color": [1, 1, 1], "intensity": 5}]}},)",
        R"("attributes": {"POSITION": 0}, "material": 0)"));
    d["nodes"][0]["camera"] = 0;
    d["nodes"][0]["extensions"]["KHR_lights_punctual"]["light"] = 0;
    return d;
}

// A GLB of `doc` with no BIN chunk (the buffer stays a data: URI).
std::string glbOf(const nlohmann::json& doc, uint32_t container = 2) {
    std::string json = doc.dump();
    json.append((4 - json.size() % 4) % 4, ' ');
    auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
    return "glTF" + u32(container) + u32(uint32_t(20 + json.size())) + u32(uint32_t(json.size())) + "JSON" + json;
}

}  // namespace

TEST(GltfSchema, WrongTypesLengthsAndEnumerationsAreErrorsNamingTheElement) {
    TempDir t;
    const nlohmann::json base = schemaBase();
    MeshLoadReport clean;
    ASSERT_NO_THROW(loadGltf(t.write("base.gltf", base.dump()), &clean));
    for (const auto& w : clean.warnings) EXPECT_EQ(w.find("clamped"), std::string::npos) << w;
    EXPECT_TRUE(checkGltfSchema(base).empty());
    struct Case {
        const char* pointer;  // JSON pointer of the property to set
        nlohmann::json value;
        const char* error;    // "where: what"
    };
    const Case cases[] = {
        {"/materials/0/emissiveFactor/0", "VEC3", R"(materials[0].emissiveFactor[0]: expected a number, got a string ('VEC3'))"},
        {"/materials/0/emissiveFactor", 5, "materials[0].emissiveFactor: expected an array of 3 numbers, got 5"},
        {"/materials/0/pbrMetallicRoughness/roughnessFactor", "0.5", "materials[0].pbrMetallicRoughness.roughnessFactor: expected a number"},
        {"/materials/0/alphaMode", "FOO", R"(materials[0].alphaMode: expected one of OPAQUE, MASK, BLEND, got a string ('FOO'))"},
        {"/materials/0/doubleSided", "", "materials[0].doubleSided: expected true or false"},
        {"/materials/0/pbrMetallicRoughness/baseColorTexture/index", 0.5,
         "materials[0].pbrMetallicRoughness.baseColorTexture.index: expected an index (an integer >= 0), got 0.5"},
        {"/materials/0/pbrMetallicRoughness", nlohmann::json::array(), "materials[0].pbrMetallicRoughness: expected an object, got an array"},
        {"/nodes/0/mesh", 0.5, "nodes[0].mesh: expected an index (an integer >= 0), got 0.5"},
        {"/nodes/0/mesh", "0", "nodes[0].mesh: expected an index"},
        {"/nodes/0/mesh", 4294967296.0, "nodes[0].mesh: expected an index (an integer >= 0)"},
        {"/nodes/0/mesh", 2147483648u, "nodes[0].mesh: expected an index below 2^31"},
        {"/nodes/0/translation", {0, 1}, "nodes[0].translation: expected an array of 3 numbers, got an array of 2"},
        {"/nodes/0/children", nlohmann::json::object(), "nodes[0].children: expected an array of indices, got an object"},
        {"/meshes/0/primitives/0/attributes", {0}, "meshes[0].primitives[0].attributes: expected an object, got an array"},
        {"/meshes/0/primitives/0/attributes/POSITION", "0", "meshes[0].primitives[0].attributes.POSITION: expected an index"},
        {"/meshes/0/primitives/0/mode", 9, "meshes[0].primitives[0].mode: expected one of 0, 1, 2, 3, 4, 5, 6, got 9"},
        {"/meshes/0/primitives", nlohmann::json::array(), "meshes[0].primitives: expected at least 1 element(s), got none"},
        {"/accessors/0/normalized", "x", "accessors[0].normalized: expected true or false"},
        {"/accessors/0/count", 0, "accessors[0].count: expected an integer >= 1, got 0"},
        {"/accessors/0/componentType", 5124, "accessors[0].componentType: expected one of 5120, 5121, 5122, 5123, 5125, 5126, got 5124"},
        {"/bufferViews/0/byteOffset", "0", "bufferViews[0].byteOffset: expected an integer >= 0"},
        {"/bufferViews/0/byteStride", 2, "bufferViews[0].byteStride: expected an integer from 4 to 252, got 2"},
        {"/buffers/0/byteLength", -42, "buffers[0].byteLength: expected an integer >= 1, got -42"},
        {"/textures/0/source", -1, "textures[0].source: expected an index (an integer >= 0), got -1"},
        {"/cameras/0/perspective/yfov", 0, "cameras[0].perspective.yfov: 0 must be > 0"},
        {"/cameras/0/type", "fisheye", "cameras[0].type: expected one of perspective, orthographic"},
        {"/extensions/KHR_lights_punctual/lights/0/intensity", -5, "extensions.KHR_lights_punctual.lights[0].intensity: -5 must be >= 0"},
        {"/extensions/KHR_lights_punctual/lights/0/color/1", -0.5, "extensions.KHR_lights_punctual.lights[0].color[1]: -0.5 must be >= 0"},
        {"/extensions/KHR_lights_punctual/lights/0/type", "area", "extensions.KHR_lights_punctual.lights[0].type: expected one of directional"},
        {"/extensions/KHR_lights_punctual/lights/0/range", 0, "extensions.KHR_lights_punctual.lights[0].range: 0 must be > 0"},
        {"/nodes/0/extensions/KHR_lights_punctual/light", "0", "nodes[0].extensions.KHR_lights_punctual.light: expected an index"},
        {"/scene", "0", R"(scene: expected an index (an integer >= 0), got a string ('0'))"},
        {"/scenes/0/nodes/0", -1, "scenes[0].nodes[0]: expected an index (an integer >= 0), got -1"},
        {"/asset/version", "1.0", R"(asset.version: '1.0' is not a glTF 2 version: lightpass reads glTF 2.0)"},
        {"/extensionsUsed", "KHR_lights_punctual", "extensionsUsed: expected an array of strings"},
    };
    int n = 0;
    for (const Case& c : cases) {
        nlohmann::json d = base;
        d[nlohmann::json::json_pointer(c.pointer)] = c.value;
        const std::string name = "case" + std::to_string(n++);
        expectOneLineError(t.write(name + ".gltf", d.dump()), c.error);
        expectOneLineError(t.write(name + ".glb", glbOf(d)), c.error);
    }
    // Required properties.
    for (const auto& [pointer, error] : std::vector<std::pair<std::string, std::string>>{
             {"/accessors/0/componentType", "accessors[0].componentType: missing (the glTF schema requires it)"},
             {"/meshes/0/primitives/0/attributes", "meshes[0].primitives[0].attributes: missing"},
             {"/materials/0/pbrMetallicRoughness/baseColorTexture/index", "baseColorTexture.index: missing"},
             {"/cameras/0/perspective/yfov", "cameras[0].perspective.yfov: missing"},
             {"/bufferViews/0/buffer", "bufferViews[0].buffer: missing"}}) {
        nlohmann::json d = base;
        const nlohmann::json::json_pointer p(pointer);
        d[p.parent_pointer()].erase(p.back());
        expectOneLineError(t.write("missing" + std::to_string(n++) + ".gltf", d.dump()), error);
    }
    // A GLB of glTF 1.0, and a required extension named before tinygltf trips over what it changes
    // (a KTX2 texture source: no Debian package decodes KTX2).
    expectOneLineError(t.write("v1.glb", glbOf(base, 1)), "GLB container version 1: lightpass reads glTF 2.0");
    nlohmann::json basisu = base;
    basisu["extensionsUsed"] = basisu["extensionsRequired"] = {"KHR_texture_basisu"};
    basisu["images"] = {{{"uri", "texture.ktx2"}}};
    basisu["textures"] = {{{"extensions", {{"KHR_texture_basisu", {{"source", 0}}}}}}};
    expectOneLineError(t.write("basisu.gltf", basisu.dump()), "extensionsRequired[0]: 'KHR_texture_basisu' is not supported");
}

// An optional extension lightpass does not read loads without it, with a warning naming it; the
// supported ones load silently.
TEST(GltfSchema, UnsupportedOptionalExtensionsAreNamedInAWarning) {
    TempDir t;
    nlohmann::json d = schemaBase();
    d["extensionsUsed"] = {"KHR_lights_punctual", "KHR_materials_iridescence", "KHR_materials_sheen", "KHR_texture_transform",
                           "KHR_materials_clearcoat"};
    MeshLoadReport report;
    loadGltf(t.write("ext.gltf", d.dump()), &report);
    std::string all;
    for (const auto& w : report.warnings) all += w + "\n";
    EXPECT_NE(all.find("extensionsUsed[1]: 'KHR_materials_iridescence' is not supported; ignored (the model may look different)"), std::string::npos) << all;
    EXPECT_NE(all.find("extensionsUsed[2]: 'KHR_materials_sheen' is not supported"), std::string::npos) << all;
    EXPECT_EQ(all.find("KHR_materials_clearcoat is not supported"), std::string::npos) << all;
    EXPECT_EQ(all.find("KHR_lights_punctual is not supported"), std::string::npos) << all;
    EXPECT_EQ(all.find("KHR_texture_transform is not supported"), std::string::npos) << all;
}

// What lightpass does not read (an accessor's min and max) or reads with a default to fall back on
// (samplers' filters and wraps) may break its rule with a warning; a byteStride of 0 (glTF 1.0's
// "packed") reads as packed.
TEST(GltfSchema, RulesOfPropertiesLightpassDoesNotReadAreWarnings) {
    TempDir t;
    nlohmann::json d = schemaBase();
    d["samplers"][0]["wrapS"] = 1;
    d["samplers"][0]["magFilter"] = 9987;
    d["accessors"][0]["min"] = {0, 0};
    d["bufferViews"][0]["byteStride"] = 0;
    MeshLoadReport report;
    const GltfContent g = loadGltf(t.write("lenient.gltf", d.dump()), &report);
    EXPECT_EQ(g.mesh.indices.size(), 3u);
    std::string all;
    for (const auto& w : report.warnings) all += w + "\n";
    for (const char* expected : {"samplers[0].wrapS: expected one of 33071, 33648, 10497, got 1; ignored (the default is used: repeat, trilinear)",
                                 "samplers[0].magFilter: expected one of 9728, 9729, got 9987; ignored",
                                 "accessors[0].min: expected an array of 3 numbers, got an array of 2; ignored (lightpass does not read it)",
                                 "bufferViews[0].byteStride: 0 is outside 4..252; read as tightly packed"})
        EXPECT_NE(all.find(expected), std::string::npos) << expected << "\nin:\n" << all;
    d["bufferViews"][0]["byteStride"] = 2;
    expectOneLineError(t.write("stride2.gltf", d.dump()), "bufferViews[0].byteStride: expected an integer from 4 to 252, got 2");
}

// Factors outside the schema's [0, 1] (and a negative alphaCutoff) load clamped, each with a warning
// naming it.
TEST(GltfSchema, OutOfRangeFactorsAreClampedWithAWarning) {
    TempDir t;
    nlohmann::json d = schemaBase();
    d["materials"][0]["pbrMetallicRoughness"]["roughnessFactor"] = 5;
    d["materials"][0]["pbrMetallicRoughness"]["metallicFactor"] = -1;
    d["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {2, 0.5, -0.25, 1};
    d["materials"][0]["emissiveFactor"] = {0, 3, 0};
    d["materials"][0]["alphaCutoff"] = -1;
    MeshLoadReport report;
    const GltfContent g = loadGltf(t.write("clamped.gltf", d.dump()), &report);
    ASSERT_EQ(g.mesh.materials.size(), 1u);
    const Material& m = g.mesh.materials[0];
    EXPECT_EQ(m.roughness, 1.0f);
    EXPECT_EQ(m.metallic, 0.0f);
    EXPECT_EQ(m.diffuse, glm::vec3(1.0f, 0.5f, 0.0f));
    EXPECT_EQ(m.emission, glm::vec3(0.0f, 1.0f, 0.0f));
    EXPECT_EQ(m.alphaCutoff, 0.0f);
    std::string all;
    for (const auto& w : report.warnings) all += w + "\n";
    for (const char* expected : {"materials[0].pbrMetallicRoughness.roughnessFactor: 5 is outside [0, 1]; clamped",
                                 "materials[0].pbrMetallicRoughness.metallicFactor: -1 is outside [0, 1]; clamped",
                                 "materials[0].pbrMetallicRoughness.baseColorFactor[0]: 2 is outside [0, 1]; clamped",
                                 "materials[0].pbrMetallicRoughness.baseColorFactor[2]: -0.25 is outside [0, 1]; clamped",
                                 "materials[0].emissiveFactor[1]: 3 is outside [0, 1]; clamped",
                                 "materials[0].alphaCutoff: -1 is outside [0, inf); clamped"})
        EXPECT_NE(all.find(expected), std::string::npos) << expected << "\nin:\n" << all;
}

// MTL: "norm" is a tangent-space normal map, "bump" a height map, Ke emission, d opacity; a map's
// `-clamp on` samples it clamped to its edge.
TEST(GltfLoader, MtlConvertsOntoTheSameMaterialModel) {
    TempDir t;
    t.write("m.mtl", "newmtl a\nKd 0.5 0.25 0.125\nKs 0.1 0.2 0.3\nNs 100\nKe 2 3 4\nnorm -bm 0.5 n.png\nbump h.png\nd 0.4\n"
                     "map_Kd -clamp on kd.png\n");
    const fs::path obj = t.write("m.obj", "mtllib m.mtl\nusemtl a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const MeshData m = loadObj(obj);
    const Material& a = m.materials[0];
    EXPECT_EQ(a.normalMap.path, t.dir / "n.png");
    EXPECT_NEAR(a.normalScale, 0.5f, 1e-6f);
    EXPECT_EQ(a.bumpMap.path, t.dir / "h.png");
    EXPECT_EQ(a.diffuseMap.path, t.dir / "kd.png");
    EXPECT_EQ(a.diffuseMap.sampler.wrapS, 33071);  // GL_CLAMP_TO_EDGE
    EXPECT_EQ(a.diffuseMap.sampler.wrapT, 33071);
    EXPECT_TRUE(a.bumpMap.sampler.isDefault()) << "no -clamp: repeating";
    EXPECT_NEAR(a.emission.z, 4.0f, 1e-6f);
    EXPECT_NEAR(a.specular.y, 0.2f, 1e-6f);
    EXPECT_EQ(a.metallic, 0.0f);
    EXPECT_NEAR(a.opacity, 0.4f, 1e-6f);
    EXPECT_EQ(a.alphaMode, AlphaMode::Blend);  // d < 1: alpha-blended by the transparent pass
    EXPECT_NEAR(shininessFromRoughness(a.roughness), 100.0f, 0.05f);
    EXPECT_TRUE(a.doubleSided);
}

TEST(GltfLoader, RoughnessShininessRoundTrip) {
    for (float n : {0.0f, 1.0f, 32.0f, 1000.0f, 10000.0f, 1e6f}) EXPECT_NEAR(shininessFromRoughness(roughnessFromShininess(n)), n, 1e-3f * (n + 1.0f));
    EXPECT_EQ(shininessFromRoughness(1.0f), 0.0f);
    EXPECT_NEAR(shininessFromRoughness(0.1f), 19998.0f, 0.1f);  // past the analytic BRDFs' 10000: IBL reaches it
    EXPECT_NEAR(shininessFromRoughness(0.0f), 1.25e7f, 10.0f);  // the floor, roughness 0.02
    EXPECT_EQ(shininessFromRoughness(0.0f), shininessFromRoughness(kMinRoughness));
}

// --up z and a scene file's "up": "z" turn a Z-up model Y-up, (x, y, z) -> (x, z, -y), before placing it.
TEST(GltfLoader, ZUpModelsAreTurnedYUp) {
    glm::vec3 lo, hi;
    const Scene yUp = sceneForModel(kData / "forms.gltf");
    yUp.bounds(lo, hi);
    EXPECT_NEAR(hi.y, 1.0f, 1e-5f);
    const Scene zUp = sceneForModel(kData / "forms.gltf", true);
    zUp.bounds(lo, hi);
    EXPECT_NEAR(hi.y, 0.0f, 1e-5f);  // the quads' y (0..1) became -z
    EXPECT_NEAR(lo.z, -1.0f, 1e-5f);
    TempDir t;
    const Scene s = parseScene(R"({"models": [{"gltf": ")" + (kData / "forms.gltf").string() + R"(", "up": "z", "translate": [0, 5, 0]}]})",
                               t.dir / "s.json");
    s.bounds(lo, hi);
    EXPECT_NEAR(lo.y, 5.0f, 1e-5f);
    EXPECT_NEAR(lo.z, -1.0f, 1e-5f);
    try {
        parseScene(R"({"models": [{"primitive": "cube", "up": "x"}]})", t.dir / "s.json");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("models[0].up: 'x': expected \"y\" or \"z\""), std::string::npos) << e.what();
    }
}

// A skinned node whose mesh has no JOINTS_0 and WEIGHTS_0 is one error line naming the primitive;
// without the skins the same file loads and its animations (on a node without a mesh) are read.
TEST(GltfLoader, SkinWithoutJointsIsAnErrorAndAnimationsAreRead) {
    TempDir t;
    const std::string text =
        replaced(triangleGltf("[" + kPositions + R"(, {"bufferView": 0, "componentType": 5126, "count": 1, "type": "SCALAR", "min": [0], "max": [0]},
                                                  {"bufferView": 0, "componentType": 5126, "count": 1, "type": "VEC3"}])",
                              kViews, 42,
                              R"("skins": [{"joints": [3]}], "animations": [
                                  {"channels": [{"sampler": 0, "target": {"node": 3, "path": "translation"}}], "samplers": [{"input": 1, "output": 2}]},
                                  {"channels": [{"sampler": 0, "target": {"node": 3, "path": "scale"}}], "samplers": [{"input": 1, "output": 2}]}],)"),
                 R"("nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}])",
                 R"("nodes": [{"mesh": 0, "skin": 0}, {"mesh": 0, "skin": 0}, {"mesh": 0, "skin": 0}, {}], "scenes": [{"nodes": [0, 1, 2, 3]}])");
    const auto skinned = t.write("skinned.gltf", text);
    EXPECT_EQ(loadError(skinned), skinned.string() + ": meshes[0].primitives[0].attributes: has no JOINTS_0 and no WEIGHTS_0, but its node "
                                                     "has skins[0] (a skinned primitive needs both)");
    MeshLoadReport report;
    std::string unskinned = text;
    for (size_t at; (at = unskinned.find(R"(, "skin": 0)")) != std::string::npos;) unskinned.erase(at, std::string(R"(, "skin": 0)").size());
    const GltfContent g = loadGltf(t.write("unskinned.gltf", unskinned), &report);
    EXPECT_EQ(g.mesh.indices.size(), 9u);
    for (const std::string& w : report.warnings) EXPECT_EQ(w.find("animation"), std::string::npos) << w;
    ASSERT_TRUE(g.animation);
    EXPECT_EQ(g.animation->clips.size(), 2u);
}
