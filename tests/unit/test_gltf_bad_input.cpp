// Bad glTF (docs/bad-input.md): JSON errors with file:line:column and a depth limit before any
// parser recursion, GLB errors naming the chunk, its offset and the lengths, user text quoted, sparse
// accessors read per the specification, repaired values warned once per kind, iterative node walks
// under a 1 MiB stack, images that fall back to the checker, and temporaries removed on signals.
#include <gtest/gtest.h>

#include <pthread.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/io/gltf_container.hpp"
#include "engine/io/gltf_loader.hpp"
#include "tests/unit/gltf_test_files.hpp"
#include "engine/io/image_io.hpp"
#include "engine/io/json_text.hpp"
#include "engine/io/temporary_files.hpp"

using namespace lp;
namespace fs = std::filesystem;
using nlohmann::json;

using lp::test::TempDir;
using lp::test::loadError;
using lp::test::base64;
using lp::test::bytesOf;
using lp::test::Doc;

namespace {

// A GLB of `jsonText` and `bin` chunks, padded as the spec says.
std::string glb(std::string jsonText, std::string bin) {
    jsonText.append((4 - jsonText.size() % 4) % 4, ' ');
    bin.append((4 - bin.size() % 4) % 4, '\0');
    std::string body = bytesOf<uint32_t>({uint32_t(jsonText.size()), 0x4E4F534Au}) + jsonText;
    if (!bin.empty()) body += bytesOf<uint32_t>({uint32_t(bin.size()), 0x004E4942u}) + bin;
    return "glTF" + bytesOf<uint32_t>({2u, uint32_t(12 + body.size())}) + body;
}

}  // namespace

// One helper quotes user text everywhere: control characters (C0, DEL, C1) and bytes that are not
// UTF-8 as \xNN, valid UTF-8 kept, cut after N characters with the length said.
TEST(UserText, QuotedEscapedAndCut) {
    EXPECT_EQ(quoteUserText("abc"), "'abc'");
    EXPECT_EQ(quoteUserText("\x1b[2J"), "'\\x1B[2J'");
    EXPECT_EQ(quoteUserText("caf\xc3\xa9"), "'caf\xc3\xa9'");                // UTF-8 kept
    EXPECT_EQ(quoteUserText("caf\xe9"), "'caf\\xE9'");                       // Latin-1 is not UTF-8
    EXPECT_EQ(quoteUserText("a\xc2\x9b" "b"), "'a\\xC2\\x9Bb'");             // C1 CSI
    EXPECT_EQ(quoteUserText("\xed\xa0\x80"), "'\\xED\\xA0\\x80'");           // a surrogate
    EXPECT_EQ(quoteUserText(std::string(100, 'x'), 10), "'xxxxxxxxxx...' (100 characters)");
    EXPECT_EQ(quoteUserText(std::string(10, 'x'), 10), "'xxxxxxxxxx'");
    const std::string line = oneLineMessage("a\nb\rc\x1b" + std::string(2000, 'z'), 20);
    EXPECT_EQ(line.substr(0, 9), "a b c\\x1B");
    EXPECT_NE(line.find("(cut: 2006 characters)"), std::string::npos);
    EXPECT_LT(line.size(), 80u);
    EXPECT_EQ(shownPath("/a/b.png"), "/a/b.png");
    EXPECT_EQ(shownPath("/a/\x1b[31m.png"), "'/a/\\x1B[31m.png'");
    EXPECT_LT(shownPath(std::string(5000, 'p')).size(), 160u);
}

