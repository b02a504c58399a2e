#include "passes/downsample_pass.hpp"

#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"
#include "engine/gl/uniforms.hpp"

namespace lp {

namespace {
struct Data {
    fg::ResourceId source, target;
};
}  // namespace

fg::ResourceId addDownsamplePass(fg::FrameGraph& graph, DownsamplePass& state, const FrameData& frame, fg::ResourceId hdr,
                                 int scale) {
    const Data& d = graph.addPass<Data>(
        "ssaa_downsample", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, Data& data) {
            data.source = b.read(hdr, fg::Usage::Sampled);
            data.target = b.create("hdr.output", {frame.outputWidth, frame.outputHeight, GL_RGBA16F}, fg::Usage::ImageStore);
        },
        [&state, frame, scale](const Data& data, const fg::PassResources& res) {
            if (!state.program) state.program = frame.shaders->compute("ssaa_downsample.comp");
            const GLuint prog = state.program.id();
            const gl::Uniforms u(frame.shaders, prog);
            u.set("uScale", scale);
            gl::dispatchTextureToImage(prog, 0, res.texture(data.source), res.texture(data.target), GL_RGBA16F,
                                       frame.outputWidth, frame.outputHeight);
        });
    return d.target;
}

}  // namespace lp
