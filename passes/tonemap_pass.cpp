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
        "tonemap", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, Data& data) {
            data.hdr = b.read(hdr, fg::Usage::Sampled);
            data.ldr = b.create("ldr.final", {frame.outputWidth, frame.outputHeight, GL_RGBA8}, fg::Usage::ImageStore);
        },
        [&state, frame](const Data& data, const fg::PassResources& res) {
            if (!state.program) state.program = frame.shaders->compute("tonemap.comp");
            const GLuint prog = state.program.id();
            glProgramUniform1f(prog, glGetUniformLocation(prog, "uExposureEV"), frame.settings->exposureEV);
            glProgramUniform1i(prog, glGetUniformLocation(prog, "uOperator"), int(frame.settings->environment.toneMap));
            gl::dispatchTextureToImage(prog, 6, res.texture(data.hdr), res.texture(data.ldr), GL_RGBA8,
                                       frame.outputWidth, frame.outputHeight);
        });
    return d.ldr;
}

}  // namespace lp
