#include "passes/post_pass.hpp"

namespace lp {

bool postRunsInCuda(PostBackend& backend, const FrameData& frame, PostSettings::Backend requested) {
    // Without a GL context (the graph only described: 'lightpass graph', unit tests) nothing can be
    // asked of the driver: an explicit --post-backend cuda is shown as CUDA, auto as GLSL.
    if (!frame.shaders) return requested == PostSettings::Backend::Cuda && PostBackend::compiledWithCuda();
    return backend.useCuda(requested);
}

fg::ResourceId addPostPasses(fg::FrameGraph& graph, PostPasses& state, const FrameData& frame, const GBuffer& gbuffer,
                             fg::ResourceId hdr) {
    post::PostConfig config = post::resolvePostConfig(frame.scene->effects, frame.settings->post, frame.farPlane);
    if (frame.settings->allPasses && !config.bloom) {  // measuring: the bloom work, added at strength 0
        config.bloom = true;
        config.bloomParams.strength = 0.0f;
    }
    config.bloomParams.kernel = post::bloomKernelAtRenderSize(config.bloomParams.kernel, frame.width, frame.outputWidth);
    ++state.backend.frameIndex;  // every built frame, so CUDA registrations age even when culled
    if (frame.settings->view == DebugView::Lighting) return hdr;  // light alone: no post effects
    const bool cuda = (config.bloom || config.toon) && postRunsInCuda(state.backend, frame, config.backend);
    if (config.bloom) {
        // CUDA fuses the composite into bloom's last kernel (one GL<->CUDA map fewer) unless the
        // bloom view shows the bloom alone or the user switched bloom_composite off on its own.
        const bool fuse = !config.bloomOnly && !frame.settings->disabledPasses.count("bloom_composite");
        BloomResult bloom = addBloomPass(graph, state.bloom, state.backend, cuda, fuse, frame, config, hdr);
        if (config.bloomOnly) return bloom.bloom;
        hdr = bloom.hdr;
    } else {
        graph.skipPass("bloom", frame.settings->post.bloom ? "switched off (--no-bloom)"
                                                           : "off in the scene (effects.bloom.enabled) and no --bloom");
    }
    if (config.toon)
        hdr = addToonPass(graph, state.toon, state.backend, cuda, frame, config, gbuffer, hdr);
    else if (!config.toon)
        graph.skipPass("toon", frame.settings->post.toon ? "switched off (--no-toon)"
                                                         : "off in the scene (effects.toon.enabled) and no --toon");
    return hdr;
}

}  // namespace lp
