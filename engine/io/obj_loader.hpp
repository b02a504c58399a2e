#pragma once
// Wavefront OBJ + MTL through tinyobjloader, into MeshData ready for the GPU.
#include <filesystem>

#include "engine/scene/mesh.hpp"

namespace lp {

// Throws lp::Error("<path>: <what>") for a missing/unreadable/special file, "<path>:<line>: <what>" for
// a number or index that does not parse (obj_text), and for a mesh with no triangles left. Warns
// (naming the file, and the line where there is one) for a missing MTL, dropped triangles, bad
// material values.
MeshData loadObj(const std::filesystem::path& path, MeshLoadReport* report = nullptr);

}  // namespace lp
