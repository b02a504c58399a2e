#include "engine/io/gltf_loader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include <glm/gtc/matrix_inverse.hpp>
#include <nlohmann/json.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/io/file_check.hpp"
#include "engine/io/gltf_compression.hpp"
#include "engine/io/gltf_container.hpp"
#include "engine/io/gltf_schema.hpp"
#include "engine/io/json_text.hpp"
#include "engine/scene/animation.hpp"
#include "engine/scene/mesh_ops.hpp"

namespace lp {
namespace fs = std::filesystem;

bool isGltfPath(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".gltf" || ext == ".glb";
}

namespace {

std::string formatNumber(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

// Extensions this loader understands; a file that requires any other is refused (the spec's rule).
// KHR_texture_basisu is not among them: its KTX2 images have no Debian decoder.
const std::set<std::string> kSupportedExtensions = {"EXT_mesh_gpu_instancing", "EXT_meshopt_compression", "KHR_draco_mesh_compression", "KHR_lights_punctual",
                                                     "KHR_materials_clearcoat", "KHR_materials_emissive_strength", "KHR_materials_ior", "KHR_materials_specular",
                                                     "KHR_materials_transmission", "KHR_materials_unlit", "KHR_materials_variants",
                                                     "KHR_materials_volume",
                                                     "KHR_mesh_quantization", "KHR_texture_transform"};
constexpr size_t kMaxElements = kMaxGltfElements;  // accessor count limit: 268M elements
constexpr size_t kMaxNodeDepth = 1024;                        // levels of the node hierarchy
constexpr size_t kMaxDrawnPrimitives = size_t(1) << 20;       // primitive instances the nodes draw
constexpr size_t kMaxDrawnVertices = size_t(1) << 26;         // their vertices and indices, instances counted
constexpr size_t kMaxMorphDeltas = size_t(1) << 25;           // morph-target deltas held for posing, all targets and vertices

// tinygltf reads external buffers through these: only the files the document's buffers name, checked
// by checkBuffers (it would also read every external image, which SceneGpu reads itself with its
// checks, and look for a missing file in the current folder). It asks for a buffer by its own spelling
// of the path (the folder, "/", the URI decoded with '+' as a space); `paths` maps that to the file the
// URI names (RFC 3986: '+' is a plus), read with the same regular-file check as every other input.
struct BufferFiles {
    std::map<std::string, fs::path> paths;
    const fs::path* find(const std::string& asked) const {
        const auto it = paths.find(asked);
        return it == paths.end() ? nullptr : &it->second;
    }
};
// The path tinygltf asks for when a buffer's URI is `uri` (its dlib::urldecode and JoinPath).
std::string tinygltfPath(const std::string& baseDir, const std::string& uri) {
    auto hex = [](unsigned char c) -> unsigned char {
        if (c >= '0' && c <= '9') return c - '0';
        if (c >= 'a' && c <= 'f') return c - 'a' + 10;
        if (c >= 'A' && c <= 'F') return c - 'A' + 10;
        return 0;
    };
    std::string decoded;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '+') {
            decoded += ' ';
        } else if (uri[i] == '%' && uri.size() > i + 2) {
            decoded += char(hex(static_cast<unsigned char>(uri[i + 1])) << 4 | hex(static_cast<unsigned char>(uri[i + 2])));
            i += 2;
        } else {
            decoded += uri[i];
        }
    }
    if (baseDir.empty()) return decoded;
    return baseDir.back() == '/' ? baseDir + decoded : baseDir + "/" + decoded;
}
bool fileExists(const std::string& path, void* files) { return static_cast<const BufferFiles*>(files)->find(path) != nullptr; }
std::string expandPath(const std::string& path, void*) { return path; }
bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* files) {
    const fs::path* file = static_cast<const BufferFiles*>(files)->find(path);
    if (!file) return false;
    try {
        const std::string bytes = readFileChecked(*file, kMaxImageFileBytes, "a glTF buffer");
        out->assign(bytes.begin(), bytes.end());
        return true;
    } catch (const Error& e) {
        if (err) *err += e.what();
        return false;
    }
}

// The file a relative URI names, beside the glTF.
fs::path uriFile(const std::string& baseDir, const std::string& uri) {
    return (fs::path(baseDir) / percentDecoded(uri)).lexically_normal();
}

// Every buffer's data, checked before tinygltf reads it (it refuses any fault with the whole data URI
// or path in its message, or none at all): a data URI decoded strictly to exactly byteLength bytes; an
// external file that exists, is a regular file and holds byteLength bytes; a GLB's first buffer without
// a URI within the BIN chunk. The external files are listed in `files` for the callbacks above.
// EXT_meshopt_compression's fallback buffers are not read: they hold no data.
void checkBuffers(const nlohmann::json& root, const GltfSource& source, const std::string& file, const std::string& baseDir,
                  const GltfCompressedParts& compressed, BufferFiles& files) {
    const auto buffers = root.find("buffers");
    if (buffers == root.end()) return;
    for (size_t i = 0; i < buffers->size(); ++i) {
        if (compressed.fallbackBuffers.count(i)) continue;
        const nlohmann::json& b = (*buffers)[i];
        const std::string w = file + ": buffers[" + std::to_string(i) + "]";
        const uint64_t byteLength = b["byteLength"].get<uint64_t>();  // the schema: an integer >= 1
        const auto uriAt = b.find("uri");
        if (uriAt == b.end()) {
            if (!source.binary || i > 0)
                throw Error(w + ": has no uri (only a GLB's first buffer has none: its data is the GLB's BIN chunk)");
            if (!source.bin || source.binBytes == 0) throw Error(w + ": has no uri, and the GLB has no BIN chunk to hold its data");
            if (byteLength > source.binBytes)
                throw Error(w + ".byteLength: " + std::to_string(byteLength) + " bytes, but the GLB's BIN chunk (chunk 1 at byte " +
                            std::to_string(source.binOffset) + ") holds " + std::to_string(source.binBytes));
            continue;
        }
        const std::string uri = uriAt->get<std::string>();
        if (isDataUri(uri)) {
            const DataUri d = decodeDataUri(uri);
            if (!d.problem.empty()) throw Error(w + ".uri: " + d.problem);
            if (d.mediaType != "application/octet-stream" && d.mediaType != "application/gltf-buffer")
                throw Error(w + ".uri: a data URI of media type " + quoteUserText(d.mediaType) +
                            "; a buffer's is application/octet-stream or application/gltf-buffer");
            if (d.bytes.size() != byteLength)
                throw Error(w + ".uri: the data URI holds " + std::to_string(d.bytes.size()) + " bytes, but byteLength is " +
                            std::to_string(byteLength));
            continue;
        }
        const fs::path path = uriFile(baseDir, uri);
        uintmax_t size = 0;
        try {
            size = requireRegularFile(path, kMaxImageFileBytes, "a glTF buffer");
        } catch (const Error& e) {
            // "<path>: file not found": the path as the file names it (a URI may hold anything).
            std::string why = e.what();
            if (why.compare(0, path.string().size() + 2, path.string() + ": ") == 0) why.erase(0, path.string().size() + 2);
            throw Error(w + ".uri: " + quoteUserText(uri, 120) + ": " + why);
        }
        if (size != byteLength)
            throw Error(w + ".uri: " + quoteUserText(uri, 120) + " is " + std::to_string(size) + " bytes, but byteLength is " +
                        std::to_string(byteLength));
        files.paths[tinygltfPath(baseDir, uri)] = path;
    }
}

// What one of the document's images holds, as read here rather than by tinygltf.
struct ImageSource {
    std::shared_ptr<const std::string> encoded;  // a data URI's bytes
    fs::path path;                                // an external file
    std::string problem;                          // a data URI that does not decode: why
    // None of them: a buffer view's bytes (tinygltf's, range-checked by keepEncodedImage).
};
std::vector<ImageSource> imageSources(const nlohmann::json& root, const std::string& baseDir) {
    std::vector<ImageSource> out;
    const auto images = root.find("images");
    if (images == root.end()) return out;
    for (const nlohmann::json& image : *images) {
        ImageSource s;
        const auto uri = image.find("uri");
        if (uri != image.end()) {
            const std::string text = uri->get<std::string>();
            if (isDataUri(text)) {
                DataUri d = decodeDataUri(text);
                if (!d.problem.empty()) s.problem = d.problem;
                else if (d.bytes.empty()) s.problem = "data URI: no data";
                else s.encoded = std::make_shared<const std::string>(std::move(d.bytes));
            } else {
                s.path = uriFile(baseDir, text);
            }
        }
        out.push_back(std::move(s));
    }
    return out;
}

bool writeWholeFile(std::string*, const std::string&, const std::vector<unsigned char>&, void*) { return false; }

// Images are decoded when they are uploaded (SceneGpu), so that a bad one becomes a checker with a
// warning: tinygltf only hands over the encoded bytes (embedded or data: URIs).
// tinygltf hands an image stored in a buffer view over as buffer + byteOffset, byteLength bytes without
// checking them against the buffer (a lying byteLength read the heap past it): `model` is the one being
// filled, whose buffers are parsed before its images.
bool keepEncodedImage(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int, const unsigned char* bytes,
                      int size, void* model) {
    if (size < 0) size = 0;
    const auto& m = *static_cast<const tinygltf::Model*>(model);
    if (image->bufferView >= 0) {
        const std::string where = "images[" + std::to_string(index) + "]: bufferViews[" + std::to_string(image->bufferView) + "]";
        if (size_t(image->bufferView) >= m.bufferViews.size()) {
            if (err) *err += where + " does not exist";
            return false;
        }
        const tinygltf::BufferView& view = m.bufferViews[size_t(image->bufferView)];
        const size_t bufferBytes = view.buffer >= 0 && size_t(view.buffer) < m.buffers.size() ? m.buffers[size_t(view.buffer)].data.size() : 0;
        if (view.byteOffset > bufferBytes || view.byteLength > bufferBytes - view.byteOffset) {
            if (err)
                *err += where + ": bytes " + std::to_string(view.byteOffset) + "+" + std::to_string(view.byteLength) + " run past the end of buffers[" +
                        std::to_string(view.buffer) + "] (" + std::to_string(bufferBytes) + " bytes)";
            return false;
        }
    }
    image->image.assign(bytes, bytes + size);
    image->as_is = true;
    return true;
}

struct Loader {
    const tinygltf::Model& model;
    std::string file;
    MeshLoadReport& report;
    const std::vector<ImageSource>& images;  // what the document's images hold, by index

    [[noreturn]] void fail(const std::string& where, const std::string& what) const { throw Error(file + ": " + where + ": " + what); }
    // Kept in the report and printed only once the whole file has loaded: a file that fails prints its
    // one error line alone.
    void warn(const std::string& where, const std::string& what) const { report.warnings.push_back(file + ": " + where + ": " + what); }

    static int componentCount(int type) {
        switch (type) {
            case TINYGLTF_TYPE_SCALAR: return 1;
            case TINYGLTF_TYPE_VEC2: return 2;
            case TINYGLTF_TYPE_VEC3: return 3;
            case TINYGLTF_TYPE_VEC4: return 4;
            case TINYGLTF_TYPE_MAT2: return 4;
            case TINYGLTF_TYPE_MAT3: return 9;
            case TINYGLTF_TYPE_MAT4: return 16;
        }
        return 0;
    }
    static int componentSize(int type) {
        switch (type) {
            case TINYGLTF_COMPONENT_TYPE_BYTE:
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
            case TINYGLTF_COMPONENT_TYPE_SHORT:
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        }
        return 0;
    }

    // The accessor's bytes, checked to lie inside its buffer view and buffer: tinygltf checks neither.
    // A sparse accessor's are its dense bytes (or zeros, without a buffer view) with its values put in
    // at its indices, per the spec; they are held by `owned`.
    struct View {
        const unsigned char* data = nullptr;  // nullptr: no buffer view and not sparse (all zeros, per the spec)
        size_t stride = 0, count = 0;
        int components = 0, componentType = 0;
        bool normalized = false;
        std::shared_ptr<std::vector<unsigned char>> owned;
    };
    // `count`, when given, is the element count the accessor must have (checked before a sparse one's
    // bytes are made: its count is bounded by no bytes of the file).
    View view(int index, const std::string& where, const std::set<int>& types, const std::set<int>& componentTypes,
              std::optional<size_t> count = std::nullopt) const {
        const std::string aw = where + " (accessors[" + std::to_string(index) + "])";
        if (index < 0 || size_t(index) >= model.accessors.size())
            fail(where, "accessor " + std::to_string(index) + " does not exist (" + std::to_string(model.accessors.size()) + " accessors)");
        const tinygltf::Accessor& a = model.accessors[size_t(index)];
        if (!types.count(a.type)) fail(aw, "unexpected type " + std::to_string(a.type) + " for this attribute");
        if (!componentTypes.count(a.componentType))
            fail(aw, "unexpected componentType " + std::to_string(a.componentType) + " for this attribute");
        if (a.count > kMaxElements) fail(aw, "count " + std::to_string(a.count) + " is over the limit");
        if (count && a.count != *count) fail(where, std::to_string(a.count) + " elements, but POSITION has " + std::to_string(*count));
        View v;
        v.components = componentCount(a.type);
        v.componentType = a.componentType;
        v.normalized = a.normalized;
        v.count = a.count;
        const size_t elementSize = size_t(v.components) * size_t(componentSize(a.componentType));
        v.stride = elementSize;
        if (a.bufferView >= 0) {
            const auto [bytes, viewBytes, viewStride] = bufferView(a.bufferView);
            const std::string bw = "bufferViews[" + std::to_string(a.bufferView) + "]";
            if (viewStride) {
                if (viewStride < elementSize) fail(bw, "byteStride " + std::to_string(viewStride) + " is smaller than an element");
                v.stride = viewStride;
            }
            if (a.count > 0) {
                const size_t last = a.byteOffset + v.stride * (a.count - 1) + elementSize;  // < 2^28 * 2^8 + ..., no overflow
                if (a.byteOffset > viewBytes || last > viewBytes)
                    fail(aw, std::to_string(a.count) + " elements from byte " + std::to_string(a.byteOffset) + " run past the end of " + bw +
                                 " (" + std::to_string(viewBytes) + " bytes)");
            }
            v.data = bytes + a.byteOffset;
        }
        if (a.sparse.isSparse) applySparse(a, aw, elementSize, v);
        return v;
    }

