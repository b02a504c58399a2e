#pragma once
// The viewer's comparison with physical truth ('c' or the panel's "compare with the path tracer"):
// the raster frame, the path tracer's image of the same view (docs/path-tracer.md) and a heat map of
// the raster's error against it, in a 2 x 2 grid over the viewport. The tracer is a second renderer
// with its own accumulation: a still view keeps its samples, a moved one traces them again.
#include <memory>
#include <string>

#include "app/viewer_layout.hpp"
#include "engine/gl/handles.hpp"
#include "frame/renderer.hpp"

namespace lp::app {

// What the comparison measured on its last frame (the tiles' HDR buffers, read back).
struct TruthComparisonStats {
    int samples = 0;                  // the tracer's samples a pixel
    double truthNoise = 0.0;          // its mean relative standard error
    double meanRelativeError = 0.0;   // mean |raster - truth| / truth luminance over lit pixels
    double rmse = 0.0;                // over the RGB channels of every pixel
    double exposureEv = 0.0;          // the one exposure both images are shown with
};

struct TruthComparison {
    const Scene* scene = nullptr;       // what `tracer` was made for
    std::unique_ptr<Renderer> tracer;   // renders the same settings with --render-path pathtraced
    gl::Program program;                // shaders/truth_compare.comp
    gl::Texture grid;                   // the 2 x 2 tiles, RGBA8
    TruthComparisonStats stats;
    std::string describedStats;         // the last "compare: ..." line printed (empty: print the next)
    double describedAt = 0.0;           // and when (wall seconds): a line at most every 2 s
};

// Why the frame's settings cannot be compared with the path tracer (empty when they can): it is the
// path tracer already, or a view that is not the lit frame.
std::string truthComparisonUnavailable(const RenderSettings& settings);

// The text beside the grid: what each tile is, the heat map's scale and the last numbers.
std::string truthComparisonLegend(const TruthComparisonStats& stats);

// The size each tile (and both renders) has in a viewport: half of it, at least one pixel.
ViewerViewport comparisonTile(const ViewerViewport& viewport);

// Renders the path tracer with `settings` (the raster frame's, just rendered by `raster` with
// keepHdr at comparisonTile's size) at `time`, fills the grid and blits it into `viewport` through
// `readFramebuffer`. Returns the stats line when they changed, at most every 2 s of `wallSeconds`
// (lights that move with the clock trace again every frame), else empty.
std::string drawTruthComparison(TruthComparison& state, Renderer& raster, const Scene& scene, const RenderSettings& settings,
                                float time, double wallSeconds, const ViewerViewport& viewport, GLuint readFramebuffer);

// Mean |a - b| / max(lum(b), floor) over the pixels where b's luminance is above `floor`, and the RMSE
// over every pixel's RGB, of two HDR images of one size (a: the raster frame, b: the truth).
TruthComparisonStats compareWithTruth(const ImageF& raster, const ImageF& truth, float floor);

}  // namespace lp::app
