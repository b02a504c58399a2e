#include "passes/bloom_pass.hpp"

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
    fg::ResourceId hdr, bloom;
    fg::ResourceId bright, blurH, mips;  // the GLSL path's scratch
};

// One step of the chain; the next step reads what this one stored (a barrier within the pass).
void dispatch(GLuint prog, int width, int height) {
    glUseProgram(prog);
    gl::dispatch2D(width, height);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

void unbind() {
    glUseProgram(0);
    glBindTextureUnit(0, 0);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
}

// The separable blur as two full-screen triangles (bright -> blurH -> bloom); same taps.
void blurWithFragments(BloomPass& st, const gl::ShaderLibrary& shaders, const BloomScratch& scratch,
                       const std::vector<float>& w, GLuint bloom, int width, int height) {
    if (!st.blurFragment) st.blurFragment = shaders.graphics("fullscreen.vert", "bloom_blur.frag");
    if (!st.fbo) st.fbo = gl::makeFramebuffer("bloom.blur_fragment");
    if (!st.vao) st.vao = gl::makeVertexArray("bloom.blur_fragment");
    const GLuint prog = st.blurFragment.id();
    const gl::Uniforms u(&shaders, prog);
    u.setArray("uWeights", w.data(), int(w.size()));
    u.set("uRadius", int(w.size()) - 1);
    gl::ScopedFramebuffer bind(st.fbo.id(), width, height);
    gl::ScopedEnable depth(GL_DEPTH_TEST, false);
    gl::ScopedEnable blend(GL_BLEND, false);
    glUseProgram(prog);
    glBindVertexArray(st.vao.id());
    const GLuint sources[2] = {scratch.bright, scratch.blurH}, targets[2] = {scratch.blurH, bloom};
    for (int pass = 0; pass < 2; ++pass) {
        glNamedFramebufferTexture(st.fbo.id(), GL_COLOR_ATTACHMENT0, targets[pass], 0);
        u.set("uDirection", glm::ivec2(pass == 0, pass == 1));
        glBindTextureUnit(0, sources[pass]);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glNamedFramebufferTexture(st.fbo.id(), GL_COLOR_ATTACHMENT0, 0, 0);
    glBindVertexArray(0);
    unbind();
}

}  // namespace

BloomScratchDescs bloomScratchDescs(const post::BloomParams& p, int width, int height) {
    BloomScratchDescs d;
    if (p.method == post::BloomMethod::Separable) {
        d.bright = {width, height, GL_RGBA16F};
        d.blurH = {width, height, GL_RGBA16F};
    } else {
        d.mips = {post::mipSize(width, 0), post::mipSize(height, 0), GL_RGBA16F,
                  post::mipLevelCount(p.kernel, width, height)};
    }
    return d;
}

void runBloomGlsl(BloomPass& st, const gl::ShaderLibrary& shaders, const BloomScratch& scratch, GLuint hdr,
                  GLuint bloom, int width, int height, const post::BloomParams& p) {
    if (p.method == post::BloomMethod::Separable) {
        if (!st.bright) st.bright = shaders.compute("bloom_bright.comp");
        if (!st.blur) st.blur = shaders.compute("bloom_blur.comp");
        GLuint prog = st.bright.id();
        const gl::Uniforms bright(&shaders, prog);
        bright.set("uThreshold", p.threshold);
        bright.set("uKnee", p.knee);
        bright.set("uHighlight", p.highlight);
        glBindTextureUnit(0, hdr);
        glBindImageTexture(0, scratch.bright, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        dispatch(prog, width, height);

        const std::vector<float> w = post::gaussianWeights(p.kernel);
        if (p.fragmentBlur) {
            blurWithFragments(st, shaders, scratch, w, bloom, width, height);
            return;
        }
        prog = st.blur.id();
        const gl::Uniforms blur(&shaders, prog);
        blur.setArray("uWeights", w.data(), int(w.size()));
        blur.set("uRadius", int(w.size()) - 1);
        blur.set("uDirection", glm::ivec2(1, 0));
        glBindTextureUnit(0, scratch.bright);
        glBindImageTexture(0, scratch.blurH, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        dispatch(prog, width, height);
        blur.set("uDirection", glm::ivec2(0, 1));
        glBindTextureUnit(0, scratch.blurH);
        glBindImageTexture(0, bloom, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        glUseProgram(prog);
        gl::dispatch2D(width, height);  // the last step: the graph orders what reads `bloom`
        unbind();
        return;
    }
    if (!st.down) st.down = shaders.compute("bloom_down.comp");
    if (!st.up) st.up = shaders.compute("bloom_up.comp");
    const int levels = post::mipLevelCount(p.kernel, width, height);
    // texelFetch of levels > 0 needs a mipmapped minification filter to be defined; nearest keeps
    // every tap exact (the pool hands the texture over with the default linear filter).
    glTextureParameteri(scratch.mips, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
    GLuint prog = st.down.id();
    const gl::Uniforms down(&shaders, prog);
    down.set("uThreshold", p.threshold);
    down.set("uKnee", p.knee);
    down.set("uHighlight", p.highlight);
    down.set("uKaris", p.karis);
    for (int l = 0; l < levels; ++l) {
        down.set("uFirst", l == 0);
        down.set("uSourceLevel", l == 0 ? 0 : l - 1);
        glBindTextureUnit(0, l == 0 ? hdr : scratch.mips);
        glBindImageTexture(0, scratch.mips, l, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        dispatch(prog, post::mipSize(width, l), post::mipSize(height, l));
    }
    prog = st.up.id();
    const gl::Uniforms up(&shaders, prog);
    glBindTextureUnit(0, scratch.mips);
    for (int l = levels - 2; l >= 0; --l) {
        up.set("uCoarseLevel", l + 1);
        up.set("uAddFine", 1);
        up.set("uScale", 1.0f);
        glBindImageTexture(0, scratch.mips, l, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
        dispatch(prog, post::mipSize(width, l), post::mipSize(height, l));
    }
    up.set("uCoarseLevel", 0);
    up.set("uAddFine", 0);
    up.set("uScale", 1.0f / float(levels));
    glBindImageTexture(0, bloom, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
    glUseProgram(prog);
    gl::dispatch2D(width, height);  // the last step: the graph orders what reads `bloom`
    unbind();
}

void runBloomCompositeGlsl(BloomPass& st, const gl::ShaderLibrary& shaders, GLuint hdr, GLuint bloom, int width,
                           int height, float strength) {
    if (!st.composite) st.composite = shaders.compute("bloom_composite.comp");
    const GLuint prog = st.composite.id();
    gl::Uniforms(&shaders, prog).set("uStrength", strength);
    glBindTextureUnit(0, bloom);
    glBindImageTexture(0, hdr, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
    glUseProgram(prog);
    gl::dispatch2D(width, height);
    unbind();
}

BloomResult addBloomPass(fg::FrameGraph& graph, BloomPass& state, PostBackend& backend, const PostBackendChoice& choice,
                         bool fuse, const FrameData& frame, const post::PostConfig& config, fg::ResourceId hdr) {
    const post::BloomParams params = config.bloomParams;
    const unsigned long frameIndex = backend.frameIndex;
    const fg::TextureDesc bloomDesc{frame.width, frame.height, GL_RGBA16F};
    const bool cuda = choice.bloom;
    fuse = fuse && choice.bloom && choice.composite;
    const Data* made = nullptr;
    if (cuda) {
        made = &graph.addPass<Data>(
            "bloom", fg::PassKind::Cuda,
            [&](fg::PassBuilder& b, Data& data) {
                if (fuse) data.hdr = b.write(hdr, fg::Usage::Cuda);
                else data.hdr = b.read(hdr, fg::Usage::Cuda);
                data.bloom = b.create("bloom", bloomDesc, fg::Usage::Cuda);
            },
            [&backend, frame, params, fuse, frameIndex](const Data& data, const fg::PassResources& res) {
                backend.beginFrame(frameIndex);
#ifdef LIGHTPASS_HAVE_CUDA
                const GLuint hdrTex = res.texture(data.hdr), bloomTex = res.texture(data.bloom);
                cuda::PostTiming t =
                    fuse ? backend.interop->bloomComposite(hdrTex, bloomTex, frame.width, frame.height, params)
                         : backend.interop->bloom(hdrTex, bloomTex, frame.width, frame.height, params);
                if (res.timers()) {
                    res.timers()->addExternal("bloom (cuda kernels)", t.kernelMs);
                    res.timers()->addExternal("bloom (cuda interop)", t.interopMs);
                }
#else
                (void)data, (void)res, (void)frame, (void)params, (void)fuse;
#endif
            });
        if (fuse) return {made->hdr, made->bloom, true};
    } else {
        const BloomScratchDescs scratch = bloomScratchDescs(params, frame.width, frame.height);
        const bool separable = params.method == post::BloomMethod::Separable;
        const bool fragmentBlur = separable && params.fragmentBlur;
        made = &graph.addPass<Data>(
            "bloom", fragmentBlur ? fg::PassKind::Raster : fg::PassKind::Compute,
            [&](fg::PassBuilder& b, Data& data) {
                data.hdr = b.read(hdr, fg::Usage::Sampled);
                const fg::Usage blurTarget = fragmentBlur ? fg::Usage::ColorAttachment : fg::Usage::ImageStore;
                data.bloom = b.create("bloom", bloomDesc, separable ? blurTarget : fg::Usage::ImageLoadStore);
                // Scratch lives and dies inside this pass: the pool lends it and takes it back.
                if (separable) {
                    data.bright = b.create("bloom.bright", scratch.bright, fg::Usage::ImageStore);
                    data.blurH = b.create("bloom.blur_h", scratch.blurH, blurTarget);
                } else {
                    data.mips = b.create("bloom.mips", scratch.mips, fg::Usage::ImageLoadStore);
                }
            },
            [&state, frame, params](const Data& data, const fg::PassResources& res) {
                BloomScratch s;
                if (data.bright.valid()) {
                    s.bright = res.texture(data.bright);
                    s.blurH = res.texture(data.blurH);
                }
                if (data.mips.valid()) s.mips = res.texture(data.mips);
                runBloomGlsl(state, *frame.shaders, s, res.texture(data.hdr), res.texture(data.bloom), frame.width,
                             frame.height, params);
            });
    }
    const bool cudaComposite = choice.composite;
    const Data& composited = graph.addPass<Data>(
        "bloom_composite", cudaComposite ? fg::PassKind::Cuda : fg::PassKind::Compute,
        [&](fg::PassBuilder& b, Data& data) {
            const fg::Usage how = cudaComposite ? fg::Usage::Cuda : fg::Usage::Sampled;
            data.bloom = b.read(made->bloom, how);
            data.hdr = b.write(hdr, cudaComposite ? fg::Usage::Cuda : fg::Usage::ImageLoadStore);
        },
        [&state, &backend, frame, params, cuda = cudaComposite, frameIndex](const Data& data,
                                                                            const fg::PassResources& res) {
            const GLuint hdrTex = res.texture(data.hdr), bloomTex = res.texture(data.bloom);
            if (cuda) {
                backend.beginFrame(frameIndex);
#ifdef LIGHTPASS_HAVE_CUDA
                cuda::PostTiming t = backend.interop->composite(hdrTex, bloomTex, frame.width, frame.height, params.strength);
                if (res.timers()) {
                    res.timers()->addExternal("bloom_composite (cuda kernels)", t.kernelMs);
                    res.timers()->addExternal("bloom_composite (cuda interop)", t.interopMs);
                }
#endif
                return;
            }
            runBloomCompositeGlsl(state, *frame.shaders, hdrTex, bloomTex, frame.width, frame.height, params.strength);
        });
    return {composited.hdr, made->bloom};
}

}  // namespace lp