// JSON: the bracket that goes past the depth limit is named by line and column before any parser
// sees the text; syntax errors, numbers past a double and bytes that are not UTF-8 the same way.
TEST(JsonText, ErrorsNameLineAndColumn) {
    auto error = [](const std::string& text) {
        try {
            parseJsonText(text, "f.gltf");
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    const std::string deep = "{\"a\": 1,\n \"extras\": " + std::string(20000, '[') + std::string(20000, ']') + "}";
    EXPECT_EQ(error(deep), "f.gltf:2:139: arrays and objects nested more than 128 levels deep (the limit for a JSON document)");
    EXPECT_EQ(error("[\"[[[[\", " + std::string(127, '[') + std::string(127, ']') + "]"), "");  // brackets in strings are text
    EXPECT_EQ(error("{\"a\": 1,\n  \"b\": 1e309}"), "f.gltf:2:8: number '1e309' is beyond the range of a double (about 1.8e308)");
    EXPECT_EQ(error("{\"a\": tru\n}"), "f.gltf:1:9: invalid JSON: syntax error while parsing value - invalid literal; last read: '\"a\": tru<U+000A>'");
    EXPECT_EQ(error("{\"\xc3\xa9\": 1,}"), "f.gltf:1:9: invalid JSON: syntax error while parsing object key - unexpected '}'; expected string literal");
    EXPECT_EQ(error(""), "f.gltf:1:1: invalid JSON: syntax error while parsing value - unexpected end of input; expected '[', '{', or a literal");
    EXPECT_NE(error("{\"a\": \"\xff\"}").find("f.gltf:1:8: invalid JSON: syntax error while parsing value - invalid string: ill-formed UTF-8 byte"),
              std::string::npos);
    // An unterminated 10000-character string: its token is quoted and cut.
    const std::string cut = error("{\"a\": \"" + std::string(10000, 'q'));
    EXPECT_LT(cut.size(), 300u);
    EXPECT_NE(cut.find("(10001 characters)"), std::string::npos) << cut;
    EXPECT_EQ(textPosition("ab\ncd\xc3\xa9" "f", 7), "2:4");  // the f after an e-acute of two bytes
}

// The GLB container: every length checked, each error naming the chunk, its offset and the lengths.
TEST(GlbContainer, ErrorsNameChunkOffsetAndLengths) {
    Doc d;
    d.node({{"mesh", d.quad()}});
    json j = d.j;
    j["buffers"] = {{{"byteLength", d.bin.size()}}};
    const std::string good = glb(j.dump(), d.bin);
    const uint32_t jsonBytes = uint32_t(j.dump().size() + 3) / 4 * 4, binAt = 20 + jsonBytes;
    auto error = [](const std::string& bytes) {
        try {
            readGltfContainer(bytes, "m.glb", true);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    auto patched = [&](size_t at, uint32_t value) {
        std::string b = good;
        std::memcpy(b.data() + at, &value, 4);
        return b;
    };
    const std::string size = std::to_string(good.size());
    EXPECT_EQ(error(good), "");
    EXPECT_EQ(error(good.substr(0, 7)), "m.glb: GLB header: the file has 7 bytes, the header needs 12");
    EXPECT_EQ(error(good.substr(0, good.size() - 8)),
              "m.glb: GLB header (byte 8): length " + size + ", but the file has " + std::to_string(good.size() - 8) + " bytes (truncated)");
    EXPECT_EQ(error(patched(12, 100000)), "m.glb: chunk 0 (JSON) at byte 12: length 100000, but " + std::to_string(good.size() - 20) +
                                              " bytes follow its header (the GLB is " + size + " bytes)");
    EXPECT_EQ(error(patched(binAt, 100000)), "m.glb: chunk 1 (BIN) at byte " + std::to_string(binAt) + ": length 100000, but " +
                                                 std::to_string(good.size() - binAt - 8) + " bytes follow its header (the GLB is " + size + " bytes)");
    EXPECT_EQ(error(patched(16, 0x12345678)), "m.glb: chunk 0 at byte 12: type 'xV4\\x12' (0x12345678), but the first chunk must be JSON 'JSON' (0x4E4F534A)");
    EXPECT_EQ(error(patched(binAt, uint32_t(d.bin.size() - 2))).find("m.glb: chunk 1 (BIN) at byte " + std::to_string(binAt) + ": length "), 0u);
    EXPECT_EQ(error("GLTF" + good.substr(4)), "m.glb: not a GLB file: it starts with 'GLTF', not the magic 'glTF' (nor with JSON text)");
    // A chunk of unknown type as chunk 1 is ignored (the spec's rule); tinygltf is handed a rebuilt GLB.
    std::string unknown = good.substr(0, binAt) + bytesOf<uint32_t>({4u, 0x41525458u}) + "1234";
    std::memcpy(unknown.data() + 8, bytesOf<uint32_t>({uint32_t(unknown.size())}).data(), 4);
    const GltfSource s = readGltfContainer(unknown, "m.glb", true);
    EXPECT_TRUE(s.rebuild);
    EXPECT_EQ(s.bin, nullptr);
    // Trailing bytes: warned and ignored.
    EXPECT_EQ(readGltfContainer(good + std::string(8, '\0'), "m.glb", true).warnings.size(), 1u);
}

// Data URIs are decoded strictly: a byte that is not base64 is named with its position.
TEST(DataUri, StrictBase64) {
    EXPECT_EQ(decodeDataUri("data:application/octet-stream;base64,AAEC").bytes, std::string("\0\1\2", 3));
    EXPECT_EQ(decodeDataUri("data:image/png;base64,AAE=").bytes, std::string("\0\1", 2));
    EXPECT_EQ(decodeDataUri("data:image/png;base64,AAE").bytes, std::string("\0\1", 2));  // padding may be left out
    EXPECT_EQ(decodeDataUri("data:image/png;base64,AA%C").problem, "data URI: character 3 of its base64 data, '%', is not base64");
    EXPECT_EQ(decodeDataUri("data:image/png;base64,AAAAA").problem,
              "data URI: 5 characters of base64 data, which no whole number of bytes encodes (cut short?)");
    EXPECT_NE(decodeDataUri("data:image/png,%89PNG").problem.find("not base64-encoded"), std::string::npos);
    EXPECT_EQ(decodeDataUri("data:image/png;base64,AAAA").mediaType, "image/png");
}

// Sparse accessors (core glTF 2.0): the dense positions, or zeros without a buffer view, with the
// sparse values put in at their indices; indices past the count or out of order are errors.
TEST(GltfSparse, PositionsReadAsTheSpecSays) {
    TempDir t;
    auto sparseQuad = [](bool base, std::initializer_list<uint8_t> indices, std::initializer_list<float> values) {
        Doc d;
        json sparse = {{"count", indices.size()},
                       {"indices", {{"bufferView", d.view(bytesOf(indices))}, {"componentType", 5121}}},
                       {"values", {{"bufferView", d.view(bytesOf(values))}}}};
        json position = {{"componentType", 5126}, {"type", "VEC3"}, {"count", 4}, {"sparse", sparse}};
        if (base) position["bufferView"] = d.view(bytesOf({-1.f, -1.f, 0.f, 1.f, -1.f, 0.f, 1.f, 1.f, 0.f, -1.f, 1.f, 0.f}));
        const int p = d.accessor(position);
        const int idx = d.accessor({{"bufferView", d.view(bytesOf<uint16_t>({0, 1, 2, 0, 2, 3}))}, {"componentType", 5123},
                                    {"type", "SCALAR"}, {"count", 6}});
        d.j["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", p}}}, {"indices", idx}}}}}};
        d.node({{"mesh", 0}});
        return d;
    };
    // Corners 1 and 2 moved out to x = 3: the quad spans x in [-1, 3].
    const MeshData m = loadGltf(t.write("over_base.gltf", sparseQuad(true, {1, 2}, {3, -1, 0, 3, 1, 0}).text())).mesh;
    EXPECT_FLOAT_EQ(m.boundsMin.x, -1.0f);
    EXPECT_FLOAT_EQ(m.boundsMax.x, 3.0f);
    EXPECT_FLOAT_EQ(m.boundsMax.y, 1.0f);
    // Over zeros: corners 0, 2 and 3 given, corner 1 stays at the origin.
    const MeshData z = loadGltf(t.write("over_zeros.gltf", sparseQuad(false, {0, 2, 3}, {-1, -1, 0, 2, 1, 0, -1, 2, 0}).text())).mesh;
    bool origin = false;
    for (const Vertex& v : z.vertices) origin |= glm::length(v.position) < 1e-6f;
    EXPECT_TRUE(origin);
    EXPECT_EQ(z.indices.size(), 6u);
    EXPECT_FLOAT_EQ(z.boundsMin.x, -1.0f);
    EXPECT_FLOAT_EQ(z.boundsMax.x, 2.0f);
    EXPECT_FLOAT_EQ(z.boundsMax.y, 2.0f);
    // As a GLB too.
    Doc g = sparseQuad(true, {1, 2}, {3, -1, 0, 3, 1, 0});
    json j = g.j;
    j["buffers"] = {{{"byteLength", g.bin.size()}}};
    EXPECT_FLOAT_EQ(loadGltf(t.write("sparse.glb", glb(j.dump(), g.bin))).mesh.boundsMax.x, 3.0f);
    EXPECT_NE(loadError(t.write("past.gltf", sparseQuad(true, {1, 4}, {3, -1, 0, 3, 1, 0}).text()))
                  .find("attributes.POSITION (accessors[0]).sparse.indices: index 4 at position 1 is beyond the accessor's 4 elements"),
              std::string::npos);
    EXPECT_NE(loadError(t.write("order.gltf", sparseQuad(true, {2, 2}, {3, -1, 0, 3, 1, 0}).text()))
                  .find("sparse.indices: index 2 at position 1 does not follow 2 (sparse indices are strictly increasing)"),
              std::string::npos);
}