    // Buffer view `index`: its first byte, length and stride, checked to lie inside its buffer.
    std::tuple<const unsigned char*, size_t, size_t> bufferView(int index) const {
        const std::string bw = "bufferViews[" + std::to_string(index) + "]";
        if (index < 0 || size_t(index) >= model.bufferViews.size())
            fail(bw, "does not exist (" + std::to_string(model.bufferViews.size()) + " buffer views)");
        const tinygltf::BufferView& bv = model.bufferViews[size_t(index)];
        if (bv.buffer < 0 || size_t(bv.buffer) >= model.buffers.size())
            fail(bw, "buffer " + std::to_string(bv.buffer) + " does not exist (" + std::to_string(model.buffers.size()) + " buffers)");
        const tinygltf::Buffer& buffer = model.buffers[size_t(bv.buffer)];
        if (bv.byteOffset > buffer.data.size() || bv.byteLength > buffer.data.size() - bv.byteOffset)
            fail(bw, "bytes " + std::to_string(bv.byteOffset) + "+" + std::to_string(bv.byteLength) + " run past the end of buffers[" +
                         std::to_string(bv.buffer) + "] (" + std::to_string(buffer.data.size()) + " bytes)");
        return {buffer.data.data() + bv.byteOffset, bv.byteLength, bv.byteStride};
    }

    // The spec's sparse storage: `sparse.count` indices (unsigned, strictly increasing, below the
    // accessor's count) and as many tightly packed values of the accessor's type, each replacing the
    // element at its index of the dense bytes (zeros without a buffer view).
    void applySparse(const tinygltf::Accessor& a, const std::string& aw, size_t elementSize, View& v) const {
        const auto& sp = a.sparse;
        const std::string sw = aw + ".sparse";
        const size_t n = size_t(sp.count);
        if (sp.count < 1 || n > a.count) fail(sw + ".count", std::to_string(sp.count) + " must be from 1 to the accessor's count " + std::to_string(a.count));
        size_t indexSize = 0;
        switch (sp.indices.componentType) {
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: indexSize = 1; break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: indexSize = 2; break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: indexSize = 4; break;
            default: fail(sw + ".indices.componentType", std::to_string(sp.indices.componentType) + " is not 5121, 5123 or 5125");
        }
        auto part = [&](int viewIndex, int byteOffset, size_t bytes, const std::string& pw) {
            const auto [data, viewBytes, viewStride] = bufferView(viewIndex);
            (void)viewStride;  // sparse data is tightly packed whatever the view says
            if (byteOffset < 0 || size_t(byteOffset) > viewBytes || bytes > viewBytes - size_t(byteOffset))
                fail(pw, std::to_string(n) + " elements of " + std::to_string(bytes / n) + " bytes from byte " + std::to_string(byteOffset) +
                             " run past the end of bufferViews[" + std::to_string(viewIndex) + "] (" + std::to_string(viewBytes) + " bytes)");
            return data + byteOffset;
        };
        const unsigned char* indices = part(sp.indices.bufferView, sp.indices.byteOffset, n * indexSize, sw + ".indices");
        const unsigned char* values = part(sp.values.bufferView, sp.values.byteOffset, n * elementSize, sw + ".values");
        auto dense = std::make_shared<std::vector<unsigned char>>(v.count * elementSize, 0);
        if (v.data)
            for (size_t e = 0; e < v.count; ++e) std::memcpy(dense->data() + e * elementSize, v.data + e * v.stride, elementSize);
        View indexView;
        indexView.data = indices;
        indexView.stride = indexSize;
        indexView.componentType = sp.indices.componentType;
        uint64_t previous = 0;
        for (size_t k = 0; k < n; ++k) {
            const uint32_t at = index(indexView, k);
            if (at >= v.count)
                fail(sw + ".indices", "index " + std::to_string(at) + " at position " + std::to_string(k) + " is beyond the accessor's " +
                                          std::to_string(v.count) + " elements");
            if (k > 0 && at <= previous)
                fail(sw + ".indices", "index " + std::to_string(at) + " at position " + std::to_string(k) + " does not follow " +
                                          std::to_string(previous) + " (sparse indices are strictly increasing)");
            std::memcpy(dense->data() + size_t(at) * elementSize, values + k * elementSize, elementSize);
            previous = at;
        }
        v.owned = dense;
        v.data = dense->data();
        v.stride = elementSize;
    }

