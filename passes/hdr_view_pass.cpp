#include "passes/hdr_view_pass.hpp"

#include "engine/render/exposure.hpp"
#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"
#include "engine/gl/uniforms.hpp"

namespace lp {

namespace {
struct Data {
    fg::ResourceId hdr, exposure, ldr;
};
constexpr GLuint kExposureUnit = 7;  // uExposure in hdr_view.comp
}  // namespace

bool isHdrView(DebugView view) { return view == DebugView::InvalidPixels || view == DebugView::ExposureEv; }

fg::ResourceId addHdrViewPass(fg::FrameGraph& graph, HdrViewPass& state, const FrameData& frame, fg::ResourceId hdr,
                              fg::ResourceId autoExposure, DebugView view) {
    const int mode = view == DebugView::InvalidPixels ? 1 : 2;
    const Data& d = graph.addPass<Data>(
        "hdr_view", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, Data& data) {
            data.hdr = b.read(hdr, fg::Usage::Sampled);
            if (autoExposure.valid()) data.exposure = b.read(autoExposure, fg::Usage::Sampled);
            data.ldr = b.create("ldr.hdr_view", {frame.outputWidth, frame.outputHeight, GL_RGBA8}, fg::Usage::ImageStore);
        },
        [&state, frame, mode](const Data& data, const fg::PassResources& res) {
            if (!state.program) state.program = frame.shaders->compute("hdr_view.comp");
            const GLuint prog = state.program.id();
            const gl::Uniforms u(frame.shaders, prog);
            u.set("uMode", mode);
            u.set("uExposureEV", exposureEvBase(*frame.settings, *frame.scene));
            u.set("uOperator", int(frame.settings->environment.toneMap));
            u.set("uAutoExposure", data.exposure.valid());
            if (data.exposure.valid()) glBindTextureUnit(kExposureUnit, res.texture(data.exposure));
            const fg::TextureDesc& out = res.desc(data.ldr);
            gl::dispatchTextureToImage(prog, 0, res.texture(data.hdr), res.texture(data.ldr), GL_RGBA8, out.width,
                                       out.height);
            if (data.exposure.valid()) glBindTextureUnit(kExposureUnit, 0);
        });
    return d.ldr;
}

}  // namespace lp
