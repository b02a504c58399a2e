#pragma once
// glTF 2.0 (.gltf + .bin, .glb) through tinygltf, into the same MeshData the OBJ loader makes, plus the
// file's cameras and KHR_lights_punctual lights.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "engine/scene/animation.hpp"
#include "engine/scene/mesh.hpp"
#include "engine/scene/scene.hpp"

namespace lp {

// A mesh that several still nodes draw (loadGltf with instanceReusedMeshes): its primitives once, in
// the mesh's own space, and the world transform of each node that draws it.
struct GltfInstancedMesh {
    int meshIndex = 0;  // into the file's meshes
    MeshData mesh;      // with every material of GltfContent::mesh (its sub-meshes index them alike)
    std::vector<glm::mat4> transforms;
};

struct GltfContent {
    // Every triangle primitive of the file's scene (its default scene, else scenes[0], else every root
    // node), each node's world transform (parent x translation x rotation x scale, or its matrix) baked
    // into positions, normals and tangents. Texture v is flipped to the OBJ convention (v = 0 at the
    // bottom of the image), with tangents to match.
    MeshData mesh;
    std::vector<Camera> cameras;  // perspective cameras placed by their nodes, in file order
    std::vector<DirectionalLight> directionalLights;
    std::vector<PointLight> pointLights;  // point lights, and spot lights (`spot` set: the node's -Z, the cone)
    // The file's animations (node translation, rotation and scale), checked whole; null when it has
    // none. The mesh above is the rest pose; the vertices of nodes a channel moves are also kept in
    // their node's space (NodeAnimation::ranges). Cameras and lights stay where the rest pose puts them.
    std::shared_ptr<const NodeAnimation> animation;
    // instanceReusedMeshes: the meshes drawn by more than one node that no clip, skin or morph target
    // moves (a node that mirrors stays baked), left out of `mesh` above.
    std::vector<GltfInstancedMesh> instancedMeshes;
};

// Throws lp::Error("<path>: <element>: <what>"), the element as the file names it
// ("meshes[2].primitives[0].indices", "accessors[5]", "extensionsRequired"), for what cannot be drawn
// right: a file tinygltf cannot parse, a missing buffer, an accessor or buffer view beyond its buffer,
// an index beyond the vertices, a required extension this loader lacks, a node cycle, no triangles.
// Warns (naming the element) and goes on for a missing or bad texture (checker), non-triangle
// primitives, orthographic cameras, spot lights (as points), BLEND materials (as MASK).
// instanceReusedMeshes: a mesh several still nodes draw is stored once (GltfContent::instancedMeshes)
// instead of baked once per node.
GltfContent loadGltf(const std::filesystem::path& path, MeshLoadReport* report = nullptr, bool instanceReusedMeshes = false);

// ".gltf" or ".glb" (any case).
bool isGltfPath(const std::filesystem::path& path);

}  // namespace lp
