#pragma once
// CPU-side mesh and material data, as loaded from OBJ/MTL or glTF or made by the primitive generators.
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

namespace lp {

struct Vertex {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 1.0f, 0.0f};
    glm::vec2 uv{0.0f};
    glm::vec4 tangent{1.0f, 0.0f, 0.0f, 1.0f};  // xyz tangent, w = handedness (+1/-1) for the bitangent
    // Linear RGBA multiplying the material's base colour and alpha (glTF COLOR_0); white: none.
    glm::vec4 color{1.0f};
    // The second uv set (glTF TEXCOORD_1), read by the textures whose uvSet is 1. Last, so that the
    // GPU's vertex buffer is the 64 bytes before it (lp::GpuVertex); it travels in a second buffer,
    // and only for the meshes that sample it.
    glm::vec2 uv1{0.0f};
};

// How a texture is sampled: a glTF sampler's wraps and filters, as glTF writes them (OpenGL's enum
// values). 0 for a filter: lightpass's default (trilinear, 8x anisotropic).
struct TextureSampler {
    int wrapS = 10497;  // GL_REPEAT; GL_CLAMP_TO_EDGE 33071, GL_MIRRORED_REPEAT 33648
    int wrapT = 10497;
    int magFilter = 0;  // GL_NEAREST 9728, GL_LINEAR 9729
    int minFilter = 0;  // GL_NEAREST .. GL_LINEAR_MIPMAP_LINEAR (9728, 9729, 9984..9987)
    bool isDefault() const { return wrapS == 10497 && wrapT == 10497 && magFilter == 0 && minFilter == 0; }
};

// A texture: a file, or an image embedded in a glTF (encoded bytes, decoded when uploaded), or one
// known to be unusable (`problem`: a data URI that is not base64, a texture without an image), which
// is uploaded as the checker with a warning "<key>: <problem>; using a checker texture". `key`
// identifies the image for sharing ("<file>" or "<gltf>#images[3]"); one image sampled two ways is
// two textures.
struct TextureRef {
    std::filesystem::path path;
    std::shared_ptr<const std::string> encoded;
    std::string problem;
    std::string key;
    TextureSampler sampler;
    int uvSet = 0;  // the uv set it is sampled with: 0 (Vertex::uv, TEXCOORD_0) or 1 (Vertex::uv1, TEXCOORD_1)
    bool empty() const { return path.empty() && !encoded && problem.empty(); }
    void clear() { *this = TextureRef{}; }
    static TextureRef file(const std::filesystem::path& p) {
        TextureRef t;
        t.path = p;
        t.key = p.string();
        return t;
    }
};

enum class AlphaMode { Opaque, Mask, Blend };

// A material's maps as bits, in the order of their texture units (shaders/common/material.glsl), the
// emissive map last; the shaders' LP_MAP_* (common/uv_sets.glsl) are the same values.
enum MaterialMapBit : uint32_t {
    kDiffuseMapBit = 1, kBumpMapBit = 2, kNormalMapBit = 4, kMetalRoughMapBit = 8, kOcclusionMapBit = 16, kEmissiveMapBit = 32,
    kSpecularMapBit = 64, kSpecularColorMapBit = 128, kClearcoatMapBit = 256, kClearcoatRoughnessMapBit = 512,
    kClearcoatNormalMapBit = 1024, kTransmissionMapBit = 2048, kThicknessMapBit = 4096
};