    static float component(const View& v, size_t element, int c) {
        if (!v.data) return 0.0f;
        const unsigned char* p = v.data + v.stride * element + size_t(c) * size_t(componentSize(v.componentType));
        switch (v.componentType) {
            case TINYGLTF_COMPONENT_TYPE_FLOAT: {
                float f;
                std::memcpy(&f, p, 4);
                return f;
            }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return v.normalized ? float(*p) / 255.0f : float(*p);
            case TINYGLTF_COMPONENT_TYPE_BYTE: {
                const float x = float(int8_t(*p));
                return v.normalized ? std::max(x / 127.0f, -1.0f) : x;
            }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                uint16_t s;
                std::memcpy(&s, p, 2);
                return v.normalized ? float(s) / 65535.0f : float(s);
            }
            case TINYGLTF_COMPONENT_TYPE_SHORT: {
                int16_t s;
                std::memcpy(&s, p, 2);
                return v.normalized ? std::max(float(s) / 32767.0f, -1.0f) : float(s);
            }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
                uint32_t u;
                std::memcpy(&u, p, 4);
                return float(u);
            }
        }
        return 0.0f;
    }
    static uint32_t index(const View& v, size_t element) {
        if (!v.data) return 0;
        const unsigned char* p = v.data + v.stride * element;
        switch (v.componentType) {
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return *p;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                uint16_t s;
                std::memcpy(&s, p, 2);
                return s;
            }
            default: {
                uint32_t u;
                std::memcpy(&u, p, 4);
                return u;
            }
        }
    }

    // The uv set a texture reads: its texCoord, or its KHR_texture_transform's texCoord, which
    // overrides it. lightpass keeps two sets (TEXCOORD_0 and TEXCOORD_1); a higher one reads TEXCOORD_0.
    static int texCoordOf(int texCoord, const tinygltf::ExtensionMap& extensions) {
        const auto it = extensions.find("KHR_texture_transform");
        if (it != extensions.end() && it->second.IsObject() && it->second.Has("texCoord") && it->second.Get("texCoord").IsNumber())
            return it->second.Get("texCoord").GetNumberAsInt();
        return texCoord;
    }
    static int uvSetOf(int texCoord, const tinygltf::ExtensionMap& extensions) {
        const int n = texCoordOf(texCoord, extensions);
        return n == 1 ? 1 : 0;
    }

    // Texture `textureIndex` of a material, sampled with TEXCOORD_`texCoord` (a textureInfo's fields).
    TextureRef texture(int textureIndex, int texCoord, const tinygltf::ExtensionMap& extensions, const std::string& where) const {
        if (textureIndex < 0) return {};
        if (size_t(textureIndex) >= model.textures.size()) {
            warn(where, "texture " + std::to_string(textureIndex) + " does not exist; ignored");
            return {};
        }
        const int n = texCoordOf(texCoord, extensions);
        if (n > 1) warn(where, "uses TEXCOORD_" + std::to_string(n) + "; only TEXCOORD_0 and TEXCOORD_1 are read, so it reads TEXCOORD_0");
        const int uvSet = uvSetOf(texCoord, extensions);
        const tinygltf::Texture& t = model.textures[size_t(textureIndex)];
        const std::string iw = "textures[" + std::to_string(textureIndex) + "]";
        if (t.source < 0 || size_t(t.source) >= model.images.size()) {
            TextureRef r;
            r.problem = (t.source < 0 ? "has no source image" : "image " + std::to_string(t.source) + " does not exist");
            r.key = file + "#" + iw;
            r.uvSet = uvSet;
            return r;
        }
        TextureRef r = imageTexture(model.images[size_t(t.source)], t.source);
        r.sampler = sampler(t.sampler, iw);
        r.uvSet = uvSet;
        return r;
    }

    // Texture `where`'s sampler `index`: its wraps and filters that are valid (the schema check warned
    // about the others, which keep the default).
    TextureSampler sampler(int index, const std::string& where) const {
        TextureSampler s;
        if (index < 0) return s;
        if (size_t(index) >= model.samplers.size()) {
            warn(where, "sampler " + std::to_string(index) + " does not exist; the default is used");
            return s;
        }
        const tinygltf::Sampler& g = model.samplers[size_t(index)];
        const auto oneOf = [](int v, const std::vector<int64_t>& valid) {
            return std::find(valid.begin(), valid.end(), int64_t(v)) != valid.end();
        };
        if (oneOf(g.wrapS, kGltfSamplerWraps)) s.wrapS = g.wrapS;
        if (oneOf(g.wrapT, kGltfSamplerWraps)) s.wrapT = g.wrapT;
        if (oneOf(g.magFilter, kGltfMagFilters)) s.magFilter = g.magFilter;
        if (oneOf(g.minFilter, kGltfMinFilters)) s.minFilter = g.minFilter;
        return s;
    }

    // images[source]: its encoded bytes (a buffer view's, or a data URI's), the file its URI names, or
    // why it has neither (the checker then stands in, with a warning).
    TextureRef imageTexture(const tinygltf::Image& image, int source) const {
        TextureRef r;
        r.key = file + "#images[" + std::to_string(source) + "]";
        const ImageSource& from = images[size_t(source)];
        if (!from.problem.empty()) {
            r.problem = from.problem;
        } else if (from.encoded) {
            r.encoded = from.encoded;
        } else if (!from.path.empty()) {
            r = TextureRef::file(from.path);  // SceneGpu reads it with its checks: missing, FIFO, corrupt
        } else if (!image.image.empty()) {
            r.encoded = std::make_shared<const std::string>(image.image.begin(), image.image.end());
        } else {
            r.problem = "holds no image data";
        }
        return r;
    }

    // KHR_texture_transform on one texture: uv' = linear * uv + offset in glTF's uv (origin top left),
    // the extension's translation * rotation * scale.
    struct UvTransform {
        glm::dmat2 linear{1.0};
        glm::dvec2 offset{0.0};
        bool identity() const { return linear == glm::dmat2(1.0) && offset == glm::dvec2(0.0); }
        // Whether the uv axes turn or flip: tangents made for the file's uv then no longer fit.
        bool turnsAxes() const { return linear[1][0] != 0.0 || linear[0][1] != 0.0 || linear[0][0] <= 0.0 || linear[1][1] <= 0.0; }
        bool operator==(const UvTransform& o) const { return linear == o.linear && offset == o.offset; }
    };
    UvTransform uvTransform(const tinygltf::ExtensionMap& extensions, const std::string& where) const {
        UvTransform t;
        const auto it = extensions.find("KHR_texture_transform");
        if (it == extensions.end() || !it->second.IsObject()) return t;
        const tinygltf::Value& x = it->second;
        auto pair = [&](const char* key, glm::dvec2 fallback) {
            if (!x.Has(key) || !x.Get(key).IsArray() || x.Get(key).ArrayLen() != 2) return fallback;
            return glm::dvec2(x.Get(key).Get(0).GetNumberAsDouble(), x.Get(key).Get(1).GetNumberAsDouble());
        };
        const glm::dvec2 offset = pair("offset", glm::dvec2(0.0)), scale = pair("scale", glm::dvec2(1.0));
        const double rotation = x.Has("rotation") ? x.Get("rotation").GetNumberAsDouble() : 0.0;
        if (!std::isfinite(offset.x + offset.y + scale.x + scale.y + rotation))
            fail(where + ".extensions.KHR_texture_transform", "offset, rotation and scale must be finite");
        // u' = cos u + sin v, v' = -sin u + cos v: the extension's "uvs turned counter-clockwise, the
        // image clockwise" (its example maps offset (0, 1), rotation pi/2, scale 0.5 onto the lower left
        // quadrant, and Khronos' TextureTransformTest marks this direction green). The README's GLSL,
        // read as GLSL's column-major mat3, turns the other way.
        const double c = std::cos(rotation), sn = std::sin(rotation);
        t.linear = glm::dmat2(c, -sn, sn, c) * glm::dmat2(scale.x, 0.0, 0.0, scale.y);  // columns
        t.offset = offset;
        return t;
    }
    // What material `index`'s textures ask of a primitive's uv sets: the transform of each set (applied
    // to the vertices' uvs, so the textures that read one set share one transform: one that disagrees
    // gets the first one's, with a warning, once per material however many primitives use it), which
    // sets are read, and which the normal map reads (the set its tangents follow).
    struct MaterialUvSets {
        UvTransform transform[2];
        bool reads[2] = {false, false};
        int normalSet = 0;
    };
    // A textureInfo inside a material extension (tinygltf keeps an extension's JSON as a Value; the
    // schema checked its index and texCoord): index -1 when absent.
    struct ExtensionTexture {
        int index = -1, texCoord = 0;
        tinygltf::ExtensionMap extensions;
    };
    static ExtensionTexture extensionTexture(const tinygltf::Material& m, const char* extension, const char* key) {
        ExtensionTexture t;
        const auto ext = m.extensions.find(extension);
        if (ext == m.extensions.end() || !ext->second.Has(key)) return t;
        const tinygltf::Value& v = ext->second.Get(key);
        if (v.Has("index") && v.Get("index").IsInt()) t.index = v.Get("index").GetNumberAsInt();
        if (v.Has("texCoord") && v.Get("texCoord").IsInt()) t.texCoord = v.Get("texCoord").GetNumberAsInt();
        if (v.Has("extensions") && v.Get("extensions").IsObject())
            for (const std::string& k : v.Get("extensions").Keys()) t.extensions[k] = v.Get("extensions").Get(k);
        return t;
    }

    mutable std::map<int, MaterialUvSets> materialUvSetsKnown{};
    MaterialUvSets materialUvSets(int index) const {
        if (index < 0 || size_t(index) >= model.materials.size()) return {};
        if (auto known = materialUvSetsKnown.find(index); known != materialUvSetsKnown.end()) return known->second;
        const tinygltf::Material& m = model.materials[size_t(index)];
        const std::string w = "materials[" + std::to_string(index) + "]";
        struct Slot {
            const char* name;
            int index, texCoord;
            const tinygltf::ExtensionMap* extensions;
        };
        const auto& pbr = m.pbrMetallicRoughness;
        const ExtensionTexture specular = extensionTexture(m, "KHR_materials_specular", "specularTexture");
        const ExtensionTexture specularColor = extensionTexture(m, "KHR_materials_specular", "specularColorTexture");
        const ExtensionTexture coat = extensionTexture(m, "KHR_materials_clearcoat", "clearcoatTexture");
        const ExtensionTexture coatRoughness = extensionTexture(m, "KHR_materials_clearcoat", "clearcoatRoughnessTexture");
        const ExtensionTexture coatNormal = extensionTexture(m, "KHR_materials_clearcoat", "clearcoatNormalTexture");
        const ExtensionTexture transmission = extensionTexture(m, "KHR_materials_transmission", "transmissionTexture");
        const ExtensionTexture thickness = extensionTexture(m, "KHR_materials_volume", "thicknessTexture");
        const Slot textures[] = {
            {"pbrMetallicRoughness.baseColorTexture", pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, &pbr.baseColorTexture.extensions},
            {"pbrMetallicRoughness.metallicRoughnessTexture", pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
             &pbr.metallicRoughnessTexture.extensions},
            {"normalTexture", m.normalTexture.index, m.normalTexture.texCoord, &m.normalTexture.extensions},
            {"occlusionTexture", m.occlusionTexture.index, m.occlusionTexture.texCoord, &m.occlusionTexture.extensions},
            {"emissiveTexture", m.emissiveTexture.index, m.emissiveTexture.texCoord, &m.emissiveTexture.extensions},
            {"extensions.KHR_materials_specular.specularTexture", specular.index, specular.texCoord, &specular.extensions},
            {"extensions.KHR_materials_specular.specularColorTexture", specularColor.index, specularColor.texCoord,
             &specularColor.extensions},
            {"extensions.KHR_materials_clearcoat.clearcoatTexture", coat.index, coat.texCoord, &coat.extensions},
            {"extensions.KHR_materials_clearcoat.clearcoatRoughnessTexture", coatRoughness.index, coatRoughness.texCoord,
             &coatRoughness.extensions},
            {"extensions.KHR_materials_clearcoat.clearcoatNormalTexture", coatNormal.index, coatNormal.texCoord,
             &coatNormal.extensions},
            {"extensions.KHR_materials_transmission.transmissionTexture", transmission.index, transmission.texCoord,
             &transmission.extensions},
            {"extensions.KHR_materials_volume.thicknessTexture", thickness.index, thickness.texCoord, &thickness.extensions}};
        MaterialUvSets out;
        if (m.normalTexture.index >= 0) out.normalSet = uvSetOf(m.normalTexture.texCoord, m.normalTexture.extensions);
        // The clearcoat's normal map shares the base's tangent space (the extension asks both to use the
        // same texture coordinates); alone, its set decides where tangents are made.
        else if (coatNormal.index >= 0) out.normalSet = uvSetOf(coatNormal.texCoord, coatNormal.extensions);
        std::string firstName[2];
        for (const Slot& texture : textures) {
            if (texture.index < 0) continue;
            const int set = uvSetOf(texture.texCoord, *texture.extensions);
            const UvTransform t = uvTransform(*texture.extensions, w + "." + texture.name);
            if (!out.reads[set]) {
                out.reads[set] = true;
                out.transform[set] = t;
                firstName[set] = texture.name;
            } else if (!(t == out.transform[set])) {
                warn(w + "." + texture.name, "its KHR_texture_transform differs from " + firstName[set] +
                                                 "'s, which is applied to every texture of the material on TEXCOORD_" + std::to_string(set));
            }
        }
        return materialUvSetsKnown[index] = out;
    }

    Material material(int index) const {
        Material out;
        out.specular = glm::vec3(0.04f);
        out.doubleSided = false;
        if (index < 0) {  // the spec's default material
            out.name = "default";
            out.diffuse = glm::vec3(1.0f);
            out.metallic = 1.0f;
            out.roughness = 1.0f;
            out.shininess = shininessFromRoughness(1.0f);
            return out;
        }
        const tinygltf::Material& m = model.materials[size_t(index)];
        const std::string w = "materials[" + std::to_string(index) + "]";
        out.name = m.name.empty() ? w : m.name;
        const auto& pbr = m.pbrMetallicRoughness;
        auto finite01 = [&](double v, double fallback, const std::string& field) {
            if (!std::isfinite(v)) {
                warn(w + "." + field, "not finite; using " + std::to_string(fallback));
                return float(fallback);
            }
            return float(std::clamp(v, 0.0, 1.0));
        };
        if (pbr.baseColorFactor.size() == 4) {
            for (int c = 0; c < 3; ++c) out.diffuse[c] = finite01(pbr.baseColorFactor[size_t(c)], 1.0, "pbrMetallicRoughness.baseColorFactor");
            out.opacity = finite01(pbr.baseColorFactor[3], 1.0, "pbrMetallicRoughness.baseColorFactor");
        } else {
            out.diffuse = glm::vec3(1.0f);
        }
        out.metallic = finite01(pbr.metallicFactor, 1.0, "pbrMetallicRoughness.metallicFactor");
        out.roughness = finite01(pbr.roughnessFactor, 1.0, "pbrMetallicRoughness.roughnessFactor");
        out.shininess = shininessFromRoughness(out.roughness);
        out.diffuseMap = texture(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, pbr.baseColorTexture.extensions,
                                 w + ".pbrMetallicRoughness.baseColorTexture");
        out.metallicRoughnessMap = texture(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                                           pbr.metallicRoughnessTexture.extensions, w + ".pbrMetallicRoughness.metallicRoughnessTexture");
        out.normalMap = texture(m.normalTexture.index, m.normalTexture.texCoord, m.normalTexture.extensions, w + ".normalTexture");
        out.normalScale = std::isfinite(m.normalTexture.scale) ? float(m.normalTexture.scale) : 1.0f;
        out.occlusionMap = texture(m.occlusionTexture.index, m.occlusionTexture.texCoord, m.occlusionTexture.extensions, w + ".occlusionTexture");
        out.occlusionStrength = finite01(m.occlusionTexture.strength, 1.0, "occlusionTexture.strength");
        out.emissiveMap = texture(m.emissiveTexture.index, m.emissiveTexture.texCoord, m.emissiveTexture.extensions, w + ".emissiveTexture");
        float strength = 1.0f;
        auto ext = m.extensions.find("KHR_materials_emissive_strength");
        if (ext != m.extensions.end() && ext->second.Has("emissiveStrength")) {
            const double s = ext->second.Get("emissiveStrength").GetNumberAsDouble();
            if (std::isfinite(s) && s >= 0.0 && s <= 1e9) strength = float(s);
            else warn(w + ".extensions.KHR_materials_emissive_strength", "emissiveStrength must be in [0, 1e9]; using 1");
        }
        if (m.emissiveFactor.size() == 3)
            for (int c = 0; c < 3; ++c) {
                const double e = m.emissiveFactor[size_t(c)];
                out.emission[c] = std::isfinite(e) ? float(std::clamp(e, 0.0, 1.0)) * strength : 0.0f;
            }
        // KHR_materials_ior: the dielectric F0 of the index, ((ior - 1) / (ior + 1))^2 (1.5: the default 0.04),
        // and the refracted ray's bend (Material::ior; 0, the specular-glossiness conversion, bends none).
        if (auto ior = m.extensions.find("KHR_materials_ior"); ior != m.extensions.end() && ior->second.Has("ior")) {
            const double n = ior->second.Get("ior").GetNumberAsDouble();
            out.specular = glm::vec3(float(((n - 1.0) / (n + 1.0)) * ((n - 1.0) / (n + 1.0))));
            out.ior = std::isfinite(n) ? float(std::max(n, 1.0)) : 1.5f;
        }
        // KHR_materials_transmission: transmissionFactor x transmissionTexture.r of the dielectric base
        // refracts (Material::transmission); KHR_materials_volume: the volume under it, thicknessFactor x
        // thicknessTexture.g thick (model space; 0, the default, thin-walled), absorbing as
        // attenuationColor^(d / attenuationDistance) (default +inf: none). The schema refused values
        // outside the extensions' ranges; the clamps only keep the promise.
        auto number = [](const tinygltf::Value& v, const char* key, double fallback) {
            if (!v.Has(key) || !v.Get(key).IsNumber()) return fallback;
            const double x = v.Get(key).GetNumberAsDouble();
            return std::isfinite(x) ? x : fallback;
        };
        if (auto tr = m.extensions.find("KHR_materials_transmission"); tr != m.extensions.end()) {
            out.transmission = float(std::clamp(number(tr->second, "transmissionFactor", 0.0), 0.0, 1.0));
            const ExtensionTexture map = extensionTexture(m, "KHR_materials_transmission", "transmissionTexture");
            if (out.transmission > 0.0f)
                out.transmissionMap = texture(map.index, map.texCoord, map.extensions,
                                              w + ".extensions.KHR_materials_transmission.transmissionTexture");
        }
        if (auto vol = m.extensions.find("KHR_materials_volume"); vol != m.extensions.end()) {
            const tinygltf::Value& v = vol->second;
            out.thickness = float(std::max(number(v, "thicknessFactor", 0.0), 0.0));
            const double distance = v.Has("attenuationDistance") && v.Get("attenuationDistance").IsNumber()
                                        ? v.Get("attenuationDistance").GetNumberAsDouble()
                                        : std::numeric_limits<double>::infinity();
            out.attenuationDistance = distance > 0.0 ? float(distance) : std::numeric_limits<float>::infinity();
            if (v.Has("attenuationColor") && v.Get("attenuationColor").IsArray() && v.Get("attenuationColor").ArrayLen() == 3)
                for (int c = 0; c < 3; ++c) {
                    const double x = v.Get("attenuationColor").Get(c).GetNumberAsDouble();
                    out.attenuationColor[c] = std::isfinite(x) ? float(std::clamp(x, 0.0, 1.0)) : 1.0f;
                }
            const ExtensionTexture map = extensionTexture(m, "KHR_materials_volume", "thicknessTexture");
            if (out.transmission > 0.0f && out.thickness > 0.0f)
                out.thicknessMap =
                    texture(map.index, map.texCoord, map.extensions, w + ".extensions.KHR_materials_volume.thicknessTexture");
        }
        // KHR_materials_specular: the dielectric's F0 = min(F0_ior x specularColor, 1) x specular and its
        // f90 = specular, given (shaders/common/brdf.glsl's materialFresnelEnds), each factor times its
        // texture: `specular` keeps F0_ior x specularColorFactor (clamped with the texture, in the shader)
        // and dielectricF90 the factor. The schema refused values outside [0, 1] and colours below 0;
        // the clamps only keep the promise.
        if (auto sp = m.extensions.find("KHR_materials_specular"); sp != m.extensions.end()) {
            const tinygltf::Value& v = sp->second;
            const std::string sw = w + ".extensions.KHR_materials_specular";
            double weight = 1.0;
            if (v.Has("specularFactor") && v.Get("specularFactor").IsNumber()) weight = v.Get("specularFactor").GetNumberAsDouble();
            weight = std::isfinite(weight) ? std::clamp(weight, 0.0, 1.0) : 1.0;
            glm::dvec3 colour(1.0);
            if (v.Has("specularColorFactor") && v.Get("specularColorFactor").IsArray() &&
                v.Get("specularColorFactor").ArrayLen() == 3)
                for (int c = 0; c < 3; ++c) {
                    const double x = v.Get("specularColorFactor").Get(c).GetNumberAsDouble();
                    colour[c] = std::isfinite(x) ? std::max(x, 0.0) : 1.0;
                }
            out.specular = glm::vec3(glm::dvec3(out.specular) * colour);
            out.dielectricF90 = float(weight);
            const ExtensionTexture weightMap = extensionTexture(m, "KHR_materials_specular", "specularTexture");
            const ExtensionTexture colourMap = extensionTexture(m, "KHR_materials_specular", "specularColorTexture");
            out.specularMap = texture(weightMap.index, weightMap.texCoord, weightMap.extensions, sw + ".specularTexture");
            out.specularColorMap =
                texture(colourMap.index, colourMap.texCoord, colourMap.extensions, sw + ".specularColorTexture");
        }
        // KHR_materials_clearcoat: a GGX coat over the material (Material::clearcoat), each factor times its
        // texture (r, g), its own normal map or none. The schema refused factors outside [0, 1] and
        // non-numbers; the clamps only keep the promise. Next to KHR_materials_unlit (which the
        // extension excludes) the coat is dropped with the unlit material below.
        if (auto cc = m.extensions.find("KHR_materials_clearcoat"); cc != m.extensions.end()) {
            const tinygltf::Value& v = cc->second;
            const std::string cw = w + ".extensions.KHR_materials_clearcoat";
            auto factor = [&](const char* key) {
                double x = 0.0;
                if (v.Has(key) && v.Get(key).IsNumber()) x = v.Get(key).GetNumberAsDouble();
                return float(std::isfinite(x) ? std::clamp(x, 0.0, 1.0) : 0.0);
            };
            out.clearcoat = factor("clearcoatFactor");
            out.clearcoatRoughness = factor("clearcoatRoughnessFactor");
            const ExtensionTexture coat = extensionTexture(m, "KHR_materials_clearcoat", "clearcoatTexture");
            const ExtensionTexture roughness = extensionTexture(m, "KHR_materials_clearcoat", "clearcoatRoughnessTexture");
            const ExtensionTexture normal = extensionTexture(m, "KHR_materials_clearcoat", "clearcoatNormalTexture");
            if (out.clearcoat > 0.0f) {
                out.clearcoatMap = texture(coat.index, coat.texCoord, coat.extensions, cw + ".clearcoatTexture");
                out.clearcoatRoughnessMap =
                    texture(roughness.index, roughness.texCoord, roughness.extensions, cw + ".clearcoatRoughnessTexture");
                out.clearcoatNormalMap = texture(normal.index, normal.texCoord, normal.extensions, cw + ".clearcoatNormalTexture");
                if (v.Has("clearcoatNormalTexture") && v.Get("clearcoatNormalTexture").Has("scale") &&
                    v.Get("clearcoatNormalTexture").Get("scale").IsNumber()) {
                    const double scale = v.Get("clearcoatNormalTexture").Get("scale").GetNumberAsDouble();
                    out.clearcoatNormalScale = std::isfinite(scale) ? float(scale) : 1.0f;
                }
            }
        }
        // KHR_materials_unlit: the base colour as it is, untouched by light: lightpass's flat-lit material
        // (which shows base x (1 - metallic)).
        if (m.extensions.count("KHR_materials_unlit")) {
            out.flat = true;
            out.metallic = 0.0f;
        }
        out.doubleSided = m.doubleSided;
        out.alphaCutoff = std::isfinite(m.alphaCutoff) ? float(std::max(m.alphaCutoff, 0.0)) : 0.5f;
        if (m.alphaMode == "MASK") {
            out.alphaMode = AlphaMode::Mask;
        } else if (m.alphaMode == "BLEND") {
            out.alphaMode = AlphaMode::Blend;  // drawn by the transparent pass
        }
        return out;
    }

    // The rotation a node's (x, y, z, w) stands for: the spec asks for a unit quaternion. Another
    // length is normalised (divided by its largest component first, so that a denormal one such as
    // 1e-310 keeps its direction instead of collapsing to no rotation); length 0 is no rotation at all:
    // the identity. `problem` is set for either (empty for a unit quaternion, or one non-finite: the
    // transform check refuses that).
    static glm::dquat rotation(const std::vector<double>& q, std::string& problem) {
        problem.clear();
        if (q.size() != 4) return glm::dquat(1.0, 0.0, 0.0, 0.0);
        const glm::dvec4 v(q[0], q[1], q[2], q[3]);
        const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z), std::abs(v.w)});
        if (!std::isfinite(largest)) return glm::dquat(v.w, v.x, v.y, v.z);
        if (largest == 0.0) {
            problem = "zero";
            return glm::dquat(1.0, 0.0, 0.0, 0.0);
        }
        const glm::dvec4 scaled = v / largest;
        const double length = glm::length(scaled) * largest;
        if (std::abs(length - 1.0) > 1e-3) problem = "length";
        const glm::dvec4 unit = glm::normalize(scaled);
        return glm::dquat(unit.w, unit.x, unit.y, unit.z);
    }

    static glm::mat4 localMatrix(const tinygltf::Node& n, const glm::dquat& r) {
        if (n.matrix.size() == 16) {
            glm::dmat4 m;
            for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = n.matrix[size_t(i)];  // column-major, like glm
            return glm::mat4(m);
        }
        glm::dvec3 t(0.0), s(1.0);
        if (n.translation.size() == 3) t = glm::dvec3(n.translation[0], n.translation[1], n.translation[2]);
        if (n.scale.size() == 3) s = glm::dvec3(n.scale[0], n.scale[1], n.scale[2]);
        return glm::mat4(glm::translate(glm::dmat4(1.0), t) * glm::mat4_cast(r) * glm::scale(glm::dmat4(1.0), s));
    }
};

}  // namespace

