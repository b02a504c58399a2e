#pragma once
// CPU-side mesh and material data, as loaded from OBJ/MTL or made by the primitive generators.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace lp {

struct Vertex {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 1.0f, 0.0f};
    glm::vec2 uv{0.0f};
    glm::vec4 tangent{1.0f, 0.0f, 0.0f, 1.0f};  // xyz tangent, w = handedness (+1/-1) for the bitangent
};

// MTL-style material. Colours are linear RGB. Texture paths are absolute (resolved by the loader
// against the MTL file's folder) or empty.
struct Material {
    std::string name = "default";
    glm::vec3 diffuse{0.8f};    // Kd
    glm::vec3 specular{0.04f};  // Ks
    float shininess = 32.0f;    // Ns (Blinn-Phong exponent), clamped to [0, 10000]
    glm::vec3 emission{0.0f};   // Ke
    std::filesystem::path diffuseMap;  // map_Kd (sRGB)
    std::filesystem::path bumpMap;     // map_Bump / bump / norm (linear)
    float bumpScale = 1.0f;            // -bm
    // Flat-lit (seed 003): shown as its diffuse colour, untouched by any light (lamps, light globes).
    bool flat = false;
};

struct SubMesh {
    uint32_t firstIndex = 0;
    uint32_t indexCount = 0;
    int material = 0;  // index into MeshData::materials
};

struct MeshData {
    std::string name;
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;  // triangles
    std::vector<SubMesh> subMeshes;
    std::vector<Material> materials;  // at least one
    glm::vec3 boundsMin{0.0f};
    glm::vec3 boundsMax{0.0f};
};

// What a load did besides succeeding; also logged as warnings by the loader.
struct MeshLoadReport {
    size_t droppedDegenerate = 0;  // zero-area or repeated-index triangles
    size_t droppedNonFinite = 0;   // triangles with a NaN/Inf position
    bool generatedNormals = false;
    bool generatedTangents = false;
    std::vector<std::string> warnings;
};

}  // namespace lp
