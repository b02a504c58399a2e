#pragma once
// Image files in and out: 8-bit textures (stb_image), HDR environment maps (.hdr via stb_image, .exr via
// OpenEXR), PNG/EXR output. Every failure is an lp::Error whose message starts with the file's path.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <vector>

namespace lp {

// Always 4 channels (RGBA), rows top first.
struct Image8 {
    int width = 0, height = 0;
    std::vector<uint8_t> rgba;
};

// Always 4 channels (RGBA), linear float, rows top first.
struct ImageF {
    int width = 0, height = 0;
    std::vector<float> rgba;
};

// PNG/JPG/TGA/BMP (anything stb_image reads), expanded to RGBA.
Image8 loadImage8(const std::filesystem::path& path);
// Magenta/black checker: the deliberately ugly stand-in for a texture that failed to load.
Image8 makeCheckerImage(int size = 64, int cells = 8);
// loadImage8, or one warning and the checker: a missing texture should not stop a render.
Image8 loadTextureOrChecker(const std::filesystem::path& path);

// .hdr (Radiance) or .exr (any compression, read as float32; the display window is the image, texels
// outside the data window are 0). Negative/NaN components become 0 and +Inf the largest finite value,
// with one warning per file, so later passes (log, sqrt, importance sampling) can trust the data.
ImageF loadHdrImage(const std::filesystem::path& path);

// Atomic writes: nothing at `path` changes unless the whole file was written.
void writePng(const std::filesystem::path& path, const Image8& image);
void writeExr(const std::filesystem::path& path, const ImageF& image);  // float32 RGBA, ZIP

// Calls writer(tmp) with tmp = path + ".tmp-<pid>" in the same folder, then renames tmp over path.
// If the writer throws or the rename fails, tmp is removed and an lp::Error naming path is thrown.
void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path& tmp)>& writer);

}  // namespace lp
