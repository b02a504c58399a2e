#pragma once
// glTF's compressed geometry, decoded with Debian's libraries so that the loader then reads plain
// buffer views and accessors:
//   EXT_meshopt_compression (meshoptimizer): a buffer view's bytes are a compressed stream in another
//     buffer (ATTRIBUTES, TRIANGLES or INDICES, with an optional OCTAHEDRAL, QUATERNION or EXPONENTIAL
//     filter); its own buffer may be a fallback that holds no data.
//   KHR_draco_mesh_compression (Draco): a primitive's attributes and indices are one Draco mesh in a
//     buffer view; the accessors keep their componentType, count and normalized but may have no
//     buffer view (or point at uncompressed fallback data, which the decoded data replaces).
// Every fault is one Error line "file: element: what" (docs/bad-input.md).
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <utility>

#include <nlohmann/json_fwd.hpp>

namespace tinygltf {
class Model;
}

namespace lp {

inline constexpr const char* kDracoExtension = "KHR_draco_mesh_compression";
inline constexpr const char* kMeshoptExtension = "EXT_meshopt_compression";
inline constexpr size_t kMaxGltfElements = size_t(1) << 28;  // an accessor's or decoded view's count limit: 268M elements

// What the two extensions change in a document, found before tinygltf reads it.
struct GltfCompressedParts {
    // EXT_meshopt_compression's fallback buffers (marked `fallback: true`, or without a uri where only
    // a GLB's first buffer may have none, and read by compressed buffer views only): index -> their
    // byteLength. They hold no data: tinygltf gets a one-byte stand-in.
    std::map<size_t, uint64_t> fallbackBuffers;
    // Draco primitives (mesh, primitive) -> their `indices` accessor, hidden from tinygltf, which
    // refuses an indices accessor without a buffer view (-1: none).
    std::map<std::pair<size_t, size_t>, int> dracoPrimitives;
    bool empty() const { return fallbackBuffers.empty() && dracoPrimitives.empty(); }
};

// The parts of `root` (already checked against the glTF schema) that use the two extensions. `binary`:
// a GLB, whose first buffer may have no uri.
GltfCompressedParts findCompressedParts(const nlohmann::json& root, bool binary);

// `doc` (a copy of the document) as tinygltf can read it: fallback buffers a one-byte data URI, Draco
// primitives without `indices`.
void hideCompressedParts(const GltfCompressedParts& parts, nlohmann::json& doc);

// After tinygltf: every EXT_meshopt_compression buffer view decoded into a buffer of its own (the view
// then reads it like any other), then every Draco primitive's attributes and indices decoded into new
// buffer views of its accessors. `root` is the document as the file holds it; `file` names errors.
void decodeCompressedParts(tinygltf::Model& model, const nlohmann::json& root, const GltfCompressedParts& parts, const std::string& file);

}  // namespace lp
