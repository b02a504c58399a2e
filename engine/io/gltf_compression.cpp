#include "engine/io/gltf_compression.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <new>
#include <optional>
#include <set>
#include <vector>

#include <draco/compression/decode.h>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "engine/core/error.hpp"

namespace lp {
namespace {

using json = nlohmann::json;

// One decoded buffer view or Draco attribute may hold at most this many bytes: the file's numbers
// (a count, a stride) size the decoders' output before any stream is read.
constexpr uint64_t kMaxDecodedBytes = uint64_t(1) << 31;

// The extension's modes and filters, each with what its stride must be.
enum class MeshoptMode { Attributes, Triangles, Indices };
enum class MeshoptFilter { None, Octahedral, Quaternion, Exponential };
struct MeshoptModeName {
    const char* name;
    MeshoptMode mode;
};
constexpr MeshoptModeName kMeshoptModes[] = {
    {"ATTRIBUTES", MeshoptMode::Attributes}, {"TRIANGLES", MeshoptMode::Triangles}, {"INDICES", MeshoptMode::Indices}};
struct MeshoptFilterName {
    const char* name;
    MeshoptFilter filter;
};
constexpr MeshoptFilterName kMeshoptFilters[] = {{"NONE", MeshoptFilter::None},
                                                 {"OCTAHEDRAL", MeshoptFilter::Octahedral},
                                                 {"QUATERNION", MeshoptFilter::Quaternion},
                                                 {"EXPONENTIAL", MeshoptFilter::Exponential}};

const json* member(const json& object, const char* key) {
    if (!object.is_object()) return nullptr;
    const auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
}
const json* extensionOf(const json& object, const char* name) {
    const json* extensions = member(object, "extensions");
    return extensions ? member(*extensions, name) : nullptr;
}

std::string describe(const json& v) {
    if (v.is_string()) return quoteUserText(v.get<std::string>(), 32);
    if (v.is_number()) return v.dump();
    return std::string("a") + (v.is_object() || v.is_array() ? "n " : " ") + v.type_name();
}

// Reads the extension objects' properties, each fault one line naming the property.
struct ExtensionReader {
    const json& object;
    std::string where;  // "file: bufferViews[3].extensions.EXT_meshopt_compression"

    [[noreturn]] void fail(const std::string& what) const { throw Error(where + ": " + what); }
    [[noreturn]] void fail(const std::string& key, const std::string& what) const { throw Error(where + "." + key + ": " + what); }

