#include "passes/ibl_pass.hpp"

#include <glm/gtc/type_ptr.hpp>

#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"

namespace lp {

namespace {
struct Data {
    GBuffer in;
    fg::ResourceId hdr;
};
struct DebugData {
    GBuffer in;
    fg::ResourceId ldr;
};

glm::mat3 eyeToWorld(const FrameData& frame) { return glm::transpose(glm::mat3(frame.view)); }

void setSh(GLuint prog, const BakedEnvironment& env) {
    glProgramUniform3fv(prog, glGetUniformLocation(prog, "uSh"), 9, glm::value_ptr(env.sh[0]));
}
}  // namespace

bool isEnvironmentView(DebugView view) {
    return view == DebugView::Environment || view == DebugView::Irradiance || view == DebugView::Prefiltered ||
           view == DebugView::Dfg;
}

fg::ResourceId addIblPass(fg::FrameGraph& graph, IblPass& state, const FrameData& frame, const GBuffer& gbuffer,
                          fg::ResourceId hdr, bool lightingOnly) {
    const bool wanted = frame.settings->environment.ibl.value_or(frame.scene->environment.ibl) &&
                        !frame.scene->environment.map.empty();
    if (!wanted && !frame.settings->allPasses) return hdr;
    const Data& d = graph.addPass<Data>(
        "ibl",
        [&](fg::PassBuilder& b, Data& data) {
            data.in = gbuffer;
            readGBuffer(b, gbuffer, !lightingOnly);
            data.hdr = b.write(hdr);
        },
        [&state, frame, lightingOnly](const Data& data, const fg::PassResources& res) {
            const EnvironmentSettings& s = frame.settings->environment;
            const BakedEnvironment& env = state.environments.get(*frame.scene, s, *frame.shaders, true);
            const gl::Texture& dfg = state.environments.dfgLut(s, *frame.shaders);
            programForLayout(state.program, state.layout, frame, [&](const std::vector<std::string>& defines) {
                return frame.shaders->compute("ibl.comp", defines);
            });
            const GLuint prog = state.program.id();
            setSh(prog, env);
            glProgramUniform1i(prog, glGetUniformLocation(prog, "uDiffuseFromCube"),
                               s.diffuse == IrradianceSource::Cubemap);
            glProgramUniformMatrix3fv(prog, glGetUniformLocation(prog, "uEyeToWorld"), 1, GL_FALSE,
                                      glm::value_ptr(eyeToWorld(frame)));
            glProgramUniform1f(prog, glGetUniformLocation(prog, "uIntensity"), frame.scene->environment.intensity);
            glProgramUniform1f(prog, glGetUniformLocation(prog, "uMaxLod"), float(env.prefiltered.levels - 1));
            glProgramUniform1i(prog, glGetUniformLocation(prog, "uLightingOnly"), lightingOnly);
            gl::ScopedEnable seamless(GL_TEXTURE_CUBE_MAP_SEAMLESS, true);
            bindGBuffer(prog, res, data.in, frame, !lightingOnly);
            glBindTextureUnit(7, env.irradiance.id());
            glBindTextureUnit(8, env.prefiltered.id());
            glBindTextureUnit(9, dfg.id());
            glBindImageTexture(0, res.texture(data.hdr), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
            glUseProgram(prog);
            gl::dispatch2D(frame.width, frame.height);
            glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            glUseProgram(0);
            for (GLuint u : {0u, 1u, 2u, 3u, 4u, 7u, 8u, 9u}) glBindTextureUnit(u, 0);
            glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
        });
    return d.hdr;
}

fg::ResourceId addIblDebugViewPass(fg::FrameGraph& graph, IblPass& state, const FrameData& frame,
                                   const GBuffer& gbuffer, DebugView view) {
    const int mode = view == DebugView::Environment ? 1 : view == DebugView::Irradiance ? 2
                     : view == DebugView::Prefiltered ? 3 : 4;
    const DebugData& d = graph.addPass<DebugData>(
        "debug_view",
        [&](fg::PassBuilder& b, DebugData& data) {
            data.in = gbuffer;
            readGBuffer(b, gbuffer, false);
            data.ldr = b.create("ldr.debug", {frame.width, frame.height, GL_RGBA8});
        },
        [&state, frame, mode](const DebugData& data, const fg::PassResources& res) {
            const EnvironmentSettings& s = frame.settings->environment;
            const bool bake = mode == 2 || mode == 3;
            const BakedEnvironment& env = state.environments.get(*frame.scene, s, *frame.shaders, bake);
            const gl::Texture& dfg = state.environments.dfgLut(s, *frame.shaders);
            programForLayout(state.debugProgram, state.debugLayout, frame, [&](const std::vector<std::string>& defines) {
                return frame.shaders->compute("ibl_debug.comp", defines);
            });
            const GLuint prog = state.debugProgram.id();
            if (bake) setSh(prog, env);
            const float maxMip = bake ? float(env.prefiltered.levels - 1) : 0.0f;
            glProgramUniform1i(prog, glGetUniformLocation(prog, "uMode"), mode);
            glProgramUniform1i(prog, glGetUniformLocation(prog, "uDiffuseFromCube"),
                               s.diffuse == IrradianceSource::Cubemap);
            glProgramUniformMatrix3fv(prog, glGetUniformLocation(prog, "uEyeToWorld"), 1, GL_FALSE,
                                      glm::value_ptr(eyeToWorld(frame)));
            glProgramUniformMatrix4fv(prog, glGetUniformLocation(prog, "uInvProjection"), 1, GL_FALSE,
                                      glm::value_ptr(glm::inverse(frame.projection)));
            // Without a map the environment is the plain colour, already scaled here.
            const float intensity = frame.scene->environment.intensity;
            glProgramUniform1f(prog, glGetUniformLocation(prog, "uIntensity"), intensity);
            glProgramUniform1f(prog, glGetUniformLocation(prog, "uMip"), std::min(float(s.debugMip), maxMip));
            glProgramUniform1f(prog, glGetUniformLocation(prog, "uExposureEV"), frame.settings->exposureEV);
            glProgramUniform1i(prog, glGetUniformLocation(prog, "uOperator"), int(s.toneMap));
            gl::ScopedEnable seamless(GL_TEXTURE_CUBE_MAP_SEAMLESS, true);
            bindGBuffer(prog, res, data.in, frame, false);
            glBindTextureUnit(7, env.cube.id());
            glBindTextureUnit(8, bake ? env.irradiance.id() : 0);
            glBindTextureUnit(9, bake ? env.prefiltered.id() : 0);
            glBindTextureUnit(10, dfg.id());
            glBindImageTexture(0, res.texture(data.ldr), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
            glUseProgram(prog);
            gl::dispatch2D(frame.width, frame.height);
            glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                            GL_TEXTURE_UPDATE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
            glUseProgram(0);
            for (GLuint u : {0u, 1u, 3u, 4u, 7u, 8u, 9u, 10u}) glBindTextureUnit(u, 0);
            glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
        });
    return d.ldr;
}

void addIblBakePass(fg::FrameGraph& graph, IblPass& state, const FrameData& frame, bool bake) {
    graph.addPass(
        "ibl_bake", [](fg::PassBuilder& b) { b.sideEffect(); },
        [&state, frame, bake](const fg::PassResources&) {
            state.environments.get(*frame.scene, frame.settings->environment, *frame.shaders, bake);
            if (bake) state.environments.dfgLut(frame.settings->environment, *frame.shaders);
        });
}

}  // namespace lp
