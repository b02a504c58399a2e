// Bad input, parser by parser (docs/bad-input.md): special files, numbers tinyobjloader would read as
// 0, indices that would wrap, degenerate triangles judged by their own size, a UTF-8 BOM, truncated
// and corrupt images, an EXR display window around almost nothing, scene values out of range,
// repeated warnings and all-or-nothing outputs. The CLI side is tests/bad_input/.
#include <gtest/gtest.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/gl/limits.hpp"
#include "engine/io/file_check.hpp"
#include "engine/io/gltf_loader.hpp"
#include "engine/io/image_io.hpp"
#include "engine/io/obj_loader.hpp"
#include "engine/io/obj_text.hpp"
#include "engine/scene/scene_loader.hpp"

using namespace lp;
namespace fs = std::filesystem;

namespace {

template <typename F>
std::string errorOf(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A fresh empty folder per test, removed afterwards.
class BadInput : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("lightpass-bad-" + std::to_string(getpid()) + "-" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }
    fs::path write(const std::string& name, const std::string& bytes) const {
        std::ofstream(dir / name, std::ios::binary) << bytes;
        return dir / name;
    }
    std::string read(const fs::path& p) const {
        std::ifstream in(p, std::ios::binary);
        return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    }
    fs::path dir;
};

}  // namespace

// ---- 1. special files ---------------------------------------------------------------------------------

TEST_F(BadInput, FifoDeviceFolderAndHugeFileAreRefusedWithoutReading) {
    const fs::path fifo = dir / "pipe.obj";
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
    const auto t0 = std::chrono::steady_clock::now();  // no writer: a read would block forever
    EXPECT_EQ(errorOf([&] { loadObj(fifo); }), fifo.string() + ": is a FIFO, not a regular file");
    EXPECT_EQ(errorOf([&] { loadScene(fifo); }), fifo.string() + ": is a FIFO, not a regular file");
    EXPECT_EQ(errorOf([&] { loadImage8(fifo); }), fifo.string() + ": is a FIFO, not a regular file");
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
    EXPECT_EQ(errorOf([&] { loadObj("/dev/zero"); }), "/dev/zero: is a character device, not a regular file");
    EXPECT_EQ(errorOf([&] { loadScene(dir); }), dir.string() + ": is a folder, not a scene file");
    EXPECT_EQ(errorOf([&] { loadObj(dir); }), dir.string() + ": is a folder, not an OBJ file");
    EXPECT_EQ(errorOf([&] { loadObj(dir / "none.obj"); }), (dir / "none.obj").string() + ": file not found");
    const fs::path big = write("big.obj", std::string(2000, '#'));
    EXPECT_EQ(errorOf([&] { readFileChecked(big, 1000, "an OBJ file"); }),
              big.string() + ": file is 2000 bytes, over the 1000-byte limit");
}

