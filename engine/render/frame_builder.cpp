#include "engine/render/frame_builder.hpp"

#include <algorithm>

namespace lp {

FrameOutputs buildFrameGraph(fg::FrameGraph& graph, PassStates& passes, const FrameData& frame) {
    const RenderSettings& s = *frame.settings;
    const bool channelView = s.view != DebugView::Final && s.view != DebugView::Lighting;
    const bool lightingView = s.view == DebugView::Lighting;

    GBuffer gbuffer = addGBufferPass(graph, passes.gbuffer, frame, channelsForView(s.view));
    // [shadows] shadow-map passes go here (before the global lights, which read them).
    fg::ResourceId hdr = addGlobalLightPass(graph, passes.globalLights, frame, gbuffer, lightingView);
    // [ibl] the IBL pass adds into hdr here.
    // [local-lights] the local-light pass adds into hdr here.
    if (!lightingView) hdr = addSkyPass(graph, passes.sky, frame, gbuffer.depth, hdr);
    // [post] bloom and toon read and write hdr here, before the tone map.
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
