#include "passes/bloom_pass.hpp"

#include <algorithm>

#include "engine/gl/gpu_timer.hpp"
#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"

#ifdef LIGHTPASS_HAVE_CUDA
#include "cuda/post_cuda.hpp"
#endif

namespace lp {

namespace {

struct Data {
    fg::ResourceId hdr, bloom;
};

void uniform1f(GLuint prog, const char* name, float v) { glProgramUniform1f(prog, glGetUniformLocation(prog, name), v); }
void uniform1i(GLuint prog, const char* name, int v) { glProgramUniform1i(prog, glGetUniformLocation(prog, name), v); }

void ensureTexture(gl::Texture& t, int width, int height, int levels, const char* name) {
    if (t && t.width == width && t.height == height && t.levels == levels) return;
    t = gl::makeTexture2D(GL_RGBA16F, width, height, levels, name);
    // texelFetch of levels > 0 needs a mipmapped minification filter to be defined.
    if (levels > 1) glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
}

void dispatch(GLuint prog, int width, int height) {
    glUseProgram(prog);
    gl::dispatch2D(width, height);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

#ifdef LIGHTPASS_HAVE_CUDA
// CUDA fuses the composite into the bloom pass (one GL<->CUDA map fewer) only when that cannot be
// seen: bloom_composite runs, and runs right after bloom, so no pass reads the HDR buffer between.
bool compositeRunsRightAfterBloom(const fg::FrameGraph& graph) {
    const std::vector<std::string> order = graph.executionOrder();
    const auto it = std::find(order.begin(), order.end(), "bloom");
    if (it == order.end() || it + 1 == order.end() || *(it + 1) != "bloom_composite") return false;
    for (const fg::PassDecision& d : graph.explain())
        if (d.name == "bloom_composite") return d.runs;
    return false;
}
#endif

void unbind() {
    glUseProgram(0);
    glBindTextureUnit(0, 0);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
}


// The separable blur as two full-screen triangles (scratchA -> scratchB -> bloom); same taps.
void blurWithFragments(BloomPass& st, const gl::ShaderLibrary& shaders, const std::vector<float>& w, GLuint bloom,
                       int width, int height) {
    if (!st.blurFragment) st.blurFragment = shaders.graphics("fullscreen.vert", "bloom_blur.frag");
    if (!st.fbo) st.fbo = gl::makeFramebuffer("bloom.blur_fragment");
    if (!st.vao) st.vao = gl::makeVertexArray("bloom.blur_fragment");
    const GLuint prog = st.blurFragment.id();
    glProgramUniform1fv(prog, glGetUniformLocation(prog, "uWeights"), GLsizei(w.size()), w.data());
    glProgramUniform1i(prog, glGetUniformLocation(prog, "uRadius"), int(w.size()) - 1);
    gl::ScopedFramebuffer bind(st.fbo.id(), width, height);
    gl::ScopedEnable depth(GL_DEPTH_TEST, false);
    gl::ScopedEnable blend(GL_BLEND, false);
    glUseProgram(prog);
    glBindVertexArray(st.vao.id());
    const GLuint sources[2] = {st.scratchA.id(), st.scratchB.id()}, targets[2] = {st.scratchB.id(), bloom};
    for (int pass = 0; pass < 2; ++pass) {
        glNamedFramebufferTexture(st.fbo.id(), GL_COLOR_ATTACHMENT0, targets[pass], 0);
        glProgramUniform2i(prog, glGetUniformLocation(prog, "uDirection"), pass == 0, pass == 1);
        glBindTextureUnit(0, sources[pass]);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glNamedFramebufferTexture(st.fbo.id(), GL_COLOR_ATTACHMENT0, 0, 0);
    glBindVertexArray(0);
    unbind();
}

}  // namespace

void runBloomGlsl(BloomPass& st, const gl::ShaderLibrary& shaders, GLuint hdr, GLuint bloom, int width, int height,
                  const post::BloomParams& p) {
    if (p.method == post::BloomMethod::Separable) {
        if (!st.bright) st.bright = shaders.compute("bloom_bright.comp");
        if (!st.blur) st.blur = shaders.compute("bloom_blur.comp");
        ensureTexture(st.scratchA, width, height, 1, "bloom.bright");
        ensureTexture(st.scratchB, width, height, 1, "bloom.blur_h");
        GLuint prog = st.bright.id();
        uniform1f(prog, "uThreshold", p.threshold);
        uniform1f(prog, "uKnee", p.knee);
        uniform1f(prog, "uHighlight", p.highlight);
        glBindTextureUnit(0, hdr);
        glBindImageTexture(0, st.scratchA.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        dispatch(prog, width, height);

        const std::vector<float> w = post::gaussianWeights(p.kernel);
        if (p.fragmentBlur) {
            blurWithFragments(st, shaders, w, bloom, width, height);
            return;
        }
        prog = st.blur.id();
        glProgramUniform1fv(prog, glGetUniformLocation(prog, "uWeights"), GLsizei(w.size()), w.data());
        uniform1i(prog, "uRadius", int(w.size()) - 1);
        const GLint dir = glGetUniformLocation(prog, "uDirection");
        glProgramUniform2i(prog, dir, 1, 0);
        glBindTextureUnit(0, st.scratchA.id());
        glBindImageTexture(0, st.scratchB.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        dispatch(prog, width, height);
        glProgramUniform2i(prog, dir, 0, 1);
        glBindTextureUnit(0, st.scratchB.id());
        glBindImageTexture(0, bloom, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        dispatch(prog, width, height);
        unbind();
        return;
    }
    if (!st.down) st.down = shaders.compute("bloom_down.comp");
    if (!st.up) st.up = shaders.compute("bloom_up.comp");
    const int levels = post::mipLevelCount(p.kernel, width, height);
    ensureTexture(st.mips, post::mipSize(width, 0), post::mipSize(height, 0), levels, "bloom.mips");
    GLuint prog = st.down.id();
    uniform1f(prog, "uThreshold", p.threshold);
    uniform1f(prog, "uKnee", p.knee);
    uniform1f(prog, "uHighlight", p.highlight);
    uniform1i(prog, "uKaris", p.karis);
    for (int l = 0; l < levels; ++l) {
        uniform1i(prog, "uFirst", l == 0);
        uniform1i(prog, "uSourceLevel", l == 0 ? 0 : l - 1);
        glBindTextureUnit(0, l == 0 ? hdr : st.mips.id());
        glBindImageTexture(0, st.mips.id(), l, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        dispatch(prog, post::mipSize(width, l), post::mipSize(height, l));
    }
    prog = st.up.id();
    glBindTextureUnit(0, st.mips.id());
    for (int l = levels - 2; l >= 0; --l) {
        uniform1i(prog, "uCoarseLevel", l + 1);
        uniform1i(prog, "uAddFine", 1);
        uniform1f(prog, "uScale", 1.0f);
        glBindImageTexture(0, st.mips.id(), l, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
        dispatch(prog, post::mipSize(width, l), post::mipSize(height, l));
    }
    uniform1i(prog, "uCoarseLevel", 0);
    uniform1i(prog, "uAddFine", 0);
    uniform1f(prog, "uScale", 1.0f / float(levels));
    glBindImageTexture(0, bloom, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
    dispatch(prog, width, height);
    unbind();
}

void runBloomCompositeGlsl(BloomPass& st, const gl::ShaderLibrary& shaders, GLuint hdr, GLuint bloom, int width,
                           int height, float strength) {
    if (!st.composite) st.composite = shaders.compute("bloom_composite.comp");
    const GLuint prog = st.composite.id();
    uniform1f(prog, "uStrength", strength);
    glBindTextureUnit(0, bloom);
    glBindImageTexture(0, hdr, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
    dispatch(prog, width, height);
    unbind();
}

BloomResult addBloomPass(fg::FrameGraph& graph, BloomPass& state, PostBackend& backend, const FrameData& frame,
                         const post::PostConfig& config, fg::ResourceId hdr) {
    const post::BloomParams params = config.bloomParams;
    const PostSettings::Backend requested = config.backend;
    const Data& made = graph.addPass<Data>(
        "bloom",
        [&](fg::PassBuilder& b, Data& data) {
            data.hdr = b.read(hdr);
            data.bloom = b.create("bloom", {frame.width, frame.height, GL_RGBA16F});
        },
        [&graph, &state, &backend, frame, params, requested, frameIndex = backend.frameIndex](
            const Data& data, const fg::PassResources& res) {
            const GLuint hdrTex = res.texture(data.hdr), bloomTex = res.texture(data.bloom);
            if (backend.useCuda(requested)) {
                backend.beginFrame(frameIndex);
#ifdef LIGHTPASS_HAVE_CUDA
                const bool fuse = compositeRunsRightAfterBloom(graph);
                cuda::PostTiming t =
                    fuse ? backend.interop->bloomComposite(hdrTex, bloomTex, frame.width, frame.height, params)
                         : backend.interop->bloom(hdrTex, bloomTex, frame.width, frame.height, params);
                if (fuse) state.cudaCompositedFrame = frameIndex;
                if (res.timers()) {
                    res.timers()->addExternal("bloom (cuda kernels)", t.kernelMs);
                    res.timers()->addExternal("bloom (cuda interop)", t.interopMs);
                }
#endif
                return;
            }
            runBloomGlsl(state, *frame.shaders, hdrTex, bloomTex, frame.width, frame.height, params);
        });
    const Data& composited = graph.addPass<Data>(
        "bloom_composite",
        [&](fg::PassBuilder& b, Data& data) {
            data.bloom = b.read(made.bloom);
            data.hdr = b.write(hdr);
        },
        [&state, &backend, frame, params, requested, frameIndex = backend.frameIndex](const Data& data,
                                                                                      const fg::PassResources& res) {
            const GLuint hdrTex = res.texture(data.hdr), bloomTex = res.texture(data.bloom);
            if (backend.useCuda(requested)) {
                if (state.cudaCompositedFrame == frameIndex) return;  // done by the bloom pass
#ifdef LIGHTPASS_HAVE_CUDA
                cuda::PostTiming t =
                    backend.interop->composite(hdrTex, bloomTex, frame.width, frame.height, params.strength);
                if (res.timers()) {
                    res.timers()->addExternal("bloom_composite (cuda kernels)", t.kernelMs);
                    res.timers()->addExternal("bloom_composite (cuda interop)", t.interopMs);
                }
#endif
                return;
            }
            runBloomCompositeGlsl(state, *frame.shaders, hdrTex, bloomTex, frame.width, frame.height, params.strength);
        });
    return {composited.hdr, made.bloom};
}

}  // namespace lp