TEST_F(BadInput, MtllibNamingAFifoIsAnErrorNamingBoth) {
    ASSERT_EQ(mkfifo((dir / "m.mtl").c_str(), 0600), 0);
    const fs::path obj = write("a.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_EQ(errorOf([&] { loadObj(obj); }), obj.string() + ": mtllib " + (dir / "m.mtl").string() + ": is a FIFO, not a regular file");
}

// ---- 4. numbers and indices ----------------------------------------------------------------------------

TEST(ObjText, UnparsableNumbersAndWrappingIndicesNameFileAndLine) {
    auto scanError = [](const std::string& text) { return errorOf([&] { scanObjText(text, "m.obj"); }); };
    EXPECT_EQ(scanError("v 0 0 0\nv a b c\n"), "m.obj:2: v: 'a' is not a number");
    EXPECT_EQ(scanError("v 0 0 0\nv 1 2\n"), "m.obj:2: v needs 3 numbers, got 2");
    EXPECT_EQ(scanError("vn 0 0 1x\n"), "m.obj:1: vn: '1x' is not a number");
    EXPECT_EQ(scanError("v 0 0 0\nf 1 2 4294967296\n"), "m.obj:2: index 4294967296 is out of range");
    EXPECT_EQ(scanError("f 1/1/-99999999999 2 3\n"), "m.obj:1: index -99999999999 is out of range");
    EXPECT_EQ(scanError("f 1 2 x\n"), "m.obj:1: 'x' is not a vertex index");
    EXPECT_EQ(scanError("f 1 0 2\n"), "m.obj:1: index 0 (OBJ indices start at 1)");
    EXPECT_EQ(scanError("v 1 2 3 # comment a b\r\nf 1//2 -1 3/4\n"), "");  // comments, CRLF, all corner forms
    // Control bytes in a bad token are shown escaped: raw, an ESC sequence or a backspace garbles the line.
    EXPECT_EQ(scanError(std::string("v 0 1\x08") + "2 3\n"), "m.obj:1: v: '1\\x082' is not a number");
    EXPECT_EQ(scanError("f 1 2 \x1b[2J3\n"), "m.obj:1: '\\x1B[2J3' is not a vertex index");
    EXPECT_EQ(scanError("v 0 0 " + std::string(100, 'x') + "\n"), "m.obj:1: v: '" + std::string(64, 'x') + "...' (100 characters) is not a number");
}

// Triangulating a polygon takes the parser time quadratic in its corners: one face of 90000 corners
// ran for minutes. Faces over 4 corners are bounded in total (sum of squared corners <= 2^25).
TEST(ObjText, HugePolygonsAreAnErrorNotAHang) {
    auto face = [](size_t corners) {
        std::string f = "f";
        for (size_t i = 0; i < corners; ++i) f += " " + std::to_string(i % 3 + 1);
        return f + "\n";
    };
    const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    const std::string err = errorOf([&] { scanObjText(vertices + face(90000), "m.obj"); });
    EXPECT_EQ(err, "m.obj:4: a face of 90000 corners; polygons over 4 corners add up to more than 33554432 squared corners "
                   "(their triangulation takes quadratic time)");
    // Many mid-sized polygons add up: 3000 faces of 128 corners, the line where the sum passes the bound.
    std::string many = vertices;
    for (int i = 0; i < 3000; ++i) many += face(128);
    EXPECT_NE(errorOf([&] { scanObjText(many, "m.obj"); }).find("m.obj:2052: a face of 128 corners"), std::string::npos);
    // Ordinary n-gons pass.
    EXPECT_EQ(errorOf([&] { scanObjText(vertices + face(4) + face(64) + face(1000), "m.obj"); }), "");
    // End to end: the loader stops at once with the same line.
    const auto start = std::chrono::steady_clock::now();
    const fs::path p = fs::temp_directory_path() / ("lp_polygon_" + std::to_string(::getpid()) + ".obj");
    std::ofstream(p) << vertices + face(90000);
    EXPECT_NE(errorOf([&] { loadObj(p); }).find(p.string() + ":4: a face of 90000 corners"), std::string::npos);
    fs::remove(p);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 2.0);
}

TEST(ObjText, NanAndOverflowPositionsAreKeptAsNonFiniteAndCounted) {
    ObjTextScan scan = scanObjText("v 0 0 0\nv nan 7 7\nv 1e39 0 0\nvt inf 0\n", "m.obj");
    ASSERT_EQ(scan.positions.size(), 9u);
    EXPECT_TRUE(std::isnan(scan.positions[3]));
    EXPECT_TRUE(std::isinf(scan.positions[6]));
    EXPECT_EQ(scan.nonFinitePositions, 2u);
    EXPECT_EQ(scan.firstNonFinitePositionLine, 2u);
    EXPECT_EQ(scan.nonFiniteAttributes, 1u);
    EXPECT_EQ(scan.firstNonFiniteAttributeLine, 4u);
}