    uint64_t integer(const char* key, std::optional<uint64_t> fallback = std::nullopt) const {
        const json* v = member(object, key);
        if (!v) {
            if (!fallback) fail(key, "missing");
            return *fallback;
        }
        if (v->is_number_unsigned()) return v->get<uint64_t>();
        if (v->is_number_float()) {
            const double d = v->get<double>();
            if (d >= 0.0 && d < 9007199254740992.0 && std::floor(d) == d) return uint64_t(d);
        }
        fail(key, "expected an integer >= 0, got " + describe(*v));
    }
    std::string string(const char* key, const char* fallback) const {
        const json* v = member(object, key);
        if (!v) {
            if (!fallback) fail(key, "missing");
            return fallback;
        }
        if (!v->is_string()) fail(key, "expected a string, got " + describe(*v));
        return v->get<std::string>();
    }
};

std::string bufferWhere(size_t index) { return "buffers[" + std::to_string(index) + "]"; }

// EXT_meshopt_compression: each compressed buffer view decoded into a new buffer, which the view then
// reads from byte 0 (its byteLength is the decoded size).
void decodeMeshoptViews(tinygltf::Model& model, const json& root, const GltfCompressedParts& parts, const std::string& file) {
    const json* views = member(root, "bufferViews");
    if (!views) return;
    for (size_t i = 0; i < views->size() && i < model.bufferViews.size(); ++i) {
        const json* ext = extensionOf((*views)[i], kMeshoptExtension);
        if (!ext) continue;
        const ExtensionReader r{*ext, file + ": bufferViews[" + std::to_string(i) + "].extensions." + kMeshoptExtension};
        if (!ext->is_object()) r.fail("expected an object, got " + describe(*ext));
        const uint64_t buffer = r.integer("buffer");
        const uint64_t byteOffset = r.integer("byteOffset", 0);
        const uint64_t byteLength = r.integer("byteLength");
        const uint64_t stride = r.integer("byteStride");
        const uint64_t count = r.integer("count");
        const std::string modeName = r.string("mode", nullptr);
        const std::string filterName = r.string("filter", "NONE");
        const MeshoptModeName* mode = nullptr;
        for (const MeshoptModeName& m : kMeshoptModes)
            if (modeName == m.name) mode = &m;
        if (!mode) r.fail("mode", quoteUserText(modeName, 32) + " is not ATTRIBUTES, TRIANGLES or INDICES");
        const MeshoptFilterName* filter = nullptr;
        for (const MeshoptFilterName& f : kMeshoptFilters)
            if (filterName == f.name) filter = &f;
        if (!filter) r.fail("filter", quoteUserText(filterName, 32) + " is not NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL");

        if (buffer >= model.buffers.size())
            r.fail("buffer", std::to_string(buffer) + " does not exist (" + std::to_string(model.buffers.size()) + " buffers)");
        if (parts.fallbackBuffers.count(size_t(buffer)))
            r.fail("buffer", bufferWhere(buffer) + " is a fallback buffer, which holds no data");
        const std::vector<unsigned char>& source = model.buffers[size_t(buffer)].data;
        if (byteOffset > source.size() || byteLength > source.size() - byteOffset)
            r.fail("bytes " + std::to_string(byteOffset) + "+" + std::to_string(byteLength) + " run past the end of " + bufferWhere(buffer) +
                   " (" + std::to_string(source.size()) + " bytes)");

        // The spec's rules for the stride of each mode and filter (meshoptimizer asserts them).
        if (count == 0) r.fail("count", "must be at least 1");
        if (count > kMaxGltfElements) r.fail("count", std::to_string(count) + " is over the limit (" + std::to_string(kMaxGltfElements) + ")");
        switch (mode->mode) {
            case MeshoptMode::Attributes:
                if (stride == 0 || stride > 256 || stride % 4 != 0)
                    r.fail("byteStride", std::to_string(stride) + " is not a multiple of 4 from 4 to 256 (mode ATTRIBUTES)");
                break;
            case MeshoptMode::Triangles:
                if (count % 3 != 0) r.fail("count", std::to_string(count) + " is not a multiple of 3 (mode TRIANGLES)");
                [[fallthrough]];
            case MeshoptMode::Indices:
                if (stride != 2 && stride != 4) r.fail("byteStride", std::to_string(stride) + " is not 2 or 4 (mode " + modeName + ")");
                break;
        }
        if (filter->filter != MeshoptFilter::None && mode->mode != MeshoptMode::Attributes)
            r.fail("filter", filterName + " applies to mode ATTRIBUTES only, not " + modeName);
        if ((filter->filter == MeshoptFilter::Octahedral && stride != 4 && stride != 8) ||
            (filter->filter == MeshoptFilter::Quaternion && stride != 8))
            r.fail("byteStride", std::to_string(stride) + " does not suit filter " + filterName +
                                     (filter->filter == MeshoptFilter::Octahedral ? " (4 or 8)" : " (8)"));
        tinygltf::BufferView& view = model.bufferViews[i];
        // The view must lie inside its own buffer (the fallback's declared byteLength), as any view.
        const std::string viewWhere = file + ": bufferViews[" + std::to_string(i) + "]";
        if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
            throw Error(viewWhere + ": buffer " + std::to_string(view.buffer) + " does not exist (" + std::to_string(model.buffers.size()) + " buffers)");
        const auto fallback = parts.fallbackBuffers.find(size_t(view.buffer));
        const uint64_t parentBytes = fallback != parts.fallbackBuffers.end() ? fallback->second : model.buffers[size_t(view.buffer)].data.size();
        if (view.byteOffset > parentBytes || view.byteLength > parentBytes - view.byteOffset)
            throw Error(viewWhere + ": bytes " + std::to_string(view.byteOffset) + "+" + std::to_string(view.byteLength) + " run past the end of " +
                        bufferWhere(size_t(view.buffer)) + " (" + std::to_string(parentBytes) + " bytes)");
        const uint64_t decodedBytes = count * stride;  // < 2^28 * 2^8
        if (decodedBytes != view.byteLength)
            r.fail("count " + std::to_string(count) + " x byteStride " + std::to_string(stride) + " = " + std::to_string(decodedBytes) +
                   " bytes, but the buffer view's byteLength is " + std::to_string(view.byteLength));
        if (view.byteStride != 0 && view.byteStride != stride)
            r.fail("byteStride", std::to_string(stride) + " differs from the buffer view's byteStride " + std::to_string(view.byteStride));
        if (decodedBytes > kMaxDecodedBytes) r.fail(std::to_string(decodedBytes) + " decoded bytes are over the limit (" + std::to_string(kMaxDecodedBytes) + ")");

        tinygltf::Buffer decoded;
        decoded.data.resize(size_t(decodedBytes));
        const unsigned char* stream = source.data() + byteOffset;
        int rc = 0;
        switch (mode->mode) {
            case MeshoptMode::Attributes: rc = meshopt_decodeVertexBuffer(decoded.data.data(), count, stride, stream, byteLength); break;
            case MeshoptMode::Triangles: rc = meshopt_decodeIndexBuffer(decoded.data.data(), count, stride, stream, byteLength); break;
            case MeshoptMode::Indices: rc = meshopt_decodeIndexSequence(decoded.data.data(), count, stride, stream, byteLength); break;
        }
        if (rc != 0)
            r.fail("meshopt decoding failed (" + modeName + ", " + std::to_string(count) + " elements of " + std::to_string(stride) +
                   " bytes from " + std::to_string(byteLength) + " bytes): the stream is corrupt, truncated or of an unknown version (code " +
                   std::to_string(rc) + ")");
        switch (filter->filter) {
            case MeshoptFilter::None: break;
            case MeshoptFilter::Octahedral: meshopt_decodeFilterOct(decoded.data.data(), count, stride); break;
            case MeshoptFilter::Quaternion: meshopt_decodeFilterQuat(decoded.data.data(), count, stride); break;
            case MeshoptFilter::Exponential: meshopt_decodeFilterExp(decoded.data.data(), count, stride); break;
        }
        model.buffers.push_back(std::move(decoded));
        view.buffer = int(model.buffers.size() - 1);
        view.byteOffset = 0;
    }
    // What is left in a fallback buffer has no data behind it.
    for (size_t i = 0; i < model.bufferViews.size(); ++i) {
        const int b = model.bufferViews[i].buffer;
        if (b >= 0 && parts.fallbackBuffers.count(size_t(b)))
            throw Error(file + ": bufferViews[" + std::to_string(i) + "]: reads " + bufferWhere(size_t(b)) + ", a " + kMeshoptExtension +
                        " fallback buffer, which holds no data (only views with the extension may name it)");
    }
    for (const auto& [index, byteLength] : parts.fallbackBuffers) {
        (void)byteLength;
        if (index < model.buffers.size()) model.buffers[index].data.clear();  // the stand-in byte
    }
}

// One Draco attribute value as the accessor's component type. An integer attribute into an integer
// accessor, and anything into a float one, is Draco's conversion (which dequantises and normalises
// as the stream says); a float attribute into a (normalised) integer accessor is rounded here, as the
// glTF spec's normalisation rules (round(f * max)) say.
template <typename OutT>
bool storeValue(const draco::PointAttribute& att, draco::AttributeValueIndex value, int components, bool normalized, unsigned char* out) {
    OutT converted[4] = {};
    if (std::is_floating_point<OutT>::value || draco::IsDataTypeIntegral(att.data_type())) {
        if (!att.ConvertValue<OutT>(value, int8_t(components), converted)) return false;
    } else {
        float f[4] = {};
        if (!att.ConvertValue<float>(value, int8_t(components), f)) return false;
        for (int c = 0; c < components; ++c) {
            const double x = normalized ? double(f[c]) * double(std::numeric_limits<OutT>::max()) : double(f[c]);
            const double rounded = std::round(x);
            if (!(rounded >= double(std::numeric_limits<OutT>::min()) && rounded <= double(std::numeric_limits<OutT>::max()))) return false;
            converted[c] = OutT(rounded);
        }
    }
    std::memcpy(out, converted, sizeof(OutT) * size_t(components));
    return true;
}

bool storeComponents(int componentType, const draco::PointAttribute& att, draco::AttributeValueIndex value, int components, bool normalized,
                     unsigned char* out) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: return storeValue<int8_t>(att, value, components, normalized, out);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return storeValue<uint8_t>(att, value, components, normalized, out);
        case TINYGLTF_COMPONENT_TYPE_SHORT: return storeValue<int16_t>(att, value, components, normalized, out);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return storeValue<uint16_t>(att, value, components, normalized, out);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return storeValue<uint32_t>(att, value, components, normalized, out);
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return storeValue<float>(att, value, components, normalized, out);
    }
    return false;
}

