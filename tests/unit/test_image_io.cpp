// Image I/O: exact round trips, atomic writes, clean errors on bad files, and the shared HDR maps.
#include <gtest/gtest.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <functional>
#include <iterator>
#include <cmath>
#include <fstream>
#include <limits>
#include <string>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/io/image_io.hpp"

using namespace lp;
namespace fs = std::filesystem;

namespace {

// A fresh empty folder per test, removed afterwards.
class ImageIo : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = fs::temp_directory_path() /
              ("lightpass-image-" + std::to_string(getpid()) + "-" + info->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }

    std::vector<fs::path> filesIn(const fs::path& d) const {
        std::vector<fs::path> out;
        for (const auto& e : fs::recursive_directory_iterator(d)) out.push_back(e.path());
        return out;
    }
    fs::path dir;
};

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

void writeBytes(const fs::path& p, const std::string& bytes) {
    std::ofstream f(p, std::ios::binary);
    f << bytes;
}

ImageF solid(int w, int h, float v) {
    ImageF img{w, h, std::vector<float>(size_t(w) * h * 4, v)};
    for (size_t i = 3; i < img.rgba.size(); i += 4) img.rgba[i] = 1.0f;
    return img;
}

// Writes an EXR directly with OpenEXR, for layouts writeExr never produces: `values` holds
// names.size() floats a texel, in the order of `names`.
void writeExrChannels(const fs::path& p, const Imath::Box2i& display, const Imath::Box2i& data,
                      const std::vector<std::string>& names, const std::vector<float>& values) {
    Imf::Header header(display, data);
    const int w = data.max.x - data.min.x + 1;
    const size_t n = names.size();
    Imf::FrameBuffer fb;
    for (size_t c = 0; c < n; ++c) {
        header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
        fb.insert(names[c], Imf::Slice::Make(Imf::FLOAT, values.data() + c, data, n * sizeof(float), size_t(w) * n * sizeof(float)));
    }
    Imf::OutputFile file(p.c_str(), header);
    file.setFrameBuffer(fb);
    file.writePixels(data.max.y - data.min.y + 1);
}

void writeRgbExr(const fs::path& p, const Imath::Box2i& display, const Imath::Box2i& data, const std::vector<float>& rgb) {
    writeExrChannels(p, display, data, {"R", "G", "B"}, rgb);
}

}  // namespace

TEST_F(ImageIo, PngRoundTripIsExact) {
    Image8 img{7, 5, {}};
    for (int i = 0; i < 7 * 5 * 4; ++i) img.rgba.push_back(uint8_t(i * 37 + 11));
    const fs::path p = dir / "round.png";
    writePng(p, img);
    Image8 back = loadImage8(p);
    EXPECT_EQ(back.width, 7);
    EXPECT_EQ(back.height, 5);
    EXPECT_EQ(back.rgba, img.rgba);
    EXPECT_EQ(filesIn(dir), std::vector<fs::path>{p});  // the temporary was renamed, not left behind
}

TEST_F(ImageIo, ExrRoundTripIsExactInFloat32) {
    ImageF img{5, 3, {}};
    const float values[] = {0.0f, 1e-7f, 0.1f, 1.0f / 3.0f, 1.0f, 65504.0f, 65505.0f, 86528.5f, 1e30f};
    for (int i = 0; i < 5 * 3 * 4; ++i) img.rgba.push_back(values[i % 9]);
    const fs::path p = dir / "round.exr";
    writeExr(p, img);
    const int warnings = warningCount();
    ImageF back = loadHdrImage(p);
    EXPECT_EQ(warningCount(), warnings);
    EXPECT_EQ(back.width, 5);
    EXPECT_EQ(back.height, 3);
    EXPECT_EQ(back.rgba, img.rgba);  // bit-exact: float32 + ZIP is lossless
}

TEST_F(ImageIo, WriteIntoMissingFolderThrowsAndLeavesNothing) {
    const fs::path png = dir / "missing" / "out.png", exr = dir / "missing" / "out.exr";
    std::string e1 = errorOf([&] { writePng(png, makeCheckerImage(4, 2)); });
    std::string e2 = errorOf([&] { writeExr(exr, solid(4, 4, 0.5f)); });
    EXPECT_NE(e1.find(png.string()), std::string::npos) << e1;
    EXPECT_NE(e2.find(exr.string()), std::string::npos) << e2;
    EXPECT_TRUE(filesIn(dir).empty());
}