TEST(ObjText, BadMtlNumbersFallBackToTheDefaultWithALineNumber) {
    std::vector<std::string> warnings;
    const std::string out = sanitizeMtlText("newmtl m\nKd nan nan nan\nNs abc\nd 1e999\nKs 0.5 0.5 0.5\n", "m.mtl", warnings);
    ASSERT_EQ(warnings.size(), 3u);
    EXPECT_EQ(warnings[0], "m.mtl:2: Kd: 'nan' is not a finite number; using the default 0.8 0.8 0.8");
    EXPECT_EQ(warnings[1], "m.mtl:3: Ns: 'abc' is not a number; using the default 32.000000");
    EXPECT_EQ(warnings[2], "m.mtl:4: d: '1e999' is not a finite number; line ignored");
    EXPECT_EQ(out, "newmtl m\nKd 0.8 0.8 0.8\nNs 32.000000\nKs 0.5 0.5 0.5\n");
}

// Reflectances above 1 gave back more light than arrives; a negative one subtracted light; a single
// value read as red. Each is clamped (or made grey) in place, with a warning naming file and line.
TEST(ObjText, MtlValuesOutsideTheirPhysicalRangeAreClampedWithALineNumber) {
    std::vector<std::string> warnings;
    const std::string out = sanitizeMtlText(
        "newmtl m\nKd 5 0.5 -1\nKs 0.25\nKe -3 2 100\nNs 20000\nd 1.5\nTr -0.5\nKd 0.2 0.3 0.4\nKa -1 2 3\n", "m.mtl", warnings);
    ASSERT_EQ(warnings.size(), 5u);
    EXPECT_EQ(warnings[0], "m.mtl:2: Kd 5 0.5 -1: outside [0, 1]; clamped to 1 0.5 0");
    EXPECT_EQ(warnings[1], "m.mtl:4: Ke -3 2 100: below 0; clamped to 0 2 100");
    EXPECT_EQ(warnings[2], "m.mtl:5: Ns 20000: outside [0, 10000]; clamped to 10000");
    EXPECT_EQ(warnings[3], "m.mtl:6: d 1.5: outside [0, 1]; clamped to 1");
    EXPECT_EQ(warnings[4], "m.mtl:7: Tr -0.5: outside [0, 1]; clamped to 0");
    EXPECT_EQ(out, "newmtl m\nKd 1 0.5 0\nKs 0.25 0.25 0.25\nKe 0 2 100\nNs 10000\nd 1\nTr 0\nKd 0.2 0.3 0.4\nKa -1 2 3\n");
}

TEST_F(BadInput, MtlKdAboveOneAndGreyShorthandReachTheMaterial) {
    write("m.mtl", "newmtl bright\nKd 3 3 3\nnewmtl grey\nKd 0.5\n");
    const fs::path obj = write("a.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl bright\nf 1 2 3\nusemtl grey\nf 1 3 2\n");
    MeshLoadReport report;
    const MeshData mesh = loadObj(obj, &report);
    int found = 0;
    for (const Material& m : mesh.materials) {
        if (m.name == "bright") {
            EXPECT_EQ(m.diffuse, glm::vec3(1.0f));
            ++found;
        }
        if (m.name == "grey") {
            EXPECT_EQ(m.diffuse, glm::vec3(0.5f)) << "tinyobjloader alone reads 'Kd 0.5' as (0.5, 0, 0)";
            ++found;
        }
    }
    EXPECT_EQ(found, 2);
    bool warned = false;
    for (const auto& w : report.warnings) warned |= w.find("m.mtl:2: Kd 3 3 3: outside [0, 1]; clamped to 1 1 1") != std::string::npos;
    EXPECT_TRUE(warned);
}

TEST_F(BadInput, ObjNanVertexDropsItsTriangleAndNanKdUsesTheDefault) {
    write("m.mtl", "newmtl red\nKd nan nan nan\n");
    const fs::path obj = write("a.obj", "mtllib m.mtl\nusemtl red\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 7 7\nf 1 2 3\nf 1 2 4\n");
    MeshLoadReport report;
    MeshData mesh = loadObj(obj, &report);
    EXPECT_EQ(mesh.indices.size(), 3u);
    EXPECT_EQ(report.droppedNonFinite, 1u) << "tinyobjloader alone reads nan as 0 and keeps the triangle";
    ASSERT_FALSE(mesh.materials.empty());
    EXPECT_EQ(mesh.materials[0].diffuse, glm::vec3(0.8f));
}

