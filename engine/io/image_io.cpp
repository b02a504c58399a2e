#include "engine/io/image_io.hpp"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfOutputFile.h>
#include <stb_image.h>
#include <stb_image_write.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <cmath>
#include <memory>
#include <set>
#include <sstream>
#include <string>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/io/file_check.hpp"

namespace fs = std::filesystem;

namespace lp {
namespace {

const char* const kChannels[4] = {"R", "G", "B", "A"};

[[noreturn]] void fail(const fs::path& path, const std::string& what) { throw Error(shownPath(path) + ": " + what); }

// Checked up front (file_check) so a missing file reads "file not found", not a decoder's "can't fopen",
// and a FIFO or device is refused instead of read.
void requireFile(const fs::path& path) { requireRegularFile(path, kMaxImageFileBytes, "an image file"); }

// stb_image decoding from bytes in memory, through callbacks that notice when the decoder asks for data
// past the end: stb fills a truncated file with zeros and reports success.
struct StbSource {
    const std::string& bytes;
    size_t pos = 0;
    bool readPastEnd = false;
    // Past the end stb_image reads zeros, and its Radiance run-length decoder takes a zero count as
    // "no pixels" without advancing: a cut .hdr looped forever. For Radiance, newlines are handed out
    // instead: they end the header's line and token loops, and as a count (10) the run-length loop
    // advances, so the decoder finishes at once and the cut is reported as truncation.
    bool fillPastEnd = false;
};
const stbi_io_callbacks kStbCallbacks = {
    [](void* user, char* data, int size) -> int {
        auto& s = *static_cast<StbSource*>(user);
        const size_t n = std::min(size_t(std::max(size, 0)), s.bytes.size() - s.pos);
        if (n == 0 && size > 0) {
            s.readPastEnd = true;
            if (s.fillPastEnd) {
                std::memset(data, '\n', size_t(size));
                return size;
            }
        }
        std::memcpy(data, s.bytes.data() + s.pos, n);
        s.pos += n;
        return int(n);
    },
    [](void* user, int n) {
        auto& s = *static_cast<StbSource*>(user);
        const long long to = std::clamp<long long>((long long)s.pos + n, 0, (long long)s.bytes.size());
        if ((long long)s.pos + n > (long long)s.bytes.size()) s.readPastEnd = true;
        s.pos = size_t(to);
    },
    [](void* user) -> int {
        auto& s = *static_cast<StbSource*>(user);
        return s.pos >= s.bytes.size() ? 1 : 0;
    },
};

uint32_t crc32(const unsigned char* data, size_t size, uint32_t crc = 0) {
    static const std::array<uint32_t, 256> table = [] {
        std::array<uint32_t, 256> t{};
        for (uint32_t i = 0; i < 256; ++i) {
            uint32_t c = i;
            for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            t[i] = c;
        }
        return t;
    }();
    crc = ~crc;
    for (size_t i = 0; i < size; ++i) crc = table[(crc ^ data[i]) & 0xFF] ^ (crc >> 8);
    return ~crc;
}

uint32_t bigEndian32(const unsigned char* p) { return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | p[3]; }

// stb_image checks no PNG CRC and stops at a cut: walk the chunks first. Empty when the file is whole.
std::string pngDamage(const std::string& bytes) {
    const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
    size_t pos = 8;
    while (pos + 12 <= bytes.size()) {
        const uint32_t length = bigEndian32(p + pos);
        // The type as printable text: a corrupt one may hold a CR or an escape that would garble the line.
        const std::string type = printableBytes(bytes.substr(pos + 4, 4), true);
        if (length > bytes.size() - pos - 12)
            return "truncated: chunk " + type + " at byte " + std::to_string(pos) + " needs " + std::to_string(length) +
                   " bytes, the file ends " + std::to_string(bytes.size() - pos - 12 < bytes.size() ? bytes.size() - pos - 8 : 0) +
                   " bytes later";
        if (crc32(p + pos + 4, size_t(length) + 4) != bigEndian32(p + pos + 8 + length))
            return "corrupt: CRC mismatch in chunk " + type + " at byte " + std::to_string(pos);
        if (type == "IEND") return {};
        pos += size_t(length) + 12;
    }
    return "truncated: the file ends after " + std::to_string(bytes.size()) + " bytes without an IEND chunk";
}

std::string truncatedReason(const std::string& bytes) {
    return "truncated: the decoder needed more than the file's " + std::to_string(bytes.size()) + " bytes";
}

std::string stbReason() {
    const char* r = stbi_failure_reason();
    return r && *r ? std::string("unreadable image (") + r + ")" : std::string("unreadable image");
}

// Decoders allocate what the header claims before they find the data missing: an 18-byte TGA or a
// 51-byte Radiance header claiming 16384x16384 cost a gigabyte and seconds before "truncated". No
// format here expands a file more than ~33000 times (a 1-bit PNG of one colour, deflated, as RGBA8),
// so a claim beyond 65536 times the file's size (and beyond 64 MiB) is refused before decoding, as is
// an image with no pixels.
constexpr uint64_t kMaxExpansion = 65536;
constexpr uint64_t kAlwaysAllowedBytes = uint64_t(64) << 20;
// Empty when the size is plausible, else what is wrong with it.
std::string implausibleSize(int64_t width, int64_t height, uint64_t bytesPerTexel, uint64_t fileBytes) {
    if (width <= 0 || height <= 0) return "has no pixels (" + std::to_string(width) + "x" + std::to_string(height) + ")";
    const uint64_t decoded = uint64_t(width) * uint64_t(height) * bytesPerTexel;  // < 2^31 * 2^31 * 16: no overflow
    if (decoded > std::max(kAlwaysAllowedBytes, kMaxExpansion * fileBytes))
        return "claims " + std::to_string(width) + "x" + std::to_string(height) + " texels (" + std::to_string(decoded >> 20) +
               " MiB decoded) from a " + std::to_string(fileBytes) + "-byte file: truncated or corrupt (more than 65536 times the file's size is refused)";
    return {};
}
void requirePlausibleSize(const fs::path& path, int64_t width, int64_t height, uint64_t bytesPerTexel, uint64_t fileBytes) {
    const std::string problem = implausibleSize(width, height, bytesPerTexel, fileBytes);
    if (!problem.empty()) fail(path, problem);
}

// The size the header of an stb_image format claims, checked before the decoder allocates it.
void requirePlausibleStbSize(const fs::path& path, const std::string& bytes, uint64_t bytesPerTexel) {
    int w = 0, h = 0, n = 0;
    if (stbi_info_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), int(std::min<size_t>(bytes.size(), INT32_MAX)), &w, &h, &n))
        requirePlausibleSize(path, w, h, bytesPerTexel, bytes.size());
}