// Values the file gets wrong are repaired with one warning per kind naming the first place, its
// count and how many more (the normals: their triangles' normal, not an arbitrary +Y).
TEST(GltfRepairs, NormalsTexcoordsTangentsAndRotationsWarnedOncePerKind) {
    TempDir t;
    const float nan = std::nanf(""), inf = INFINITY;
    Doc d;
    for (int i = 0; i < 3; ++i) {
        json a;
        a["NORMAL"] = d.floats({nan, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 1}, "VEC3", 4);
        a["TEXCOORD_0"] = d.floats({inf, 0, 1, 0, 1, 1, 0, 1}, "VEC2", 4);
        a["TANGENT"] = d.floats({1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 0.5f, nan, 0, 0, 1}, "VEC4", 4);
        d.node({{"mesh", d.quad(a)}, {"translation", {3 * i, 0, 0}}, {"rotation", {0, 0, 0, 0}}});
    }
    MeshLoadReport report;
    const int warningsBefore = warningCount();
    const MeshData m = loadGltf(t.write("repairs.gltf", d.text()), &report).mesh;
    EXPECT_EQ(warningCount() - warningsBefore, 4);
    ASSERT_EQ(report.warnings.size(), 4u);
    auto has = [&](const std::string& s) {
        for (const std::string& w : report.warnings)
            if (w.find(s) != std::string::npos) return true;
        return false;
    };
    EXPECT_TRUE(has("repairs.gltf: meshes[0].primitives[0].attributes.NORMAL (accessors[0]): 2 normals not finite or zero-length (and 4 more "
                    "in 2 other accessors); each replaced by the normal of its triangles"));
    EXPECT_TRUE(has("meshes[0].primitives[0].attributes.TEXCOORD_0 (accessors[1]): 1 texture coordinates not finite (and 2 more in 2 other "
                    "accessors); read as 0"));
    EXPECT_TRUE(has("meshes[0].primitives[0].attributes.TANGENT (accessors[2]): 2 tangents not finite, zero-length or with w other than 1 "
                    "or -1 (and 4 more in 2 other accessors); the primitive's tangents generated instead (MikkTSpace)"));
    EXPECT_TRUE(has("nodes[0].rotation: 1 rotations of length 0 (not a rotation) (and 2 more in 2 other nodes); no rotation used"));
    for (const Vertex& v : m.vertices) {
        EXPECT_NEAR(v.normal.z, 1.0f, 1e-6f);  // the quad's own normal
        EXPECT_TRUE(std::isfinite(v.uv.x));
        EXPECT_NEAR(std::abs(v.tangent.w), 1.0f, 1e-6f);
        EXPECT_NEAR(glm::length(glm::vec3(v.tangent)), 1.0f, 1e-4f);
    }
    EXPECT_FLOAT_EQ(m.boundsMax.x, 7.0f);  // no rotation: the third quad spans x 5..7
}