TEST_F(BadInput, ObjIndexTooLargeForAnIntIsAnErrorNotTheLastVertex) {
    const fs::path obj = write("a.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4294967299\n");
    EXPECT_EQ(errorOf([&] { loadObj(obj); }), obj.string() + ":4: index 4294967299 is out of range");
}

// ---- 5. degenerate triangles by their own size -----------------------------------------------------------

TEST_F(BadInput, MillimetreCubeBesideKilometrePlaneKeepsEveryTriangle) {
    std::string text;
    for (int i = 0; i < 8; ++i)
        text += "v " + std::to_string((i & 1) ? 0.0025 : -0.0025) + " " + std::to_string((i & 2) ? 0.0025 : -0.0025) + " " +
                std::to_string((i & 4) ? 0.0025 : -0.0025) + "\n";
    text += "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
    text += "v -10000 -1 -10000\nv 10000 -1 -10000\nv 10000 -1 10000\nv -10000 -1 10000\nf 9 12 11 10\n";
    MeshLoadReport report;
    MeshData mesh = loadObj(write("a.obj", text), &report);
    EXPECT_EQ(report.droppedDegenerate, 0u);
    EXPECT_EQ(mesh.indices.size(), 3u * 14u);
}

TEST_F(BadInput, QuadBesideAStrayVertexFarAwayIsKept) {
    MeshLoadReport report;
    MeshData mesh = loadObj(write("a.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 1e15 1e15 1e15\nf 1 2 3 4\n"), &report);
    EXPECT_EQ(report.droppedDegenerate, 0u);
    EXPECT_EQ(mesh.indices.size(), 6u);
}

TEST_F(BadInput, VertexBeyond1e18CountsAsInfAndIsDroppedWithItsTriangles) {
    MeshLoadReport report;
    MeshData mesh = loadObj(write("a.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1e30 0 0\nf 1 2 3\nf 1 4 3\n"), &report);
    EXPECT_EQ(mesh.indices.size(), 3u);
    EXPECT_EQ(report.droppedNonFinite, 1u);
    EXPECT_TRUE(std::isinf(scanObjText("v 1e19 0 0\n", "a.obj").positions[0]));
    EXPECT_EQ(scanObjText("v 1e18 0 0\n", "a.obj").positions[0], 1e18f);
}

TEST_F(BadInput, SliverIsStillDegenerateAtAnyScale) {
    // Bound: area / longest edge^2 below 1e-10 is a sliver, for a 1 m and a 1 km triangle alike.
    for (double scale : {1.0, 1000.0}) {
        const std::string s = std::to_string(scale), thin = std::to_string(scale * 1e-12);
        MeshLoadReport report;
        loadObj(write("a.obj", "v 0 0 0\nv " + s + " 0 0\nv 0 " + s + " 0\nv 0 0 " + thin + "\nf 1 2 3\nf 1 4 2\n"), &report);
        EXPECT_EQ(report.droppedDegenerate, 1u) << "scale " << scale;
    }
}

// ---- 6. text details -------------------------------------------------------------------------------------

