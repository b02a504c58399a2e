#include "engine/io/image_io.hpp"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <stb_image.h>
#include <stb_image_write.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <memory>
#include <sstream>
#include <string>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"

namespace fs = std::filesystem;

namespace lp {
namespace {

const char* const kChannels[4] = {"R", "G", "B", "A"};

[[noreturn]] void fail(const fs::path& path, const std::string& what) { throw Error(path.string() + ": " + what); }

// Checked up front so a missing file reads "file not found", not a decoder's "can't fopen".
void requireFile(const fs::path& path) {
    std::error_code ec;
    if (fs::is_regular_file(path, ec)) return;
    fail(path, fs::exists(path, ec) ? "not a regular file" : "file not found");
}

const char* stbReason() {
    const char* r = stbi_failure_reason();
    return r ? r : "unreadable image";
}

void requireSize(const fs::path& path, int width, int height, size_t values) {
    if (width <= 0 || height <= 0) fail(path, "cannot write an empty image");
    if (values != size_t(width) * size_t(height) * 4)
        fail(path, "pixel buffer holds " + std::to_string(values) + " values, expected " + std::to_string(width) +
                       "x" + std::to_string(height) + "x4");
}

ImageF loadRadiance(const fs::path& path) {
    // stbi_loadf would also accept an LDR file (converting it with a guessed gamma); a .hdr must be Radiance.
    if (!stbi_is_hdr(path.c_str())) fail(path, "not a Radiance HDR file");
    int w = 0, h = 0, n = 0;
    std::unique_ptr<float, void (*)(void*)> px(stbi_loadf(path.c_str(), &w, &h, &n, 4), stbi_image_free);
    if (!px) fail(path, stbReason());
    ImageF img{w, h, {}};
    img.rgba.assign(px.get(), px.get() + size_t(w) * h * 4);  // stb sets alpha to 1
    return img;
}

// Width/height of an EXR window; a corrupt header must not turn into a huge allocation.
std::pair<int, int> windowSize(const Imath::Box2i& b) {
    const int64_t w = int64_t(b.max.x) - b.min.x + 1, h = int64_t(b.max.y) - b.min.y + 1;
    if (w <= 0 || h <= 0 || w * h > (int64_t(1) << 28))
        throw Error("implausible image size " + std::to_string(w) + "x" + std::to_string(h));
    return {int(w), int(h)};
}

ImageF loadExr(const fs::path& path) {
    try {
        // The general InputFile converts every channel type and compression (DWAB, PIZ, ...) to float32;
        // RgbaInputFile would go through half and turn a sun above 65504 into +Inf.
        Imf::InputFile file(path.c_str());
        const Imf::Header& header = file.header();
        const Imf::ChannelList& channels = header.channels();
        if (!channels.findChannel("R") && !channels.findChannel("G") && !channels.findChannel("B"))
            throw Error("no R, G or B channel");
        const Imath::Box2i data = header.dataWindow(), display = header.displayWindow();
        const auto [dataW, dataH] = windowSize(data);
        const auto [dispW, dispH] = windowSize(display);

        std::vector<float> pixels(size_t(dataW) * dataH * 4);
        Imf::FrameBuffer fb;
        for (int c = 0; c < 4; ++c)  // absent channels are filled: RGB with 0, A with 1
            fb.insert(kChannels[c], Imf::Slice::Make(Imf::FLOAT, pixels.data() + c, data, 4 * sizeof(float),
                                                     size_t(dataW) * 4 * sizeof(float), 1, 1, c == 3 ? 1.0 : 0.0));
        file.setFrameBuffer(fb);
        file.readPixels(data.min.y, data.max.y);

        ImageF img{dispW, dispH, {}};
        if (data == display) {
            img.rgba = std::move(pixels);
            return img;
        }
        // The display window is the image; OpenEXR defines everything outside the data window as 0.
        img.rgba.assign(size_t(dispW) * dispH * 4, 0.0f);
        const int x0 = std::max(data.min.x, display.min.x), x1 = std::min(data.max.x, display.max.x);
        const int y0 = std::max(data.min.y, display.min.y), y1 = std::min(data.max.y, display.max.y);
        for (int y = y0; y <= y1 && x0 <= x1; ++y)
            std::copy_n(&pixels[(size_t(y - data.min.y) * dataW + (x0 - data.min.x)) * 4], size_t(x1 - x0 + 1) * 4,
                        &img.rgba[(size_t(y - display.min.y) * dispW + (x0 - display.min.x)) * 4]);
        return img;
    } catch (const std::exception& e) {  // Iex::BaseExc, lp::Error, std::bad_alloc
        fail(path, e.what());
    }
}

// Later passes take logs, square roots and CDFs of these values: make every texel finite and >= 0.
void sanitize(const fs::path& path, ImageF& img) {
    size_t negative = 0, nan = 0, inf = 0;
    float maxFinite = 0.0f;  // over RGB: alpha is coverage, not a brightness to borrow
    for (size_t i = 0; i < img.rgba.size(); ++i) {
        const float v = img.rgba[i];
        if (std::isnan(v)) ++nan;
        else if (v < 0.0f) ++negative;  // includes -Inf
        else if (std::isinf(v)) ++inf;
        else if (i % 4 != 3) maxFinite = std::max(maxFinite, v);
    }
    if (negative + nan + inf == 0) return;
    const float infValue = maxFinite > 0.0f ? maxFinite : 65504.0f;  // none to borrow: the largest half
    for (float& v : img.rgba) {
        if (std::isnan(v) || v < 0.0f) v = 0.0f;
        else if (std::isinf(v)) v = infValue;
    }
    std::ostringstream msg;
    msg << path.string() << ": replaced " << negative << " negative, " << nan << " NaN and " << inf
        << " +Inf texel components (negative/NaN -> 0";
    if (inf) msg << ", +Inf -> " << infValue;
    msg << ")";
    logWarn(msg.str());
}

}  // namespace

Image8 loadImage8(const fs::path& path) {
    requireFile(path);
    int w = 0, h = 0, n = 0;
    std::unique_ptr<stbi_uc, void (*)(void*)> px(stbi_load(path.c_str(), &w, &h, &n, 4), stbi_image_free);
    if (!px) fail(path, stbReason());
    Image8 img{w, h, {}};
    img.rgba.assign(px.get(), px.get() + size_t(w) * h * 4);
    return img;
}

Image8 makeCheckerImage(int size, int cells) {
    size = std::max(size, 1);
    cells = std::clamp(cells, 1, size);
    Image8 img{size, size, std::vector<uint8_t>(size_t(size) * size * 4)};
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const bool magenta = (x * cells / size + y * cells / size) % 2 == 0;
            uint8_t* p = &img.rgba[(size_t(y) * size + x) * 4];
            p[0] = p[2] = magenta ? 255 : 0;
            p[1] = 0;
            p[3] = 255;
        }
    return img;
}