std::string formatMiB(uint64_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, bytes % (uint64_t(1) << 20) ? "%.1f" : "%.0f", double(bytes) / double(uint64_t(1) << 20));
    return text;
}

// A texture's size from its header against kMaxTextureBytes, before decoding.
void requireTextureWithinLimit(const fs::path& path, const std::string& bytes) {
    int w = 0, h = 0, n = 0;
    if (!stbi_info_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), int(std::min<size_t>(bytes.size(), INT32_MAX)), &w, &h, &n))
        return;  // the decoder names what is wrong
    const uint64_t decoded = uint64_t(w) * uint64_t(h) * 4;
    if (decoded > kMaxTextureBytes)
        fail(path, std::to_string(w) + "x" + std::to_string(h) + " texels (" + formatMiB(decoded) + " MiB decoded) are more than one texture may take (" +
                       formatMiB(kMaxTextureBytes) + " MiB: 8192x8192); refused before decoding");
}

void requireSize(const fs::path& path, int width, int height, size_t values) {
    if (width <= 0 || height <= 0) fail(path, "cannot write an empty image");
    if (values != size_t(width) * size_t(height) * 4)
        fail(path, "pixel buffer holds " + std::to_string(values) + " values, expected " + std::to_string(width) +
                       "x" + std::to_string(height) + "x4");
}

