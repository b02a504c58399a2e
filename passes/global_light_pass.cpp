#include "passes/global_light_pass.hpp"

#include <algorithm>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "engine/core/log.hpp"
#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"

namespace lp {

namespace {
constexpr int kMaxLights = 16;  // matches MAX_LIGHTS in global_light.comp
struct Data {
    GBuffer in;
    fg::ResourceId hdr;
};
}  // namespace

fg::ResourceId addGlobalLightPass(fg::FrameGraph& graph, GlobalLightPass& state, const FrameData& frame,
                                  const GBuffer& gbuffer, bool lightingOnly) {
    const Data& d = graph.addPass<Data>(
        "global_lights",
        [&](fg::PassBuilder& b, Data& data) {
            data.in = gbuffer;
            b.read(gbuffer.depth);
            b.read(gbuffer.normal);
            if (!lightingOnly) b.read(gbuffer.diffuse);
            b.read(gbuffer.position);
            b.read(gbuffer.specular);
            data.hdr = b.create("hdr", {frame.width, frame.height, GL_RGBA16F});
        },
        [&state, frame, lightingOnly](const Data& data, const fg::PassResources& res) {
            if (!state.program) state.program = frame.shaders->compute("global_light.comp");
            const GLuint prog = state.program.id();
            const auto& lights = frame.scene->directionalLights;
            if (int(lights.size()) > kMaxLights)
                logWarn("only the first " + std::to_string(kMaxLights) + " of " + std::to_string(lights.size()) +
                        " directional lights are drawn");
            const int count = std::min<int>(int(lights.size()), kMaxLights);
            std::vector<glm::vec3> dirs, irr;
            for (int i = 0; i < count; ++i) {
                glm::vec3 toLight = -lights[size_t(i)].direction;
                dirs.push_back(glm::normalize(glm::mat3(frame.view) * toLight));
                irr.push_back(lights[size_t(i)].color * lights[size_t(i)].intensity);
            }
            glProgramUniform1i(prog, glGetUniformLocation(prog, "uLightCount"), count);
            if (count > 0) {
                glProgramUniform3fv(prog, glGetUniformLocation(prog, "uLightDirEye"), count, glm::value_ptr(dirs[0]));
                glProgramUniform3fv(prog, glGetUniformLocation(prog, "uLightIrradiance"), count, glm::value_ptr(irr[0]));
            }
            glProgramUniform3fv(prog, glGetUniformLocation(prog, "uAmbient"), 1, glm::value_ptr(frame.scene->ambient));
            glProgramUniform1i(prog, glGetUniformLocation(prog, "uLightingOnly"), lightingOnly);
            glBindTextureUnit(0, res.texture(data.in.depth));
            glBindTextureUnit(1, res.texture(data.in.normal));
            glBindTextureUnit(2, lightingOnly ? 0 : res.texture(data.in.diffuse));
            glBindTextureUnit(3, res.texture(data.in.position));
            glBindTextureUnit(4, res.texture(data.in.specular));
            glBindImageTexture(0, res.texture(data.hdr), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
            glUseProgram(prog);
            gl::dispatch2D(frame.width, frame.height);
            glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            glUseProgram(0);
            for (GLuint u = 0; u < 5; ++u) glBindTextureUnit(u, 0);
            glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        });
    return d.hdr;
}

}  // namespace lp
