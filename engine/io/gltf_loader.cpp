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
#include "engine/io/gltf_schema.hpp"
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
const std::set<std::string> kSupportedExtensions = {"KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_materials_ior",
                                                     "KHR_materials_unlit", "KHR_mesh_quantization", "KHR_texture_transform"};
constexpr size_t kMaxElements = size_t(1) << 28;  // accessor count limit: 268M elements
constexpr size_t kMaxNodeDepth = 1024;                        // levels of the node hierarchy
constexpr size_t kMaxDrawnPrimitives = size_t(1) << 20;       // primitive instances the nodes draw
constexpr size_t kMaxDrawnVertices = size_t(1) << 26;         // their vertices and indices, instances counted

// The JSON text of a .gltf file, or of a GLB's first chunk (empty when the GLB header does not
// hold one: tinygltf then names what is wrong).
std::string gltfJsonText(const std::string& bytes, bool binary) {
    if (!binary) return bytes;
    if (bytes.size() < 20) return {};
    uint32_t length = 0, type = 0;
    std::memcpy(&length, bytes.data() + 12, 4);
    std::memcpy(&type, bytes.data() + 16, 4);
    if (type != 0x4E4F534Au || length > bytes.size() - 20) return {};  // "JSON"
    return bytes.substr(20, length);
}

