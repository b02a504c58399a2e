#pragma once
// The scene as the path tracer reads it (passes/path_trace_pass, shaders/path_trace.comp): every
// triangle in world space in BVH leaf order, its material as the raster passes evaluate it without
// textures, and the BVH. Plain data, no GL; the records are std430 (shaders/common/path_trace.glsl).
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "engine/render/bvh.hpp"
#include "engine/scene/scene.hpp"

namespace lp {

// One triangle: world positions (position[0].w: the material index), shading normals, both uv sets
// (xy: TEXCOORD_0, zw: TEXCOORD_1) and world tangents (w: the bitangent's handedness).
struct PathTraceTriangle {
    glm::vec4 position[3];
    glm::vec4 normal[3];
    glm::vec4 uv[3];
    glm::vec4 tangent[3];
};
static_assert(sizeof(PathTraceTriangle) == 192, "std430 layout of LpPathTraceTriangle");

// The maps the tracer samples, in this order in PathTraceMaterial::maps and its bit fields.
enum PathTraceMap : int { kPtMapBase = 0, kPtMapMetalRough = 1, kPtMapNormal = 2, kPtMapEmissive = 3, kPtMapCount = 4 };

// A material's factors (lp::Material after the scene file's overrides) and maps: what material.glsl
// makes of them, per hit.
struct PathTraceMaterial {
    glm::vec4 baseOpacity;        // base colour, opacity
    glm::vec4 specularMetallic;   // dielectric F0 (MTL Ks), metallic
    glm::vec4 emissionShininess;  // emitted radiance, Blinn-Phong exponent (the roughness's)
    glm::vec4 flags;              // x: flat-lit, y: double-sided, z: alpha mode (0 opaque, 1 MASK, 2 BLEND), w: cutoff
    // Layer of each PathTraceMap in its array (base colour and emissive: the sRGB array; metallic-
    // roughness and normal: the linear one), -1 without the map.
    glm::vec4 maps;
    // x: normal scale, y: perceptual roughness factor (multiplied by the map's g), z: the maps'
    // sampling bits (pathTraceMapBits), w: the dielectric f90 KHR_materials_specular gives (its
    // factor; the maps are not sampled), -1 without it (f90 derived from F0 as the raster does).
    glm::vec4 mapParams;
    // KHR_materials_clearcoat: x its factor (0: no coat), y its roughness factor (the coat's maps are
    // not sampled: the factors alone, warned with the other unsampled maps), zw 0.
    glm::vec4 clearcoat{0.0f};
    // KHR_materials_transmission (MTL glass): x the transmission factor (0: none; its map is not
    // sampled), y the index of refraction, z the volume's thickness factor (0: thin-walled, the ray
    // passes straight through; the tracer takes the volume from the geometry), w attenuationDistance
    // (0: infinite, no absorption).
    glm::vec4 transmission{0.0f, 1.5f, 0.0f, 0.0f};
    glm::vec4 attenuation{1.0f};  // rgb: KHR_materials_volume's attenuationColor
};
static_assert(sizeof(PathTraceMaterial) == 144, "std430 layout of LpPathTraceMaterial");

// How each map (PathTraceMap i) is sampled, as bits (exact in a float): bit 4i the second uv set;
// bits 4i + 1, 4i + 2 the wrap across u and bits 16 + 2i, 17 + 2i across v (0 repeat, 1 clamp to
// edge, 2 mirrored repeat). The shader (lpPtMapUv in path_trace.comp) reads the same layout.
int pathTraceMapBits(const TextureRef* const maps[kPtMapCount]);

struct PathTraceScene {
    Bvh bvh;
    std::vector<PathTraceTriangle> triangles;  // in bvh.triangleOrder
    std::vector<PathTraceMaterial> materials;
    // The maps' images, in layer order: base colour and emissive (sRGB), metallic-roughness and normal
    // (linear); one entry per distinct image and sampler (TextureRef::key).
    std::vector<TextureRef> srgbMaps, linearMaps;
    bool hasMaskedMaterials = false;  // MASK or BLEND: rays test the base colour's alpha at hits
    // What the tracer leaves out of lightpass's material model (warned once by the pass).
    // Materials with maps the tracer does not sample (their factors are used): height (bump) maps
    // (normal maps are sampled), KHR_materials_specular's two maps and KHR_materials_transmission's and
    // _volume's (the factors are used).
    size_t unsampledMapMaterials = 0;
    // (KHR_materials_clearcoat's three maps count among them: the tracer takes the coat's factors.)
};

// Every model's triangles through its transform (normals by the inverse transpose), an animated
// glTF's posed at `time` as the raster frame poses it (its playing clips: skins, morph targets, nodes).
PathTraceScene buildPathTraceScene(const Scene& scene, double time = 0.0);

}  // namespace lp
