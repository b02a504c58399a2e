#pragma once
// Image files in and out: 8-bit textures (stb_image), HDR environment maps (.hdr via stb_image, .exr via
// OpenEXR), PNG/EXR output. Every failure is an lp::Error whose message starts with the file's path.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "engine/io/temporary_files.hpp"

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

// The most one texture may take decoded (RGBA8): 8192x8192 texels. Checked from the header before the
// decoder allocates anything: a 1 MB PNG of 16384x16384 texels (1 GiB decoded) took 3.5 GiB and 20 s
// on its way to the GPU. A texture over it is refused (a checker with a warning, as for any texture
// that cannot be read).
constexpr uint64_t kMaxTextureBytes = uint64_t(256) << 20;

// PNG/JPG/TGA/BMP (anything stb_image reads), expanded to RGBA. A file the decoder needed more bytes
// of than it has is "truncated", a PNG chunk whose CRC does not match "corrupt": errors, never garbage;
// so is a header claiming more than kMaxTextureBytes decoded.
Image8 loadImage8(const std::filesystem::path& path);
// The same from an encoded image in memory (a glTF's embedded image); `label` names it in errors.
Image8 decodeImage8(const std::string& bytes, const std::filesystem::path& label);
// Magenta/black checker: the deliberately ugly stand-in for a texture that failed to load.
Image8 makeCheckerImage(int size = 64, int cells = 8);
// loadImage8, or one warning and the checker: a missing texture should not stop a render.
Image8 loadTextureOrChecker(const std::filesystem::path& path);
Image8 decodeTextureOrChecker(const std::string& bytes, const std::filesystem::path& label);

// .hdr (Radiance; a truncated file is an error, not zero-filled) or .exr (any compression, read as
// float32; the display window is the image, texels outside the data window are 0, and a display window
// over 16x its data window and 16M texels is refused). Negative/NaN components become 0 and +Inf the largest finite value,
// with one warning per file, so later passes (log, sqrt, importance sampling) can trust the data.
ImageF loadHdrImage(const std::filesystem::path& path);

// Halved (2x2 box) until neither side exceeds maxSize: for images wider than the GPU's
// GL_MAX_TEXTURE_SIZE, which the caller warns about. Unchanged when it already fits.
Image8 downscaleToFit(const Image8& image, int maxSize);
ImageF downscaleToFit(const ImageF& image, int maxSize);

// Atomic writes: nothing at `path` changes unless the whole file was written (every write, the fsync
// and the close checked: a full disk is an error, never a 0-byte file).
void writePng(const std::filesystem::path& path, const Image8& image);
void writeExr(const std::filesystem::path& path, const ImageF& image);  // float32 RGBA, ZIP

// Calls writer(tmp) with tmp = path + ".tmp-<pid>" in the same folder, then renames tmp over path.
// If the writer throws or the rename fails, tmp is removed and an lp::Error naming path is thrown; so
// is it if SIGINT, SIGTERM or SIGHUP ends the process meanwhile (installTemporaryFileCleanup).
void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path& tmp)>& writer);

// Whole files in memory, for writeBytesChecked and OutputFiles.
std::string encodePng(const Image8& image);
std::string encodeExr(const ImageF& image);
// Creates/truncates `path` and writes `bytes`, checking every write, fsync and close; throws lp::Error
// with the system's reason (without the path).
void writeBytesChecked(const std::filesystem::path& path, const std::string& bytes);
// Throws "<path>: ..." unless a file could be written there: the folder exists and is writable, and
// the path is not a folder or special file. Commands call it for every output before rendering.
void requireWritableOutput(const std::filesystem::path& path);

// A command's outputs, all or nothing: each add() writes a temporary file beside its target at once
// (checked), commit() renames them all over their targets; temporaries not committed are removed when
// this goes out of scope, or by the signal handler of installTemporaryFileCleanup if SIGINT, SIGTERM or
// SIGHUP ends the process first, so a failure anywhere leaves no output and no partial file.
class OutputFiles {
public:
    OutputFiles() = default;
    OutputFiles(const OutputFiles&) = delete;
    OutputFiles& operator=(const OutputFiles&) = delete;
    ~OutputFiles();

    void add(const std::filesystem::path& path, const std::string& bytes);
    void addPng(const std::filesystem::path& path, const Image8& image);
    void addExr(const std::filesystem::path& path, const ImageF& image);
    void commit();

private:
    struct Staged {
        std::filesystem::path path, tmp;
        TemporaryFileGuard guard;  // registered before the temporary is created
    };
    std::vector<Staged> staged_;
};

}  // namespace lp