Image8 loadTextureOrChecker(const fs::path& path) {
    try {
        return loadImage8(path);
    } catch (const Error& e) {
        logWarn(std::string(e.what()) + "; using a checker texture");
        return makeCheckerImage();
    }
}

ImageF loadHdrImage(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext != ".hdr" && ext != ".exr") fail(path, "unsupported HDR image type '" + ext + "' (expected .hdr or .exr)");
    requireFile(path);
    ImageF img = ext == ".hdr" ? loadRadiance(path) : loadExr(path);
    sanitize(path, img);
    return img;
}

void writeFileAtomically(const fs::path& path, const std::function<void(const fs::path& tmp)>& writer) {
    // Same folder as the target, so the rename stays on one file system and is atomic.
    const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) fail(path, "folder " + folder.string() + " does not exist");
    fs::path tmp = path;
    tmp += ".tmp-" + std::to_string(getpid());
    try {
        writer(tmp);
        if (!fs::exists(tmp, ec)) throw Error("nothing was written");
        fs::rename(tmp, path, ec);
        if (ec) throw Error(ec.message());
    } catch (const std::exception& e) {
        fs::remove(tmp, ec);
        fail(path, std::string("cannot write: ") + e.what());
    } catch (...) {
        fs::remove(tmp, ec);
        throw;
    }
}

void writePng(const fs::path& path, const Image8& img) {
    requireSize(path, img.width, img.height, img.rgba.size());
    writeFileAtomically(path, [&](const fs::path& tmp) {
        if (!stbi_write_png(tmp.c_str(), img.width, img.height, 4, img.rgba.data(), img.width * 4))
            throw Error("PNG encoder failed");
    });
}

void writeExr(const fs::path& path, const ImageF& img) {
    requireSize(path, img.width, img.height, img.rgba.size());
    writeFileAtomically(path, [&](const fs::path& tmp) {
        Imf::Header header(img.width, img.height);
        header.compression() = Imf::ZIP_COMPRESSION;
        Imf::FrameBuffer fb;
        for (int c = 0; c < 4; ++c) {
            header.channels().insert(kChannels[c], Imf::Channel(Imf::FLOAT));
            fb.insert(kChannels[c],
                      Imf::Slice::Make(Imf::FLOAT, img.rgba.data() + c, Imath::V2i(0, 0), img.width, img.height,
                                       4 * sizeof(float), size_t(img.width) * 4 * sizeof(float)));
        }
        Imf::OutputFile file(tmp.c_str(), header);  // closed (line offsets written) before the rename
        file.setFrameBuffer(fb);
        file.writePixels(img.height);
    });
}

}  // namespace lp