// tinygltf reads external buffers and images through these: the same regular-file check as every
// other input (a FIFO named as a buffer would block the read forever).
bool fileExists(const std::string& path, void*) {
    std::error_code ec;
    return fs::exists(path, ec);
}
std::string expandPath(const std::string& path, void*) { return path; }
bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
    try {
        const std::string bytes = readFileChecked(path, kMaxImageFileBytes, "a glTF buffer or image");
        out->assign(bytes.begin(), bytes.end());
        return true;
    } catch (const Error& e) {
        if (err) *err += e.what();
        return false;
    }
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

    [[noreturn]] void fail(const std::string& where, const std::string& what) const { throw Error(file + ": " + where + ": " + what); }
    void warn(const std::string& where, const std::string& what) const {
        const std::string msg = file + ": " + where + ": " + what;
        report.warnings.push_back(msg);
        logWarn(msg);
    }

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
    struct View {
        const unsigned char* data = nullptr;  // nullptr: no buffer view (all zeros, per the spec)
        size_t stride = 0, count = 0;
        int components = 0, componentType = 0;
        bool normalized = false;
    };
    View view(int index, const std::string& where, const std::set<int>& types, const std::set<int>& componentTypes) const {
        const std::string aw = where + " (accessors[" + std::to_string(index) + "])";
        if (index < 0 || size_t(index) >= model.accessors.size())
            fail(where, "accessor " + std::to_string(index) + " does not exist (" + std::to_string(model.accessors.size()) + " accessors)");
        const tinygltf::Accessor& a = model.accessors[size_t(index)];
        if (a.sparse.isSparse) fail(aw, "sparse accessors are not supported");
        if (!types.count(a.type)) fail(aw, "unexpected type " + std::to_string(a.type) + " for this attribute");
        if (!componentTypes.count(a.componentType))
            fail(aw, "unexpected componentType " + std::to_string(a.componentType) + " for this attribute");
        if (a.count > kMaxElements) fail(aw, "count " + std::to_string(a.count) + " is over the limit");
        View v;
        v.components = componentCount(a.type);
        v.componentType = a.componentType;
        v.normalized = a.normalized;
        v.count = a.count;
        const size_t elementSize = size_t(v.components) * size_t(componentSize(a.componentType));
        v.stride = elementSize;
        if (a.bufferView < 0) return v;
        if (size_t(a.bufferView) >= model.bufferViews.size())
            fail(aw, "bufferView " + std::to_string(a.bufferView) + " does not exist (" + std::to_string(model.bufferViews.size()) + " buffer views)");
        const tinygltf::BufferView& bv = model.bufferViews[size_t(a.bufferView)];
        const std::string bw = "bufferViews[" + std::to_string(a.bufferView) + "]";
        if (bv.buffer < 0 || size_t(bv.buffer) >= model.buffers.size())
            fail(bw, "buffer " + std::to_string(bv.buffer) + " does not exist (" + std::to_string(model.buffers.size()) + " buffers)");
        const tinygltf::Buffer& buffer = model.buffers[size_t(bv.buffer)];
        if (bv.byteOffset > buffer.data.size() || bv.byteLength > buffer.data.size() - bv.byteOffset)
            fail(bw, "bytes " + std::to_string(bv.byteOffset) + "+" + std::to_string(bv.byteLength) + " run past the end of buffers[" +
                         std::to_string(bv.buffer) + "] (" + std::to_string(buffer.data.size()) + " bytes)");
        if (bv.byteStride) {
            if (bv.byteStride < elementSize) fail(bw, "byteStride " + std::to_string(bv.byteStride) + " is smaller than an element");
            v.stride = bv.byteStride;
        }
        if (a.count > 0) {
            const size_t last = a.byteOffset + v.stride * (a.count - 1) + elementSize;  // < 2^28 * 2^8 + ..., no overflow
            if (a.byteOffset > bv.byteLength || last > bv.byteLength)
                fail(aw, std::to_string(a.count) + " elements from byte " + std::to_string(a.byteOffset) + " run past the end of " + bw +
                             " (" + std::to_string(bv.byteLength) + " bytes)");
        }
        v.data = buffer.data.data() + bv.byteOffset + a.byteOffset;
        return v;
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
            warn(iw, "image " + std::to_string(t.source) + " does not exist; using a checker texture");
            TextureRef r;
            r.encoded = std::make_shared<const std::string>();  // decodes to the checker, with a warning
            r.key = file + "#" + iw;
            r.uvSet = uvSet;
            return r;
        }
        const tinygltf::Image& image = model.images[size_t(t.source)];
        TextureRef r = imageTexture(image, t.source);
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

    // images[source]: its encoded bytes, or the file its URI names.
    TextureRef imageTexture(const tinygltf::Image& image, int source) const {
        TextureRef r;
        r.key = file + "#images[" + std::to_string(source) + "]";
        if (!image.image.empty()) {
            r.encoded = std::make_shared<const std::string>(image.image.begin(), image.image.end());
        } else if (!image.uri.empty() && image.uri.rfind("data:", 0) != 0) {
            // Not read (missing or unreadable, tinygltf warned): SceneGpu loads the file or warns and
            // uses the checker. URIs are percent-encoded.
            std::string decoded;
            for (size_t i = 0; i < image.uri.size(); ++i) {
                if (image.uri[i] == '%' && i + 2 < image.uri.size() && std::isxdigit((unsigned char)image.uri[i + 1]) &&
                    std::isxdigit((unsigned char)image.uri[i + 2])) {
                    decoded += char(std::stoi(image.uri.substr(i + 1, 2), nullptr, 16));
                    i += 2;
                } else {
                    decoded += image.uri[i];
                }
            }
            const fs::path p = fs::path(file).parent_path() / decoded;
            r = TextureRef::file(p.lexically_normal());
        } else {
            r.encoded = std::make_shared<const std::string>();
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
        const Slot textures[] = {
            {"pbrMetallicRoughness.baseColorTexture", pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, &pbr.baseColorTexture.extensions},
            {"pbrMetallicRoughness.metallicRoughnessTexture", pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
             &pbr.metallicRoughnessTexture.extensions},
            {"normalTexture", m.normalTexture.index, m.normalTexture.texCoord, &m.normalTexture.extensions},
            {"occlusionTexture", m.occlusionTexture.index, m.occlusionTexture.texCoord, &m.occlusionTexture.extensions},
            {"emissiveTexture", m.emissiveTexture.index, m.emissiveTexture.texCoord, &m.emissiveTexture.extensions}};
        MaterialUvSets out;
        if (m.normalTexture.index >= 0) out.normalSet = uvSetOf(m.normalTexture.texCoord, m.normalTexture.extensions);
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
        // KHR_materials_ior: the dielectric F0 of the index, ((ior - 1) / (ior + 1))^2 (1.5: the default 0.04).
        if (auto ior = m.extensions.find("KHR_materials_ior"); ior != m.extensions.end() && ior->second.Has("ior")) {
            const double n = ior->second.Get("ior").GetNumberAsDouble();
            out.specular = glm::vec3(float(((n - 1.0) / (n + 1.0)) * ((n - 1.0) / (n + 1.0))));
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

    static glm::mat4 localMatrix(const tinygltf::Node& n) {
        if (n.matrix.size() == 16) {
            glm::dmat4 m;
            for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = n.matrix[size_t(i)];  // column-major, like glm
            return glm::mat4(m);
        }
        glm::dvec3 t(0.0), s(1.0);
        glm::dquat r(1.0, 0.0, 0.0, 0.0);  // w, x, y, z
        if (n.translation.size() == 3) t = glm::dvec3(n.translation[0], n.translation[1], n.translation[2]);
        if (n.scale.size() == 3) s = glm::dvec3(n.scale[0], n.scale[1], n.scale[2]);
        if (n.rotation.size() == 4) r = glm::normalize(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]));
        return glm::mat4(glm::translate(glm::dmat4(1.0), t) * glm::mat4_cast(r) * glm::scale(glm::dmat4(1.0), s));
    }
};

}  // namespace