TEST_F(BadInput, Utf8BomKeepsTheFirstVertex) {
    MeshLoadReport report;
    MeshData mesh = loadObj(write("a.obj", "\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), &report);
    EXPECT_EQ(mesh.indices.size(), 3u);
    EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
    EXPECT_EQ(readFileChecked(write("b.txt", "\xEF\xBB\xBFok"), 100, "a file", true), "ok");
}

TEST_F(BadInput, ModelInPlaneXConstIsFramedFaceOn) {
    Scene s = sceneForModel(write("a.obj", "v 2 -1 -1\nv 2 1 -1\nv 2 1 1\nv 2 -1 1\nf 1 2 3 4\n"));
    const glm::vec3 view = glm::normalize(s.camera.target - s.camera.position);
    EXPECT_GT(std::abs(view.x), 0.9f) << "looking along x, at the face of the plane";
}

// ---- 7. images -------------------------------------------------------------------------------------------

TEST_F(BadInput, PngWithCorruptDataOrCutShortIsRefusedWithTheReason) {
    const fs::path good = dir / "good.png";
    Image8 img{16, 16, std::vector<uint8_t>(16 * 16 * 4)};
    for (size_t i = 0; i < img.rgba.size(); ++i) img.rgba[i] = uint8_t(i * 7);
    writePng(good, img);
    std::string bytes = read(good);
    std::string corrupt = bytes;
    corrupt[bytes.find("IDAT") + 12] ^= 0x55;
    const fs::path bad = write("corrupt.png", corrupt), cut = write("cut.png", bytes.substr(0, bytes.size() / 2));
    EXPECT_TRUE(contains(errorOf([&] { loadImage8(bad); }), bad.string() + ": corrupt: CRC mismatch in chunk IDAT"));
    const std::string e = errorOf([&] { loadImage8(cut); });
    EXPECT_TRUE(contains(e, cut.string() + ": truncated: chunk IDAT")) << e;
    EXPECT_EQ(loadImage8(good).rgba, img.rgba);
    // A chunk type damaged into a CR is named escaped: raw, it garbled the one-line message.
    std::string crType = bytes;
    crType[bytes.find("IDAT") + 2] = '\r';
    const fs::path cr = write("cr_type.png", crType);
    EXPECT_EQ(errorOf([&] { loadImage8(cr); }),
              cr.string() + ": corrupt: CRC mismatch in chunk ID\\x0DT at byte " + std::to_string(bytes.find("IDAT") - 4));
}

TEST_F(BadInput, TruncatedRadianceIsRefusedNotZeroFilled) {
    std::string hdr = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8 +X 16\n";
    for (int i = 0; i < 16 * 8; ++i) hdr += std::string("\x80\x80\x80\x81", 4);
    EXPECT_EQ(loadHdrImage(write("whole.hdr", hdr)).width, 16);
    const fs::path cut = write("cut.hdr", hdr.substr(0, hdr.size() - 100));
    EXPECT_TRUE(contains(errorOf([&] { loadHdrImage(cut); }), cut.string() + ": truncated:"));
}

TEST_F(BadInput, ExrDisplayWindowFarLargerThanItsDataIsRefused) {
    const fs::path p = dir / "sparse.exr";
    {
        Imf::Header header(Imath::Box2i({0, 0}, {16383, 8191}), Imath::Box2i({0, 0}, {1, 0}));
        header.channels().insert("R", Imf::Channel(Imf::FLOAT));
        float px[2] = {1.0f, 2.0f};
        Imf::FrameBuffer fb;
        fb.insert("R", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(px), sizeof(float), 0));
        Imf::OutputFile file(p.c_str(), header);
        file.setFrameBuffer(fb);
        file.writePixels(1);
    }
    const auto t0 = std::chrono::steady_clock::now();
    const std::string e = errorOf([&] { loadHdrImage(p); });
    EXPECT_TRUE(contains(e, p.string() + ": display window 16384x8192 is ")) << e;
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 2.0);
}

TEST(Downscale, HalvesUntilItFitsAveragingBoxes) {
    ImageF img{5, 2, {}};
    for (int i = 0; i < 10; ++i)
        for (int c = 0; c < 4; ++c) img.rgba.push_back(float(i));
    ImageF half = downscaleToFit(img, 4);
    ASSERT_EQ(half.width, 2);
    ASSERT_EQ(half.height, 1);
    EXPECT_FLOAT_EQ(half.rgba[0], (0 + 1 + 5 + 6) / 4.0f);
    EXPECT_FLOAT_EQ(half.rgba[4], (2 + 3 + 4 + 7 + 8 + 9) / 6.0f);  // the odd last column joins the box
    EXPECT_EQ(downscaleToFit(img, 8).rgba, img.rgba);
}

// ---- 2. outputs all or nothing ---------------------------------------------------------------------------

