// The glTF 2.0 JSON schema's rules for the properties lightpass reads, checked on the document
// before it is used: tinygltf silently skips a property of the wrong JSON type (an `emissiveFactor`
// of strings, a `mesh` of 0.5, `attributes` given as an array), so without this such files loaded
// as if the property were absent.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace lp {

struct GltfSchemaIssue {
    std::string where;  // the element as the file names it: materials[0].pbrMetallicRoughness.roughnessFactor
    std::string what;
    bool error = true;  // false: a value outside the schema's range that the loader clamps (a warning)
};

// Every issue of `root` (a glTF document's JSON), errors and warnings, in document order:
// - errors: a property of the wrong JSON type, an array of the wrong length or element type, an index
//   that is not an integer >= 0, a value not in its enumeration (componentType, type, mode, alphaMode,
//   camera and light types), a required property missing, a count, length
//   or camera extent the schema requires positive, a negative light intensity or colour;
// - warnings: material factors outside [0, 1] and a negative alphaCutoff (the loader clamps them), a
//   bufferView's byteStride of 0 (read as packed), a sampler's filter or wrap outside its enumeration
//   (the loader keeps the default), and any rule broken by a property lightpass does not read (an
//   accessor's min and max).
// - errors also for what tinygltf would refuse without naming the element: an image with both or neither
//   of uri and bufferView, a sparse accessor's parts, a spot light without `spot`, a skin without
//   joints, an animation channel or sampler missing what the schema requires, a primitive's indices
//   accessor that does not exist or has no bufferView.
// Other extensions and extras are not checked.
std::vector<GltfSchemaIssue> checkGltfSchema(const nlohmann::json& root);

// A sampler's enumerations (OpenGL's enum values), which the check and the loader both hold values to.
inline const std::vector<int64_t> kGltfSamplerWraps = {33071, 33648, 10497};  // CLAMP_TO_EDGE, MIRRORED_REPEAT, REPEAT
inline const std::vector<int64_t> kGltfMagFilters = {9728, 9729};             // NEAREST, LINEAR
inline const std::vector<int64_t> kGltfMinFilters = {9728, 9729, 9984, 9985, 9986, 9987};  // .. LINEAR_MIPMAP_LINEAR

}  // namespace lp
