#pragma once
// Helpers shared by the GL tests: the context, a GLSL compute harness, and small scenes.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gl/context.hpp"
#include "engine/gl/shader.hpp"
#include "engine/render/settings.hpp"

namespace lp {
struct Scene;
struct ShadowMapPass;
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

// IBL on with a bake small enough for a software rasteriser (32^2 cubes, 64 GGX samples, a 32^2
// DFG LUT of `dfgSamples` samples per texel).
EnvironmentSettings smallIblBake(int dfgSamples);

// The first sun's whole depth atlas (every cascade tile), drawn by the shadow map passes alone with
// `kept` (a fresh ShadowMapPass where null) and read back.
std::vector<float> shadowAtlas(const Scene& scene, const RenderSettings& settings, ShadowMapPass* kept = nullptr);

}  // namespace lp::test