ImageF loadRadiance(const fs::path& path) {
    const std::string bytes = readFileChecked(path, kMaxImageFileBytes, "an image file");
    // stbi_loadf would also accept an LDR file (converting it with a guessed gamma); a .hdr must be Radiance.
    if (!stbi_is_hdr_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), int(std::min<size_t>(bytes.size(), INT32_MAX))))
        fail(path, "not a Radiance HDR file");
    requirePlausibleStbSize(path, bytes, 4 * sizeof(float));
    int w = 0, h = 0, n = 0;
    StbSource source{bytes};
    source.fillPastEnd = true;
    std::unique_ptr<float, void (*)(void*)> px(stbi_loadf_from_callbacks(&kStbCallbacks, &source, &w, &h, &n, 4),
                                               stbi_image_free);
    if (!px) fail(path, source.readPastEnd ? truncatedReason(bytes) : stbReason());
    if (source.readPastEnd) fail(path, truncatedReason(bytes));
    requirePlausibleSize(path, w, h, 4 * sizeof(float), bytes.size());
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
        // Which channels make R, G, B and A: the bare ones; else a luminance image's Y (grey); else
        // the first layer holding R, G and B (a renderer's multi-layer file), named in a warning.
        std::string names[4] = {"R", "G", "B", "A"};
        if (!channels.findChannel("R") && !channels.findChannel("G") && !channels.findChannel("B")) {
            if (channels.findChannel("RY") || channels.findChannel("BY"))
                throw Error("a luminance-chroma (Y, RY, BY) image is not supported; write it as RGB");
            if (channels.findChannel("Y")) {
                names[0] = names[1] = names[2] = "Y";
            } else {
                std::set<std::string> layers;
                channels.layers(layers);
                // The rendered image's layer where one is named so (Blender's "Combined", "beauty"),
                // else the first: data passes (albedo, normals) hold R, G, B too.
                auto isBeauty = [](std::string l) {
                    l = l.substr(l.rfind('.') == std::string::npos ? 0 : l.rfind('.') + 1);
                    std::transform(l.begin(), l.end(), l.begin(), [](unsigned char c) { return char(std::tolower(c)); });
                    return l == "combined" || l == "beauty" || l == "rgba" || l == "rgb";
                };
                std::string chosen, all;
                for (const std::string& l : layers) {
                    if (!channels.findChannel(l + ".R") || !channels.findChannel(l + ".G") || !channels.findChannel(l + ".B")) continue;
                    if (chosen.empty() || (isBeauty(l) && !isBeauty(chosen))) chosen = l;
                    all += (all.empty() ? "" : ", ") + l;
                }
                if (chosen.empty()) throw Error("no R, G, B or Y channel, and no layer with R, G and B");
                for (std::string& n : names) n = chosen + "." + n;
                logWarn(shownPath(path) + ": no R, G, B channels; read layer " + quoteUserText(chosen) + " (layers with R, G and B: " + all + ")");
            }
        }
        const Imath::Box2i data = header.dataWindow(), display = header.displayWindow();
        const auto [dataW, dataH] = windowSize(data);
        const auto [dispW, dispH] = windowSize(display);
        // The zeros around the data cost memory too: a 400-byte file can claim a 16384x8192 display
        // window around 2x1 texels. Padding is allowed up to 16x the data (or 16M texels in all).
        const int64_t dataArea = int64_t(dataW) * dataH, displayArea = int64_t(dispW) * dispH;
        if (displayArea > std::max<int64_t>(16 * dataArea, int64_t(1) << 24))
            throw Error("display window " + std::to_string(dispW) + "x" + std::to_string(dispH) + " is " +
                        std::to_string(displayArea / std::max<int64_t>(dataArea, 1)) + " times the " + std::to_string(dataW) +
                        "x" + std::to_string(dataH) + " data window (more than 16x padding over 16M texels is refused)");

        std::vector<float> pixels(size_t(dataW) * dataH * 4);
        Imf::FrameBuffer fb;
        const bool grey = names[0] == names[1];  // Y into R, copied to G and B after the read
        for (int c = 0; c < 4; ++c)  // absent channels are filled: RGB with 0, A with 1
            if (!grey || c == 0 || c == 3)
                fb.insert(names[c], Imf::Slice::Make(Imf::FLOAT, pixels.data() + c, data, 4 * sizeof(float),
                                                     size_t(dataW) * 4 * sizeof(float), 1, 1, c == 3 ? 1.0 : 0.0));
        file.setFrameBuffer(fb);
        file.readPixels(data.min.y, data.max.y);
        if (grey)
            for (size_t i = 0; i < pixels.size(); i += 4) pixels[i + 1] = pixels[i + 2] = pixels[i];

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
    return decodeImage8(readFileChecked(path, kMaxImageFileBytes, "an image file"), path);
}