TEST_F(BadInput, OutputFilesAppearOnlyOnCommit) {
    {
        OutputFiles outputs;
        outputs.add(dir / "a.txt", "a");
        outputs.addPng(dir / "b.png", makeCheckerImage(4, 2));
        // No commit: an error in between leaves nothing, not even the temporaries.
    }
    EXPECT_TRUE(fs::is_empty(dir));
    {
        OutputFiles outputs;
        outputs.add(dir / "a.txt", "a");
        EXPECT_EQ(errorOf([&] { outputs.add(dir / "missing" / "b.txt", "b"); }),
                  (dir / "missing" / "b.txt").string() + ": folder " + (dir / "missing").string() + " does not exist");
    }
    EXPECT_TRUE(fs::is_empty(dir));
    OutputFiles outputs;
    outputs.add(dir / "a.txt", "a");
    outputs.add(dir / "b.txt", "b");
    outputs.commit();
    EXPECT_EQ(read(dir / "a.txt"), "a");
    EXPECT_EQ(read(dir / "b.txt"), "b");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);
}

TEST(CheckedWrite, FullDiskIsAnError) {
    EXPECT_EQ(errorOf([] { writeBytesChecked("/dev/full", "x"); }), "No space left on device");
}

// ---- 3. GPU limits (the check itself; the CLI test drives it with LIGHTPASS_GPU_FREE_BYTES) -----------

TEST(GpuLimits, SizeOverALimitNamesTheSizeAndTheLimit) {
    gl::RenderTargetLimits limits;
    limits.maxTextureSize = 8192;
    limits.maxViewport[0] = limits.maxViewport[1] = 16384;
    limits.freeBytes = int64_t(1) << 30;
    EXPECT_EQ(errorOf([&] { gl::requireRenderSizeFits(9000, 100, 0, limits); }),
              "--size 9000x100: larger than this GPU's limit of 8192 (GL_MAX_TEXTURE_SIZE)");
    EXPECT_EQ(errorOf([&] { gl::requireRenderSizeFits(4000, 4000, size_t(2) << 30, limits); }),
              "--size 4000x4000: the frame's render targets need 2.00 GiB, more than the 1.00 GiB this GPU has free");
    EXPECT_EQ(errorOf([&] { gl::requireRenderSizeFits(8192, 8192, 1 << 20, limits); }), "");
}

// ---- 8. scene values --------------------------------------------------------------------------------------

TEST(SceneValues, OutOfRangeValuesNameFileAndField) {
    auto errorFor = [](const std::string& json) { return errorOf([&] { parseScene(json, "s.json", false); }); };
    EXPECT_EQ(errorFor(R"({"camera": {"position": [1e400, 0, 0]}})"), "s.json: invalid JSON: number overflow parsing '1e400'");
    EXPECT_EQ(errorFor(R"({"description": 42})"), "s.json: description: expected a string");
    EXPECT_EQ(errorFor(R"({"description": "fine"})"), "");
    EXPECT_EQ(errorFor(R"({"camera": {"far": 3e38}})"), "s.json: camera.far: 3e+38 is beyond the 1e+07 m maximum");
    EXPECT_EQ(errorFor(R"({"camera": {"near": 1e-30, "far": 1e30}})"), "s.json: camera.near: 1e-30 is below the 1e-06 m minimum");
    EXPECT_TRUE(contains(errorFor(R"({"camera": {"near": 1e-5, "far": 1e5}})"), "s.json: camera.far: far / near is 1e+10"));
    EXPECT_EQ(errorFor(R"({"camera": {"position": [1e30, 0, 1]}})"),
              "s.json: camera.position: 1e+30 is too far from the origin (limit +-1e+07 m)");
    EXPECT_EQ(errorFor(R"({"lights": [{"type": "point", "position": [0, 1e35, 0]}]})"),
              "s.json: lights[0].position: 1e+35 is too far from the origin (limit +-1e+07 m)");
    EXPECT_EQ(errorFor(R"({"lights": [{"type": "directional", "intensity": 1e30}]})"),
              "s.json: lights[0].intensity: 1e+30 is outside [0, 1e+09]");
    EXPECT_TRUE(contains(errorFor(R"({"models": [{"primitive": "cube", "scale": 1e30}]})"), "s.json: models[0].scale: 1e+30"));
    // Any finite range is a valid scene: the shading holds at every range (tests/gl).
    EXPECT_EQ(errorFor(R"({"lights": [{"type": "point", "range": 1e30}]})"), "");
}

