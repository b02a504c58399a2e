#include "passes/toon_pass.hpp"

#include "engine/gl/gpu_timer.hpp"
#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"

namespace lp {

namespace {
struct Data {
    fg::ResourceId position, normal, hdr;
};
}  // namespace

void runToonGlsl(ToonPass& state, const gl::ShaderLibrary& shaders, GLuint hdr, GLuint position, GLuint normal,
                 int width, int height, const post::ToonParams& p) {
    if (!state.program) state.program = shaders.compute("toon.comp");
    const GLuint prog = state.program.id();
    glProgramUniform1i(prog, glGetUniformLocation(prog, "uLevels"), p.levels);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "uDepthEdge"), p.depthEdge);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "uNormalEdge"), p.normalEdge);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "uFarDepth"), p.farDepth);
    glBindTextureUnit(0, position);
    glBindTextureUnit(1, normal);
    glBindImageTexture(0, hdr, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
    glUseProgram(prog);
    gl::dispatch2D(width, height);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glUseProgram(0);
    glBindTextureUnit(0, 0);
    glBindTextureUnit(1, 0);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
}

fg::ResourceId addToonPass(fg::FrameGraph& graph, ToonPass& state, PostBackend& backend, const FrameData& frame,
                           const post::PostConfig& config, fg::ResourceId position, fg::ResourceId normal,
                           fg::ResourceId hdr) {
    const post::ToonParams params = config.toonParams;
    const PostSettings::Backend requested = config.backend;
    const Data& d = graph.addPass<Data>(
        "toon",
        [&](fg::PassBuilder& b, Data& data) {
            data.position = b.read(position);
            data.normal = b.read(normal);
            data.hdr = b.write(hdr);
        },
        [&state, &backend, frame, params, requested, frameIndex = backend.frameIndex](const Data& data,
                                                                                      const fg::PassResources& res) {
            const GLuint hdrTex = res.texture(data.hdr), posTex = res.texture(data.position),
                         normalTex = res.texture(data.normal);
            if (backend.useCuda(requested)) {
                backend.beginFrame(frameIndex);  // idempotent within a frame
#ifdef LIGHTPASS_HAVE_CUDA
                cuda::PostTiming t = backend.interop->toon(hdrTex, posTex, normalTex, frame.width, frame.height, params);
                if (res.timers()) {
                    res.timers()->addExternal("toon (cuda kernels)", t.kernelMs);
                    res.timers()->addExternal("toon (cuda interop)", t.interopMs);
                }
#endif
                return;
            }
            runToonGlsl(state, *frame.shaders, hdrTex, posTex, normalTex, frame.width, frame.height, params);
        });
    return d.hdr;
}

}  // namespace lp