// Integer texture coordinates need `normalized` (the spec's attribute table) unless
// KHR_mesh_quantization allows raw ones: read as normalised with a warning, not as 0..255.
TEST(GltfRepairs, UnnormalizedByteTexcoordsAreReadNormalized) {
    TempDir t;
    for (const bool normalized : {false, true}) {
        Doc d;
        const int uv = d.accessor({{"bufferView", d.view(bytesOf<uint8_t>({0, 255, 255, 255, 255, 0, 0, 0}))}, {"componentType", 5121},
                                   {"type", "VEC2"}, {"count", 4}, {"normalized", normalized}});
        d.node({{"mesh", d.quad({{"TEXCOORD_0", uv}})}});
        MeshLoadReport report;
        const MeshData m = loadGltf(t.write("uv.gltf", d.text()), &report).mesh;
        float most = 0.0f;
        for (const Vertex& v : m.vertices) most = std::max({most, v.uv.x, v.uv.y});
        EXPECT_FLOAT_EQ(most, 1.0f);
        ASSERT_EQ(report.warnings.size(), normalized ? 0u : 1u);
        if (!normalized)
            EXPECT_NE(report.warnings[0].find("TEXCOORD_0 (accessors[0]): integer texture coordinates without \"normalized\": true"),
                      std::string::npos);
    }
}

