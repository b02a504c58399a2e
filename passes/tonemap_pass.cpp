#include "passes/tonemap_pass.hpp"

#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"

namespace lp {

namespace {
struct Data {
    fg::ResourceId hdr, ldr;
};
}  // namespace

fg::ResourceId addToneMapPass(fg::FrameGraph& graph, ToneMapPass& state, const FrameData& frame, fg::ResourceId hdr) {
    const Data& d = graph.addPass<Data>(
        "tonemap",
        [&](fg::PassBuilder& b, Data& data) {
            data.hdr = b.read(hdr);
            data.ldr = b.create("ldr.final", {frame.outputWidth, frame.outputHeight, GL_RGBA8});
        },
        [&state, frame](const Data& data, const fg::PassResources& res) {
            if (!state.program) state.program = frame.shaders->compute("tonemap.comp");
            const GLuint prog = state.program.id();
            glProgramUniform1f(prog, glGetUniformLocation(prog, "uExposureEV"), frame.settings->exposureEV);
            glProgramUniform1i(prog, glGetUniformLocation(prog, "uOperator"), int(frame.settings->environment.toneMap));
            glBindTextureUnit(6, res.texture(data.hdr));
            glBindImageTexture(0, res.texture(data.ldr), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
            glUseProgram(prog);
            gl::dispatch2D(frame.outputWidth, frame.outputHeight);
            glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                            GL_TEXTURE_UPDATE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
            glUseProgram(0);
            glBindTextureUnit(6, 0);
            glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
        });
    return d.ldr;
}

}  // namespace lp