// The one material model of both formats: metallic-roughness (glTF 2.0), with the dielectric F0
// (`specular`) kept as a colour so that MTL's Ks maps onto it exactly. What the lights see per texel:
//   kd = base (1 - metallic), F0 = mix(specular, base, metallic), GGX alpha = roughness^2,
//   Blinn-Phong exponent n = 2 / alpha^2 - 2 (the Beckmann equivalence alpha = sqrt(2 / (n + 2))).
// MTL: base = Kd, specular = Ks, metallic 0, n = Ns; glTF: specular 0.04, n from roughnessFactor.
// Colours are linear RGB. Texture coordinates use v = 0 at the bottom of the image (glTF's are flipped
// on load).
struct Material {
    std::string name = "default";
    glm::vec3 diffuse{0.8f};    // base colour: Kd, or baseColorFactor.rgb
    float opacity = 1.0f;       // baseColorFactor.a, or MTL d (1 - Tr)
    glm::vec3 specular{0.04f};  // dielectric F0: Ks, or 0.04 for glTF (KHR_materials_specular: below)
    // KHR_materials_specular: the dielectric's f90, its specular weight (specularFactor), given instead
    // of derived from F0 (shaders/common/brdf.glsl); `specular` then holds F0_ior x specularColorFactor,
    // unclamped: the dielectric's F0 is min(specular x specularColorMap.rgb, 1) x weight x specularMap.a
    // (dielectricF0Of on the CPU, material.glsl on the GPU).
    std::optional<float> dielectricF90;
    TextureRef specularMap;       // KHR_materials_specular specularTexture: the weight in a (linear)
    TextureRef specularColorMap;  // specularColorTexture: F0's colour in rgb (sRGB)
    // KHR_materials_clearcoat: a GGX layer over the whole material (shaders/common/brdf.glsl's
    // ClearcoatLayer): clearcoat = clearcoat x clearcoatMap.r (0: no coat, the plain material), its
    // roughness = clearcoatRoughness x clearcoatRoughnessMap.g, its normal the interpolated one or
    // clearcoatNormalMap's (scaled by clearcoatNormalScale). The maps are linear.
    float clearcoat = 0.0f;
    float clearcoatRoughness = 0.0f;
    TextureRef clearcoatMap;
    TextureRef clearcoatRoughnessMap;
    TextureRef clearcoatNormalMap;
    float clearcoatNormalScale = 1.0f;
    // KHR_materials_transmission + KHR_materials_volume (MTL: illum 4/6/7, Tf, Ni): the dielectric's
    // base mixes its diffuse BRDF with a refracting BTDF by transmission x transmissionMap.r; the
    // volume under the surface is thickness x thicknessMap.g (model space; 0: thin-walled) thick and
    // absorbs as attenuationColor^(d / attenuationDistance) (infinite: no absorption). ior is the
    // index of refraction (KHR_materials_ior; MTL Ni): the refracted ray's bend (the dielectric's F0
    // stays `specular`).
    float transmission = 0.0f;
    TextureRef transmissionMap;
    float ior = 1.5f;
    float thickness = 0.0f;
    TextureRef thicknessMap;
    float attenuationDistance = std::numeric_limits<float>::infinity();
    glm::vec3 attenuationColor{1.0f};
    float metallic = 0.0f;      // metallicFactor (MTL: 0)
    float shininess = 32.0f;    // Ns (Blinn-Phong exponent), clamped to [0, 10000]; glTF: from roughness
    float roughness = 0.5f;     // perceptual roughness: roughnessFactor, or from Ns (used with metallicRoughnessMap)
    glm::vec3 emission{0.0f};   // Ke, or emissiveFactor x KHR_materials_emissive_strength: radiance added
    TextureRef diffuseMap;            // map_Kd / baseColorTexture (sRGB; its alpha multiplies opacity)
    TextureRef metallicRoughnessMap;  // glTF: roughness in g, metallic in b (linear)
    TextureRef normalMap;             // MTL norm / glTF normalTexture: tangent-space normal (linear)
    float normalScale = 1.0f;         // normalTexture.scale / norm -bm: scales the map's x and y
    TextureRef bumpMap;               // MTL map_Bump / bump: height map in r (linear)
    float bumpScale = 1.0f;           // -bm
    TextureRef occlusionMap;          // glTF occlusionTexture: r darkens ambient and IBL light only
    float occlusionStrength = 1.0f;
    TextureRef emissiveMap;           // map_Ke / emissiveTexture (sRGB), multiplies `emission`
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;         // MASK: texels with alpha below it are not drawn
    bool doubleSided = true;          // MTL: always (thin walls); glTF: doubleSided
    // Flat-lit (seed 003): shown as its diffuse colour, untouched by any light (lamps, light globes).
    bool flat = false;
    // The MaterialMapBit of each of its maps sampled with the second uv set (Vertex::uv1).
    uint32_t secondUvMaps() const {
        const std::pair<const TextureRef*, MaterialMapBit> maps[] = {
            {&diffuseMap, kDiffuseMapBit},         {&bumpMap, kBumpMapBit},           {&normalMap, kNormalMapBit},
            {&metallicRoughnessMap, kMetalRoughMapBit}, {&occlusionMap, kOcclusionMapBit}, {&emissiveMap, kEmissiveMapBit},
            {&specularMap, kSpecularMapBit}, {&specularColorMap, kSpecularColorMapBit},
            {&clearcoatMap, kClearcoatMapBit}, {&clearcoatRoughnessMap, kClearcoatRoughnessMapBit},
            {&clearcoatNormalMap, kClearcoatNormalMapBit}, {&transmissionMap, kTransmissionMapBit},
            {&thicknessMap, kThicknessMapBit}};
        uint32_t bits = 0;
        for (const auto& [map, bit] : maps)
            if (!map->empty() && map->uvSet == 1) bits |= bit;
        return bits;
    }
    bool samplesUv1() const { return secondUvMaps() != 0; }
    // KHR_materials_clearcoat with a layer (the factor above 0; unlit materials take none).
    bool hasClearcoat() const { return clearcoat > 0.0f && !flat; }
    // KHR_materials_transmission with some transmission (unlit materials take none): drawn by the
    // transparent pass, refracting the opaque frame (passes/transparent_pass).
    bool transmissive() const { return transmission > 0.0f && !flat; }
    // The dielectric's F0 of the factors alone (the maps taken as white): Ks, F0_ior, or with
    // KHR_materials_specular min(F0_ior x colour, 1) x weight.
    glm::vec3 dielectricF0Of() const {
        const glm::vec3 f0 = glm::clamp(specular, 0.0f, 1.0f);
        return dielectricF90 ? f0 * std::clamp(*dielectricF90, 0.0f, 1.0f) : f0;
    }
};

// Smallest perceptual roughness a material can have (GGX alpha = r^2 = 4e-4). The G-buffer's
// shininess channel holds it (shaders/common/gbuffer_layout.glsl gbufferEncodeShininess).
constexpr float kMinRoughness = 0.02f;

// The Blinn-Phong exponent equivalent to a perceptual roughness (alpha = r^2 = sqrt(2 / (n + 2))),
// r clamped to [kMinRoughness, 1] (n from 0 to 1.25e7), and back. The analytic BRDFs clamp n to
// 10000 themselves (r >= 0.119, shaders/common/brdf.glsl); image-based lighting reaches the floor.
float shininessFromRoughness(float roughness);
float roughnessFromShininess(float shininess);

struct SubMesh {
    uint32_t firstIndex = 0;
    uint32_t indexCount = 0;
    int material = 0;  // index into MeshData::materials: the one drawn
    // KHR_materials_variants: the material of each of MeshData::materialVariants (empty: the same for
    // every variant), and the one drawn without a variant (selectMaterialVariant switches between them).
    std::vector<int> variantMaterials;
    int defaultMaterial = 0;
};

struct MeshData {
    std::string name;
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;  // triangles
    std::vector<SubMesh> subMeshes;
    std::vector<Material> materials;  // at least one
    // KHR_materials_variants: the file's variant names, in its order (empty: none).
    std::vector<std::string> materialVariants;
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