// Appends `bytes` (4-byte aligned) to `buffer` as a new buffer view and points `accessor` at it.
void attachView(tinygltf::Model& model, int bufferIndex, std::vector<unsigned char>& buffer, const std::vector<unsigned char>& bytes,
                tinygltf::Accessor& accessor) {
    buffer.resize((buffer.size() + 3) / 4 * 4);
    tinygltf::BufferView view;
    view.buffer = bufferIndex;
    view.byteOffset = buffer.size();
    view.byteLength = bytes.size();
    buffer.insert(buffer.end(), bytes.begin(), bytes.end());
    model.bufferViews.push_back(view);
    accessor.bufferView = int(model.bufferViews.size() - 1);
    accessor.byteOffset = 0;
}

// KHR_draco_mesh_compression: each primitive's Draco mesh decoded into new buffer views of the
// accessors its `attributes` (by unique id) and its `indices` name, in their componentType.
void decodeDracoPrimitives(tinygltf::Model& model, const json& root, const GltfCompressedParts& parts, const std::string& file) {
    // Accessor -> where its data was decoded from: one accessor filled by two different streams is an error.
    std::map<int, std::pair<uint64_t, std::string>> decodedFrom;
    for (const auto& [key, indicesAccessor] : parts.dracoPrimitives) {
        const auto [meshIndex, primIndex] = key;
        tinygltf::Primitive& prim = model.meshes.at(meshIndex).primitives.at(primIndex);
        prim.indices = indicesAccessor;
        const std::string pw = "meshes[" + std::to_string(meshIndex) + "].primitives[" + std::to_string(primIndex) + "]";
        const json& ext = *extensionOf(root["meshes"][meshIndex]["primitives"][primIndex], kDracoExtension);
        const ExtensionReader r{ext, file + ": " + pw + ".extensions." + kDracoExtension};
        if (!ext.is_object()) r.fail("expected an object, got " + describe(ext));
        if (prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP || prim.mode == TINYGLTF_MODE_TRIANGLE_FAN)
            r.fail("a Draco mesh is a triangle list (mode 4), but the primitive's mode is " + std::to_string(prim.mode));
        if (prim.mode != TINYGLTF_MODE_TRIANGLES) continue;  // points and lines: not drawn (the loader says so)
        const uint64_t viewIndex = r.integer("bufferView");
        const json* attributes = member(ext, "attributes");
        if (!attributes) r.fail("attributes", "missing");
        if (!attributes->is_object()) r.fail("attributes", "expected an object, got " + describe(*attributes));
        if (viewIndex >= model.bufferViews.size())
            r.fail("bufferView", std::to_string(viewIndex) + " does not exist (" + std::to_string(model.bufferViews.size()) + " buffer views)");
        const tinygltf::BufferView& view = model.bufferViews[size_t(viewIndex)];
        if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
            r.fail("bufferView", "bufferViews[" + std::to_string(viewIndex) + "] names buffer " + std::to_string(view.buffer) + ", which does not exist");
        const std::vector<unsigned char>& source = model.buffers[size_t(view.buffer)].data;
        if (view.byteOffset > source.size() || view.byteLength > source.size() - view.byteOffset)
            r.fail("bufferView", "bufferViews[" + std::to_string(viewIndex) + "]: bytes " + std::to_string(view.byteOffset) + "+" +
                                     std::to_string(view.byteLength) + " run past the end of " + bufferWhere(size_t(view.buffer)) + " (" +
                                     std::to_string(source.size()) + " bytes)");

        // The decoder reads the buffer view's bytes and no further.
        draco::DecoderBuffer stream;
        stream.Init(reinterpret_cast<const char*>(source.data() + view.byteOffset), view.byteLength);
        const auto geometry = draco::Decoder::GetEncodedGeometryType(&stream);
        if (!geometry.ok()) r.fail("Draco decoding failed: " + oneLineMessage(geometry.status().error_msg_string(), 200));
        if (geometry.value() != draco::TRIANGULAR_MESH) r.fail("Draco decoding failed: the stream holds a point cloud, not a triangle mesh");
        draco::Decoder decoder;
        auto decoded = decoder.DecodeMeshFromBuffer(&stream);
        if (!decoded.ok()) r.fail("Draco decoding failed: " + oneLineMessage(decoded.status().error_msg_string(), 200));
        const draco::Mesh& mesh = *decoded.value();
        const size_t points = mesh.num_points();

        const int bufferIndex = int(model.buffers.size());
        tinygltf::Buffer out;
        std::vector<unsigned char> bytes;
        for (const auto& [name, idValue] : attributes->items()) {
            const std::string aw = "attributes." + name;
            if (!idValue.is_number_unsigned()) r.fail(aw, "expected a Draco attribute id (an integer >= 0), got " + describe(idValue));
            const uint64_t id = idValue.get<uint64_t>();
            const auto it = prim.attributes.find(name);
            if (it == prim.attributes.end()) r.fail(aw, "the primitive has no " + quoteUserText(name, 32) + " attribute to decode it into");
            const int accessorIndex = it->second;
            if (accessorIndex < 0 || size_t(accessorIndex) >= model.accessors.size())
                r.fail(aw, "accessor " + std::to_string(accessorIndex) + " does not exist (" + std::to_string(model.accessors.size()) + " accessors)");
            if (const auto seen = decodedFrom.find(accessorIndex); seen != decodedFrom.end()) {
                if (seen->second.first == viewIndex && seen->second.second == name + "/" + std::to_string(id)) continue;  // the same stream again
                r.fail(aw, "accessors[" + std::to_string(accessorIndex) + "] is also decoded from another Draco stream or attribute");
            }
            tinygltf::Accessor& accessor = model.accessors[size_t(accessorIndex)];
            const std::string accessorWhere = "accessors[" + std::to_string(accessorIndex) + "]";
            const draco::PointAttribute* att = id <= std::numeric_limits<uint32_t>::max() ? mesh.GetAttributeByUniqueId(uint32_t(id)) : nullptr;
            if (!att) r.fail(aw, "the Draco mesh has no attribute of id " + std::to_string(id));
            const int components = tinygltf::GetNumComponentsInType(uint32_t(accessor.type));
            const int componentBytes = tinygltf::GetComponentSizeInBytes(uint32_t(accessor.componentType));
            if (components < 1 || components > 4 || componentBytes < 1)
                r.fail(aw, accessorWhere + " is not a scalar or vector of a glTF component type");
            if (att->num_components() != components)
                r.fail(aw, "the Draco attribute has " + std::to_string(att->num_components()) + " components, but " + accessorWhere + " has " +
                               std::to_string(components));
            if (accessor.count != points)
                r.fail(aw, "the Draco mesh has " + std::to_string(points) + " points, but " + accessorWhere + " has count " +
                               std::to_string(accessor.count));
            const size_t elementBytes = size_t(components) * size_t(componentBytes);
            if (uint64_t(points) * elementBytes > kMaxDecodedBytes) r.fail(aw, std::to_string(points) + " points are over the limit");
            bytes.assign(points * elementBytes, 0);
            for (size_t p = 0; p < points; ++p) {
                const draco::AttributeValueIndex value = att->mapped_index(draco::PointIndex(uint32_t(p)));
                if (value.value() >= att->size() ||
                    !storeComponents(accessor.componentType, *att, value, components, accessor.normalized, bytes.data() + p * elementBytes))
                    r.fail(aw, "point " + std::to_string(p) + "'s value cannot be stored as " + accessorWhere + "'s componentType " +
                                   std::to_string(accessor.componentType) + (accessor.normalized ? " (normalized)" : ""));
            }
            attachView(model, bufferIndex, out.data, bytes, accessor);
            decodedFrom[accessorIndex] = {viewIndex, name + "/" + std::to_string(id)};
        }
        if (prim.indices < 0) r.fail("the primitive has no indices accessor for the Draco mesh's triangles");
        if (size_t(prim.indices) >= model.accessors.size())
            r.fail("indices: accessor " + std::to_string(prim.indices) + " does not exist (" + std::to_string(model.accessors.size()) + " accessors)");
        if (const auto seen = decodedFrom.find(prim.indices); seen != decodedFrom.end()) {
            if (seen->second.first != viewIndex || seen->second.second != "indices")
                r.fail("indices: accessors[" + std::to_string(prim.indices) + "] is also decoded from another Draco stream or attribute");
        } else {
            tinygltf::Accessor& accessor = model.accessors[size_t(prim.indices)];
            const std::string accessorWhere = "accessors[" + std::to_string(prim.indices) + "]";
            const size_t faces = mesh.num_faces();
            if (accessor.type != TINYGLTF_TYPE_SCALAR) r.fail("indices: " + accessorWhere + " is not SCALAR");
            uint64_t largest = 0;
            switch (accessor.componentType) {
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: largest = 0xFF; break;
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: largest = 0xFFFF; break;
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: largest = 0xFFFFFFFF; break;
                default: r.fail("indices: " + accessorWhere + "'s componentType " + std::to_string(accessor.componentType) + " is not 5121, 5123 or 5125");
            }
            if (accessor.count != 3 * faces)
                r.fail("indices: the Draco mesh has " + std::to_string(faces) + " triangles (" + std::to_string(3 * faces) + " indices), but " +
                       accessorWhere + " has count " + std::to_string(accessor.count));
            const size_t indexBytes = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(accessor.componentType)));
            if (uint64_t(3 * faces) * indexBytes > kMaxDecodedBytes) r.fail("indices: " + std::to_string(faces) + " triangles are over the limit");
            bytes.assign(3 * faces * indexBytes, 0);
            for (size_t f = 0; f < faces; ++f) {
                const draco::Mesh::Face& face = mesh.face(draco::FaceIndex(uint32_t(f)));
                for (size_t c = 0; c < 3; ++c) {
                    const uint32_t index = face[c].value();
                    if (index > largest)
                        r.fail("indices: index " + std::to_string(index) + " does not fit " + accessorWhere + "'s componentType " +
                               std::to_string(accessor.componentType));
                    const uint8_t u8 = uint8_t(index);
                    const uint16_t u16 = uint16_t(index);
                    unsigned char* at = bytes.data() + (3 * f + c) * indexBytes;
                    if (indexBytes == 1) std::memcpy(at, &u8, 1);
                    else if (indexBytes == 2) std::memcpy(at, &u16, 2);
                    else std::memcpy(at, &index, 4);
                }
            }
            attachView(model, bufferIndex, out.data, bytes, accessor);
            decodedFrom[prim.indices] = {viewIndex, "indices"};
        }
        if (!out.data.empty()) model.buffers.push_back(std::move(out));
    }
}

}  // namespace

