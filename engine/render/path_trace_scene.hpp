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

// One triangle: world positions (position[0].w: the material index) and shading normals.
struct PathTraceTriangle {
    glm::vec4 position[3];
    glm::vec4 normal[3];
};
static_assert(sizeof(PathTraceTriangle) == 96, "std430 layout of LpPathTraceTriangle");

// A material's factors (lp::Material after the scene file's overrides): what material.glsl makes of
// them where no texture is sampled.
struct PathTraceMaterial {
    glm::vec4 baseOpacity;        // base colour, opacity
    glm::vec4 specularMetallic;   // dielectric F0 (MTL Ks), metallic
    glm::vec4 emissionShininess;  // emitted radiance, Blinn-Phong exponent (the roughness's)
    glm::vec4 flags;              // x: flat-lit, y: double-sided
};
static_assert(sizeof(PathTraceMaterial) == 64, "std430 layout of LpPathTraceMaterial");

struct PathTraceScene {
    Bvh bvh;
    std::vector<PathTraceTriangle> triangles;  // in bvh.triangleOrder
    std::vector<PathTraceMaterial> materials;
    // What the tracer leaves out of lightpass's material model (warned once by the pass).
    size_t texturedMaterials = 0;  // materials with a map; traced with their factors alone
    size_t blendedMaterials = 0;   // alpha-blended materials; traced as opaque
};

// Every model's triangles through its transform (normals by the inverse transpose).
PathTraceScene buildPathTraceScene(const Scene& scene);

}  // namespace lp
