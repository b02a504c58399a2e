#pragma once
// Helpers shared by the GL tests: the context, a GLSL compute harness, and small scenes.
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gl/context.hpp"
#include "engine/gl/shader.hpp"
#include "engine/render/settings.hpp"
#include "engine/render/shadows.hpp"

namespace lp {
struct Scene;
class SceneGpu;
struct ShadowMapPass;
namespace fg {
class TexturePool;
}
}  // namespace lp

namespace lp::test {

extern gl::GpuContext* gContext;

// A file of the repository: from the source tree the tests were built in, or (on another machine,
// run from a copy of the repository) relative to the working directory.
std::string repoPath(const std::string& relative);

// Runs `vec4 lpTest(vec4 x) { <body> }` over `inputs` in a compute shader that includes
// `includes` (e.g. "common/tonemap.glsl") and returns the outputs. This is how the functions in
// shaders/common/ are checked on the real driver against double-precision C++ references.
// `globals` is GLSL placed before lpTest (e.g. a sampler the caller binds).
std::vector<glm::vec4> runGlsl(const std::vector<std::string>& includes, const std::string& body,
                               const std::vector<glm::vec4>& inputs, const std::string& globals = "");

// IEC 61966-2-1 sRGB transfer functions in double precision, and what the G-buffer's 8-bit sRGB
// colour targets give back for a linear colour (kd in gbuffer.diffuse; F0 in the seed formats'
// specular): the nearest code, decoded (the tests' colours are chosen away from rounding ties).
double srgbEncode(double linear);
double srgbDecode(double encoded);
double srgb8Stored(double linear);
glm::dvec3 srgb8Stored(glm::dvec3 linear);

// The white furnace's environment: a uniform equirect map of radiance 1, 128 x 64 (the CPU SH
// projection of a coarser map leaks ~0.5% into the l = 2 band), in a temporary EXR named after `name`
// and the process, removed with the object.
struct WhiteFurnaceMap {
    std::filesystem::path path;
    explicit WhiteFurnaceMap(const std::string& name);
    ~WhiteFurnaceMap();
    WhiteFurnaceMap(const WhiteFurnaceMap&) = delete;
    WhiteFurnaceMap& operator=(const WhiteFurnaceMap&) = delete;
};

// IBL on with a bake small enough for a software rasteriser (32^2 cubes, 64 GGX samples, a 32^2
// DFG LUT of `dfgSamples` samples per texel).
EnvironmentSettings smallIblBake(int dfgSamples);

// GGX's Smith terms in double precision, for either masking model (shaders/common/brdf.glsl's
// ggxVisibilityOf and smithShadowingGivenMasking, without their clamps): Lambda at a direction of
// cosine c to the normal, the visibility G2 / (4 N.L N.V), and G2 / G1(V).
double smithLambdaRef(double c, double alpha);
double ggxVisibilityRef(SpecularMasking masking, double nv, double nl, double alpha);
double smithShadowingGivenMaskingRef(SpecularMasking masking, double lambdaV, double lambdaL);

// One frame of the first sun's shadow map passes alone, drawn with `state` from `pool` (both the
// caller's, so they may be kept across frames): the whole depth atlas read back (every cascade tile;
// tileSize x columns texels wide), its frustum and the pass's notes.
struct ShadowAtlasFrame {
    std::vector<float> depth;
    ShadowFrustum frustum;
    std::vector<std::string> notes;
};
ShadowAtlasFrame drawShadowAtlas(const Scene& scene, const SceneGpu& gpu, const RenderSettings& settings,
                                 ShadowMapPass& state, fg::TexturePool& pool, float time = 0.0f);

// The same atlas's depth alone, with `kept` (a fresh ShadowMapPass where null) and a fresh pool.
std::vector<float> shadowAtlas(const Scene& scene, const RenderSettings& settings, ShadowMapPass* kept = nullptr);

}  // namespace lp::test