GltfContent loadGltf(const fs::path& path, MeshLoadReport* reportOut) {
    MeshLoadReport report;
    const std::string file = path.string();
    const std::string bytes = readFileChecked(path, kMaxImageFileBytes, "a glTF file");
    tinygltf::TinyGLTF gltf;
    gltf.SetFsCallbacks({&fileExists, &expandPath, &readWholeFile, &writeWholeFile, nullptr});
    tinygltf::Model model;
    gltf.SetImageLoader(&keepEncodedImage, &model);
    std::string err, warnText;
    const std::string baseDir = path.has_parent_path() ? path.parent_path().string() : std::string(".");
    const bool binary = bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0;
    if (bytes.size() > 0xFFFFFFFFull) throw Error(file + ": over 4 GiB");
    if (!binary) requireUtf8Text(path, bytes);
    if (binary && bytes.size() >= 8) {
        uint32_t container = 0;
        std::memcpy(&container, bytes.data() + 4, 4);
        if (container != 2) throw Error(file + ": GLB container version " + std::to_string(container) + ": lightpass reads glTF 2.0 (GLB version 2)");
    }
    // The schema first: tinygltf skips a property of the wrong type silently, and names the element
    // of the ones it refuses only by the property. A document that does not parse is tinygltf's to name.
    std::vector<GltfSchemaIssue> schemaIssues;
    {
        const nlohmann::json root = nlohmann::json::parse(gltfJsonText(bytes, binary), nullptr, false);
        if (!root.is_discarded()) schemaIssues = checkGltfSchema(root);
        for (const GltfSchemaIssue& issue : schemaIssues)
            if (issue.error) throw Error(file + ": " + issue.where + ": " + issue.what);
        // Before tinygltf, which fails on what such an extension changes (a Draco mesh's accessors
        // have no bufferView) with a message that does not name the extension.
        if (root.is_object() && root.contains("extensionsRequired"))
            for (const auto& e : root["extensionsRequired"])
                if (!kSupportedExtensions.count(e.get<std::string>())) {
                    std::string supported;
                    for (const std::string& name : kSupportedExtensions) supported += (supported.empty() ? "" : ", ") + name;
                    throw Error(file + ": extensionsRequired: " + e.get<std::string>() + " is not supported (supported: " + supported + ")");
                }
    }
    const bool ok = binary ? gltf.LoadBinaryFromMemory(&model, &err, &warnText, reinterpret_cast<const unsigned char*>(bytes.data()),
                                                      unsigned(bytes.size()), baseDir)
                           : gltf.LoadASCIIFromString(&model, &err, &warnText, bytes.data(), unsigned(bytes.size()), baseDir);
    auto firstLine = [](std::string s) {
        while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
        for (char& c : s)
            if (c == '\n') c = ' ';
        return s;
    };
    if (!ok) {
        // tinygltf names a missing buffer file but not the buffer: name it as the file does.
        if (!binary) {
            const nlohmann::json root = nlohmann::json::parse(bytes, nullptr, false);
            if (root.is_object() && root.contains("buffers") && root["buffers"].is_array())
                for (size_t i = 0; i < root["buffers"].size(); ++i) {
                    const auto& b = root["buffers"][i];
                    if (!b.is_object() || !b.contains("uri") || !b["uri"].is_string()) continue;
                    const std::string uri = b["uri"].get<std::string>();
                    std::error_code ec;
                    if (uri.rfind("data:", 0) != 0 && !fs::exists(fs::path(baseDir) / uri, ec))
                        throw Error(file + ": buffers[" + std::to_string(i) + "]: " + (fs::path(baseDir) / uri).string() + ": file not found");
                }
        }
        throw Error(file + ": " + (err.empty() ? std::string("could not be parsed as glTF") : firstLine(err)));
    }
    Loader L{model, file, report};
    for (const GltfSchemaIssue& issue : schemaIssues) L.warn(issue.where, issue.what);
    // An extension the file uses but does not require is optional to read, yet the model looks
    // different without it (a texture transform, clearcoat, transmission): say which are ignored.
    for (size_t i = 0; i < model.extensionsUsed.size(); ++i)
        if (!kSupportedExtensions.count(model.extensionsUsed[i]))
            L.warn("extensionsUsed[" + std::to_string(i) + "]", model.extensionsUsed[i] + " is not supported; ignored (the model may look different)");
    if (!warnText.empty()) {
        const std::string msg = file + ": " + firstLine(warnText);
        report.warnings.push_back(msg);
        logWarn(msg);
    }

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

    // KHR_mesh_quantization (gltfpack's output): integer positions and uvs, normalised integer
    // normals and tangents; the node transform (and a texture transform) scales them back.
    const bool quantized = std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(), "KHR_mesh_quantization") != model.extensionsUsed.end();
    const std::set<int> floats = {TINYGLTF_COMPONENT_TYPE_FLOAT};
    const std::set<int> integers = {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                    TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};
    const std::set<int> signedNormalised = {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT};
    const std::set<int>& positionTypes = quantized ? integers : floats;
    const std::set<int>& directionTypes = quantized ? signedNormalised : floats;  // normals and tangents
    const std::set<int> uvTypes = quantized ? integers
                                            : std::set<int>{TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                                            TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};
    const std::set<int> colorTypes = {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};
    std::set<std::string> noted;  // what notedOnce has seen
    auto notedOnce = [&noted](const std::string& what) { return noted.insert(what).second; };
    auto addPrimitive = [&](int meshIndex, int primIndex, const glm::mat4& world) {
        const tinygltf::Primitive& prim = model.meshes[size_t(meshIndex)].primitives[size_t(primIndex)];
        const std::string w = "meshes[" + std::to_string(meshIndex) + "].primitives[" + std::to_string(primIndex) + "]";
        if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP && prim.mode != TINYGLTF_MODE_TRIANGLE_FAN) {
            L.warn(w, "mode " + std::to_string(prim.mode) + " (points or lines) is not drawn");
            return;
        }
        auto attr = prim.attributes.find("POSITION");
        if (attr == prim.attributes.end()) L.fail(w, "has no POSITION attribute");
        const auto pos = L.view(attr->second, w + ".attributes.POSITION", {TINYGLTF_TYPE_VEC3}, positionTypes);
        // Without a buffer view (and not sparse) every element is zero: no triangle could come of it, and
        // its count, bounded by no bytes of the file, would size the allocations.
        auto requireData = [&](const Loader::View& v, int accessor, const std::string& where) {
            if (!v.data && v.count > 0)
                L.fail(where + " (accessors[" + std::to_string(accessor) + "])",
                       "has no bufferView, so its " + std::to_string(v.count) + " elements would all be zero");
        };
        requireData(pos, attr->second, w + ".attributes.POSITION");
        const size_t vertexCount = pos.count;
        auto optional = [&](const char* name, const std::set<int>& types, const std::set<int>& componentTypes, Loader::View& v) {
            auto it = prim.attributes.find(name);
            if (it == prim.attributes.end()) return false;
            v = L.view(it->second, w + ".attributes." + name, types, componentTypes);
            if (v.count != vertexCount)
                L.fail(w + ".attributes." + name, std::to_string(v.count) + " elements, but POSITION has " + std::to_string(vertexCount));
            return true;
        };
        // Attributes lightpass does not draw with: said once per file (a model with morph targets
        // looks different without them).
        if (!prim.targets.empty() && notedOnce("targets"))
            L.warn(w + ".targets", "morph targets are not applied; drawn with the base shape");
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
        // COLOR_0: linear RGB or RGBA multiplying the base colour; float, or normalised unsigned bytes
        // or shorts (the spec requires `normalized`; an integer accessor without it is read as
        // normalised, with a warning, rather than as colours up to 255 or 65535).
        const bool hasColors = optional("COLOR_0", {TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4}, colorTypes, col);
        if (hasColors && col.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !col.normalized) {
            L.warn(w + ".attributes.COLOR_0", "integer colours must be normalized; read as normalized");
            col.normalized = true;
        }
        const int colorComponents = hasColors ? std::min(col.components, 4) : 0;
        size_t colorsClamped = 0;
        // KHR_texture_transform: applied to the uvs here. Where it turns or flips the uv axes of the
        // normal map's set, the file's tangents (made for the untransformed uvs) are replaced by
        // generated ones.
        const bool hasTangents = optional("TANGENT", {TINYGLTF_TYPE_VEC4}, directionTypes, tan) &&
                                 !uvSets.transform[uvSets.normalSet].turnsAxes();

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
        for (size_t v = 0; v < vertexCount; ++v) {
            Vertex& vx = part.vertices[v];
            const glm::vec3 p(Loader::component(pos, v, 0), Loader::component(pos, v, 1), Loader::component(pos, v, 2));
            vx.position = glm::vec3(world * glm::vec4(p, 1.0f));
            if (hasNormals) {
                const glm::vec3 n = normalMatrix * glm::vec3(Loader::component(nrm, v, 0), Loader::component(nrm, v, 1), Loader::component(nrm, v, 2));
                const float len = glm::length(n);
                vx.normal = (len > 0.0f && std::isfinite(len)) ? n / len : glm::vec3(0.0f, 1.0f, 0.0f);
            }
            // A set's uvs through its transform, flipped to v = 0 at the bottom; not finite: 0.
            auto uvOf = [&](const Loader::View& view, const Loader::UvTransform& transform, glm::vec2& out) {
                glm::vec2 t(Loader::component(view, v, 0), Loader::component(view, v, 1));
                if (!transform.identity()) t = glm::vec2(transform.linear * glm::dvec2(t) + transform.offset);
                if (std::isfinite(t.x) && std::isfinite(t.y)) out = glm::vec2(t.x, 1.0f - t.y);
            };
            if (hasUv) uvOf(uv, uvSets.transform[0], vx.uv);
            if (hasUv1) uvOf(uv1, uvSets.transform[1], vx.uv1);
            else if (uvSets.reads[1] && hasUv) uvOf(uv, uvSets.transform[1], vx.uv1);
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
                vx.tangent = (len > 0.0f && std::isfinite(len)) ? glm::vec4(t / len, hand) : glm::vec4(anyPerpendicular(vx.normal), 1.0f);
            }
        }
        if (colorsClamped > 0)
            L.warn(w + ".attributes.COLOR_0", std::to_string(colorsClamped) +
                                                  " colours outside [0, 1] or not finite; clamped (not finite: 1)");
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
        if (!hasNormals) {
            // The spec's rule: flat normals. Each triangle gets its own three vertices.
            MeshData flat;
            for (size_t i = 0; i + 2 < part.indices.size(); i += 3) {
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
            report.generatedNormals = true;
        }
        if (!hasTangents) {
            // Tangents follow the normal map's uv set: MikkTSpace on TEXCOORD_1 when it reads that.
            auto swapSets = [&part] {
                for (Vertex& vx : part.vertices) std::swap(vx.uv, vx.uv1);
            };
            if (uvSets.normalSet == 1) swapSets();
            computeTangents(part);
            if (uvSets.normalSet == 1) swapSets();
            report.generatedTangents = true;
        }
        const int mat = materialFor(prim.material);
        const uint32_t base = uint32_t(mesh.vertices.size());
        if (mesh.vertices.size() + part.vertices.size() > 0xFFFFFFFFull) L.fail(w, "too many vertices in the file");
        mesh.subMeshes.push_back(SubMesh{uint32_t(mesh.indices.size()), uint32_t(part.indices.size()), mat});
        for (uint32_t i : part.indices) mesh.indices.push_back(base + i);
        mesh.vertices.insert(mesh.vertices.end(), part.vertices.begin(), part.vertices.end());
    };

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
    {
        std::vector<int> parent(model.nodes.size(), -1);
        std::vector<bool> reached(model.nodes.size(), false);
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
    std::vector<bool> onPath(model.nodes.size(), false);
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
    std::function<void(int, const glm::mat4&, const std::string&)> visit = [&](int n, const glm::mat4& parent, const std::string& from) {
        if (n < 0 || size_t(n) >= model.nodes.size()) L.fail(from, "node " + std::to_string(n) + " does not exist (" + std::to_string(model.nodes.size()) + " nodes)");
        const std::string w = "nodes[" + std::to_string(n) + "]";
        if (onPath[size_t(n)]) L.fail(w, "is its own ancestor (the node hierarchy has a cycle)");
        onPath[size_t(n)] = true;
        const tinygltf::Node& node = model.nodes[size_t(n)];
        const glm::mat4 world = parent * Loader::localMatrix(node);
        for (int i = 0; i < 16; ++i)
            if (!std::isfinite(glm::value_ptr(world)[i])) L.fail(w, "transform is not finite");
        if (node.mesh >= 0) {
            if (size_t(node.mesh) >= model.meshes.size())
                L.fail(w + ".mesh", std::to_string(node.mesh) + " does not exist (" + std::to_string(model.meshes.size()) + " meshes)");
            if (node.skin >= 0) L.warn(w, "skinning is not supported; drawn in its bind pose");
            for (size_t p = 0; p < model.meshes[size_t(node.mesh)].primitives.size(); ++p) addPrimitive(node.mesh, int(p), world);
        }
        const glm::vec3 origin(world[3]);
        const glm::vec3 forward = glm::normalize(glm::mat3(world) * glm::vec3(0, 0, -1));
        if (node.camera >= 0) {
            if (size_t(node.camera) >= model.cameras.size()) L.fail(w + ".camera", std::to_string(node.camera) + " does not exist");
            const tinygltf::Camera& c = model.cameras[size_t(node.camera)];
            if (c.type != "perspective") {
                L.warn("cameras[" + std::to_string(node.camera) + "]", "type '" + c.type + "' is not supported (perspective only); ignored");
            } else {
                Camera cam;
                cam.position = origin;
                cam.target = origin + forward;
                cam.up = glm::normalize(glm::mat3(world) * glm::vec3(0, 1, 0));
                const double fov = glm::degrees(c.perspective.yfov);
                cam.fovYDegrees = (std::isfinite(fov) && fov > 0.5 && fov < 179.0) ? float(fov) : 45.0f;
                if (std::isfinite(c.perspective.znear) && c.perspective.znear > 1e-6) cam.nearPlane = float(c.perspective.znear);
                cam.farPlane = (std::isfinite(c.perspective.zfar) && c.perspective.zfar > cam.nearPlane) ? float(c.perspective.zfar)
                                                                                                       : cam.nearPlane * 1e5f;
                cam.farPlane = std::min(cam.farPlane, cam.nearPlane * 1e6f);
                if (std::isfinite(glm::dot(cam.position, cam.up)) && std::isfinite(forward.x + forward.y + forward.z))
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
                L.warn(lw, "unknown light type '" + l.type + "'; ignored");
            }
        }
        for (int c : node.children) visit(c, world, w + ".children");
        onPath[size_t(n)] = false;
    };
    for (int r : roots) visit(r, glm::mat4(1.0f), sceneIndex >= 0 ? "scenes[" + std::to_string(sceneIndex) + "].nodes" : "nodes");

    if (report.droppedDegenerate || report.droppedNonFinite) {
        const std::string msg = file + ": dropped " + std::to_string(report.droppedDegenerate) + " degenerate and " +
                                std::to_string(report.droppedNonFinite) + " non-finite triangles";
        report.warnings.push_back(msg);
        logWarn(msg);
    }
    if (mesh.indices.empty()) throw Error(file + ": no triangles (in the scene's nodes)");
    computeBounds(mesh);
    if (reportOut) *reportOut = report;
    return out;
}

}  // namespace lp