// A perspective camera's yfov (radians; the schema made it > 0) as the renderer's vertical field of
// view in degrees, within its (0.5, 179) limits. At pi or above it is no field of view at all: 45
// degrees stands in; below or above the limits it is clamped; either with a warning.
template <typename Warn>
float gltfFieldOfView(double yfov, const std::string& where, Warn&& warn) {
    constexpr double kPi = 3.14159265358979323846;
    if (!(yfov < kPi)) {
        warn(where, formatNumber(yfov) + " rad is not below pi (a field of view under 180 degrees); 45 degrees used");
        return 45.0f;
    }
    const double degrees = yfov * 180.0 / kPi;
    if (degrees < 0.5) {
        warn(where, formatNumber(yfov) + " rad (" + formatNumber(degrees) + " degrees) is below the renderer's 0.5 degrees; 0.5 used");
        return 0.5f;
    }
    if (degrees > 179.0) {
        warn(where, formatNumber(yfov) + " rad (" + formatNumber(degrees) + " degrees) is above the renderer's 179 degrees; 179 used");
        return 179.0f;
    }
    return float(degrees);
}

// What the file gets wrong and the loader repairs, said once per kind and file: the first place, its
// count, and how many more in how many other places ("meshes[0].primitives[0].attributes.NORMAL
// (accessors[2]): 3 normals not finite or zero-length (and 9 more in 2 other accessors); each replaced
// by the normal of its triangles"). A place is counted once, however many nodes draw its mesh.
struct Repairs {
    struct Kind {
        std::string problem, repair, unit, first;
        size_t firstCount = 0, more = 0, otherPlaces = 0;
    };
    std::vector<Kind> kinds;
    std::set<std::pair<std::string, std::string>> counted;  // (problem, place)
    // `count` 0: the place as a whole (an accessor read as normalized), not a number of values.
    void add(const std::string& where, size_t count, const std::string& problem, const std::string& repair, const std::string& unit) {
        if (!counted.insert({problem, where}).second) return;
        for (Kind& k : kinds)
            if (k.problem == problem) {
                ++k.otherPlaces;
                k.more += count;
                return;
            }
        kinds.push_back({problem, repair, unit, where, count, 0, 0});
    }
    void warn(const Loader& L) const {
        for (const Kind& k : kinds) {
            std::string text = (k.firstCount ? std::to_string(k.firstCount) + " " : std::string()) + k.problem;
            if (k.otherPlaces)
                text += " (and " + (k.firstCount ? std::to_string(k.more) + " more " : std::string()) + "in " +
                        std::to_string(k.otherPlaces) + " other " + k.unit + ")";
            L.warn(k.first, text + "; " + k.repair);
        }
    }
};

