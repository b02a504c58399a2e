#pragma once
// A glTF file's bytes before tinygltf reads them: the GLB container taken apart with every length
// checked (tinygltf says only "Invalid glTF binary." and trusts a BIN chunk's header), and the URIs a
// document holds (base64 data URIs decoded strictly, others percent-decoded into file names).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace lp {

// The parts of a .gltf or .glb file.
struct GltfSource {
    bool binary = false;
    std::string json;                  // the whole .gltf, or the GLB's JSON chunk
    const unsigned char* bin = nullptr;  // the GLB's BIN chunk (chunk 1), inside the file's bytes; null: none
    size_t binBytes = 0;
    size_t binOffset = 0;  // where the BIN chunk's header starts in the file
    // Whether tinygltf must be handed a GLB rebuilt of these parts (makeGlb) rather than the file: it
    // refuses a valid file whose chunk 1 is of a type it does not know (the spec says to ignore such
    // chunks) and reads past a file shorter than its header's length.
    bool rebuild = false;
    std::vector<std::string> warnings;  // without the file's name: bytes after the GLB's length, a second BIN chunk
};

// Takes `bytes` (the file `file`) apart. GLB when it starts with the magic "glTF"; a ".glb" that does not
// is an error unless it holds JSON text. Throws lp::Error "<file>: <what>" naming the header field or the
// chunk, its byte offset and the expected and actual lengths:
// "x.glb: chunk 1 (BIN) at byte 1020: length 4096, but 96 bytes follow its header (the GLB is 1124 bytes)".
GltfSource readGltfContainer(const std::string& bytes, const std::string& file, bool glbByName);

// A GLB of `json` (padded with spaces) and `bin` (padded with zeros; none when binBytes is 0).
std::string makeGlb(const std::string& json, const unsigned char* bin, size_t binBytes);

// A data URI ("data:[<media type>][;base64],<data>") decoded, or why it cannot be: not base64-encoded,
// a byte that is not base64 (named with its position), the wrong length.
struct DataUri {
    std::string mediaType;  // as written: "image/png", "application/octet-stream", or empty
    std::string bytes;
    std::string problem;  // empty: decoded
};
bool isDataUri(const std::string& uri);
DataUri decodeDataUri(const std::string& uri);

// A relative URI's %XX escapes decoded (the file name it stands for).
std::string percentDecoded(const std::string& uri);

}  // namespace lp
