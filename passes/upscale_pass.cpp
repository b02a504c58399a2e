#include "passes/upscale_pass.hpp"

#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"

namespace lp {

namespace {
struct Data {
    fg::ResourceId source, target;
};
}  // namespace

fg::ResourceId addUpscalePass(fg::FrameGraph& graph, UpscalePass& state, const FrameData& frame, fg::ResourceId input,
                              UpscaleInput kind) {
    const bool debug = kind == UpscaleInput::DebugView;
    const GLenum format = debug ? GL_RGBA8 : GL_RGBA16F;
    const Data& d = graph.addPass<Data>(
        debug ? "upscale_debug" : "upscale",
        [&](fg::PassBuilder& b, Data& data) {
            data.source = b.read(input);
            data.target = b.create(debug ? "ldr.debug.output" : "hdr.output",
                                   {frame.outputWidth, frame.outputHeight, format});
        },
        [&state, frame, debug, format](const Data& data, const fg::PassResources& res) {
            gl::Program& program = debug ? state.debugProgram : state.hdrProgram;
            if (!program)
                program = frame.shaders->compute("upscale.comp", debug ? std::vector<std::string>{"LP_UPSCALE_DEBUG"}
                                                                       : std::vector<std::string>{});
            glBindTextureUnit(0, res.texture(data.source));
            glBindImageTexture(0, res.texture(data.target), 0, GL_FALSE, 0, GL_WRITE_ONLY, format);
            glUseProgram(program.id());
            gl::dispatch2D(frame.outputWidth, frame.outputHeight);
            glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                            GL_TEXTURE_UPDATE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
            glUseProgram(0);
            glBindTextureUnit(0, 0);
            glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, format);
        });
    return d.target;
}

}  // namespace lp
