#include "engine/gl/gradient_probe.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gl/handles.hpp"
#include "engine/gl/state.hpp"

namespace lp::gl {

const char* anisotropicLevelsName(AnisotropicLevels levels) {
    switch (levels) {
        case AnisotropicLevels::Floor: return "floor";
        case AnisotropicLevels::Nearest: return "nearest";
        default: return "blended";
    }
}

namespace {
constexpr int kSize = 16, kLevels = 5, kGrid = 8;
constexpr float kAnisotropy = 8.0f;

// The value farthest from `expected` (NaN counts as farthest).
double farthest(const std::vector<float>& values, double expected) {
    double worst = expected;
    for (float v : values)
        if (!(std::abs(v - expected) <= std::abs(worst - expected))) worst = v;
    return worst;
}

Texture levelTexture() {
    Texture t = makeTexture2D(GL_RGBA8, kSize, kSize, kLevels, "gradient_probe.levels");
    std::vector<uint8_t> texels(size_t(kSize) * kSize * 4);
    GLint unpackAlignment = 4;
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &unpackAlignment);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    for (int level = 0; level < kLevels; ++level) {
        const uint8_t red = uint8_t(std::lround(255.0 * level / (kLevels - 1)));
        for (size_t i = 0; i < texels.size(); i += 4) {
            texels[i] = red;
            texels[i + 1] = texels[i + 2] = 0;
            texels[i + 3] = 255;
        }
        glTextureSubImage2D(t.id(), level, 0, 0, kSize >> level, kSize >> level, GL_RGBA, GL_UNSIGNED_BYTE, texels.data());
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, unpackAlignment);
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    return t;
}

void setAnisotropy(GLuint texture, float anisotropy) {
    if (GLAD_GL_EXT_texture_filter_anisotropic) glTextureParameterf(texture, GL_TEXTURE_MAX_ANISOTROPY_EXT, anisotropy);
}

// Every invocation samples the same point with gradients dx, dy (texels): the levels read.
std::vector<float> computeLevels(const Program& program, GLuint texture, const Buffer& result, glm::vec2 dx, glm::vec2 dy) {
    glProgramUniform2f(program.id(), glGetUniformLocation(program.id(), "uDx"), dx.x / kSize, dx.y / kSize);
    glProgramUniform2f(program.id(), glGetUniformLocation(program.id(), "uDy"), dy.x / kSize, dy.y / kSize);
    glBindTextureUnit(0, texture);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, result.id());
    glUseProgram(program.id());
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<float> levels(kGrid * kGrid);
    glGetNamedBufferSubData(result.id(), 0, GLsizeiptr(levels.size() * sizeof(float)), levels.data());
    return levels;
}

