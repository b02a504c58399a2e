#include "passes/post_pass.hpp"

#include <algorithm>
#include <cstdio>
#include <variant>

#include "engine/core/log.hpp"
#include "engine/gl/handles.hpp"
#include "engine/graph/texture_pool.hpp"

#ifdef LIGHTPASS_HAVE_CUDA
#include "cuda/post_cuda.hpp"
#endif

namespace lp {

namespace {

#ifdef LIGHTPASS_HAVE_CUDA
// A texture for the start-up measurement: shared like the pool would make it when CUDA runs on
// shared textures (and `useShared`), else ordinary (mapped per use).
struct MeasureTexture {
    cuda::PostInterop& interop;
    gl::Texture plain;
    std::shared_ptr<fg::ExternalTexture> shared;
    MeasureTexture(cuda::PostInterop& cu, const fg::TextureDesc& d, const std::string& label, bool useShared)
        : interop(cu) {
        fg::ExternalTextureSource* source = useShared ? cu.sharedTextureSource() : nullptr;
        if (source) shared = source->make(d, label);
        if (!shared) plain = gl::makeTexture2D(d.format, d.width, d.height, d.levels, label);
    }
    // Its id may come back for a pool texture of the same size: no stale map/unmap registration.
    ~MeasureTexture() {
        if (plain) interop.forgetTexture(plain.id());
    }
    MeasureTexture(const MeasureTexture&) = delete;
    MeasureTexture& operator=(const MeasureTexture&) = delete;
    GLuint id() const { return shared ? shared->texture() : plain.id(); }
};

constexpr int kMeasureRuns = 7;

// GPU ms per run of `work` as the frame pays it: a GL timer query around kMeasureRuns runs after one
// untimed run, a barrier after each as the graph would issue before the next pass. For a CUDA call
// the GL timeline holds everything the frame waits for: the hand-over to CUDA and back (semaphores,
// host waits or map/unmap), and the kernels in between.
template <typename Work>
double glTimedMs(Work&& work) {
    work();
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    gl::Query query = gl::makeQuery(GL_TIME_ELAPSED);
    glBeginQuery(GL_TIME_ELAPSED, query.id());
    for (int i = 0; i < kMeasureRuns; ++i) {
        work();
        glMemoryBarrier(GL_ALL_BARRIER_BITS);
    }
    glEndQuery(GL_TIME_ELAPSED);
    GLuint64 ns = 0;
    glGetQueryObjectui64v(query.id(), GL_QUERY_RESULT, &ns);
    return double(ns) * 1e-6 / kMeasureRuns;
}

// `shared`: CUDA on shared textures (where the interop has them), else on mapped ones.
post::BackendTimes measureEffect(PostPasses& st, const FrameData& frame, const post::PostConfig& config,
                                 post::PostEffect effect, bool shared) {
    const int w = frame.width, h = frame.height;
    cuda::PostInterop& cu = *st.backend.interop;
    const float hdrFill[4] = {1.5f, 0.75f, 3.0f, 1.0f};  // above the threshold: the bloom does its work
    MeasureTexture hdr(cu, {w, h, GL_RGBA16F}, "post_measure.hdr", shared);
    glClearTexImage(hdr.id(), 0, GL_RGBA, GL_FLOAT, hdrFill);
    post::BackendTimes t;
    const post::BloomParams& p = config.bloomParams;
    if (effect == post::PostEffect::Bloom || effect == post::PostEffect::Composite) {
        MeasureTexture bloom(cu, {w, h, GL_RGBA16F}, "post_measure.bloom", shared);
        glClearTexImage(bloom.id(), 0, GL_RGBA, GL_FLOAT, hdrFill);
        if (effect == post::PostEffect::Bloom) {
            const BloomScratchDescs d = bloomScratchDescs(p, w, h);
            std::vector<gl::Texture> scratch;
            BloomScratch s;
            if (d.bright.width > 0) {
                scratch.push_back(gl::makeTexture2D(d.bright.format, d.bright.width, d.bright.height, 1, "post_measure.bright"));
                scratch.push_back(gl::makeTexture2D(d.blurH.format, d.blurH.width, d.blurH.height, 1, "post_measure.blur_h"));
                s.bright = scratch[0].id();
                s.blurH = scratch[1].id();
            } else {
                scratch.push_back(gl::makeTexture2D(d.mips.format, d.mips.width, d.mips.height, d.mips.levels, "post_measure.mips"));
                s.mips = scratch[0].id();
            }
            t.glslMs = glTimedMs([&] { runBloomGlsl(st.bloom, *frame.shaders, s, hdr.id(), bloom.id(), w, h, p); });
            t.cudaMs = glTimedMs([&] { cu.bloom(hdr.id(), bloom.id(), w, h, p); });
        } else {
            t.glslMs = glTimedMs([&] { runBloomCompositeGlsl(st.bloom, *frame.shaders, hdr.id(), bloom.id(), w, h, p.strength); });
            t.cudaMs = glTimedMs([&] { cu.composite(hdr.id(), bloom.id(), w, h, p.strength); });
        }
        return t;
    }
    // Toon on the default G-buffer layout (what its CUDA kernel reads): a flat surface at depth 2.
    const float position[4] = {0.0f, 0.0f, -2.0f, 1.0f}, normal[4] = {0.0f, 0.0f, 1.0f, 0.0f}, depth = 0.5f;
    MeasureTexture pos(cu, {w, h, GL_RGBA32F}, "post_measure.position", shared);
    MeasureTexture nrm(cu, {w, h, GL_RGBA32F}, "post_measure.normal", shared);
    gl::Texture dep = gl::makeTexture2D(GL_DEPTH_COMPONENT32F, w, h, 1, "post_measure.depth");
    glClearTexImage(pos.id(), 0, GL_RGBA, GL_FLOAT, position);
    glClearTexImage(nrm.id(), 0, GL_RGBA, GL_FLOAT, normal);
    glClearTexImage(dep.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, &depth);
    const glm::mat4& proj = frame.projection;
    const ToonGBufferTextures g{dep.id(), nrm.id(), pos.id(), GBufferSettings{},
                                glm::vec4(frame.nearPlane, frame.farPlane, 1.0f / proj[1][1], proj[1][1] / proj[0][0])};
    t.glslMs = glTimedMs([&] { runToonGlsl(st.toon, *frame.shaders, hdr.id(), g, w, h, config.toonParams); });
    t.cudaMs = glTimedMs([&] { cu.toon(hdr.id(), pos.id(), nrm.id(), w, h, config.toonParams); });
    return t;
}

// --cuda-interop auto where shared textures work with semaphores: measures the effects on shared
// textures and on mapped ones at this frame's size (cached like auto's times), keeps whichever
// path is cheaper for the frame, and says so once.
void decideInterop(PostPasses& state, const FrameData& frame, const post::PostConfig& config,
                   const std::vector<post::PostEffect>& effects, bool cudaForAll) {
    PostBackend& b = state.backend;
    const bool remeasure = frame.settings->post.remeasure;
    auto timesOn = [&](const char* interop, bool shared) {
        return b.effectTimes(postTimingKey(frame, config, interop), effects, remeasure,
                             [&](post::PostEffect e) { return measureEffect(state, frame, config, e, shared); });
    };
    const auto viaShared = timesOn(kInteropSemaphores, true);
    const auto viaMap = timesOn(kInteropMap, false);
    const bool shared = sharedInteropWins(viaShared, viaMap, cudaForAll);
    char line[320];
    std::snprintf(line, sizeof line,
                  "post effects: --cuda-interop auto at %dx%d: %s (shared textures with %s %.3f ms, map/unmap %.3f ms)",
                  frame.width, frame.height, shared ? "shared textures" : "map/unmap", b.interop->syncName().c_str(),
                  postEffectsMs(viaShared, cudaForAll), postEffectsMs(viaMap, cudaForAll));
    logInfo(line);
    if (shared) b.keepSharedInterop();
    else b.useMapInterop();
}
#endif

std::string glString(GLenum name) {
    const char* s = reinterpret_cast<const char*>(glGetString(name));
    return s ? s : "";
}

}  // namespace

post::TimingKey postTimingKey(const FrameData& frame, const post::PostConfig& config, const std::string& interop) {
    post::TimingKey key;
    key.gpu = glString(GL_RENDERER);
    key.driver = glString(GL_VERSION);  // NVIDIA's names the driver: "4.6.0 NVIDIA 550.54.15"
    key.width = frame.width;
    key.height = frame.height;
    key.kernel = config.bloomParams.kernel;
    key.method = post::bloomMethodName(config.bloomParams.method);
    key.interop = interop;
    return key;
}

PostBackendChoice postBackendChoice(PostPasses& state, const FrameData& frame, const post::PostConfig& config) {
    const PostSettings::Backend requested = config.backend;
    // Without a GL context (the graph only described: 'lightpass graph', unit tests) nothing can be
    // asked of the driver: an explicit --post-backend cuda is shown as CUDA, auto as GLSL.
    if (!frame.shaders) {
        const bool cuda = requested == PostSettings::Backend::Cuda && PostBackend::compiledWithCuda();
        return {cuda, cuda, cuda};
    }
    if (!(config.bloom || config.toon)) return {};
    if (!state.backend.cudaUsable(requested, frame.settings->post.cudaInterop)) return {};
#ifdef LIGHTPASS_HAVE_CUDA
    std::vector<post::PostEffect> effects;
    if (config.bloom) effects.push_back(post::PostEffect::Bloom);
    if (config.bloom && !config.bloomOnly) effects.push_back(post::PostEffect::Composite);
    // The CUDA toon reads the default G-buffer layout only: other layouts run the GLSL toon anyway.
    if (config.toon && frame.settings->gbuffer == GBufferSettings{}) effects.push_back(post::PostEffect::Toon);
    if (state.backend.interopUndecided())
        decideInterop(state, frame, config, effects, requested == PostSettings::Backend::Cuda);
    if (requested == PostSettings::Backend::Cuda) return {true, true, true};
    const bool shared = state.backend.interopPath() != kInteropMap;
    return state.backend.autoChoice(postTimingKey(frame, config, state.backend.interopPath()), effects,
                                    frame.settings->post.remeasure, [&](post::PostEffect effect) {
                                        return measureEffect(state, frame, config, effect, shared);
                                    });
#else
    if (requested == PostSettings::Backend::Cuda) return {true, true, true};
    return {};
#endif
}

PostResult addPostPasses(fg::FrameGraph& graph, PostPasses& state, const FrameData& frame, const GBuffer& gbuffer,
                         fg::ResourceId hdr) {
    PostResult out{hdr, {}};
    post::PostConfig config = post::resolvePostConfig(frame.scene->effects, frame.settings->post, frame.farPlane);
    if (frame.settings->allPasses && !config.bloom) {  // measuring: the bloom work, added at strength 0
        config.bloom = true;
        config.bloomParams.strength = 0.0f;
    }
    config.bloomParams.kernel = post::bloomKernelAtRenderSize(config.bloomParams.kernel, frame.width, frame.outputWidth);
    ++state.backend.frameIndex;  // every built frame, so CUDA registrations age even when culled
    // light alone, or one of its terms: no post effects
    if (frame.settings->view == DebugView::Lighting || isShadingTermView(frame.settings->view)) return out;
    const PostBackendChoice cuda = postBackendChoice(state, frame, config);
    if (config.bloom) {
        // CUDA fuses the composite into bloom's last kernel when both run in CUDA, unless the bloom
        // view shows the bloom alone or the user switched bloom_composite off on its own.
        const bool fuse = !config.bloomOnly && !frame.settings->disabledPasses.count("bloom_composite");
        BloomResult bloom = addBloomPass(graph, state.bloom, state.backend, cuda, fuse, frame, config, hdr);
        if (bloom.fusedComposite) out.skipped.emplace_back("bloom_composite", "fused into the CUDA bloom pass");
        if (config.bloomOnly) {
            out.hdr = bloom.bloom;
            return out;
        }
        out.hdr = bloom.hdr;
    } else {
        out.skipped.emplace_back("bloom", frame.settings->post.bloom ? "switched off (--no-bloom)"
                                                                     : "off in the scene (effects.bloom.enabled) and no --bloom");
    }
    if (config.toon)
        out.hdr = addToonPass(graph, state.toon, state.backend, cuda.toon, frame, config, gbuffer, out.hdr);
    else
        out.skipped.emplace_back("toon", frame.settings->post.toon ? "switched off (--no-toon)"
                                                                   : "off in the scene (effects.toon.enabled) and no --toon");
    return out;
}

}  // namespace lp
