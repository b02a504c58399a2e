#include "passes/toon_pass.hpp"

#include "engine/core/log.hpp"
#include "engine/gl/gpu_timer.hpp"
#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"
#include "engine/gl/uniforms.hpp"

#ifdef LIGHTPASS_HAVE_CUDA
#include "cuda/post_cuda.hpp"
#endif

namespace lp {

namespace {
struct Data {
    GBuffer in;
    fg::ResourceId hdr;
};
}  // namespace

void runToonGlsl(ToonPass& state, const gl::ShaderLibrary& shaders, GLuint hdr, const ToonGBufferTextures& g,
                 int width, int height, const post::ToonParams& p) {
    if (!state.program || state.layout != g.layout) {
        state.program = shaders.compute("toon.comp", gbufferDefines(g.layout));
        state.layout = g.layout;
    }
    const GLuint prog = state.program.id();
    const gl::Uniforms u(&shaders, prog);
    u.set("uGbufferCamera", g.camera);
    u.set("uLevels", p.levels);
    u.set("uDepthEdge", p.depthEdge);
    u.set("uNormalEdge", p.normalEdge);
    u.set("uFarDepth", p.farDepth);
    glBindTextureUnit(0, g.depth);
    glBindTextureUnit(1, g.normal);
    glBindTextureUnit(3, g.position);
    glBindImageTexture(0, hdr, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
    glUseProgram(prog);
    gl::dispatch2D(width, height);
    glUseProgram(0);
    for (GLuint u : {0u, 1u, 3u}) glBindTextureUnit(u, 0);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
}

fg::ResourceId addToonPass(fg::FrameGraph& graph, ToonPass& state, PostBackend& backend, bool cuda,
                           const FrameData& frame, const post::PostConfig& config, const GBuffer& gbuffer,
                           fg::ResourceId hdr) {
    const post::ToonParams params = config.toonParams;
    const bool defaultLayout = frame.settings->gbuffer == GBufferSettings{};  // what the CUDA kernel reads
    if (cuda && !defaultLayout && !state.toldGlslForLayout) {
        logInfo("toon: the CUDA kernel reads the unpacked, stored G-buffer; --gbuffer " +
                std::string(gbufferFormatName(frame.settings->gbuffer.normal)) + " --gbuffer-position " +
                gbufferPositionName(frame.settings->gbuffer.position) + " runs the GLSL toon");
        state.toldGlslForLayout = true;
    }
    const bool useCuda = cuda && defaultLayout;
    const Data& d = graph.addPass<Data>(
        "toon", useCuda ? fg::PassKind::Cuda : fg::PassKind::Compute,
        [&](fg::PassBuilder& b, Data& data) {
            const fg::Usage how = useCuda ? fg::Usage::Cuda : fg::Usage::Sampled;
            data.in = gbuffer;
            b.read(gbuffer.depth, how);
            b.read(gbuffer.normal, how);
            if (gbuffer.position.valid()) b.read(gbuffer.position, how);
            data.hdr = b.write(hdr, useCuda ? fg::Usage::Cuda : fg::Usage::ImageLoadStore);
        },
        [&state, &backend, frame, params, useCuda, frameIndex = backend.frameIndex](const Data& data,
                                                                                    const fg::PassResources& res) {
            const GLuint hdrTex = res.texture(data.hdr), normalTex = res.texture(data.in.normal);
            const GLuint posTex = data.in.position.valid() ? res.texture(data.in.position) : 0;
            if (useCuda) {
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
            const glm::mat4& proj = frame.projection;
            ToonGBufferTextures g{res.texture(data.in.depth), normalTex, posTex, frame.settings->gbuffer,
                                  glm::vec4(frame.nearPlane, frame.farPlane, 1.0f / proj[1][1], proj[1][1] / proj[0][0])};
            runToonGlsl(state, *frame.shaders, hdrTex, g, frame.width, frame.height, params);
        });
    return d.hdr;
}

}  // namespace lp
