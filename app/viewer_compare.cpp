#include "app/viewer_compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/gl/state.hpp"
#include "engine/render/image_metrics.hpp"

namespace lp::app {

namespace {
// Relative error at full colour in the heat map, and the luminance below which a pixel counts as dark
// (its error is taken against this, so noise in black corners does not fill the map).
constexpr float kFullScale = 0.5f;
constexpr float kDarkLuminance = 1e-3f;

double luminance(const float* c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }
}  // namespace

std::string truthComparisonUnavailable(const RenderSettings& settings) {
    if (settings.renderPath == RenderPath::PathTraced) return "the frame is the path tracer's already (render path)";
    if (settings.view != DebugView::Final) return "only in the final view (0), which the path tracer renders too";
    return "";
}

std::string truthComparisonLegend(const TruthComparisonStats& stats) {
    char text[512];
    std::snprintf(text, sizeof text,
                  "top left: raster   top right: path tracer\n"
                  "both shown at %+.1f EV (the path tracer's mean on grey)\n"
                  "bottom left: raster luminance against the tracer's,\n"
                  "  red brighter, blue darker, full at +-%.0f%%\n\n"
                  "path tracer: %d samples a pixel, noise %.1f%%\n"
                  "mean |relative error| %.1f%%   RMSE %.4g\n"
                  "(c leaves; a moved view traces again)",
                  stats.exposureEv, 100.0 * kFullScale, stats.samples, 100.0 * stats.truthNoise,
                  100.0 * stats.meanRelativeError, stats.rmse);
    return text;
}

ViewerViewport comparisonTile(const ViewerViewport& viewport) {
    ViewerViewport tile = viewport;
    tile.width = std::max(1, viewport.width / 2);
    tile.height = std::max(1, viewport.height / 2);
    return tile;
}

TruthComparisonStats compareWithTruth(const ImageF& raster, const ImageF& truth, float floor) {
    TruthComparisonStats s;
    const ImageError error = compareHdr(raster, truth);  // throws when the sizes differ
    s.rmse = error.rmse;
    double sum = 0.0, logSum = 0.0;
    size_t lit = 0, pixels = size_t(truth.width) * size_t(truth.height);
    for (size_t i = 0; i < pixels; ++i) {
        const double lt = luminance(&truth.rgba[4 * i]), lr = luminance(&raster.rgba[4 * i]);
        if (!std::isfinite(lt) || !std::isfinite(lr)) continue;
        logSum += std::log(std::max(lt, 1e-6));
        if (lt <= floor) continue;
        sum += std::fabs(lr - lt) / lt;
        ++lit;
    }
    s.meanRelativeError = lit ? sum / double(lit) : 0.0;
    // One exposure for both images: the truth's mean log luminance brought to middle grey (0.18).
    s.exposureEv = pixels ? std::log2(0.18) - logSum / double(pixels) / std::log(2.0) : 0.0;
    s.exposureEv = std::clamp(s.exposureEv, -16.0, 16.0);
    return s;
}

std::string drawTruthComparison(TruthComparison& state, Renderer& raster, const Scene& scene, const RenderSettings& settings,
                                float time, double wallSeconds, const ViewerViewport& viewport, GLuint readFramebuffer) {
    if (state.scene != &scene || !state.tracer) {
        state.tracer = std::make_unique<Renderer>(scene, raster.shaders());
        state.scene = &scene;
    }
    RenderSettings traced = settings;
    traced.renderPath = RenderPath::PathTraced;
    traced.keepHdr = true;
    state.tracer->render(traced, time, false);
    if (!state.program) state.program = raster.shaders().compute("truth_compare.comp");
    const int w = settings.width, h = settings.height;
    if (!state.grid || state.grid.width != 2 * w || state.grid.height != 2 * h)
        state.grid = gl::makeTexture2D(GL_RGBA8, 2 * w, 2 * h, 1, "viewer.truth_compare");

    const ImageF rasterHdr = raster.readHdr(), truthHdr = state.tracer->readHdr();
    TruthComparisonStats stats = compareWithTruth(rasterHdr, truthHdr, kDarkLuminance);
    stats.samples = state.tracer->pathTraceNoise().samples;
    stats.truthNoise = state.tracer->pathTraceNoise().meanRelativeStandardError;
    state.stats = stats;

    const GLuint prog = state.program.id();
    glProgramUniform1f(prog, glGetUniformLocation(prog, "uExposureEv"), float(stats.exposureEv));
    glProgramUniform1i(prog, glGetUniformLocation(prog, "uOperator"), int(settings.environment.toneMap));
    glProgramUniform1f(prog, glGetUniformLocation(prog, "uFullScale"), kFullScale);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "uFloor"), kDarkLuminance);
    glBindTextureUnit(0, raster.hdrTexture());
    glBindTextureUnit(1, state.tracer->hdrTexture());
    glBindImageTexture(0, state.grid.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
    glUseProgram(prog);
    gl::dispatch2D(2 * w, 2 * h);
    glUseProgram(0);
    glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
    glBindTextureUnit(0, 0);
    glBindTextureUnit(1, 0);
    glNamedFramebufferTexture(readFramebuffer, GL_COLOR_ATTACHMENT0, state.grid.id(), 0);
    glBlitNamedFramebuffer(readFramebuffer, 0, 0, 0, 2 * w, 2 * h, viewport.x, viewport.y, viewport.x + 2 * w,
                           viewport.y + 2 * h, GL_COLOR_BUFFER_BIT, GL_NEAREST);

    char line[256];
    std::snprintf(line, sizeof line,
                  "compare: path tracer %d samples a pixel (noise %.1f%%); raster against it: mean |relative error| "
                  "%.1f%%, RMSE %.4g",
                  stats.samples, 100.0 * stats.truthNoise, 100.0 * stats.meanRelativeError, stats.rmse);
    if (line == state.describedStats || (!state.describedStats.empty() && wallSeconds - state.describedAt < 2.0)) return "";
    state.describedStats = line;
    state.describedAt = wallSeconds;
    return line;
}

}  // namespace lp::app