TEST_F(BadInput, ModelPlacedBeyond1e18IsAnErrorNamingTheModel) {
    write("big.obj", "v 0 0 0\nv 1e18 0 0\nv 0 1e18 0\nf 1 2 3\n");
    const fs::path scene = write("s.json", R"({"models": [{"primitive": "cube"}, {"obj": "big.obj", "scale": 1e6}]})");
    EXPECT_EQ(errorOf([&] { loadScene(scene); }), scene.string() + ": models[1]: placed up to 1e+24 m from the origin, beyond the 1e+18 m limit");
}

// Every model is its own copy of its mesh: a 3 MB scene naming 100000 spheres asked for 15 GB. The
// models' vertices and indices together are bounded (2^26); 4800 spheres (14049 each) pass it.
TEST(SceneValues, ModelsAddingUpPastTheSceneLimitAreAnError) {
    std::string models;
    for (int i = 0; i < 4800; ++i) models += std::string(i ? ", " : "") + R"({"primitive": "sphere"})";
    const std::string err = errorOf([&] { parseScene("{\"models\": [" + models + "]}", "many.json"); });
    EXPECT_EQ(err, "many.json: models[4776]: the models so far add up to 67112073 vertices and indices, over the scene's limit of 67108864");
    EXPECT_EQ(parseScene(R"({"models": [{"primitive": "sphere"}, {"primitive": "sphere"}]})", "two.json").models.size(), 2u);
}

// A glTF named under "obj" was read as OBJ text and failed as "no triangles".
TEST(SceneValues, GltfNamedAsObjIsNamedAsSuch) {
    EXPECT_EQ(errorOf([&] { parseScene(R"({"models": [{"obj": "ship.glb"}]})", "s.json", false); }),
              "s.json: models[0].obj: ship.glb: is a glTF file; name it under \"gltf\"");
}

TEST(SceneValues, HugeAndTinyDirectionsBecomeFiniteUnitVectors) {
    Scene s = parseScene(R"({"camera": {"up": [0, 1e-40, 0]},
                             "lights": [{"type": "directional", "direction": [1e38, -1e38, 1e38]},
                                        {"type": "directional", "direction": [0, -1e-40, 0]}]})", "s.json", false);
    for (const auto& l : s.directionalLights) {
        EXPECT_TRUE(std::isfinite(l.direction.x) && std::isfinite(l.direction.y) && std::isfinite(l.direction.z));
        EXPECT_NEAR(glm::length(l.direction), 1.0f, 1e-6f);
    }
    EXPECT_NEAR(s.camera.up.y, 1.0f, 1e-6f);
    EXPECT_EQ(errorOf([] { parseScene(R"({"lights": [{"type": "directional", "direction": [0, 0, 0]}]})", "s.json", false); }),
              "s.json: lights[0].direction: is the zero vector");
}