Image8 decodeImage8(const std::string& bytes, const fs::path& path) {
    if (bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0) {
        const std::string damage = pngDamage(bytes);
        if (!damage.empty()) fail(path, damage);
    }
    requirePlausibleStbSize(path, bytes, 4);
    requireTextureWithinLimit(path, bytes);
    int w = 0, h = 0, n = 0;
    StbSource source{bytes};
    std::unique_ptr<stbi_uc, void (*)(void*)> px(stbi_load_from_callbacks(&kStbCallbacks, &source, &w, &h, &n, 4),
                                                 stbi_image_free);
    if (!px) fail(path, source.readPastEnd ? truncatedReason(bytes) : stbReason());
    if (source.readPastEnd) fail(path, truncatedReason(bytes));
    requirePlausibleSize(path, w, h, 4, bytes.size());
    Image8 img{w, h, {}};
    img.rgba.assign(px.get(), px.get() + size_t(w) * h * 4);
    return img;
}

namespace {
// 2x2 box halving until both sides fit (an odd last column/row is averaged into its neighbour's box).
template <typename Image, typename Accumulate>
Image halveUntilFits(Image img, int maxSize, Accumulate toTexel) {
    maxSize = std::max(maxSize, 1);
    while (img.width > maxSize || img.height > maxSize) {
        const int w = std::max(img.width / 2, 1), h = std::max(img.height / 2, 1);
        Image half{w, h, {}};
        half.rgba.resize(size_t(w) * h * 4);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                for (int c = 0; c < 4; ++c) {
                    double sum = 0.0;
                    int n = 0;
                    for (int sy = 2 * y; sy < std::min(2 * y + 2, img.height) + (y == h - 1 && img.height > 2 * h ? 1 : 0); ++sy)
                        for (int sx = 2 * x; sx < std::min(2 * x + 2, img.width) + (x == w - 1 && img.width > 2 * w ? 1 : 0); ++sx) {
                            sum += double(img.rgba[(size_t(sy) * img.width + sx) * 4 + c]);
                            ++n;
                        }
                    half.rgba[(size_t(y) * w + x) * 4 + c] = toTexel(sum / std::max(n, 1));
                }
        img = std::move(half);
    }
    return img;
}
}  // namespace

Image8 downscaleToFit(const Image8& image, int maxSize) {
    return halveUntilFits(image, maxSize, [](double v) { return uint8_t(std::clamp(v + 0.5, 0.0, 255.0)); });
}

ImageF downscaleToFit(const ImageF& image, int maxSize) {
    return halveUntilFits(image, maxSize, [](double v) { return float(v); });
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

Image8 decodeTextureOrChecker(const std::string& bytes, const fs::path& label) {
    try {
        return decodeImage8(bytes, label);
    } catch (const Error& e) {
        logWarn(std::string(e.what()) + "; using a checker texture");
        return makeCheckerImage();
    }
}

ImageF loadHdrImage(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext != ".hdr" && ext != ".exr") fail(path, "unsupported HDR image type " + quoteUserText(ext) + " (expected .hdr or .exr)");
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
    const TemporaryFileGuard guard(tmp);
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

void writeBytesChecked(const fs::path& path, const std::string& bytes) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) throw Error(std::strerror(errno));
    size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const int err = n < 0 ? errno : EIO;
            ::close(fd);
            throw Error(std::strerror(err));
        }
        done += size_t(n);
    }
    // A full disk may only show at fsync or close (delayed allocation): both are checked.
    if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) {
        const int err = errno;
        ::close(fd);
        throw Error(std::strerror(err));
    }
    if (::close(fd) != 0) throw Error(std::strerror(errno));
}

std::string encodePng(const Image8& img) {
    std::string bytes;
    const int ok = stbi_write_png_to_func(
        [](void* context, void* data, int size) { static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size)); },
        &bytes, img.width, img.height, 4, img.rgba.data(), img.width * 4);
    if (!ok || bytes.empty()) throw Error("PNG encoder failed");
    return bytes;
}