TEST_F(ImageIo, FailedWriterRemovesTemporaryAndKeepsOldFile) {
    const fs::path p = dir / "keep.txt";
    writeBytes(p, "old");
    std::string e = errorOf([&] {
        writeFileAtomically(p, [](const fs::path& tmp) {
            writeBytes(tmp, "half-written");
            throw std::runtime_error("disk full");
        });
    });
    EXPECT_EQ(e, p.string() + ": cannot write: disk full");
    EXPECT_EQ(filesIn(dir), std::vector<fs::path>{p});
    std::ifstream f(p);
    std::string content((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    EXPECT_EQ(content, "old");
}

TEST_F(ImageIo, WrongPixelCountIsRejected) {
    Image8 bad{4, 4, std::vector<uint8_t>(10)};
    std::string e = errorOf([&] { writePng(dir / "bad.png", bad); });
    EXPECT_NE(e.find("bad.png"), std::string::npos) << e;
    EXPECT_TRUE(filesIn(dir).empty());
}

TEST_F(ImageIo, MissingAndCorruptPngThrowNamingTheFile) {
    const fs::path missing = dir / "nope.png", corrupt = dir / "corrupt.png";
    EXPECT_EQ(errorOf([&] { loadImage8(missing); }), missing.string() + ": file not found");
    writeBytes(corrupt, std::string("\x89PNG\r\n\x1a\n", 8) + "this is not a PNG chunk stream");
    std::string e = errorOf([&] { loadImage8(corrupt); });
    EXPECT_EQ(e.rfind(corrupt.string() + ": ", 0), 0u) << e;
}

TEST_F(ImageIo, TruncatedAndGarbageExrThrowNamingTheFile) {
    // A noisy image so the compressed pixel data is large enough to cut in the middle.
    ImageF img{64, 64, {}};
    for (int i = 0; i < 64 * 64 * 4; ++i) img.rgba.push_back(float((i * 7919) % 1000) / 7.0f);
    const fs::path good = dir / "good.exr", cut = dir / "cut.exr", garbage = dir / "garbage.exr";
    writeExr(good, img);
    std::ifstream in(good, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (size_t keep : {bytes.size() / 2, size_t(20)}) {  // cut in the pixels, and in the header
        writeBytes(cut, bytes.substr(0, keep));
        std::string e = errorOf([&] { loadHdrImage(cut); });
        EXPECT_EQ(e.rfind(cut.string() + ": ", 0), 0u) << "kept " << keep << " bytes: " << e;
    }
    writeBytes(garbage, std::string(4096, '\x5a'));
    std::string e = errorOf([&] { loadHdrImage(garbage); });
    EXPECT_EQ(e.rfind(garbage.string() + ": ", 0), 0u) << e;
}

TEST_F(ImageIo, GarbageHdrAndUnknownExtensionThrowNamingTheFile) {
    const fs::path hdr = dir / "garbage.hdr", png = dir / "fake.hdr", tif = dir / "map.tif";
    writeBytes(hdr, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y banana +X 12\n\x01\x02\x03");
    std::string e = errorOf([&] { loadHdrImage(hdr); });
    EXPECT_EQ(e.rfind(hdr.string() + ": ", 0), 0u) << e;
    writePng(png, makeCheckerImage(4, 2));  // a PNG is not a Radiance file, whatever its name
    e = errorOf([&] { loadHdrImage(png); });
    EXPECT_EQ(e, png.string() + ": not a Radiance HDR file");
    writeBytes(tif, "II*\0");
    e = errorOf([&] { loadHdrImage(tif); });
    EXPECT_EQ(e.rfind(tif.string() + ": unsupported", 0), 0u) << e;
    EXPECT_EQ(errorOf([&] { loadHdrImage(dir / "none.exr"); }), (dir / "none.exr").string() + ": file not found");
}

TEST_F(ImageIo, MissingTextureGivesCheckerAndOneWarning) {
    const int warnings = warningCount();
    Image8 img = loadTextureOrChecker(dir / "missing.png");
    EXPECT_EQ(warningCount(), warnings + 1);
    Image8 checker = makeCheckerImage();
    EXPECT_EQ(img.width, checker.width);
    EXPECT_EQ(img.rgba, checker.rgba);
}

TEST(ImageChecker, IsMagentaAndBlackCells) {
    Image8 img = makeCheckerImage(64, 8);  // 8-pixel cells
    ASSERT_EQ(img.width, 64);
    ASSERT_EQ(img.rgba.size(), 64u * 64u * 4u);
    auto px = [&](int x, int y) {
        const uint8_t* p = &img.rgba[size_t(y * 64 + x) * 4];
        return std::vector<uint8_t>(p, p + 4);
    };
    const std::vector<uint8_t> magenta{255, 0, 255, 255}, black{0, 0, 0, 255};
    EXPECT_EQ(px(0, 0), magenta);
    EXPECT_EQ(px(7, 7), magenta);
    EXPECT_EQ(px(8, 0), black);
    EXPECT_EQ(px(0, 8), black);
    EXPECT_EQ(px(8, 8), magenta);
    EXPECT_EQ(px(63, 63), magenta);
}

TEST_F(ImageIo, ExrNanNegativeAndInfAreReplacedWithOneWarning) {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    ImageF img{2, 2, {nan, -1.0f, inf, 1.0f,  //
                      5.0f, 0.5f, -inf, 1.0f,  //
                      inf, 2.0f, nan, 1.0f,    //
                      0.25f, 0.0f, -0.004f, 1.0f}};
    const fs::path p = dir / "bad_values.exr";
    writeExr(p, img);
    const int warnings = warningCount();
    ImageF back = loadHdrImage(p);
    EXPECT_EQ(warningCount(), warnings + 1);
    const std::vector<float> expected{0.0f, 0.0f, 5.0f, 1.0f,  //
                                      5.0f, 0.5f, 0.0f, 1.0f,  //
                                      5.0f, 2.0f, 0.0f, 1.0f,  //
                                      0.25f, 0.0f, 0.0f, 1.0f};
    EXPECT_EQ(back.rgba, expected);

    // No positive finite value to borrow: +Inf becomes 65504 (the largest half).
    ImageF allInf{1, 1, {inf, inf, 0.0f, 1.0f}};
    writeExr(p, allInf);
    EXPECT_EQ(loadHdrImage(p).rgba, (std::vector<float>{65504.0f, 65504.0f, 0.0f, 1.0f}));
}

// A luminance image is grey; a multi-layer file without bare R, G, B is read from its rendered
// layer ("Combined", "beauty"), else the first with R, G, B (each value from its own channel, not a
// neighbour's); no colour at all is an error.
TEST_F(ImageIo, ExrLuminanceIsGreyAndLayersAreReadByName) {
    const Imath::Box2i box({0, 0}, {1, 0});
    const fs::path y = dir / "y.exr";
    writeExrChannels(y, box, box, {"Y"}, {0.25f, 3.0f});
    EXPECT_EQ(loadHdrImage(y).rgba, (std::vector<float>{0.25f, 0.25f, 0.25f, 1, 3, 3, 3, 1}));
    const fs::path layered = dir / "layers.exr";
    writeExrChannels(layered, box, box, {"Albedo.B", "Albedo.G", "Albedo.R", "Combined.A", "Combined.B", "Combined.G", "Combined.R", "Depth.Z"},
                     {9, 9, 9, 0.5f, 3, 2, 1, 7, 9, 9, 9, 0.25f, 6, 5, 4, 7});
    EXPECT_EQ(loadHdrImage(layered).rgba, (std::vector<float>{1, 2, 3, 0.5f, 4, 5, 6, 0.25f})) << "the rendered layer, not the albedo pass";
    writeExrChannels(layered, box, box, {"Albedo.B", "Albedo.G", "Albedo.R", "Normal.B", "Normal.G", "Normal.R"}, {3, 2, 1, 9, 9, 9, 6, 5, 4, 9, 9, 9});
    EXPECT_EQ(loadHdrImage(layered).rgba, (std::vector<float>{1, 2, 3, 1, 4, 5, 6, 1})) << "no rendered layer: the first";
    const fs::path depth = dir / "depth.exr";
    writeExrChannels(depth, box, box, {"Z"}, {1, 2});
    EXPECT_EQ(errorOf([&] { loadHdrImage(depth); }), depth.string() + ": no R, G, B or Y channel, and no layer with R, G and B");
}

TEST_F(ImageIo, ExrDataWindowIsPlacedInDisplayWindowAndAlphaDefaultsToOne) {
    // Display 6x4 at (10,20); data 2x2 at (13,21) holding RGB only.
    const Imath::Box2i display({10, 20}, {15, 23}), data({13, 21}, {14, 22});
    const std::vector<float> rgb{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
    const fs::path p = dir / "window.exr";
    writeRgbExr(p, display, data, rgb);
    ImageF img = loadHdrImage(p);
    ASSERT_EQ(img.width, 6);
    ASSERT_EQ(img.height, 4);
    auto px = [&](int x, int y) {
        const float* p = &img.rgba[size_t(y * 6 + x) * 4];
        return std::vector<float>(p, p + 4);
    };
    EXPECT_EQ(px(3, 1), (std::vector<float>{1, 2, 3, 1}));
    EXPECT_EQ(px(4, 1), (std::vector<float>{4, 5, 6, 1}));
    EXPECT_EQ(px(3, 2), (std::vector<float>{7, 8, 9, 1}));
    EXPECT_EQ(px(4, 2), (std::vector<float>{10, 11, 12, 1}));
    EXPECT_EQ(px(0, 0), (std::vector<float>{0, 0, 0, 0}));  // outside the data window: all channels 0
    EXPECT_EQ(px(5, 3), (std::vector<float>{0, 0, 0, 0}));

    // A data window larger than the display window (overscan) is cropped, not overrun.
    const Imath::Box2i small({0, 0}, {1, 0}), big({-1, -1}, {2, 1});
    std::vector<float> rgbBig(4 * 3 * 3);
    for (size_t i = 0; i < rgbBig.size(); ++i) rgbBig[i] = float(i);
    writeRgbExr(p, small, big, rgbBig);
    img = loadHdrImage(p);
    ASSERT_EQ(img.width, 2);
    ASSERT_EQ(img.height, 1);
    EXPECT_EQ(img.rgba, (std::vector<float>{15, 16, 17, 1, 18, 19, 20, 1}));  // row y=0 of data, x=0..1
}

// ---- shared assets ----

namespace {
const fs::path kAssets = LIGHTPASS_SHARED_ASSETS;

float maxComponent(const ImageF& img) {
    float m = 0.0f;
    for (size_t i = 0; i < img.rgba.size(); ++i)
        if (i % 4 != 3) m = std::max(m, img.rgba[i]);
    return m;
}
}  // namespace

TEST(ImageAssets, EveryHdrMapLoadsFiniteAndNonNegative) {
    int loaded = 0;
    for (const char* sub : {"hdri-polyhaven-1k", "hdri-blender-studiolights"}) {
        const fs::path folder = kAssets / sub;
        if (!fs::is_directory(folder)) GTEST_SKIP() << folder << " is not there (shared assets absent)";
        for (const auto& entry : fs::recursive_directory_iterator(folder)) {
            const std::string ext = entry.path().extension().string();
            if (ext != ".hdr" && ext != ".exr") continue;
            SCOPED_TRACE(entry.path().string());
            ImageF img = loadHdrImage(entry.path());
            EXPECT_EQ(img.width, 1024);
            EXPECT_EQ(img.height, 512);
            ASSERT_EQ(img.rgba.size(), 1024u * 512u * 4u);
            size_t bad = 0;
            for (float v : img.rgba) bad += !(std::isfinite(v) && v >= 0.0f);
            EXPECT_EQ(bad, 0u);
            ++loaded;
        }
    }
    EXPECT_GE(loaded, 17);  // 4 .hdr + quarry .exr + 8 DWAB + 4 zip/ copies
}

TEST(ImageAssets, QuarrySunSurvivesInHdrAndFloatExr) {
    const fs::path hdr = kAssets / "hdri-polyhaven-1k/quarry_01_1k.hdr";
    const fs::path exr = kAssets / "hdri-polyhaven-1k/quarry_01_1k_float_zip.exr";
    if (!fs::exists(hdr) || !fs::exists(exr)) GTEST_SKIP() << "quarry_01 maps not in " << kAssets;
    ImageF a = loadHdrImage(hdr), b = loadHdrImage(exr);
    EXPECT_GE(maxComponent(a), 80000.0f);
    EXPECT_GE(maxComponent(b), 80000.0f);
    EXPECT_EQ(a.rgba, b.rgba);  // the EXR was made losslessly from the RGBE data
}

TEST(ImageAssets, DwabOriginalsMatchTheirZipCopies) {
    const fs::path folder = kAssets / "hdri-blender-studiolights";
    if (!fs::is_directory(folder / "zip")) GTEST_SKIP() << folder / "zip" << " is not there (shared assets absent)";
    for (const char* name : {"city", "courtyard", "night", "sunrise"}) {
        SCOPED_TRACE(name);
        const int warnings = warningCount();
        ImageF dwab = loadHdrImage(folder / (std::string(name) + ".exr"));
        EXPECT_EQ(warningCount(), warnings + 1);  // one warning for the file's DWAB negatives
        ImageF zip = loadHdrImage(folder / "zip" / (std::string(name) + "_float_zip.exr"));
        ASSERT_EQ(dwab.rgba.size(), zip.rgba.size());
        // Tolerance 1e-5 * max(1, |v|): the zip copies hold the decoded DWAB pixels (OpenEXR 3.1.5 matches
        // them bit for bit), so only another decoder's rounding may differ; a wrong channel order or row
        // flip would be off by far more.
        size_t off = 0;
        for (size_t i = 0; i < dwab.rgba.size(); ++i)
            off += std::abs(dwab.rgba[i] - zip.rgba[i]) > 1e-5f * std::max(1.0f, std::abs(zip.rgba[i]));
        EXPECT_EQ(off, 0u);
    }
}

// Headers that claim far more texels than their file could hold: the decoders allocated (and
// zero-filled) what the header said before noticing the data was missing, a gigabyte and seconds
// for an 18-byte TGA or a 51-byte Radiance file. Refused before decoding, naming the file; an image
// of 0x0 texels (a Radiance header "-Y 0 +X 0" decoded "successfully") is an error too.
TEST_F(ImageIo, HeaderClaimingMoreThanTheFileHoldsIsRefusedBeforeDecoding) {
    auto expectOneLine = [&](const fs::path& p, const std::function<void()>& load, const std::string& fragment) {
        const std::string err = errorOf(load);
        EXPECT_EQ(err.rfind(p.string() + ": ", 0), 0u) << err;
        EXPECT_NE(err.find(fragment), std::string::npos) << err;
        EXPECT_EQ(err.find('\n'), std::string::npos) << err;
    };
    // Uncompressed 32-bit TGA, 16384x16384, no pixel data.
    const fs::path tga = dir / "huge.tga";
    std::string header(18, '\0');
    header[2] = 2;
    header[12] = header[14] = 0;
    header[13] = header[15] = char(0x40);  // 16384, little-endian
    header[16] = 32;
    writeBytes(tga, header);
    const auto start = std::chrono::steady_clock::now();
    expectOneLine(tga, [&] { loadImage8(tga); }, "claims 16384x16384 texels (1024 MiB decoded) from a 18-byte file");
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 0.5);
    // The same through the texture path: the checker, not a gigabyte.
    EXPECT_EQ(loadTextureOrChecker(tga).width, makeCheckerImage().width);
    const fs::path hdr = dir / "huge.hdr";
    writeBytes(hdr, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8192 +X 8192\n");
    expectOneLine(hdr, [&] { loadHdrImage(hdr); }, "claims 8192x8192 texels");
    const fs::path empty = dir / "empty.hdr";
    writeBytes(empty, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 0 +X 0\n");
    expectOneLine(empty, [&] { loadHdrImage(empty); }, "has no pixels (0x0)");
    // Large but plausible: a 4097x4096 PNG of one colour (64 MiB decoded, ~1000 times its file) still loads.
    const fs::path big = dir / "big.png";
    writePng(big, Image8{4097, 4096, std::vector<uint8_t>(size_t(4097) * 4096 * 4, 200)});
    EXPECT_EQ(loadImage8(big).width, 4097);
}
