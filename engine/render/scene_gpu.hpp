#pragma once
// The scene's meshes, materials and textures on the GPU. Textures are shared by path, sRGB colour
// maps are stored as SRGB8_ALPHA8 (so sampling returns linear values) with full mip chains, and a
// missing texture becomes a visible checker with a warning.
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gl/handles.hpp"
#include "engine/render/shadow_casters.hpp"
#include "engine/scene/scene.hpp"

namespace lp {

// A vertex in the GPU's vertex buffers: lp::Vertex up to its second uv set, which a mesh whose
// materials sample it keeps in a buffer of its own (GpuMesh::uv1). 64 bytes: the visibility resolve
// reads it as four vec4.
struct GpuVertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec2 uv;
    glm::vec4 tangent;
    glm::vec4 color;
};
static_assert(sizeof(GpuVertex) == offsetof(Vertex, uv1), "GpuVertex is lp::Vertex up to uv1");

struct GpuMaterial {
    glm::vec3 diffuse{0.8f};  // base colour
    float opacity = 1.0f;
    glm::vec3 specular{0.04f};  // dielectric F0
    float metallic = 0.0f;
    float shininess = 32.0f;
    float roughness = 0.5f;
    glm::vec3 emission{0.0f};
    GLuint diffuseMap = 0;  // 0: none
    GLuint bumpMap = 0;
    float bumpScale = 1.0f;
    GLuint normalMap = 0;
    float normalScale = 1.0f;
    GLuint metallicRoughnessMap = 0;
    GLuint occlusionMap = 0;
    float occlusionStrength = 1.0f;
    GLuint emissiveMap = 0;
    uint32_t secondUvMaps = 0;  // Material::secondUvMaps: the maps sampled with the second uv set (TEXCOORD_1)
    bool alphaMask = false;
    bool alphaBlend = false;  // BLEND / MTL d < 1: drawn by the transparent pass, not into the G-buffer
    float alphaCutoff = 0.5f;
    bool doubleSided = true;
    bool flat = false;  // Material::flat; the viewer's panel switches it
    std::string name;   // the model's and the material's name, "cornell_box/light"
    bool emissive() const { return emission.x > 0.0f || emission.y > 0.0f || emission.z > 0.0f; }
};

struct GpuDraw {
    uint32_t firstIndex = 0;
    uint32_t indexCount = 0;
    int material = 0;  // into SceneGpu::materials
    glm::vec3 centre{0.0f};  // model space, the centre of the draw's bounding box
};

struct GpuMesh {
    std::string name;
    gl::VertexArray vao;
    gl::Buffer vertices;
    gl::Buffer indices;
    gl::Buffer uv1;  // the second uv set, a vec2 a vertex (attribute 5), where its materials sample it; else none
    glm::mat4 model{1.0f};
    std::vector<GpuDraw> draws;
};

class SceneGpu {
public:
    explicit SceneGpu(const Scene& scene);
    std::vector<GpuMesh> meshes;
    std::vector<GpuMaterial> materials;
    std::vector<CasterCluster> casterClusters;  // meshes[i] is CasterCluster::model i (shadow caster culling)
    size_t geometryBytes = 0;
    size_t textureBytes = 0;
    size_t triangleCount = 0;
    bool vertexColors = false;  // some vertex has a colour other than white (the G-buffer programs read them: LP_VERTEX_COLOR)
    bool secondUvSet = false;   // some material samples TEXCOORD_1 (the programs read it: LP_SECOND_UV)

private:
    GLuint texture(const TextureRef& ref, bool srgb);
    std::map<std::string, gl::Texture> textures_;
};

}  // namespace lp
