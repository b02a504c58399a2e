#include "passes/post_pass.hpp"

namespace lp {

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
    if (config.bloom) {
        BloomResult bloom = addBloomPass(graph, state.bloom, state.backend, frame, config, hdr);
        if (config.bloomOnly) return bloom.bloom;
        hdr = bloom.hdr;
    } else {
        graph.skipPass("bloom", frame.settings->post.bloom ? "switched off (--no-bloom)"
                                                           : "off in the scene (effects.bloom.enabled) and no --bloom");
    }
    if (config.toon)
        hdr = addToonPass(graph, state.toon, state.backend, frame, config, gbuffer, hdr);
    else if (!config.toon)
        graph.skipPass("toon", frame.settings->post.toon ? "switched off (--no-toon)"
                                                         : "off in the scene (effects.toon.enabled) and no --toon");
    return hdr;
}

}  // namespace lp