// A rotation of denormal length keeps its direction (normalised after scaling), with a warning; one
// of length 0 is no rotation. 90 degrees about +Y takes the quad's +X corner to -Z.
TEST(GltfRepairs, DenormalRotationKeepsItsDirection) {
    TempDir t;
    Doc d;
    d.node({{"mesh", d.quad()}, {"rotation", {0, 1e-310, 0, 1e-310}}});
    MeshLoadReport report;
    const MeshData m = loadGltf(t.write("denormal.gltf", d.text()), &report).mesh;
    EXPECT_NEAR(m.boundsMin.z, -1.0f, 1e-5f);
    EXPECT_NEAR(m.boundsMax.x, 0.0f, 1e-5f);
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_NE(report.warnings[0].find("nodes[0].rotation: 1 rotations not of unit length; normalized"), std::string::npos);
}

// Camera fields outside what they mean: a yfov of pi or more (45 degrees stands in), a tiny one
// (clamped to 0.5 degrees), zfar not beyond znear (no zfar), each with a warning.
TEST(GltfRepairs, CameraFieldsOutsideTheirRange) {
    TempDir t;
    auto camera = [&](json perspective) {
        Doc d;
        d.node({{"mesh", d.quad()}});
        d.j["cameras"] = {{{"type", "perspective"}, {"perspective", perspective}}};
        d.node({{"camera", 0}, {"translation", {0, 0, 3}}});
        MeshLoadReport report;
        const GltfContent g = loadGltf(t.write("camera.gltf", d.text()), &report);
        EXPECT_EQ(g.cameras.size(), 1u);
        EXPECT_EQ(report.warnings.size(), 1u);
        return std::make_pair(g.cameras.at(0), report.warnings.empty() ? std::string() : report.warnings[0]);
    };
    auto [wide, wideWarning] = camera({{"yfov", 4}, {"znear", 0.1}});
    EXPECT_FLOAT_EQ(wide.fovYDegrees, 45.0f);
    EXPECT_NE(wideWarning.find("cameras[0].perspective.yfov: 4 rad is not below pi"), std::string::npos);
    auto [narrow, narrowWarning] = camera({{"yfov", 1e-9}, {"znear", 0.1}});
    EXPECT_FLOAT_EQ(narrow.fovYDegrees, 0.5f);
    auto [inverted, invertedWarning] = camera({{"yfov", 0.8}, {"znear", 1}, {"zfar", 0.1}});
    EXPECT_FLOAT_EQ(inverted.nearPlane, 1.0f);
    EXPECT_FLOAT_EQ(inverted.farPlane, 1e5f);
    EXPECT_NE(invertedWarning.find("cameras[0].perspective.zfar: 0.1 is not beyond znear 1; read as no zfar"), std::string::npos);
}

