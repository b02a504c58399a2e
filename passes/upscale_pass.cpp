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
        debug ? "upscale_debug" : "upscale", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, Data& data) {
            data.source = b.read(input, fg::Usage::Sampled);
            data.target = b.create(debug ? "ldr.debug.output" : "hdr.output",
                                   {frame.outputWidth, frame.outputHeight, format}, fg::Usage::ImageStore);
        },
        [&state, frame, debug, format](const Data& data, const fg::PassResources& res) {
            gl::Program& program = debug ? state.debugProgram : state.hdrProgram;
            if (!program)
                program = frame.shaders->compute("upscale.comp", debug ? std::vector<std::string>{"LP_UPSCALE_DEBUG"}
                                                                       : std::vector<std::string>{});
            gl::dispatchTextureToImage(program.id(), 0, res.texture(data.source), res.texture(data.target), format,
                                       frame.outputWidth, frame.outputHeight);
        });
    return d.target;
}

}  // namespace lp
