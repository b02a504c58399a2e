#include "app/render_checks.hpp"

#include <cstdio>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/gl/handles.hpp"
#include "engine/gl/limits.hpp"
#include "frame/frame_builder.hpp"

namespace lp::app {

std::unique_ptr<gl::GpuContext> openHeadlessFor(const std::string& verb, const Scene& scene, const RenderSettings& settings) {
    auto ctx = gl::createHeadlessContext();
    logInfo(verb + " on " + ctx->info().renderer + " (" + ctx->info().platform + ")");
    requireFrameFitsGpu(*ctx, scene, settings);
    return ctx;
}

void requireFrameFitsGpu(const gl::GpuContext& context, const Scene& scene, const RenderSettings& settings) {
    const gl::RenderTargetLimits limits = gl::queryRenderTargetLimits(context.isSoftware());
    gl::requireRenderSizeFits(settings.width, settings.height, 0, limits);  // dimensions first: cheap
    FrameData frame = makeFrameData(scene, settings, 0.0f);
    frame.softwareRaster = context.isSoftware();  // the G-buffer mode auto picks here
    fg::FrameGraph graph;
    PassStates passes;  // never executed: sizing the graph needs no GPU
    buildFrameGraph(graph, passes, frame);
    graph.compile();
    // A misspelt --disable-pass is known from the candidates alone: said now, before an IBL bake's
    // seconds (the first frame's), not after the frames.
    checkDisabledPasses(graph, settings.disabledPasses);
    gl::requireRenderSizeFits(settings.width, settings.height, graph.liveTransientBytes(), limits);
    // One texture can be over a driver's own limit while the total fits (llvmpipe refuses one 4 GiB texture).
    for (const fg::ResourceReport& r : graph.resources()) {
        if (r.imported || !r.live || r.desc.cube) continue;
        if (gl::canAllocateTexture(r.desc.format, r.desc.width, r.desc.height)) continue;
        char gib[32];
        std::snprintf(gib, sizeof gib, "%.2f GiB", double(r.desc.bytes()) / (1024.0 * 1024.0 * 1024.0));
        throw Error("--size " + std::to_string(settings.width) + "x" + std::to_string(settings.height) + ": its " +
                    std::to_string(r.desc.width) + "x" + std::to_string(r.desc.height) + " " + gl::formatName(r.desc.format) +
                    " render target '" + r.name + "' (" + gib + ") is more than this GPU allocates for one texture");
    }
}

}  // namespace lp::app
