#include "engine/render/frame_builder.hpp"

#include <algorithm>

namespace lp {

FrameOutputs buildFrameGraph(fg::FrameGraph& graph, PassStates& passes, const FrameData& frame) {
    const RenderSettings& s = *frame.settings;
    const bool channelView = s.view != DebugView::Final && s.view != DebugView::Lighting &&
                             !isLocalLightView(s.view);  // overlays on the final image
    const bool lightingView = s.view == DebugView::Lighting;

    GBuffer gbuffer = addGBufferPass(graph, passes.gbuffer, frame, channelsForView(s.view));
    // one depth pass per shadow-casting directional light; global_lights and the shadowmap view read them.
    passes.globalLights.shadowMaps = addShadowMapPasses(graph, passes.shadowMaps, frame);
    passes.debugView.shadowMaps = &passes.globalLights.shadowMaps;
    fg::ResourceId hdr = addGlobalLightPass(graph, passes.globalLights, frame, gbuffer, lightingView);
    passes.sky.environments = &passes.ibl.environments;  // the sky and environment views read it
    passes.debugView.ibl = &passes.ibl;
    hdr = addIblPass(graph, passes.ibl, frame, gbuffer, hdr, lightingView);
    hdr = addLocalLightPass(graph, passes.localLights, frame, gbuffer, hdr, lightingView);
    if (!lightingView) hdr = addSkyPass(graph, passes.sky, frame, gbuffer.depth, hdr);
    // globes and the light-ranges / lights-per-tile overlays, over the sky too.
    if (!lightingView) hdr = addLocalLightOverlayPasses(graph, passes.localLights, frame, gbuffer, hdr);
    hdr = addPostPasses(graph, passes.post, frame, gbuffer, hdr);  // bloom, toon (not in the lighting view)
    fg::ResourceId display = addToneMapPass(graph, passes.tonemap, frame, hdr);
    if (channelView) display = addDebugViewPass(graph, passes.debugView, frame, gbuffer, s.view);

    for (const auto& name : s.disabledPasses) graph.disablePass(name);
    graph.markOutput(display);
    FrameOutputs out{display, {}};
    if (s.keepHdr && !channelView) {
        graph.markOutput(hdr);
        out.hdr = hdr;
    }
    return out;
}

FrameData makeFrameData(const Scene& scene, const RenderSettings& settings, float time) {
    FrameData f;
    f.width = settings.width;
    f.height = settings.height;
    f.view = scene.camera.view();
    f.projection = scene.camera.projection(float(settings.width) / float(std::max(settings.height, 1)));
    f.nearPlane = scene.camera.nearPlane;
    f.farPlane = scene.camera.farPlane;
    f.time = time;
    glm::vec3 lo, hi;
    scene.bounds(lo, hi);
    f.sceneExtent = std::max(glm::length(0.5f * (lo + hi) - scene.camera.position) + 0.5f * glm::length(hi - lo), 1e-3f);
    f.scene = &scene;
    f.settings = &settings;
    return f;
}

}  // namespace lp