namespace {
// OpenEXR writes through an OStream; this one keeps the file in memory, so writing it to disk is one
// checked write (OpenEXR's own file stream cannot report a full disk at close).
class MemoryOStream : public Imf::OStream {
public:
    MemoryOStream() : Imf::OStream("memory") {}
    void write(const char c[], int n) override {
        if (pos_ + size_t(n) > bytes.size()) bytes.resize(pos_ + size_t(n));
        std::memcpy(bytes.data() + pos_, c, size_t(n));
        pos_ += size_t(n);
    }
    uint64_t tellp() override { return pos_; }
    void seekp(uint64_t pos) override { pos_ = size_t(pos); }
    std::string bytes;

private:
    size_t pos_ = 0;
};
}  // namespace

std::string encodeExr(const ImageF& img) {
    MemoryOStream stream;
    {
        Imf::Header header(img.width, img.height);
        header.compression() = Imf::ZIP_COMPRESSION;
        Imf::FrameBuffer fb;
        for (int c = 0; c < 4; ++c) {
            header.channels().insert(kChannels[c], Imf::Channel(Imf::FLOAT));
            fb.insert(kChannels[c],
                      Imf::Slice::Make(Imf::FLOAT, img.rgba.data() + c, Imath::V2i(0, 0), img.width, img.height,
                                       4 * sizeof(float), size_t(img.width) * 4 * sizeof(float)));
        }
        Imf::OutputFile file(stream, header);  // the line offset table is written when it closes
        file.setFrameBuffer(fb);
        file.writePixels(img.height);
    }
    return std::move(stream.bytes);
}

void writePng(const fs::path& path, const Image8& img) {
    requireSize(path, img.width, img.height, img.rgba.size());
    const std::string bytes = encodePng(img);
    writeFileAtomically(path, [&](const fs::path& tmp) { writeBytesChecked(tmp, bytes); });
}

namespace {
// The EXR bytes of `img`, or an error naming `path`.
std::string encodeExrFor(const fs::path& path, const ImageF& img) {
    requireSize(path, img.width, img.height, img.rgba.size());
    try {
        return encodeExr(img);
    } catch (const std::exception& e) {
        fail(path, std::string("cannot write: ") + e.what());
    }
}
}  // namespace

void writeExr(const fs::path& path, const ImageF& img) {
    const std::string bytes = encodeExrFor(path, img);
    writeFileAtomically(path, [&](const fs::path& tmp) { writeBytesChecked(tmp, bytes); });
}

void requireWritableOutput(const fs::path& path) {
    if (path.empty()) throw Error("(empty path): not a file name");
    const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) fail(path, "folder " + folder.string() + " does not exist");
    if (::access(folder.c_str(), W_OK | X_OK) != 0) fail(path, "folder " + folder.string() + " is not writable");
    if (fs::is_directory(path, ec)) fail(path, "is a folder, not a file name");
    if (fs::exists(path, ec) && !fs::is_regular_file(path, ec)) fail(path, "exists and is not a regular file");
}

OutputFiles::~OutputFiles() {
    std::error_code ec;
    for (const auto& f : staged_) fs::remove(f.tmp, ec);
}

void OutputFiles::add(const fs::path& path, const std::string& bytes) {
    requireWritableOutput(path);
    for (const auto& f : staged_)
        if (f.path == path) fail(path, "named twice as an output");
    fs::path tmp = path;
    tmp += ".tmp-" + std::to_string(getpid());
    staged_.push_back({path, tmp, TemporaryFileGuard(tmp)});  // before writing, so a partial temporary is removed too
    try {
        writeBytesChecked(tmp, bytes);
    } catch (const std::exception& e) {
        fail(path, std::string("cannot write: ") + e.what());
    }
}

void OutputFiles::addPng(const fs::path& path, const Image8& img) {
    requireSize(path, img.width, img.height, img.rgba.size());
    add(path, encodePng(img));
}

void OutputFiles::addExr(const fs::path& path, const ImageF& img) {
    add(path, encodeExrFor(path, img));
}

void OutputFiles::commit() {
    for (const auto& f : staged_) {
        std::error_code ec;
        fs::rename(f.tmp, f.path, ec);
        if (ec) fail(f.path, "cannot write: " + ec.message());  // the destructor removes what is left
    }
    staged_.clear();
}

}  // namespace lp
