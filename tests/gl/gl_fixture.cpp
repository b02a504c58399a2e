#include "tests/gl/gl_fixture.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <unistd.h>

#include "engine/gl/handles.hpp"
#include "engine/io/image_io.hpp"
#include "engine/graph/texture_pool.hpp"
#include "engine/render/scene_gpu.hpp"
#include "engine/scene/scene.hpp"
#include "frame/frame_builder.hpp"
#include "passes/shadow_map_pass.hpp"

namespace lp::test {

std::string repoPath(const std::string& relative) {
    std::filesystem::path built = std::filesystem::path(LIGHTPASS_SOURCE_DIR) / relative;
    return std::filesystem::exists(built) ? built.string() : relative;
}

std::vector<glm::vec4> runGlsl(const std::vector<std::string>& includes, const std::string& body,
                               const std::vector<glm::vec4>& inputs, const std::string& globals) {
    std::string src = "#version 450\n";
    for (const auto& inc : includes) src += "#include \"" + inc + "\"\n";
    src += globals + R"(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer InData { vec4 inData[]; };
layout(std430, binding = 1) writeonly buffer OutData { vec4 outData[]; };
uniform uint uCount;
vec4 lpTest(vec4 x) {
)" + body + R"(
}
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i < uCount) outData[i] = lpTest(inData[i]);
}
)";
    gl::ShaderLibrary lib;
    gl::Program prog = lib.computeFromSource("harness.comp", src);
    const GLsizeiptr bytes = GLsizeiptr(inputs.size() * sizeof(glm::vec4));
    gl::Buffer in = gl::makeBuffer(bytes, inputs.data(), 0, "harness.in");
    gl::Buffer out = gl::makeBuffer(bytes, nullptr, GL_DYNAMIC_STORAGE_BIT, "harness.out");
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, in.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, out.id());
    glUseProgram(prog.id());
    glUniform1ui(glGetUniformLocation(prog.id(), "uCount"), GLuint(inputs.size()));
    glDispatchCompute(GLuint((inputs.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> result(inputs.size());
    glGetNamedBufferSubData(out.id(), 0, bytes, result.data());
    glUseProgram(0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, 0);
    gl::checkErrors("GLSL harness");
    return result;
}

double srgbEncode(double linear) {
    linear = std::clamp(linear, 0.0, 1.0);
    return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

double srgbDecode(double encoded) {
    encoded = std::clamp(encoded, 0.0, 1.0);
    return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

double srgb8Stored(double linear) { return srgbDecode(std::round(srgbEncode(linear) * 255.0) / 255.0); }

glm::dvec3 srgb8Stored(glm::dvec3 linear) { return {srgb8Stored(linear.x), srgb8Stored(linear.y), srgb8Stored(linear.z)}; }

WhiteFurnaceMap::WhiteFurnaceMap(const std::string& name)
    : path(std::filesystem::temp_directory_path() / ("lightpass-test-" + std::to_string(::getpid()) + "-" + name + ".exr")) {
    ImageF white;
    white.width = 128;
    white.height = 64;
    white.rgba.assign(size_t(128 * 64 * 4), 1.0f);
    writeExr(path, white);
}

WhiteFurnaceMap::~WhiteFurnaceMap() {
    std::error_code ec;
    std::filesystem::remove(path, ec);
}

EnvironmentSettings smallIblBake(int dfgSamples) {
    EnvironmentSettings s;
    s.ibl = true;
    s.cubeSize = 32;
    s.specularSize = 32;
    s.specularLevels = 6;
    s.specularSamples = 64;
    s.irradianceSize = 8;
    s.irradianceSamples = 128;
    s.dfgSize = 32;
    s.dfgSamples = dfgSamples;
    return s;
}

double smithLambdaRef(double c, double alpha) {
    const double c2 = std::max(c * c, 1e-12);
    return 0.5 * (std::sqrt(1.0 + alpha * alpha * (1.0 - c2) / c2) - 1.0);
}

// G2 / (4 N.L N.V) with G1 = 1 / (1 + Lambda) = 2 c / (c + l), l = c (1 + 2 Lambda) = sqrt(c^2 (1 - a2) + a2),
// written so that the N.L N.V of the denominator cancels (exact at N.L -> 0).
double ggxVisibilityRef(SpecularMasking masking, double nv, double nl, double alpha) {
    const double a2 = alpha * alpha;
    const double lv = std::sqrt(nv * nv * (1.0 - a2) + a2), ll = std::sqrt(nl * nl * (1.0 - a2) + a2);
    return masking == SpecularMasking::HeightCorrelated ? 0.5 / (nl * lv + nv * ll) : 1.0 / ((nv + lv) * (nl + ll));
}

double smithShadowingGivenMaskingRef(SpecularMasking masking, double lambdaV, double lambdaL) {
    return masking == SpecularMasking::HeightCorrelated ? (1.0 + lambdaV) / (1.0 + lambdaV + lambdaL)
                                                        : 1.0 / (1.0 + lambdaL);
}

ShadowAtlasFrame drawShadowAtlas(const Scene& scene, const SceneGpu& gpu, const RenderSettings& settings,
                                 ShadowMapPass& state, fg::TexturePool& pool, float time) {
    gl::ShaderLibrary shaders;
    FrameData frame = makeFrameData(scene, settings, time);
    frame.gpu = &gpu;
    frame.shaders = &shaders;
    fg::FrameGraph graph;
    SkinningPass skinning;  // --skinning gpu: the animated models posed first, as the frame builder does
    if (skinningSkipReason(frame).empty()) {
        addSkinningPass(graph, skinning, frame);
        frame.posedVerticesOnGpu = true;
    }
    const ShadowMaps maps = addShadowMapPasses(graph, state, frame);
    EXPECT_EQ(maps.size(), 1u);
    if (maps.empty()) return {};
    graph.markOutput(maps[0].depth);
    graph.compile();
    graph.execute(pool);
    ShadowAtlasFrame out;
    for (const auto& d : graph.explain())
        if (d.name == "shadow_map_0") out.notes = d.notes;
    out.frustum = maps[0].frustum;
    const int side = out.frustum.tileSize;
    const size_t n = size_t(side * out.frustum.columns) * size_t(side * out.frustum.rows);
    out.depth.resize(n);
    glGetTextureImage(graph.outputTexture(maps[0].depth), 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(n * sizeof(float)),
                      out.depth.data());
    return out;
}

std::vector<float> shadowAtlas(const Scene& scene, const RenderSettings& settings, ShadowMapPass* kept) {
    SceneGpu gpu(scene);
    ShadowMapPass local;
    fg::TexturePool pool;
    return drawShadowAtlas(scene, gpu, settings, kept ? *kept : local, pool).depth;
}

}  // namespace lp::test
