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

// MTL gives a transmissive (illum 4/6/7) material no volume thickness: each one's is the smallest
// extent of the bounding box of its triangles (a solid's width: a sphere's diameter, a slab's
// thickness; 0 for a flat pane, thin-walled). Called by loadObj.
void setObjTransmissionThickness(MeshData& mesh);

}  // namespace lp