// A file that fails prints its one error alone: the warnings found before are not printed.
TEST(GltfMessages, NoWarningsBeforeTheError) {
    TempDir t;
    Doc d;
    d.node({{"mesh", d.quad()}, {"rotation", {0, 0, 0, 0}}});
    d.j["materials"] = {{{"pbrMetallicRoughness", {{"roughnessFactor", 5}}}}};  // a schema warning
    d.j["nodes"][0]["children"] = {1};
    d.node({{"mesh", 0}, {"translation", {1e39, 0, 0}}}, false);  // a transform past a float: an error
    const int warningsBefore = warningCount();
    EXPECT_NE(loadError(t.write("late.gltf", d.text())).find("nodes[1]: transform is not finite"), std::string::npos);
    EXPECT_EQ(warningCount(), warningsBefore);
}

// A 1023-level node chain (within the 1024-level limit) loads on a thread of 1 MiB stack: the walks
// of the node tree keep their own stacks.
TEST(GltfStructure, NodeChain1023DeepLoadsUnderA1MiBStack) {
    TempDir t;
    Doc d;
    const int mesh = d.quad();
    d.node({{"children", {1}}});
    for (int i = 1; i < 1023; ++i) d.node(i + 1 < 1023 ? json{{"children", {i + 1}}, {"translation", {0.001, 0, 0}}} : json{{"mesh", mesh}}, false);
    const fs::path path = t.write("chain.gltf", d.text());
    struct Job {
        fs::path path;
        size_t triangles = 0;
        std::string error;
    } job{path};
    pthread_attr_t attr;
    pthread_attr_init(&attr);
    pthread_attr_setstacksize(&attr, 1 << 20);
    pthread_t thread;
    ASSERT_EQ(pthread_create(&thread, &attr,
                             [](void* p) -> void* {
                                 auto& j = *static_cast<Job*>(p);
                                 try {
                                     j.triangles = loadGltf(j.path).mesh.indices.size() / 3;
                                 } catch (const std::exception& e) {
                                     j.error = e.what();
                                 }
                                 return nullptr;
                             },
                             &job),
              0);
    pthread_join(thread, nullptr);
    pthread_attr_destroy(&attr);
    EXPECT_EQ(job.error, "");
    EXPECT_EQ(job.triangles, 2u);
    // One level more than the limit is an error naming the node.
    d.j["nodes"][1022].erase("mesh");
    d.j["nodes"][1022]["children"] = {1023};
    d.node({{"mesh", mesh}}, false);
    d.node({{"mesh", mesh}}, false);
    d.j["nodes"][1023]["children"] = {1024};
    EXPECT_NE(loadError(t.write("chain_1025.gltf", d.text())).find("nodes[1024]: is more than 1024 levels deep"), std::string::npos);
}