// Every fragment of an 8x8 target samples with its own derivatives of gradient_probe.frag's uv (`step`
// texels a pixel, plus `product` x y texels along u): the levels read, rows bottom first.
std::vector<float> rasterLevels(const Program& program, GLuint texture, const Framebuffer& fbo, GLuint target,
                                const VertexArray& vao, glm::vec2 step, float product = 0.0f) {
    glProgramUniform2f(program.id(), glGetUniformLocation(program.id(), "uStep"), step.x, step.y);
    glProgramUniform1f(program.id(), glGetUniformLocation(program.id(), "uProduct"), product);
    glBindTextureUnit(0, texture);
    {
        ScopedFramebuffer bind(fbo.id(), kGrid, kGrid);
        ScopedEnable depth(GL_DEPTH_TEST, false), blend(GL_BLEND, false), cull(GL_CULL_FACE, false),
            scissor(GL_SCISSOR_TEST, false);
        glUseProgram(program.id());
        glBindVertexArray(vao.id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    std::vector<float> levels(kGrid * kGrid);
    GLint packAlignment = 4;
    glGetIntegerv(GL_PACK_ALIGNMENT, &packAlignment);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(target, 0, GL_RED, GL_FLOAT, GLsizei(levels.size() * sizeof(float)), levels.data());
    glPixelStorei(GL_PACK_ALIGNMENT, packAlignment);
    return levels;
}
// The level an anisotropic sample reads for footprint axes of lx and ly texels under the measured
// model, within the probe texture's levels.
double predictedLevel(const GradientSampling& g, double lx, double ly) {
    const double major = std::max(lx, ly), minor = std::min(lx, ly);
    const double ratio = minor > 0.0 ? std::min(major / minor, double(kAnisotropy)) : double(kAnisotropy);
    double lambda = std::log2(std::max(g.rasterClampsRatio ? major / ratio : minor, 1e-30));
    if (g.rasterLevels == AnisotropicLevels::Floor) lambda = std::floor(lambda);
    if (g.rasterLevels == AnisotropicLevels::Nearest) lambda = std::round(lambda);
    return std::clamp(lambda, 0.0, double(kLevels - 1));
}
}  // namespace

GradientSampling probeGradientSampling(const ShaderLibrary& shaders) {
    GradientSampling r;
    r.anisotropyAvailable = GLAD_GL_EXT_texture_filter_anisotropic != 0;
    Texture levels = levelTexture();
    Program compute = shaders.compute("gradient_probe.comp");
    Program raster = shaders.graphics("fullscreen.vert", "gradient_probe.frag");
    Buffer result = makeBuffer(kGrid * kGrid * GLsizeiptr(sizeof(float)), nullptr, 0, "gradient_probe.result");
    Texture target = makeTexture2D(GL_R32F, kGrid, kGrid, 1, "gradient_probe.target");
    Framebuffer fbo = makeFramebuffer("gradient_probe");
    glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, target.id(), 0);
    VertexArray vao = makeVertexArray("gradient_probe");

    GLint program0 = 0, vao0 = 0, buffer0 = 0, texture0 = 0, active0 = GL_TEXTURE0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &program0);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao0);
    glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, 0, &buffer0);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active0);
    glActiveTexture(GL_TEXTURE0);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &texture0);
    glActiveTexture(GLenum(active0));

    setAnisotropy(levels.id(), 1.0f);
    r.computeIsotropic = farthest(computeLevels(compute, levels.id(), result, {4, 0}, {0, 4}), 2.0);
    if (r.anisotropyAvailable) {
        setAnisotropy(levels.id(), kAnisotropy);
        r.computeSquare = farthest(computeLevels(compute, levels.id(), result, {4, 0}, {0, 4}), 2.0);
        r.computeStretched = farthest(computeLevels(compute, levels.id(), result, {8, 0}, {0, 2}), 1.0);
        // A quarter level: far beyond rounding and 8-bit texels, far below the whole levels that
        // lane differences give (here, where every lane samples the same point: level 0).
        r.computeFollowsGradients = std::abs(r.computeSquare - 2.0) < 0.25 && std::abs(r.computeStretched - 1.0) < 0.25;
        const double fractional = std::log2(3.0);
        r.rasterFractional = farthest(rasterLevels(raster, levels.id(), fbo, target.id(), vao, {3, 3}), fractional);
        r.rasterStretched = farthest(rasterLevels(raster, levels.id(), fbo, target.id(), vao, {64, 2}), 3.0);
        r.rasterLevels = std::abs(r.rasterFractional - 1.0) < 0.2   ? AnisotropicLevels::Floor
                         : std::abs(r.rasterFractional - 2.0) < 0.2 ? AnisotropicLevels::Nearest
                                                                     : AnisotropicLevels::Blended;
        r.rasterClampsRatio = std::abs(r.rasterStretched - 3.0) < std::abs(r.rasterStretched - 1.0);
        // uv = (a x y, c y) texels: fine derivatives (a y, 0) and (a x, c) at the pixel's own row and
        // column (x, y at pixel centres); a quad's first pixel has the lower of each pair. At pixel
        // (1, 1) the two give levels log2 3 apart.
        constexpr float a = 2.0f, c = 0.25f;
        const std::vector<float> read = rasterLevels(raster, levels.id(), fbo, target.id(), vao, {0.0f, c}, a);
        for (int y = 0; y < kGrid; ++y)
            for (int x = 0; x < kGrid; ++x) {
                const double got = read[size_t(y) * kGrid + size_t(x)];
                auto predicted = [&](int px, int py) {
                    const double cx = px + 0.5, cy = py + 0.5;
                    return predictedLevel(r, a * cy, std::hypot(a * cx, double(c)));
                };
                r.rasterPerPixelError += std::abs(got - predicted(x, y));
                r.rasterPerQuadError += std::abs(got - predicted(x & ~1, y & ~1));
            }
        r.rasterLevelPerQuad = r.rasterPerQuadError < r.rasterPerPixelError;
    }

    glUseProgram(GLuint(program0));
    glBindVertexArray(GLuint(vao0));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, GLuint(buffer0));
    glBindTextureUnit(0, GLuint(texture0));
    return r;
}

}  // namespace lp::gl
