#include "passes/fxaa_pass.hpp"

#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"
#include "engine/gl/uniforms.hpp"

namespace lp {

namespace {
struct Data {
    fg::ResourceId source, target;
};
}  // namespace

fg::ResourceId addFxaaPass(fg::FrameGraph& graph, FxaaPass& state, const FrameData& frame, fg::ResourceId tonemapped) {
    const Data& d = graph.addPass<Data>(
        "fxaa", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, Data& data) {
            data.source = b.read(tonemapped, fg::Usage::Sampled);
            data.target = b.create("ldr.final", {frame.outputWidth, frame.outputHeight, GL_RGBA8}, fg::Usage::ImageStore);
        },
        [&state, frame](const Data& data, const fg::PassResources& res) {
            if (!state.program) state.program = frame.shaders->compute("fxaa.comp");
            const GLuint prog = state.program.id();
            const gl::Uniforms u(frame.shaders, prog);
            u.set("uDither", frame.settings->aa.dither);
            gl::dispatchTextureToImage(prog, 0, res.texture(data.source), res.texture(data.target), GL_RGBA8,
                                       frame.outputWidth, frame.outputHeight);
        });
    return d.target;
}

}  // namespace lp
