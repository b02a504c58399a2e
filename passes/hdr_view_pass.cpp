#include "passes/hdr_view_pass.hpp"

#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"

namespace lp {

namespace {
struct Data {
    fg::ResourceId hdr, ldr;
};
}  // namespace

bool isHdrView(DebugView view) { return view == DebugView::InvalidPixels || view == DebugView::ExposureEv; }

fg::ResourceId addHdrViewPass(fg::FrameGraph& graph, HdrViewPass& state, const FrameData& frame, fg::ResourceId hdr,
                              DebugView view) {
    const int mode = view == DebugView::InvalidPixels ? 1 : 2;
    const Data& d = graph.addPass<Data>(
        "hdr_view", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, Data& data) {
            data.hdr = b.read(hdr, fg::Usage::Sampled);
            data.ldr = b.create("ldr.hdr_view", {frame.outputWidth, frame.outputHeight, GL_RGBA8}, fg::Usage::ImageStore);
        },
        [&state, frame, mode](const Data& data, const fg::PassResources& res) {
            if (!state.program) state.program = frame.shaders->compute("hdr_view.comp");
            const GLuint prog = state.program.id();
            glProgramUniform1i(prog, glGetUniformLocation(prog, "uMode"), mode);
            glProgramUniform1f(prog, glGetUniformLocation(prog, "uExposureEV"), frame.settings->exposureEV);
            glProgramUniform1i(prog, glGetUniformLocation(prog, "uOperator"), int(frame.settings->environment.toneMap));
            const fg::TextureDesc& out = res.desc(data.ldr);
            gl::dispatchTextureToImage(prog, 0, res.texture(data.hdr), res.texture(data.ldr), GL_RGBA8, out.width,
                                       out.height);
        });
    return d.ldr;
}

}  // namespace lp