GltfCompressedParts findCompressedParts(const json& root, bool binary) {
    GltfCompressedParts parts;
    const json* buffers = member(root, "buffers");
    const json* views = member(root, "bufferViews");
    std::set<size_t> readPlainly, readCompressed;  // buffers read as data / through compressed views
    if (views && views->is_array())
        for (const json& v : *views) {
            const json* ext = extensionOf(v, kMeshoptExtension);
            const json* buffer = member(v, "buffer");
            if (buffer && buffer->is_number_unsigned()) (ext ? readCompressed : readPlainly).insert(buffer->get<size_t>());
            if (ext)
                if (const json* source = member(*ext, "buffer"); source && source->is_number_unsigned()) readPlainly.insert(source->get<size_t>());
        }
    if (buffers && buffers->is_array())
        for (size_t i = 0; i < buffers->size(); ++i) {
            const json& b = (*buffers)[i];
            const json* ext = extensionOf(b, kMeshoptExtension);
            const json* fallback = ext ? member(*ext, "fallback") : nullptr;
            const bool marked = fallback && fallback->is_boolean() && fallback->get<bool>();
            const bool noData = !member(b, "uri") && !(binary && i == 0) && readCompressed.count(i) && !readPlainly.count(i);
            const json* byteLength = member(b, "byteLength");
            if ((marked || noData) && byteLength && byteLength->is_number_unsigned()) parts.fallbackBuffers[i] = byteLength->get<uint64_t>();
        }
    if (const json* meshes = member(root, "meshes"); meshes && meshes->is_array())
        for (size_t m = 0; m < meshes->size(); ++m) {
            const json* primitives = member((*meshes)[m], "primitives");
            if (!primitives || !primitives->is_array()) continue;
            for (size_t p = 0; p < primitives->size(); ++p) {
                if (!extensionOf((*primitives)[p], kDracoExtension)) continue;
                const json* indices = member((*primitives)[p], "indices");
                parts.dracoPrimitives[{m, p}] = indices && indices->is_number_unsigned() ? indices->get<int>() : -1;
            }
        }
    return parts;
}

void hideCompressedParts(const GltfCompressedParts& parts, json& doc) {
    for (const auto& [index, byteLength] : parts.fallbackBuffers) {
        (void)byteLength;
        json& b = doc["buffers"][index];
        b["uri"] = "data:application/octet-stream;base64,AA==";
        b["byteLength"] = 1;
    }
    for (const auto& [key, indices] : parts.dracoPrimitives) {
        (void)indices;
        doc["meshes"][key.first]["primitives"][key.second].erase("indices");
    }
}

void decodeCompressedParts(tinygltf::Model& model, const json& root, const GltfCompressedParts& parts, const std::string& file) {
    try {
        decodeMeshoptViews(model, root, parts, file);
        decodeDracoPrimitives(model, root, parts, file);
    } catch (const std::bad_alloc&) {
        throw Error(file + ": the compressed geometry (" + std::string(kDracoExtension) + " or " + kMeshoptExtension +
                    ") decodes to more than this machine's memory");
    }
}

}  // namespace lp