GltfContent loadGltf(const fs::path& path, MeshLoadReport* reportOut, bool instanceReusedMeshes) {
    MeshLoadReport report;
    const std::string file = path.string();
    const std::string bytes = readFileChecked(path, kMaxImageFileBytes, "a glTF file");
    if (bytes.size() > 0xFFFFFFFFull) throw Error(file + ": over 4 GiB");
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    // Every check before tinygltf: the container's lengths, the JSON (depth, syntax, numbers), the
    // schema, the extensions, the buffers' data. tinygltf's own messages are raw ("Invalid glTF
    // binary.", the parser's exception text, a whole data URI) and its recursive walks of the document
    // overflowed the stack on deep nesting; what it is handed now it reads without complaint.
    GltfSource source = readGltfContainer(bytes, file, extension == ".glb");
    if (!source.binary) requireUtf8Text(path, source.json);
    const nlohmann::json root = parseJsonText(source.json, file);
    const std::vector<GltfSchemaIssue> schemaIssues = checkGltfSchema(root);
    for (const GltfSchemaIssue& issue : schemaIssues)
        if (issue.error) throw Error(file + ": " + issue.where + ": " + issue.what);
    // Before tinygltf, which would fail on what such an extension changes (a KHR_texture_basisu image is
    // KTX2) with a message that does not name the extension.
    if (const auto required = root.find("extensionsRequired"); required != root.end())
        for (size_t i = 0; i < required->size(); ++i) {
            const std::string name = (*required)[i].get<std::string>();
            if (kSupportedExtensions.count(name)) continue;
            // The material extensions as one group (KHR_materials_{clearcoat, ior, ...}): the list grows
            // with every extension, and the line must stay within a terminal line's 450 characters.
            const std::string group = "KHR_materials_";
            std::string supported, materials;
            for (const std::string& known : kSupportedExtensions) {
                if (known.rfind(group, 0) == 0) materials += (materials.empty() ? "" : ", ") + known.substr(group.size());
                else supported += (supported.empty() ? "" : ", ") + known;
            }
            if (!materials.empty()) supported += (supported.empty() ? "" : ", ") + group + "{" + materials + "}";
            // Quoted to 40 characters (every registered extension name is shorter).
            throw Error(file + ": extensionsRequired[" + std::to_string(i) + "]: " + quoteUserText(name, 40) +
                        " is not supported (supported: " + supported + ")");
        }
    const std::string baseDir = path.has_parent_path() ? path.parent_path().string() : std::string(".");
    const GltfCompressedParts compressed = findCompressedParts(root, source.binary);
    BufferFiles bufferFiles;
    checkBuffers(root, source, file, baseDir, compressed, bufferFiles);
    // Images: data URIs decoded here (one that does not decode becomes the checker with a warning;
    // tinygltf would refuse the whole file), external files named for SceneGpu to read.
    std::vector<ImageSource> images = imageSources(root, baseDir);
    std::string rewritten;  // the document as tinygltf gets it, where it differs from the file's
    {
        nlohmann::json forTinygltf;
        for (size_t i = 0; i < images.size(); ++i) {
            if (images[i].problem.empty()) continue;
            if (forTinygltf.is_null()) forTinygltf = root;
            forTinygltf["images"][i]["uri"] = "data:image/png;base64,AAAA";  // three zero bytes, which it passes on
        }
        if (!compressed.empty()) {
            if (forTinygltf.is_null()) forTinygltf = root;
            hideCompressedParts(compressed, forTinygltf);
        }
        if (!forTinygltf.is_null()) rewritten = forTinygltf.dump();
    }

    tinygltf::TinyGLTF gltf;
    gltf.SetFsCallbacks({&fileExists, &expandPath, &readWholeFile, &writeWholeFile, &bufferFiles});
    tinygltf::Model model;
    gltf.SetImageLoader(&keepEncodedImage, &model);
    std::string err, warnText;
    bool ok = false;
    if (source.binary) {
        const std::string glb = !rewritten.empty() || source.rebuild
                                    ? makeGlb(rewritten.empty() ? source.json : rewritten, source.bin, source.binBytes)
                                    : std::string();
        const std::string& handed = glb.empty() ? bytes : glb;
        ok = gltf.LoadBinaryFromMemory(&model, &err, &warnText, reinterpret_cast<const unsigned char*>(handed.data()),
                                       unsigned(handed.size()), baseDir);
    } else {
        const std::string& handed = rewritten.empty() ? source.json : rewritten;
        ok = gltf.LoadASCIIFromString(&model, &err, &warnText, handed.data(), unsigned(handed.size()), baseDir);
    }
    // What the checks above did not foresee, one line of it. Its warnings concern images only, which
    // are read by SceneGpu instead.
    if (!ok) throw Error(file + ": " + oneLineMessage(err.empty() ? std::string("could not be read as glTF") : err, 300));
    // Compressed buffer views and Draco meshes decoded: from here on every accessor reads plain bytes.
    decodeCompressedParts(model, root, compressed, file);
    Loader L{model, file, report, images};
    Repairs repairs;
    for (const std::string& w : source.warnings) report.warnings.push_back(file + ": " + w);
    for (const GltfSchemaIssue& issue : schemaIssues) L.warn(issue.where, issue.what);
    // An extension the file uses but does not require is optional to read, yet the model looks
    // different without it (a texture transform, clearcoat, transmission): say which are ignored.
    for (size_t i = 0; i < model.extensionsUsed.size(); ++i)
        if (!kSupportedExtensions.count(model.extensionsUsed[i]))
            L.warn("extensionsUsed[" + std::to_string(i) + "]",
                   quoteUserText(model.extensionsUsed[i]) + " is not supported; ignored (the model may look different)");

    GltfContent out;
    MeshData& mesh = out.mesh;
    mesh.name = path.stem().string();
    std::vector<int> materialSlot(model.materials.size() + 1, -1);  // glTF material (+1: default) -> mesh.materials
    auto materialFor = [&](int index) {
        if (index < -1 || index >= int(model.materials.size()))  // -1: none given (the default material)
            L.fail("materials", "material " + std::to_string(index) + " does not exist (" + std::to_string(model.materials.size()) + " materials)");
        int& slot = materialSlot[size_t(index + 1)];
        if (slot < 0) {
            slot = int(mesh.materials.size());
            mesh.materials.push_back(L.material(index));
        }
        return slot;
    };
    // KHR_materials_variants: the variants' names (the schema checked their types).
    if (auto ext = model.extensions.find("KHR_materials_variants"); ext != model.extensions.end()) {
        const tinygltf::Value& variants = ext->second.Get("variants");
        for (size_t i = 0; variants.IsArray() && i < variants.ArrayLen(); ++i)
            mesh.materialVariants.push_back(variants.Get(int(i)).Get("name").Get<std::string>());
    }
    // A primitive's material per variant: its mapping's, else its own (`material`); a mapping must name
    // a material and variants that exist, each variant at most once a primitive.
    auto variantMaterialsFor = [&](const tinygltf::Primitive& prim, int material, const std::string& w) {
        std::vector<int> perVariant;
        const auto ext = prim.extensions.find("KHR_materials_variants");
        if (ext == prim.extensions.end()) return perVariant;
        const std::string vw = w + ".extensions.KHR_materials_variants";
        if (mesh.materialVariants.empty())
            L.fail(vw, "maps materials to variants, but the file's extensions.KHR_materials_variants lists none");
        perVariant.assign(mesh.materialVariants.size(), material);
        std::vector<char> mapped(mesh.materialVariants.size(), 0);
        const tinygltf::Value& mappings = ext->second.Get("mappings");
        for (size_t i = 0; mappings.IsArray() && i < mappings.ArrayLen(); ++i) {
            const tinygltf::Value& m = mappings.Get(int(i));
            const std::string mw = vw + ".mappings[" + std::to_string(i) + "]";
            const int mat = m.Get("material").GetNumberAsInt();
            if (mat < 0 || mat >= int(model.materials.size()))
                L.fail(mw + ".material", "material " + std::to_string(mat) + " does not exist (" +
                                             std::to_string(model.materials.size()) + " materials)");
            const tinygltf::Value& vs = m.Get("variants");
            for (size_t k = 0; vs.IsArray() && k < vs.ArrayLen(); ++k) {
                const int v = vs.Get(int(k)).GetNumberAsInt();
                const std::string where = mw + ".variants[" + std::to_string(k) + "]";
                if (v < 0 || size_t(v) >= mesh.materialVariants.size())
                    L.fail(where, "variant " + std::to_string(v) + " does not exist (" +
                                      std::to_string(mesh.materialVariants.size()) + " variants)");
                if (mapped[size_t(v)]) L.fail(where, "variant " + std::to_string(v) + " is mapped twice in this primitive");
                mapped[size_t(v)] = 1;
                perVariant[size_t(v)] = materialFor(mat);
            }
        }
        return perVariant;
    };

    // KHR_mesh_quantization (gltfpack's output): integer positions and uvs, normalised integer
    // normals and tangents; the node transform (and a texture transform) scales them back.
    const bool quantized = std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(), "KHR_mesh_quantization") != model.extensionsUsed.end();
    const std::set<int> floats = {TINYGLTF_COMPONENT_TYPE_FLOAT};
    const std::set<int> integers = {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                    TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};
    const std::set<int> signedNormalised = {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT};
    const std::set<int> signedNormalisedOrUnsigned = {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                                      TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};
    const std::set<int>& positionTypes = quantized ? integers : floats;
    const std::set<int>& directionTypes = quantized ? signedNormalised : floats;  // normals and tangents
    const std::set<int> uvTypes = quantized ? integers
                                            : std::set<int>{TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                                            TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};
    const std::set<int> colorTypes = {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};
    std::set<std::string> noted;  // what notedOnce has seen
    auto notedOnce = [&noted](const std::string& what) { return noted.insert(what).second; };
    // What the last addPrimitive appended: for each vertex the accessor element it came from (flat
    // normals and tangent seams copy vertices), and whether its normals and tangents are the file's
    // (a skin's joints and a morph target's deltas are read per element and follow the copies).
    struct EmittedPrimitive {
        std::vector<uint32_t> source;
        bool fileNormals = false, fileTangents = false;
        size_t elements = 0;  // the POSITION accessor's count
    } emitted;
    auto addPrimitive = [&](int meshIndex, int primIndex, const glm::mat4& world) {
        const tinygltf::Primitive& prim = model.meshes[size_t(meshIndex)].primitives[size_t(primIndex)];
        const std::string w = "meshes[" + std::to_string(meshIndex) + "].primitives[" + std::to_string(primIndex) + "]";
        emitted = EmittedPrimitive{};
        if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP && prim.mode != TINYGLTF_MODE_TRIANGLE_FAN) {
            L.warn(w, "mode " + std::to_string(prim.mode) + " (points or lines) is not drawn");
            return;
        }
        auto attr = prim.attributes.find("POSITION");
        if (attr == prim.attributes.end()) L.fail(w, "has no POSITION attribute");
        // Without a buffer view and not sparse, every element is zero: no triangle could come of it, and
        // its count, bounded by no bytes of the file, would size the allocations.
        const tinygltf::Accessor* positions =
            attr->second >= 0 && size_t(attr->second) < model.accessors.size() ? &model.accessors[size_t(attr->second)] : nullptr;
        if (positions && positions->bufferView < 0 && !positions->sparse.isSparse && positions->count > 0)
            L.fail(w + ".attributes.POSITION (accessors[" + std::to_string(attr->second) + "])",
                   "has no bufferView and is not sparse, so its " + std::to_string(positions->count) + " elements would all be zero");
        const auto pos = L.view(attr->second, w + ".attributes.POSITION", {TINYGLTF_TYPE_VEC3}, positionTypes);
        const size_t vertexCount = pos.count;
        // An attribute's accessor as the warnings name it: meshes[0].primitives[1].attributes.NORMAL (accessors[4]).
        std::map<std::string, std::string> named;
        auto optional = [&](const char* name, const std::set<int>& types, const std::set<int>& componentTypes, Loader::View& v) {
            auto it = prim.attributes.find(name);
            if (it == prim.attributes.end()) return false;
            v = L.view(it->second, w + ".attributes." + name, types, componentTypes, vertexCount);
            named[name] = w + ".attributes." + name + " (accessors[" + std::to_string(it->second) + "])";
            return true;
        };
        Loader::View nrm, uv, uv1, tan, col;
        const bool hasNormals = optional("NORMAL", {TINYGLTF_TYPE_VEC3}, directionTypes, nrm);
        const bool hasUv = optional("TEXCOORD_0", {TINYGLTF_TYPE_VEC2}, uvTypes, uv);
        // TEXCOORD_1, read when the material samples it; where the primitive lacks it (the file is
        // then invalid) its textures read TEXCOORD_0, said once per material.
        const Loader::MaterialUvSets uvSets = L.materialUvSets(prim.material);
        const bool hasUv1 = uvSets.reads[1] && optional("TEXCOORD_1", {TINYGLTF_TYPE_VEC2}, uvTypes, uv1);
        if (uvSets.reads[1] && !hasUv1 && notedOnce("no TEXCOORD_1 for materials[" + std::to_string(prim.material) + "]"))
            L.warn(w + ".attributes", "has no TEXCOORD_1, which materials[" + std::to_string(prim.material) +
                                          "] samples; those textures read TEXCOORD_0");
        // Integer texture coordinates must be normalized (the spec's attribute table) unless
        // KHR_mesh_quantization allows raw integers (scaled by a texture transform): read as normalised,
        // with a warning, rather than as coordinates up to 255 or 65535.
        for (auto [set, view] : {std::pair<const char*, Loader::View*>{"TEXCOORD_0", hasUv ? &uv : nullptr},
                                 std::pair<const char*, Loader::View*>{"TEXCOORD_1", hasUv1 ? &uv1 : nullptr}})
            if (view && !quantized && view->componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !view->normalized) {
                repairs.add(named[set], 0, "integer texture coordinates without \"normalized\": true (required without KHR_mesh_quantization)",
                            "read as normalized", "accessors");
                view->normalized = true;
            }
        // COLOR_0: linear RGB or RGBA multiplying the base colour; float, or normalised unsigned bytes
        // or shorts (the spec requires `normalized`; an integer accessor without it is read as
        // normalised, with a warning, rather than as colours up to 255 or 65535).
        const bool hasColors = optional("COLOR_0", {TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4}, colorTypes, col);
        if (hasColors && col.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !col.normalized) {
            repairs.add(named["COLOR_0"], 0, "integer colours without \"normalized\": true (the spec requires it)", "read as normalized",
                        "accessors");
            col.normalized = true;
        }
        const int colorComponents = hasColors ? std::min(col.components, 4) : 0;
        size_t colorsClamped = 0;
        // KHR_texture_transform: applied to the uvs here. Where it turns or flips the uv axes of the
        // normal map's set, the file's tangents (made for the untransformed uvs) are replaced by
        // generated ones.
        bool hasTangents = optional("TANGENT", {TINYGLTF_TYPE_VEC4}, directionTypes, tan) && !uvSets.transform[uvSets.normalSet].turnsAxes();

        // Triangle list, as vertex numbers of this primitive.
        std::vector<uint32_t> corners;
        if (prim.indices >= 0) {
            const auto idx = L.view(prim.indices, w + ".indices", {TINYGLTF_TYPE_SCALAR},
                                    {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                     TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
            corners.resize(idx.count);
            for (size_t i = 0; i < idx.count; ++i) {
                corners[i] = Loader::index(idx, i);
                if (corners[i] >= vertexCount)
                    L.fail(w + ".indices", "index " + std::to_string(corners[i]) + " at position " + std::to_string(i) +
                                               " is beyond the " + std::to_string(vertexCount) + " vertices");
            }
        } else {
            corners.resize(vertexCount);
            for (size_t i = 0; i < vertexCount; ++i) corners[i] = uint32_t(i);
        }
        std::vector<uint32_t> tris;
        if (prim.mode == TINYGLTF_MODE_TRIANGLES) {
            tris.assign(corners.begin(), corners.begin() + ptrdiff_t(corners.size() / 3 * 3));
        } else if (prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            for (size_t i = 2; i < corners.size(); ++i) {
                const bool odd = (i & 1) != 0;
                tris.insert(tris.end(), {corners[i - 2 + (odd ? 1 : 0)], corners[i - 1 - (odd ? 1 : 0)], corners[i]});
            }
        } else {
            for (size_t i = 2; i < corners.size(); ++i) tris.insert(tris.end(), {corners[0], corners[i - 1], corners[i]});
        }

        const glm::mat3 linear(world);
        const glm::mat3 normalMatrix = glm::inverseTranspose(linear);
        const bool mirrored = glm::determinant(linear) < 0.0f;
        MeshData part;
        part.vertices.resize(vertexCount);
        std::vector<uint32_t> source(vertexCount);  // each vertex's accessor element
        for (size_t v = 0; v < vertexCount; ++v) source[v] = uint32_t(v);
        // Vertices whose normal from the file is not finite or zero-length: given their triangles' normal below.
        std::vector<uint32_t> badNormals;
        size_t badUvs = 0, badUvs1 = 0, badTangents = 0;
        for (size_t v = 0; v < vertexCount; ++v) {
            Vertex& vx = part.vertices[v];
            const glm::vec3 p(Loader::component(pos, v, 0), Loader::component(pos, v, 1), Loader::component(pos, v, 2));
            vx.position = glm::vec3(world * glm::vec4(p, 1.0f));
            if (hasNormals) {
                const glm::vec3 file(Loader::component(nrm, v, 0), Loader::component(nrm, v, 1), Loader::component(nrm, v, 2));
                const glm::vec3 n = normalMatrix * file;
                const float len = glm::length(n);
                if (len > 0.0f && std::isfinite(len) && std::isfinite(glm::length(file))) {
                    vx.normal = n / len;
                } else {
                    vx.normal = glm::vec3(0.0f, 1.0f, 0.0f);
                    badNormals.push_back(uint32_t(v));
                }
            }
            // A set's uvs through its transform, flipped to v = 0 at the bottom; not finite: 0, counted.
            auto uvOf = [&](const Loader::View& view, const Loader::UvTransform& transform, glm::vec2& out) {
                glm::vec2 t(Loader::component(view, v, 0), Loader::component(view, v, 1));
                if (!transform.identity()) t = glm::vec2(transform.linear * glm::dvec2(t) + transform.offset);
                if (!std::isfinite(t.x) || !std::isfinite(t.y)) return false;
                out = glm::vec2(t.x, 1.0f - t.y);
                return true;
            };
            if (hasUv && !uvOf(uv, uvSets.transform[0], vx.uv)) ++badUvs;
            if (hasUv1 && !uvOf(uv1, uvSets.transform[1], vx.uv1)) ++badUvs1;
            else if (!hasUv1 && uvSets.reads[1] && hasUv) uvOf(uv, uvSets.transform[1], vx.uv1);
            if (hasColors) {
                glm::vec4 c(1.0f);
                for (int k = 0; k < colorComponents; ++k) c[k] = Loader::component(col, v, k);
                // A colour multiplies the base colour: outside [0, 1] (or not a number) it would add
                // energy or poison the image. A NaN or Inf component differs from its clamp too.
                const glm::vec4 clamped = glm::clamp(c, glm::vec4(0.0f), glm::vec4(1.0f));
                if (clamped != c) ++colorsClamped;
                for (int k = 0; k < 4; ++k) vx.color[k] = std::isfinite(c[k]) ? clamped[k] : 1.0f;
            }
            if (hasTangents) {
                // glTF's bitangent cross(N, T) w points up the image (its normal maps' +Y), which is
                // +v after the flip: w is kept. A mirroring transform flips the frame's handedness.
                const glm::vec3 t = linear * glm::vec3(Loader::component(tan, v, 0), Loader::component(tan, v, 1), Loader::component(tan, v, 2));
                const float w4 = Loader::component(tan, v, 3);
                const float len = glm::length(t);
                const float hand = (w4 < 0.0f ? -1.0f : 1.0f) * (mirrored ? -1.0f : 1.0f);
                // w is +-1 (the handedness); anything else, or no direction, is a tangent the file got
                // wrong: the primitive's tangents are then generated instead.
                if (len > 0.0f && std::isfinite(len) && std::abs(std::abs(w4) - 1.0f) <= 1e-3f) vx.tangent = glm::vec4(t / len, hand);
                else ++badTangents;
            }
        }
        if (colorsClamped > 0)
            repairs.add(named["COLOR_0"], colorsClamped, "colours outside [0, 1] or not finite", "clamped (not finite: 1)",
                        "accessors");
        if (badUvs > 0)
            repairs.add(named["TEXCOORD_0"], badUvs, "texture coordinates not finite", "read as 0", "accessors");
        if (badUvs1 > 0)
            repairs.add(named["TEXCOORD_1"], badUvs1, "texture coordinates not finite", "read as 0", "accessors");
        if (badTangents > 0) {
            repairs.add(named["TANGENT"], badTangents, "tangents not finite, zero-length or with w other than 1 or -1",
                        "the primitive's tangents generated instead (MikkTSpace)", "accessors");
            hasTangents = false;
        }
        // Triangles: non-finite and degenerate ones dropped (as for OBJ); a mirroring transform
        // reverses the winding so that front faces stay front faces.
        for (size_t i = 0; i + 2 < tris.size(); i += 3) {
            uint32_t a = tris[i], b = tris[i + 1], c = tris[i + 2];
            const glm::vec3 &pa = part.vertices[a].position, &pb = part.vertices[b].position, &pc = part.vertices[c].position;
            // Past 1e18 a squared length overflows a float (NaN normals): such a vertex counts as Inf, as in OBJ.
            auto usable = [](const glm::vec3& p) { return glm::all(glm::lessThanEqual(glm::abs(p), glm::vec3(1e18f))); };
            if (!usable(pa) || !usable(pb) || !usable(pc)) {
                ++report.droppedNonFinite;
                continue;
            }
            if (a == b || b == c || a == c || degenerateTriangle(pa, pb, pc)) {
                ++report.droppedDegenerate;
                continue;
            }
            if (mirrored) std::swap(b, c);
            part.indices.insert(part.indices.end(), {a, b, c});
        }
        if (part.indices.empty()) return;
        if (!badNormals.empty()) {
            // The area-weighted normal of the triangles around each such vertex (its smooth normal).
            std::vector<glm::dvec3> sum(part.vertices.size(), glm::dvec3(0.0));
            for (size_t i = 0; i + 2 < part.indices.size(); i += 3) {
                const uint32_t a = part.indices[i], b = part.indices[i + 1], c = part.indices[i + 2];
                const glm::dvec3 pa(part.vertices[a].position), pb(part.vertices[b].position), pc(part.vertices[c].position);
                const glm::dvec3 n = glm::cross(pb - pa, pc - pa);
                for (uint32_t k : {a, b, c}) sum[k] += n;
            }
            for (uint32_t v : badNormals)
                if (glm::length(sum[v]) > 0.0) part.vertices[v].normal = glm::vec3(glm::normalize(sum[v]));
            repairs.add(named["NORMAL"], badNormals.size(), "normals not finite or zero-length",
                        "each replaced by the normal of its triangles", "accessors");
        }
        if (!hasNormals) {
            // The spec's rule: flat normals. Each triangle gets its own three vertices.
            MeshData flat;
            std::vector<uint32_t> flatSource;
            for (size_t i = 0; i + 2 < part.indices.size(); i += 3) {
                for (int k = 0; k < 3; ++k) flatSource.push_back(source[part.indices[i + size_t(k)]]);
                const Vertex &a = part.vertices[part.indices[i]], &b = part.vertices[part.indices[i + 1]], &c = part.vertices[part.indices[i + 2]];
                // In double: at coordinates near 1e18 the cross product's squared length overflows a float.
                const glm::vec3 n(glm::normalize(glm::cross(glm::dvec3(b.position - a.position), glm::dvec3(c.position - a.position))));
                for (const Vertex* src : {&a, &b, &c}) {
                    Vertex vx = *src;
                    vx.normal = n;
                    flat.indices.push_back(uint32_t(flat.vertices.size()));
                    flat.vertices.push_back(vx);
                }
            }
            part.vertices = std::move(flat.vertices);
            part.indices = std::move(flat.indices);
            source = std::move(flatSource);
            report.generatedNormals = true;
        }
        if (!hasTangents) {
            // Tangents follow the normal map's uv set: MikkTSpace on TEXCOORD_1 when it reads that.
            auto swapSets = [&part] {
                for (Vertex& vx : part.vertices) std::swap(vx.uv, vx.uv1);
            };
            if (uvSets.normalSet == 1) swapSets();
            std::vector<uint32_t> copiedFrom;
            computeTangents(part, &copiedFrom);
            for (uint32_t c : copiedFrom) source.push_back(source[c]);
            if (uvSets.normalSet == 1) swapSets();
            report.generatedTangents = true;
        }
        const int mat = materialFor(prim.material);
        const uint32_t base = uint32_t(mesh.vertices.size());
        if (mesh.vertices.size() + part.vertices.size() > 0xFFFFFFFFull) L.fail(w, "too many vertices in the file");
        SubMesh sub{uint32_t(mesh.indices.size()), uint32_t(part.indices.size()), mat};
        sub.defaultMaterial = mat;
        sub.variantMaterials = variantMaterialsFor(prim, mat, w);
        mesh.subMeshes.push_back(sub);
        for (uint32_t i : part.indices) mesh.indices.push_back(base + i);
        mesh.vertices.insert(mesh.vertices.end(), part.vertices.begin(), part.vertices.end());
        emitted.source = std::move(source);
        emitted.fileNormals = hasNormals;
        emitted.fileTangents = hasTangents;
        emitted.elements = vertexCount;
    };

    // Animations, every clip checked whole before anything is drawn (docs/bad-input.md): a channel's
    // node, path and sampler, a sampler's interpolation, its key times (finite, strictly increasing)
    // and values (finite, as many as the interpolation needs; a weights channel's, one a morph target
    // of its node's mesh).
    auto animation = std::make_shared<NodeAnimation>();
    std::vector<char> targeted(model.nodes.size(), 0);
    size_t pointerChannels = 0;
    std::string firstPointerChannel;
    // The morph targets of a mesh (every primitive has as many, checked where the mesh is drawn).
    auto meshTargets = [&](int meshIndex) -> size_t {
        if (meshIndex < 0 || size_t(meshIndex) >= model.meshes.size() || model.meshes[size_t(meshIndex)].primitives.empty()) return 0;
        return model.meshes[size_t(meshIndex)].primitives[0].targets.size();
    };
    for (size_t a = 0; a < model.animations.size(); ++a) {
        const tinygltf::Animation& an = model.animations[a];
        const std::string aw = "animations[" + std::to_string(a) + "]";
        AnimationClip clip;
        clip.name = an.name;
        std::vector<int> samplerSlot(an.samplers.size(), -1);  // an.samplers -> clip.samplers
        std::vector<AnimationPath> samplerPath(an.samplers.size());
        std::vector<size_t> samplerWeights(an.samplers.size(), 0);  // a weights sampler's values a key
        std::set<std::pair<int, int>> moved;  // (node, path) of this clip's channels
        for (size_t c = 0; c < an.channels.size(); ++c) {
            const tinygltf::AnimationChannel& ch = an.channels[c];
            const std::string cw = aw + ".channels[" + std::to_string(c) + "]";
            if (ch.sampler < 0 || size_t(ch.sampler) >= an.samplers.size())
                L.fail(cw + ".sampler", std::to_string(ch.sampler) + " does not exist (" + aw + " has " +
                                            std::to_string(an.samplers.size()) + " samplers)");
            AnimationPath path = AnimationPath::Translation;
            if (ch.target_path == "rotation") path = AnimationPath::Rotation;
            else if (ch.target_path == "scale") path = AnimationPath::Scale;
            else if (ch.target_path == "weights") path = AnimationPath::Weights;
            else if (ch.target_path != "translation")
                L.fail(cw + ".target.path", quoteUserText(ch.target_path) + " is not translation, rotation, scale or weights");
            if (ch.target_node < 0) {  // an extension (KHR_animation_pointer) says what moves
                if (pointerChannels++ == 0) firstPointerChannel = cw;
                continue;
            }
            const std::string nw = "nodes[" + std::to_string(ch.target_node) + "]";
            if (size_t(ch.target_node) >= model.nodes.size())
                L.fail(cw + ".target.node", std::to_string(ch.target_node) + " does not exist (" + std::to_string(model.nodes.size()) + " nodes)");
            if (path != AnimationPath::Weights && model.nodes[size_t(ch.target_node)].matrix.size() == 16)
                L.fail(cw + ".target.node", nw + " has a matrix; an animated node must have translation, rotation and scale instead");
            const size_t weightCount = path == AnimationPath::Weights ? meshTargets(model.nodes[size_t(ch.target_node)].mesh) : 0;
            if (path == AnimationPath::Weights && weightCount == 0)
                L.fail(cw + ".target.node", nw + " has no mesh with morph targets for its weights to move");
            if (!moved.insert({ch.target_node, int(path)}).second)
                L.fail(cw + ".target", nw + " " + ch.target_path + " is already the target of another channel of " + aw);
            const AnimationPath sharedPath = samplerPath[size_t(ch.sampler)];
            if (samplerSlot[size_t(ch.sampler)] >= 0 && sharedPath != path &&
                (path == AnimationPath::Rotation || sharedPath == AnimationPath::Rotation || path == AnimationPath::Weights ||
                 sharedPath == AnimationPath::Weights))
                L.fail(cw + ".sampler", std::to_string(ch.sampler) + " also drives a channel of another type (a rotation's values are VEC4, a translation's and scale's VEC3, weights SCALAR)");
            if (samplerSlot[size_t(ch.sampler)] >= 0 && path == AnimationPath::Weights && samplerWeights[size_t(ch.sampler)] != weightCount)
                L.fail(cw + ".sampler", std::to_string(ch.sampler) + " also drives the weights of a mesh with " +
                                            std::to_string(samplerWeights[size_t(ch.sampler)]) + " morph targets; " + nw + "'s has " +
                                            std::to_string(weightCount));
            if (samplerSlot[size_t(ch.sampler)] < 0) {
                samplerSlot[size_t(ch.sampler)] = int(clip.samplers.size());
                samplerPath[size_t(ch.sampler)] = path;
                samplerWeights[size_t(ch.sampler)] = weightCount;
                clip.samplers.emplace_back();
            }
            clip.channels.push_back({ch.target_node, path, samplerSlot[size_t(ch.sampler)]});
            targeted[size_t(ch.target_node)] = 1;
        }
        for (size_t s = 0; s < an.samplers.size(); ++s) {
            if (samplerSlot[s] < 0) continue;  // drives no channel lightpass applies
            const tinygltf::AnimationSampler& sm = an.samplers[s];
            const std::string sw = aw + ".samplers[" + std::to_string(s) + "]";
            AnimationSampler& out = clip.samplers[size_t(samplerSlot[s])];
            const auto named = std::find_if(std::begin(kAnimationInterpolationNames), std::end(kAnimationInterpolationNames),
                                            [&](const AnimationInterpolationName& n) { return sm.interpolation == n.name; });
            if (named == std::end(kAnimationInterpolationNames))
                L.fail(sw + ".interpolation", quoteUserText(sm.interpolation) + " is not LINEAR, STEP or CUBICSPLINE");
            out.interpolation = named->interpolation;
            const bool rotation = samplerPath[s] == AnimationPath::Rotation;
            const bool weights = samplerPath[s] == AnimationPath::Weights;
            const std::string iw = sw + ".input (accessors[" + std::to_string(sm.input) + "])";
            const std::string ow = sw + ".output (accessors[" + std::to_string(sm.output) + "])";
            const Loader::View in = L.view(sm.input, sw + ".input", {TINYGLTF_TYPE_SCALAR}, {TINYGLTF_COMPONENT_TYPE_FLOAT});
            // A rotation and morph weights may be normalised integers (KHR_mesh_quantization's and the spec's table).
            const Loader::View values =
                L.view(sm.output, sw + ".output", {rotation ? TINYGLTF_TYPE_VEC4 : weights ? TINYGLTF_TYPE_SCALAR : TINYGLTF_TYPE_VEC3},
                       rotation || weights ? signedNormalisedOrUnsigned : floats);
            if (values.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !values.normalized)
                L.fail(ow, std::string("integer ") + (weights ? "weights" : "rotations") + " must be \"normalized\"");
            const size_t perKey = out.interpolation == AnimationInterpolation::CubicSpline ? 3 : 1;
            if (in.count == 0) L.fail(iw, "has no key times");
            if (perKey == 3 && in.count < 2) L.fail(iw, "CUBICSPLINE needs at least 2 key times, this has 1");
            if (weights) {
                // One value a morph target a key: CUBICSPLINE's in-tangents of every target, their values, their out-tangents.
                const size_t n = samplerWeights[s];
                if (values.count != in.count * perKey * n)
                    L.fail(ow, std::to_string(values.count) + " values for " + std::to_string(in.count) + " key times of " + std::to_string(n) +
                                   " morph weights: " + sm.interpolation + " needs " + std::to_string(in.count * perKey * n) +
                                   (perKey == 3 ? " (in-tangents, values, out-tangents of every weight, a key)" : " (every weight, a key)"));
            } else if (values.count != in.count * perKey)
                L.fail(ow, std::to_string(values.count) + " values for " + std::to_string(in.count) + " key times: " + sm.interpolation +
                               " needs " + std::to_string(in.count * perKey) + (perKey == 3 ? " (in-tangent, value, out-tangent a key)" : " (one a key)"));
            out.times.resize(in.count);
            for (size_t k = 0; k < in.count; ++k) {
                const float t = Loader::component(in, k, 0);
                if (!std::isfinite(t)) L.fail(iw, "key time " + std::to_string(k) + " is not finite");
                if (k > 0 && !(t > out.times[k - 1]))
                    L.fail(iw, "key time " + std::to_string(k) + " (" + formatNumber(t) + ") is not after key time " + std::to_string(k - 1) +
                                   " (" + formatNumber(out.times[k - 1]) + "): key times must increase");
                out.times[k] = t;
            }
            if (weights) {
                out.weightCount = uint32_t(samplerWeights[s]);
                out.weights.resize(values.count);
                for (size_t k = 0; k < values.count; ++k) {
                    out.weights[k] = Loader::component(values, k, 0);
                    if (!std::isfinite(out.weights[k])) L.fail(ow, "value " + std::to_string(k) + " is not finite");
                }
                clip.duration = std::max(clip.duration, out.times.back());
                continue;
            }
            out.values.resize(values.count);
            for (size_t k = 0; k < values.count; ++k) {
                glm::vec4 v(0.0f);
                for (int i = 0; i < (rotation ? 4 : 3); ++i) v[i] = Loader::component(values, k, i);
                if (!std::isfinite(v.x + v.y + v.z + v.w)) L.fail(ow, "value " + std::to_string(k) + " is not finite");
                out.values[k] = v;
            }
            // A key rotation of length 0 is no rotation (slerp needs a direction); a tangent may be 0.
            if (rotation)
                for (size_t k = perKey == 3 ? 1 : 0; k < values.count; k += perKey)
                    if (glm::length(out.values[k]) == 0.0f) L.fail(ow, "value " + std::to_string(k) + " is a rotation of length 0");
            clip.duration = std::max(clip.duration, out.times.back());
        }
        animation->clips.push_back(std::move(clip));
    }
    if (pointerChannels > 0)
        L.warn(firstPointerChannel, std::to_string(pointerChannels) + " channel" + (pointerChannels > 1 ? "s" : "") +
                                        " without a target node (an extension's target); ignored");
    animation->nodes.resize(model.nodes.size());

    // The scene's nodes, depth first; a node met twice on one path is a cycle.
    std::vector<int> roots;
    int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : (model.scenes.empty() ? -1 : 0);
    if (sceneIndex >= int(model.scenes.size())) L.fail("scene", std::to_string(sceneIndex) + " does not exist");
    if (sceneIndex >= 0) {
        roots = model.scenes[size_t(sceneIndex)].nodes;
    } else {
        std::vector<bool> isChild(model.nodes.size(), false);
        for (const auto& n : model.nodes)
            for (int c : n.children)
                if (c >= 0 && size_t(c) < model.nodes.size()) isChild[size_t(c)] = true;
        for (size_t i = 0; i < model.nodes.size(); ++i)
            if (!isChild[i]) roots.push_back(int(i));
    }
    // The node trees are checked before anything is built. glTF nodes form strict trees: a node reached
    // twice (a second parent, or a root listed twice) is refused, so that a file cannot ask for 2^40
    // walks by naming a child twice on each of 40 levels; depth is bounded so that a chain 200000 nodes
    // deep cannot overflow the stack; the instanced primitives and vertices are bounded so that 2000
    // nodes drawing one mesh of 20000 primitives cannot take minutes and gigabytes.
    // How many nodes draw each mesh with nothing moving it (no clip on the node or above, no skin, no
    // morph targets): a mesh two of them draw is stored once (instanceReusedMeshes).
    std::vector<size_t> stillUses(model.meshes.size(), 0);
    {
        std::vector<int> parent(model.nodes.size(), -1);
        std::vector<bool> reached(model.nodes.size(), false);
        std::vector<char> moves(model.nodes.size(), 0);  // a clip moves the node or an ancestor
        size_t drawnPrimitives = 0, drawnVertices = 0;
        struct Pending {
            int node, parent;
            size_t depth;
        };
        std::vector<Pending> stack;
        for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, -1, 1});
        while (!stack.empty()) {
            const Pending p = stack.back();
            stack.pop_back();
            const std::string from = p.parent < 0 ? (sceneIndex >= 0 ? "scenes[" + std::to_string(sceneIndex) + "].nodes" : "nodes")
                                                  : "nodes[" + std::to_string(p.parent) + "].children";
            if (p.node < 0 || size_t(p.node) >= model.nodes.size())
                L.fail(from, "node " + std::to_string(p.node) + " does not exist (" + std::to_string(model.nodes.size()) + " nodes)");
            const std::string w = "nodes[" + std::to_string(p.node) + "]";
            if (reached[size_t(p.node)]) {
                for (int a = p.parent; a >= 0; a = parent[size_t(a)])
                    if (a == p.node) L.fail(w, "is its own ancestor (the node hierarchy has a cycle)");
                L.fail(w, "is reached twice (from " + from + "); a glTF node has at most one parent and is not also a scene root");
            }
            if (p.depth > kMaxNodeDepth) L.fail(w, "is more than " + std::to_string(kMaxNodeDepth) + " levels deep in the node hierarchy");
            reached[size_t(p.node)] = true;
            parent[size_t(p.node)] = p.parent;
            const tinygltf::Node& node = model.nodes[size_t(p.node)];
            moves[size_t(p.node)] = targeted[size_t(p.node)] || (p.parent >= 0 && moves[size_t(p.parent)]);
            if (node.mesh >= 0 && size_t(node.mesh) < model.meshes.size() && !moves[size_t(p.node)] && node.skin < 0 &&
                meshTargets(node.mesh) == 0)
                stillUses[size_t(node.mesh)] += node.extensions.count("EXT_mesh_gpu_instancing") ? 2 : 1;  // instances: reused
            if (node.mesh >= 0 && size_t(node.mesh) < model.meshes.size())
                for (const auto& prim : model.meshes[size_t(node.mesh)].primitives) {
                    ++drawnPrimitives;
                    auto position = prim.attributes.find("POSITION");
                    if (position != prim.attributes.end() && position->second >= 0 && size_t(position->second) < model.accessors.size())
                        drawnVertices += std::min(model.accessors[size_t(position->second)].count, kMaxElements);
                    if (prim.indices >= 0 && size_t(prim.indices) < model.accessors.size())
                        drawnVertices += std::min(model.accessors[size_t(prim.indices)].count, kMaxElements);  // flat shading makes one vertex per corner
                }
            if (drawnPrimitives > kMaxDrawnPrimitives || drawnVertices > kMaxDrawnVertices)
                L.fail(w + ".mesh", "the scene's nodes draw more than " + std::to_string(kMaxDrawnPrimitives) + " primitives or " +
                                        std::to_string(kMaxDrawnVertices) + " vertices and indices in all");
            for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) stack.push_back({*it, p.node, p.depth + 1});
        }
    }
    // glTF cone half-angles (radians, 0 <= inner < outer <= pi/2) as the renderer's (degrees, outer < 90).
    auto spotCone = [&](const tinygltf::SpotLight& s, const glm::vec3& direction, const std::string& lw) {
        const double inner = s.innerConeAngle, outer = s.outerConeAngle;
        if (!std::isfinite(inner) || !std::isfinite(outer))
            L.fail(lw + ".spot", "innerConeAngle and outerConeAngle must be finite");
        if (inner < 0.0) L.fail(lw + ".spot.innerConeAngle", formatNumber(inner) + " rad: must be >= 0");
        if (!(outer > inner))
            L.fail(lw + ".spot.outerConeAngle", formatNumber(outer) + " rad must be greater than innerConeAngle " + formatNumber(inner));
        if (!std::isfinite(direction.x + direction.y + direction.z)) L.fail(lw, "the spot's node has no -Z direction (a zero scale)");
        SpotCone c;
        c.direction = direction;
        c.outerDegrees = float(glm::degrees(outer));
        c.innerDegrees = float(glm::degrees(inner));
        // The renderer's cone stays below a hemisphere; glTF allows up to pi/2.
        constexpr float kMaxOuterDegrees = 89.0f;
        if (c.outerDegrees > kMaxOuterDegrees) {
            L.warn(lw + ".spot.outerConeAngle", formatNumber(c.outerDegrees) + " degrees clamped to " + formatNumber(kMaxOuterDegrees));
            c.outerDegrees = kMaxOuterDegrees;
            c.innerDegrees = std::min(c.innerDegrees, c.outerDegrees);
        }
        return c;
    };
    // Skins, read once each where a drawn node first uses one: joints that exist, inverse bind
    // matrices (identity when absent) that are finite, at least one a joint.
    std::vector<int> skinSlot(model.skins.size(), -1);
    auto skinFor = [&](int index, const std::string& nw) {
        if (index < 0 || size_t(index) >= model.skins.size())
            L.fail(nw + ".skin", std::to_string(index) + " does not exist (" + std::to_string(model.skins.size()) + " skins)");
        int& slot = skinSlot[size_t(index)];
        if (slot >= 0) return slot;
        const tinygltf::Skin& sk = model.skins[size_t(index)];
        const std::string sw = "skins[" + std::to_string(index) + "]";
        if (sk.joints.empty()) L.fail(sw + ".joints", "is empty (a skin needs at least one joint)");
        Skin skin;
        for (size_t j = 0; j < sk.joints.size(); ++j)
            if (sk.joints[j] < 0 || size_t(sk.joints[j]) >= model.nodes.size())
                L.fail(sw + ".joints[" + std::to_string(j) + "]", "node " + std::to_string(sk.joints[j]) + " does not exist (" +
                                                                    std::to_string(model.nodes.size()) + " nodes)");
        skin.joints = sk.joints;
        skin.inverseBind.assign(sk.joints.size(), glm::mat4(1.0f));
        if (sk.inverseBindMatrices >= 0) {
            const std::string iw = sw + ".inverseBindMatrices (accessors[" + std::to_string(sk.inverseBindMatrices) + "])";
            const Loader::View m = L.view(sk.inverseBindMatrices, sw + ".inverseBindMatrices", {TINYGLTF_TYPE_MAT4}, floats);
            if (m.count < sk.joints.size())
                L.fail(iw, std::to_string(m.count) + " matrices for " + std::to_string(sk.joints.size()) + " joints (one a joint)");
            for (size_t j = 0; j < sk.joints.size(); ++j)
                for (int c = 0; c < 16; ++c) {
                    const float f = Loader::component(m, j, c);  // column-major, as glm stores it
                    if (!std::isfinite(f)) L.fail(iw, "matrix " + std::to_string(j) + " (for joint " + std::to_string(j) + ") is not finite");
                    glm::value_ptr(skin.inverseBind[j])[c] = f;
                }
        }
        slot = int(animation->skins.size());
        animation->skins.push_back(std::move(skin));
        return slot;
    };
    // The joints and weights of the primitive addPrimitive just appended (`emitted`), one VertexJoints
    // a vertex into animation->vertexJoints: JOINTS_0/WEIGHTS_0, and JOINTS_1/WEIGHTS_1 when present.
    auto readJoints = [&](const tinygltf::Primitive& prim, const std::string& w, const Skin& skin, const std::string& skinName) {
        std::vector<VertexJoints> perElement(emitted.elements);
        for (int set = 0; set < 2; ++set) {
            const std::string jn = "JOINTS_" + std::to_string(set), wn = "WEIGHTS_" + std::to_string(set);
            const auto ji = prim.attributes.find(jn), wi = prim.attributes.find(wn);
            if (ji == prim.attributes.end() && wi == prim.attributes.end() && set == 1) break;
            if (ji == prim.attributes.end() || wi == prim.attributes.end())
                L.fail(w + ".attributes", "has " + (ji == prim.attributes.end() ? "no " + jn : jn) + " and " +
                                              (wi == prim.attributes.end() ? "no " + wn : wn) + ", but its node has " + skinName +
                                              " (a skinned primitive needs both)");
            const Loader::View joints = L.view(ji->second, w + ".attributes." + jn, {TINYGLTF_TYPE_VEC4},
                                               {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT}, emitted.elements);
            Loader::View weights = L.view(wi->second, w + ".attributes." + wn, {TINYGLTF_TYPE_VEC4},
                                          {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                           TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                                          emitted.elements);
            const std::string jw = w + ".attributes." + jn + " (accessors[" + std::to_string(ji->second) + "])";
            const std::string ww = w + ".attributes." + wn + " (accessors[" + std::to_string(wi->second) + "])";
            if (weights.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !weights.normalized) {
                repairs.add(ww, 0, "integer joint weights without \"normalized\": true (the spec requires it)", "read as normalized", "accessors");
                weights.normalized = true;
            }
            for (size_t e = 0; e < emitted.elements; ++e)
                for (int k = 0; k < 4; ++k) {
                    const float weight = Loader::component(weights, e, k);
                    const uint32_t joint = uint32_t(Loader::component(joints, e, k));
                    if (!std::isfinite(weight) || weight < 0.0f)
                        L.fail(ww, "weight " + std::to_string(k) + " of vertex " + std::to_string(e) + " is " +
                                       (std::isfinite(weight) ? "negative" : "not finite"));
                    // A joint with weight 0 may be any number (exporters pad with 0); one that counts must exist.
                    if (weight > 0.0f && joint >= skin.joints.size())
                        L.fail(jw, "joint " + std::to_string(joint) + " of vertex " + std::to_string(e) + " is beyond " + skinName + "'s " +
                                       std::to_string(skin.joints.size()) + " joints");
                    perElement[e].joint[4 * set + k] = weight > 0.0f ? joint : 0u;
                    perElement[e].weight[4 * set + k] = weight;
                }
        }
        // Weights sum to 1 within their type's precision (four rounded bytes: 2/255); others are normalised.
        const auto wi = prim.attributes.find("WEIGHTS_0");
        const std::string ww = w + ".attributes.WEIGHTS_0 (accessors[" + std::to_string(wi->second) + "])";
        const float tolerance = model.accessors[size_t(wi->second)].componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ? 2.0f / 255.0f : 2e-3f;
        size_t unnormalised = 0, unweighted = 0;
        for (VertexJoints& vj : perElement) {
            float sum = 0.0f;
            for (float x : vj.weight) sum += x;
            if (sum == 0.0f) {
                ++unweighted;
                continue;
            }
            if (std::abs(sum - 1.0f) > tolerance) ++unnormalised;
            for (float& x : vj.weight) x /= sum;
        }
        if (unnormalised > 0) repairs.add(ww, unnormalised, "vertices whose joint weights do not sum to 1", "normalized", "accessors");
        if (unweighted > 0)
            repairs.add(ww, unweighted, "vertices without a joint weight", "left where the mesh places them (not skinned)", "accessors");
        for (uint32_t src : emitted.source) animation->vertexJoints.push_back(perElement[src]);
    };
    // The morph targets' deltas of the primitive addPrimitive just appended, `targets` x its vertices
    // into animation->morphDeltas (target-major). NORMAL and TANGENT deltas apply where the normals
    // and tangents are the file's (generated ones are not morphed).
    auto readTargets = [&](const tinygltf::Primitive& prim, const std::string& w, size_t targets) {
        const size_t count = emitted.source.size();
        const size_t first = animation->morphDeltas.size();
        // Bounded as the drawn vertices are: 2^25 deltas (36 bytes each) in all.
        if (targets > kMaxMorphDeltas / std::max<size_t>(count, 1) || first + targets * count > kMaxMorphDeltas)
            L.fail(w + ".targets", std::to_string(targets) + " morph targets of " + std::to_string(count) + " vertices: the file's targets hold more than " +
                                       std::to_string(kMaxMorphDeltas) + " vertex deltas in all");
        animation->morphDeltas.resize(first + targets * count);
        for (size_t t = 0; t < targets; ++t) {
            const std::string tw = w + ".targets[" + std::to_string(t) + "]";
            for (const auto& [name, accessor] : prim.targets[t]) {
                const int kind = name == "POSITION" ? 0 : name == "NORMAL" ? 1 : name == "TANGENT" ? 2 : -1;
                if (kind < 0) {
                    repairs.add(tw + "." + name, 0, "morph target attributes other than POSITION, NORMAL and TANGENT", "not applied", "targets");
                    continue;
                }
                if ((kind == 1 && !emitted.fileNormals) || (kind == 2 && !emitted.fileTangents)) continue;
                const Loader::View d = L.view(accessor, tw + "." + name, {TINYGLTF_TYPE_VEC3},
                                              {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT},
                                              emitted.elements);
                std::vector<glm::vec3> perElement(emitted.elements);
                for (size_t e = 0; e < emitted.elements; ++e) {
                    perElement[e] = glm::vec3(Loader::component(d, e, 0), Loader::component(d, e, 1), Loader::component(d, e, 2));
                    if (!std::isfinite(perElement[e].x + perElement[e].y + perElement[e].z))
                        L.fail(tw + "." + name + " (accessors[" + std::to_string(accessor) + "])", "value " + std::to_string(e) + " is not finite");
                }
                for (size_t i = 0; i < count; ++i) {
                    MorphDelta& md = animation->morphDeltas[first + t * count + i];
                    (kind == 0 ? md.position : kind == 1 ? md.normal : md.tangent) = perElement[emitted.source[i]];
                }
            }
        }
    };
    std::map<int, size_t> instancedSlot;  // a reused mesh -> its out.instancedMeshes entry
    // One node, its parent's world transform given (the tree check above has made sure each exists and
    // is reached once); its children are returned to the walk below, which keeps its own stack (a
    // recursive walk of a chain 1023 levels deep overflowed a 1 MiB stack).
    auto visit = [&](int n, const glm::mat4& parent, int parentNode, bool animated) -> glm::mat4 {
        const std::string w = "nodes[" + std::to_string(n) + "]";
        const tinygltf::Node& node = model.nodes[size_t(n)];
        std::string rotationProblem;
        const glm::dquat r = node.matrix.size() == 16 ? glm::dquat(1.0, 0.0, 0.0, 0.0) : Loader::rotation(node.rotation, rotationProblem);
        // The node's rest transform, for posing it and its children (NodeAnimation).
        AnimatedNode& rest = animation->nodes[size_t(n)];
        rest.parent = parentNode;
        rest.hasMatrix = node.matrix.size() == 16;
        rest.matrix = Loader::localMatrix(node, r);
        if (node.translation.size() == 3) rest.translation = glm::vec3(node.translation[0], node.translation[1], node.translation[2]);
        if (node.scale.size() == 3) rest.scale = glm::vec3(node.scale[0], node.scale[1], node.scale[2]);
        rest.rotation = glm::quat(float(r.w), float(r.x), float(r.y), float(r.z));
        animation->order.push_back(n);
        if (rotationProblem == "zero")
            repairs.add(w + ".rotation", 1, "rotations of length 0 (not a rotation)", "no rotation used", "nodes");
        else if (!rotationProblem.empty())
            repairs.add(w + ".rotation", 1, "rotations not of unit length", "normalized", "nodes");
        const glm::mat4 world = parent * Loader::localMatrix(node, r);
        for (int i = 0; i < 16; ++i)
            if (!std::isfinite(glm::value_ptr(world)[i])) L.fail(w, "transform is not finite");
        // EXT_mesh_gpu_instancing: the node's mesh drawn at each instance's translation, rotation and
        // scale (T x R x S) under the node's world transform; without it, once at `world`.
        std::vector<glm::mat4> placed{world};
        if (auto ext = node.extensions.find("EXT_mesh_gpu_instancing"); ext != node.extensions.end() && node.mesh >= 0) {
            const std::string ew = w + ".extensions.EXT_mesh_gpu_instancing.attributes";
            const tinygltf::Value& attributes = ext->second.Get("attributes");
            if (!attributes.IsObject()) L.fail(ew, "missing (an object naming TRANSLATION, ROTATION and SCALE accessors)");
            std::optional<size_t> count;
            auto read = [&](const char* name, int type, Loader::View& v) {
                if (!attributes.Has(name)) return false;
                const tinygltf::Value& index = attributes.Get(name);
                if (!index.IsInt()) L.fail(ew + "." + name, "expected an accessor index");
                v = L.view(index.GetNumberAsInt(), ew + "." + name, {type}, floats);
                if (count && v.count != *count)
                    L.fail(ew + "." + name, std::to_string(v.count) + " instances, but the other attributes have " + std::to_string(*count));
                count = v.count;
                return true;
            };
            Loader::View tv, rv, sv;
            const bool hasT = read("TRANSLATION", TINYGLTF_TYPE_VEC3, tv), hasR = read("ROTATION", TINYGLTF_TYPE_VEC4, rv),
                       hasS = read("SCALE", TINYGLTF_TYPE_VEC3, sv);
            if (!count) L.fail(ew, "names none of TRANSLATION, ROTATION and SCALE");
            if (*count > kMaxDrawnPrimitives) L.fail(ew, std::to_string(*count) + " instances, over the limit of " + std::to_string(kMaxDrawnPrimitives));
            placed.clear();
            for (size_t i = 0; i < *count; ++i) {
                const std::string iw = ew + " instance " + std::to_string(i);
                glm::dvec3 t(0.0), s(1.0);
                glm::dvec4 q(0.0, 0.0, 0.0, 1.0);
                for (int c = 0; c < 3; ++c) {
                    if (hasT) t[c] = Loader::component(tv, i, c);
                    if (hasS) s[c] = Loader::component(sv, i, c);
                }
                if (hasR)
                    for (int c = 0; c < 4; ++c) q[c] = Loader::component(rv, i, c);
                if (!std::isfinite(t.x + t.y + t.z + s.x + s.y + s.z + q.x + q.y + q.z + q.w)) L.fail(iw, "is not finite");
                if (!(glm::length(q) > 0.0)) L.fail(iw, "ROTATION has length 0 (not a rotation)");
                q = glm::normalize(q);
                const glm::dmat4 local = glm::translate(glm::dmat4(1.0), t) * glm::mat4_cast(glm::dquat(q.w, q.x, q.y, q.z)) *
                                         glm::scale(glm::dmat4(1.0), s);
                placed.push_back(world * glm::mat4(local));
            }
        }
        if (node.mesh >= 0) {
            if (size_t(node.mesh) >= model.meshes.size())
                L.fail(w + ".mesh", std::to_string(node.mesh) + " does not exist (" + std::to_string(model.meshes.size()) + " meshes)");
            const tinygltf::Mesh& drawn = model.meshes[size_t(node.mesh)];
            const std::string mw = "meshes[" + std::to_string(node.mesh) + "]";
            // Morph targets: as many in every primitive; weights (the node's over the mesh's) one a target.
            const size_t targets = meshTargets(node.mesh);
            for (size_t p = 1; p < drawn.primitives.size(); ++p)
                if (drawn.primitives[p].targets.size() != targets)
                    L.fail(mw + ".primitives[" + std::to_string(p) + "].targets",
                           std::to_string(drawn.primitives[p].targets.size()) + " morph targets, but primitives[0] has " +
                               std::to_string(targets) + " (every primitive of a mesh has as many)");
            const std::vector<double>& restWeights = !node.weights.empty() ? node.weights : drawn.weights;
            if (!restWeights.empty() && restWeights.size() != targets)
                L.fail((!node.weights.empty() ? w : mw) + ".weights",
                       std::to_string(restWeights.size()) + " weights for " + std::to_string(targets) + " morph targets (one a target)");
            rest.weights.assign(targets, 0.0f);
            for (size_t t = 0; t < restWeights.size(); ++t) rest.weights[t] = float(restWeights[t]);
            const int skin = node.skin >= 0 ? skinFor(node.skin, w) : -1;
            // A mesh other still nodes draw too: its primitives once, in its own space (the first node
            // that draws it reads them), and this node's world transform. Mirroring nodes stay baked:
            // addPrimitive turns their triangles to keep front faces front.
            const bool still = !animated && skin < 0 && targets == 0;
            if (!still && placed.size() != 1)  // drawn once, at the node, as without the extension
                L.warn(w + ".extensions.EXT_mesh_gpu_instancing", "its node is animated, skinned or morphed; drawn once, without its instances");
            // The instances, each stored once (still, not mirroring, asked for) or baked.
            std::vector<glm::mat4> reusedAt, bakedAt;
            for (const glm::mat4& at : still ? placed : std::vector<glm::mat4>{world})
                (instanceReusedMeshes && still && stillUses[size_t(node.mesh)] > 1 && glm::determinant(glm::mat3(at)) > 0.0f ? reusedAt : bakedAt)
                    .push_back(at);
            for (size_t b = 1; b < bakedAt.size(); ++b)  // further baked instances (the first is drawn below)
                for (size_t p = 0; p < drawn.primitives.size(); ++p) addPrimitive(node.mesh, int(p), bakedAt[b]);
            const bool reusedHere = bakedAt.empty();
            if (!reusedAt.empty()) {
                auto [slot, first] = instancedSlot.emplace(node.mesh, out.instancedMeshes.size());
                if (first) {
                    const size_t firstVertex = mesh.vertices.size(), firstIndex = mesh.indices.size(), firstSub = mesh.subMeshes.size();
                    for (size_t p = 0; p < drawn.primitives.size(); ++p) addPrimitive(node.mesh, int(p), glm::mat4(1.0f));
                    GltfInstancedMesh im;
                    im.meshIndex = node.mesh;
                    im.mesh.name = mesh.name + "/" + (drawn.name.empty() ? mw : drawn.name);
                    im.mesh.vertices.assign(mesh.vertices.begin() + ptrdiff_t(firstVertex), mesh.vertices.end());
                    for (size_t i = firstIndex; i < mesh.indices.size(); ++i) im.mesh.indices.push_back(mesh.indices[i] - uint32_t(firstVertex));
                    for (size_t s = firstSub; s < mesh.subMeshes.size(); ++s) {
                        SubMesh sub = mesh.subMeshes[s];
                        sub.firstIndex -= uint32_t(firstIndex);
                        im.mesh.subMeshes.push_back(std::move(sub));
                    }
                    mesh.vertices.resize(firstVertex);
                    mesh.indices.resize(firstIndex);
                    mesh.subMeshes.resize(firstSub);
                    out.instancedMeshes.push_back(std::move(im));
                }
                for (const glm::mat4& at : reusedAt) out.instancedMeshes[slot->second].transforms.push_back(at);
            }
            const glm::mat4 bakedWorld = bakedAt.empty() ? world : bakedAt.front();
            const size_t primitivesHere = reusedHere ? 0 : drawn.primitives.size();  // a reused mesh: drawn above
            for (size_t p = 0; p < primitivesHere; ++p) {
                if (!animated && skin < 0 && targets == 0) {
                    addPrimitive(node.mesh, int(p), bakedWorld);
                    continue;
                }
                // A node that moves, is skinned or morphed: its primitive read in the node's own space
                // (a skinned one's: the mesh's, since a skin ignores the node's transform) and kept for
                // posing, then placed at rest through the same math as any pose (below).
                const size_t firstVertex = mesh.vertices.size(), firstIndex = mesh.indices.size();
                addPrimitive(node.mesh, int(p), glm::mat4(1.0f));
                const size_t count = mesh.vertices.size() - firstVertex;
                if (count == 0) continue;
                NodeVertexRange range;
                range.node = n;
                range.firstVertex = uint32_t(firstVertex);
                range.vertexCount = uint32_t(count);
                range.firstLocal = uint32_t(animation->restLocal.size());
                range.mirrored = skin < 0 && glm::determinant(glm::mat3(world)) < 0.0f;
                const std::string pw = mw + ".primitives[" + std::to_string(p) + "]";
                if (skin >= 0) {
                    range.skin = skin;
                    range.firstJoints = uint32_t(animation->vertexJoints.size());
                    readJoints(drawn.primitives[p], pw, animation->skins[size_t(skin)], "skins[" + std::to_string(node.skin) + "]");
                }
                if (targets > 0) {
                    range.morphTargets = uint32_t(targets);
                    range.firstDelta = uint32_t(animation->morphDeltas.size());
                    readTargets(drawn.primitives[p], pw, targets);
                }
                animation->restLocal.insert(animation->restLocal.end(), mesh.vertices.begin() + ptrdiff_t(firstVertex), mesh.vertices.end());
                animation->ranges.push_back(range);
                if (range.mirrored)  // front faces stay front faces, as addPrimitive does for a mirroring node
                    for (size_t i = firstIndex; i + 2 < mesh.indices.size(); i += 3) std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
            }
        }
        const glm::vec3 origin(world[3]);
        const glm::vec3 forward = glm::normalize(glm::mat3(world) * glm::vec3(0, 0, -1));
        if (node.camera >= 0) {
            if (size_t(node.camera) >= model.cameras.size()) L.fail(w + ".camera", std::to_string(node.camera) + " does not exist");
            const tinygltf::Camera& c = model.cameras[size_t(node.camera)];
            const std::string cw = "cameras[" + std::to_string(node.camera) + "]";
            // Said once per camera, however many nodes place it.
            const bool firstUse = notedOnce(cw);
            auto cameraWarn = [&](const std::string& where, const std::string& what) {
                if (firstUse) L.warn(where, what);
            };
            const glm::vec3 up = glm::mat3(world) * glm::vec3(0, 1, 0);
            if (c.type != "perspective") {
                cameraWarn(cw, "type " + quoteUserText(c.type) + " is not supported (perspective only); ignored");
            } else if (!std::isfinite(forward.x + forward.y + forward.z) || !(glm::length(up) > 0.0f) || !std::isfinite(glm::length(up))) {
                L.warn(w + ".camera", "the node has no direction (a zero scale), so " + cw + " does not either; ignored");
            } else {
                Camera cam;
                cam.position = origin;
                cam.target = origin + forward;
                cam.up = glm::normalize(up);
                cam.fovYDegrees = gltfFieldOfView(c.perspective.yfov, cw + ".perspective.yfov", cameraWarn);
                // The schema made znear > 0 and zfar > 0 where given (tinygltf: 0 where not); the
                // renderer's depth range: near >= 1e-6 m, far / near <= 1e6 (the scene file's limits).
                const double znear = c.perspective.znear, zfar = c.perspective.zfar;
                cam.nearPlane = float(std::max(znear, 1e-6));
                if (znear < 1e-6) cameraWarn(cw + ".perspective.znear", formatNumber(znear) + " is below the 1e-06 m minimum; 1e-06 used");
                // No zfar: an infinite projection, which the renderer's far plane at znear x 1e5 stands for.
                cam.farPlane = cam.nearPlane * 1e5f;
                if (zfar > 0.0 && zfar <= znear)
                    cameraWarn(cw + ".perspective.zfar", formatNumber(zfar) + " is not beyond znear " + formatNumber(znear) +
                                                             "; read as no zfar (far = znear x 1e5)");
                else if (zfar > 0.0 && zfar / double(cam.nearPlane) > 1e6) {
                    cameraWarn(cw + ".perspective.zfar", formatNumber(zfar) + " is more than 1e6 times znear " + formatNumber(cam.nearPlane) +
                                                             " (the depth buffer would resolve nothing); far = znear x 1e6 used");
                    cam.farPlane = cam.nearPlane * 1e6f;
                } else if (zfar > 0.0) {
                    cam.farPlane = float(zfar);
                }
                out.cameras.push_back(cam);
            }
        }
        auto lightExt = node.extensions.find("KHR_lights_punctual");
        if (lightExt != node.extensions.end() && lightExt->second.Has("light")) {
            const int li = lightExt->second.Get("light").GetNumberAsInt();
            const std::string lw = "extensions.KHR_lights_punctual.lights[" + std::to_string(li) + "]";
            if (li < 0 || size_t(li) >= model.lights.size()) L.fail(w + ".extensions.KHR_lights_punctual.light", std::to_string(li) + " does not exist");
            const tinygltf::Light& l = model.lights[size_t(li)];
            glm::vec3 color(1.0f);
            if (l.color.size() == 3) color = glm::vec3(float(l.color[0]), float(l.color[1]), float(l.color[2]));
            const float intensity = float(l.intensity);
            if (!std::isfinite(color.x + color.y + color.z + intensity) || glm::any(glm::lessThan(color, glm::vec3(0.0f))) || intensity < 0.0f ||
                intensity > 1e9f || glm::any(glm::greaterThan(color, glm::vec3(1e9f))))
                L.fail(lw, "colour and intensity must be finite, >= 0 and <= 1e9");
            // A node scaled to zero has no -Z: the light would shine in a NaN direction.
            if ((l.type == "directional" || l.type == "spot") && !std::isfinite(forward.x + forward.y + forward.z))
                L.fail(lw, "its node (" + w + ") has no -Z direction (a zero scale)");
            if (l.range > 0.0 && !std::isfinite(float(l.range)))
                L.fail(lw + ".range", formatNumber(l.range) + " is beyond a float's range");
            if (l.type == "directional") {
                DirectionalLight d;
                d.direction = forward;
                d.color = color;
                d.intensity = intensity;  // lux: irradiance at normal incidence
                out.directionalLights.push_back(d);
            } else if (l.type == "point" || l.type == "spot") {
                PointLight p;
                p.position = origin;
                p.color = color;
                p.intensity = intensity;  // candela: radiant intensity, irradiance = I / d^2
                // No range: where I max(colour) / d^2 falls to 1e-3 (the window then hides the rest).
                const float brightest = intensity * std::max({color.x, color.y, color.z, 1e-6f});
                p.range = (std::isfinite(l.range) && l.range > 0.0) ? float(l.range) : std::max(std::sqrt(brightest / 1e-3f), 1e-3f);
                p.orbitCenter = origin;
                if (l.type == "spot") p.spot = spotCone(l.spot, forward, lw);
                out.pointLights.push_back(p);
            } else {
                L.warn(lw, "unknown light type " + quoteUserText(l.type) + "; ignored");
            }
        }
        return world;
    };
    // Depth first, children in order: the order primitives are drawn in and cameras listed in.
    struct Pending {
        int node;
        glm::mat4 parentWorld;
        int parent;
        bool parentAnimated;  // a channel moves the parent or one of its ancestors
    };
    std::vector<Pending> pending;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) pending.push_back({*it, glm::mat4(1.0f), -1, false});
    while (!pending.empty()) {
        const Pending p = pending.back();
        pending.pop_back();
        const bool animated = p.parentAnimated || targeted[size_t(p.node)];
        const glm::mat4 world = visit(p.node, p.parentWorld, p.parent, animated);
        const std::vector<int>& children = model.nodes[size_t(p.node)].children;
        for (auto it = children.rbegin(); it != children.rend(); ++it) pending.push_back({*it, world, p.node, animated});
    }
    // A joint is placed by the scene's node trees; one outside them has no world transform to give.
    {
        std::vector<char> drawn(model.nodes.size(), 0);
        for (int n : animation->order) drawn[size_t(n)] = 1;
        for (size_t k = 0; k < skinSlot.size(); ++k)
            if (skinSlot[k] >= 0)
                for (size_t j = 0; j < model.skins[k].joints.size(); ++j)
                    if (!drawn[size_t(model.skins[k].joints[j])])
                        repairs.add("skins[" + std::to_string(k) + "].joints[" + std::to_string(j) + "]", 1,
                                    "joints outside the scene's node trees", "placed as if at the origin (identity world matrix)", "joints");
    }
    // The rest pose placed through the same math as every other pose: the ranges' vertices as
    // poseVertices puts them (morphed by the rest weights, then skinned or placed by the node's world
    // matrix): a skinned or morphed model that no clip moves costs nothing after loading.
    if (!animation->ranges.empty()) poseVertices(*animation, animatedNodeWorlds(*animation, {}, 0.0), mesh.vertices);
    if (!animation->clips.empty()) out.animation = animation;

    repairs.warn(L);
    if (report.droppedDegenerate || report.droppedNonFinite)
        report.warnings.push_back(file + ": dropped " + std::to_string(report.droppedDegenerate) + " degenerate and " +
                                  std::to_string(report.droppedNonFinite) + " non-finite triangles");
    // The reused meshes' materials are the file's, as `mesh` holds them (their sub-meshes index them).
    std::vector<GltfInstancedMesh> instanced;
    for (GltfInstancedMesh& im : out.instancedMeshes) {
        if (im.mesh.indices.empty()) continue;  // points or lines only
        im.mesh.materials = mesh.materials;
        im.mesh.materialVariants = mesh.materialVariants;
        computeBounds(im.mesh);
        instanced.push_back(std::move(im));
    }
    out.instancedMeshes = std::move(instanced);
    if (mesh.indices.empty() && out.instancedMeshes.empty()) throw Error(file + ": no triangles (in the scene's nodes)");
    computeBounds(mesh);
    // The whole file has loaded: now its warnings are news (a file that fails prints its one error alone).
    for (const std::string& warning : report.warnings) logWarn(warning);
    if (reportOut) *reportOut = report;
    return out;
}

}  // namespace lp