// UTF-16 text failed far from its cause ("no triangles", "invalid literal"), and a NUL ended the JSON
// and OBJ parsers' input early, so whatever followed it was silently dropped.
TEST_F(BadInput, Utf16AndNulBytesInTextFilesAreNamedAsSuch) {
    auto utf16 = [](const std::string& ascii) {
        std::string out = "\xFF\xFE";
        for (char c : ascii) out += std::string(1, c) + '\0';
        return out;
    };
    const std::string scene = R"({"models": [{"primitive": "cube"}]})";
    const fs::path s16 = write("utf16.json", utf16(scene));
    EXPECT_EQ(errorOf([&] { loadScene(s16); }), s16.string() + ": is UTF-16 text (it starts with a UTF-16 byte order mark); save it as UTF-8");
    const fs::path o16 = write("utf16.obj", utf16("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
    EXPECT_TRUE(contains(errorOf([&] { loadObj(o16); }), o16.string() + ": is UTF-16 text"));
    const fs::path g16 = write("utf16.gltf", utf16(R"({"asset": {"version": "2.0"}})"));
    EXPECT_TRUE(contains(errorOf([&] { loadGltf(g16); }), g16.string() + ": is UTF-16 text"));
    // A scene with a NUL then an unknown field: the field used to be ignored.
    const fs::path nul = write("nul.json", scene + std::string(1, '\0') + R"({"unknown": 1})");
    EXPECT_EQ(errorOf([&] { loadScene(nul); }),
              nul.string() + ": byte " + std::to_string(scene.size()) + " is NUL: not UTF-8 text (UTF-16 without a byte order mark, or a binary file)");
    // UTF-16 without a byte order mark is full of NULs.
    const fs::path bare = write("bare16.obj", utf16("v 0 0 0\n").substr(2));
    EXPECT_TRUE(contains(errorOf([&] { loadObj(bare); }), bare.string() + ": byte 1 is NUL"));
    // A UTF-8 BOM is still fine.
    EXPECT_NO_THROW(loadScene(write("bom.json", "\xEF\xBB\xBF" + scene)));
}

// stb_image reads zeros past the end of a file, and its Radiance run-length decoder takes a zero count
// without advancing: the project's own sky.hdr cut at 52404 bytes looped forever. Every cut of a
// run-length file is now "truncated", at once.
TEST_F(BadInput, RunLengthRadianceCutAnywhereIsTruncatedNotAHang) {
    const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 16\n";
    std::string lines;
    for (int y = 0; y < 4; ++y) {
        lines += std::string("\x02\x02\x00\x10", 4);
        for (int c = 0; c < 4; ++c) lines += std::string(1, char(128 + 16)) + char(c == 3 ? 129 : 100);  // a run of 16
    }
    const fs::path whole = write("whole.hdr", header + lines);
    EXPECT_EQ(loadHdrImage(whole).width, 16);
    const auto start = std::chrono::steady_clock::now();
    for (size_t cut = 0; cut < lines.size(); ++cut) {
        const fs::path p = write("cut.hdr", header + lines.substr(0, cut));
        EXPECT_TRUE(contains(errorOf([&] { loadHdrImage(p); }), p.string() + ": truncated")) << cut;
    }
    std::ifstream in(fs::path(LIGHTPASS_SOURCE_DIR) / "hdr/sky.hdr", std::ios::binary);
    const std::string sky((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_GT(sky.size(), 52404u);
    const fs::path cutSky = write("sky_cut.hdr", sky.substr(0, 52404));
    EXPECT_TRUE(contains(errorOf([&] { loadHdrImage(cutSky); }), cutSky.string() + ": truncated"));
    // Headers cut or without their blank line: the line loops must end too.
    for (const std::string& bad : {std::string("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n-Y 4 +X 16\n") + lines, std::string("#?RADIANCE\nFORMAT=32-bit_rle_rgbe"),
                                   std::string("#?RADIANCE\n") + std::string(3000, 'x')}) {
        const fs::path p = write("header.hdr", bad);
        EXPECT_TRUE(contains(errorOf([&] { loadHdrImage(p); }), p.string() + ": ")) << bad.substr(0, 40);
    }
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

// A model 1e-20 m across was framed as a 0.2 mm one and rendered as an empty image without a word:
// now it loads with one warning naming the file and its size.
TEST_F(BadInput, ModelSmallerThanTheFramingLimitIsRenderedWithAWarning) {
    resetWarningCount();
    const fs::path tiny = write("tiny.obj", "v 0 0 0\nv 1e-20 0 0\nv 0 1e-20 0\nf 1 2 3\n");
    ::testing::internal::CaptureStderr();
    const Scene s = sceneForModel(tiny);
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(warningCount(), 1);
    EXPECT_TRUE(contains(err, tiny.string() + ": the models are only 1.41421e-20 m across")) << err;
    EXPECT_TRUE(std::isfinite(s.camera.nearPlane) && s.camera.nearPlane > 0.0f);
    // A millimetre model is framed on its own size, without a warning.
    resetWarningCount();
    sceneForModel(write("mm.obj", "v 0 0 0\nv 1e-3 0 0\nv 0 1e-3 0\nf 1 2 3\n"));
    EXPECT_EQ(warningCount(), 0);
}
