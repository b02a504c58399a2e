#include "passes/tonemap_pass.hpp"

#include "engine/render/exposure.hpp"
#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"
#include "engine/gl/uniforms.hpp"

namespace lp {

namespace {
struct Data {
    fg::ResourceId hdr, exposure, ldr;
};
constexpr GLuint kExposureUnit = 7;  // uExposure in tonemap.comp
}  // namespace

fg::ResourceId addToneMapPass(fg::FrameGraph& graph, ToneMapPass& state, const FrameData& frame, fg::ResourceId hdr,
                              fg::ResourceId autoExposure, ToneMapTarget target) {
    const bool floatTarget = target == ToneMapTarget::Float16;
    const GLenum format = floatTarget ? GL_RGBA16F : GL_RGBA8;
    const Data& d = graph.addPass<Data>(
        "tonemap", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, Data& data) {
            data.hdr = b.read(hdr, fg::Usage::Sampled);
            if (autoExposure.valid()) data.exposure = b.read(autoExposure, fg::Usage::Sampled);
            data.ldr = b.create(floatTarget ? "ldr.tonemapped" : "ldr.final", {frame.outputWidth, frame.outputHeight, format},
                                fg::Usage::ImageStore);
        },
        [&state, frame, floatTarget, format](const Data& data, const fg::PassResources& res) {
            gl::Program& program = floatTarget ? state.floatProgram : state.program;
            if (!program)
                program = frame.shaders->compute("tonemap.comp", floatTarget ? std::vector<std::string>{"LP_TONEMAP_FLOAT_TARGET"}
                                                                             : std::vector<std::string>{});
            const GLuint prog = program.id();
            const gl::Uniforms u(frame.shaders, prog);
            u.set("uExposureEV", exposureEvBase(*frame.settings, *frame.scene));
            u.set("uOperator", int(frame.settings->environment.toneMap));
            u.set("uAutoExposure", data.exposure.valid());
            u.set("uDither", frame.settings->aa.dither);
            if (data.exposure.valid()) glBindTextureUnit(kExposureUnit, res.texture(data.exposure));
            gl::dispatchTextureToImage(prog, 6, res.texture(data.hdr), res.texture(data.ldr), format, frame.outputWidth,
                                       frame.outputHeight);
            if (data.exposure.valid()) glBindTextureUnit(kExposureUnit, 0);
        });
    return d.ldr;
}

}  // namespace lp
