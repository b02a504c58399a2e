#include "app/render_checks.hpp"

#include "engine/gl/limits.hpp"
#include "frame/frame_builder.hpp"

namespace lp::app {

void requireFrameFitsGpu(const gl::GpuContext& context, const Scene& scene, const RenderSettings& settings) {
    const gl::RenderTargetLimits limits = gl::queryRenderTargetLimits(context.isSoftware());
    gl::requireRenderSizeFits(settings.width, settings.height, 0, limits);  // dimensions first: cheap
    FrameData frame = makeFrameData(scene, settings, 0.0f);
    fg::FrameGraph graph;
    PassStates passes;  // never executed: sizing the graph needs no GPU
    buildFrameGraph(graph, passes, frame);
    graph.compile();
    gl::requireRenderSizeFits(settings.width, settings.height, graph.liveTransientBytes(), limits);
}

}  // namespace lp::app