// An image whose data URI does not decode is the checker, with its reason; the file loads.
TEST(GltfImages, BadDataUriImageFallsBackToTheChecker) {
    TempDir t;
    Doc d;
    d.node({{"mesh", d.quad()}});
    d.j["meshes"][0]["primitives"][0]["material"] = 0;
    d.j["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    d.j["textures"] = {{{"source", 0}}};
    d.j["images"] = {{{"uri", "data:image/png;base64,iVBO!!!!"}}};
    const MeshData m = loadGltf(t.write("image.gltf", d.text())).mesh;
    ASSERT_EQ(m.materials.size(), 1u);
    EXPECT_EQ(m.materials[0].diffuseMap.problem, "data URI: character 5 of its base64 data, '!', is not base64");
    EXPECT_FALSE(m.materials[0].diffuseMap.empty());
    // As a GLB too (tinygltf, which refuses such a file, is handed a rebuilt one).
    json j = d.j;
    j["buffers"] = {{{"byteLength", d.bin.size()}}};
    EXPECT_EQ(loadGltf(t.write("image.glb", glb(j.dump(), d.bin))).mesh.materials[0].diffuseMap.problem.substr(0, 9), "data URI:");
}

namespace {
uint32_t crc(const std::string& bytes) {
    uint32_t c = 0xFFFFFFFFu;
    for (unsigned char b : bytes) {
        c ^= b;
        for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    }
    return ~c;
}
std::string pngChunk(const std::string& type, const std::string& data) {
    auto be = [](uint32_t v) { return std::string{char(v >> 24), char(v >> 16 & 255), char(v >> 8 & 255), char(v & 255)}; };
    return be(uint32_t(data.size())) + type + data + be(crc(type + data));
}
}  // namespace

// A texture's size is checked from its header before the decoder allocates: 8193x8193 (256.1 MiB as
// RGBA8) is refused at once, whatever its data.
TEST(TextureLimit, CheckedFromTheHeaderBeforeDecoding) {
    auto be = [](uint32_t v) { return std::string{char(v >> 24), char(v >> 16 & 255), char(v >> 8 & 255), char(v & 255)}; };
    const std::string ihdr = be(8193) + be(8193) + std::string("\x08\x06\x00\x00\x00", 5);
    const std::string png = std::string("\x89PNG\r\n\x1a\n", 8) + pngChunk("IHDR", ihdr) + pngChunk("IDAT", std::string(20000, '\x55')) +
                            pngChunk("IEND", "");
    try {
        decodeImage8(png, "big.png");
        FAIL() << "decoded";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()),
                  "big.png: 8193x8193 texels (256.1 MiB decoded) are more than one texture may take (256 MiB: 8192x8192); refused before decoding");
    }
}

// SIGINT, SIGTERM and SIGHUP remove the temporaries registered at that moment and end the process by
// that signal; past the file-size limit the write fails and the temporary is removed.
TEST(TemporaryFiles, RemovedWhenASignalEndsTheProcess) {
    TempDir t;
    for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
        const fs::path out = t.dir / ("out" + std::to_string(sig) + ".png");
        const pid_t child = fork();
        ASSERT_GE(child, 0);
        if (child == 0) {
            signal(sig, SIG_DFL);
            installTemporaryFileCleanup();
            OutputFiles outputs;
            outputs.add(out, "partial");  // the temporary exists now
            raise(sig);
            _exit(0);  // not reached
        }
        int status = 0;
        waitpid(child, &status, 0);
        EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << "signal " << sig << ", status " << status;
        for (const auto& f : fs::directory_iterator(t.dir)) ADD_FAILURE() << "left behind: " << f.path();
    }
    // RLIMIT_FSIZE: SIGXFSZ (by default: the process killed on the spot) is ignored, so the write
    // fails with EFBIG and the error path removes the temporary.
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        signal(SIGXFSZ, SIG_DFL);
        installTemporaryFileCleanup();
        const rlimit limit{100, 100};
        setrlimit(RLIMIT_FSIZE, &limit);
        try {
            OutputFiles outputs;
            outputs.add(t.dir / "big.png", std::string(4096, 'x'));
        } catch (const Error& e) {
            _exit(std::string(e.what()).find("big.png: cannot write: File too large") != std::string::npos ? 3 : 4);
        }
        _exit(5);
    }
    int status = 0;
    waitpid(child, &status, 0);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 3) << status;
    for (const auto& f : fs::directory_iterator(t.dir)) ADD_FAILURE() << "left behind: " << f.path();
    EXPECT_EQ(registeredTemporaryFiles(), 0u);
}
