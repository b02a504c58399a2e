#pragma once
// `lightpass report`: one self-contained HTML page (inline SVG, images as data: URIs, no network)
// for a frame (its graph, each view, per-pass GPU ms against floors, memory) or for a sweep folder
// (error against GPU ms per knob, with each value's image). Everything here is pure: the GL side
// (app/report.cpp) fills the structs, these functions lay them out and write the page.
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "engine/io/image_io.hpp"
#include "engine/render/settings.hpp"

namespace lp::app {

// Every user text put on a page (scene names, paths, reasons, the command line) goes through this:
// & < > " ' become entities, so no text can open a tag or end an attribute.
std::string htmlEscape(const std::string& text);
std::string base64(const std::string& bytes);
// "data:image/png;base64,..." of encoded PNG bytes.
std::string pngDataUri(const std::string& pngBytes);
// An argument as a POSIX shell would need it to read back the same word ('it'\''s' for it's).
std::string shellQuote(const std::string& argument);
// "lightpass render --scene 'my scene.json'": the program name and every argument, quoted.
std::string commandLine(const std::vector<std::string>& args);

// Area-averaged down to at most maxWidth texels wide (aspect kept, at least 1 texel tall);
// unchanged when it already fits. For the page's thumbnails.
Image8 shrinkToWidth(const Image8& image, int maxWidth);

// One candidate pass of the frame, as `graph --explain` decides it.
struct ReportPass {
    std::string name;
    std::string kind;  // "raster", "compute", "cuda" for a pass that runs
    bool runs = false;
    std::string reason;  // why not, as --explain gives it
    std::vector<std::string> reads, writes;  // versioned names ("hdr@1"), as `graph` prints them
};

// The passes in the order the page draws them: those that run in execution order (`order`), each
// one that does not right after the candidate before it in `candidates` (the --explain order).
std::vector<ReportPass> passesInDrawingOrder(const std::vector<ReportPass>& candidates,
                                             const std::vector<std::string>& order);

// The frame graph drawing: one box per pass, top to bottom; an edge (an arc left of the boxes) from a
// pass to each later pass that reads what it wrote, labelled with those resources.
struct GraphBox {
    double x = 0, y = 0, width = 0, height = 0;
};
struct GraphEdge {
    size_t from = 0, to = 0;  // indices into the passes, from < to
    std::vector<std::string> resources;
    double reach = 0;  // how far left of the boxes the arc goes: longer spans go further out
};
struct GraphLayout {
    std::vector<GraphBox> boxes;  // one per pass, same order
    std::vector<GraphEdge> edges;
    double width = 0, height = 0;
};
GraphLayout layoutFrameGraph(const std::vector<ReportPass>& passes);
std::string frameGraphSvg(const std::vector<ReportPass>& passes);

// One pass's measured GPU time and its floor (none where the pass moves no texture bytes).
struct PassTiming {
    std::string name;
    double medianMs = 0;
    std::optional<double> floorMs;
    std::string floorBasis;  // "compute copy", "fragment fill"
    std::string noFloorReason;  // shown where floorMs is empty ("moves no texture bytes"); may be empty
};
// Bars on one scale: the largest time or floor spans `width` pixels.
struct TimingBar {
    double timeWidth = 0;
    std::optional<double> floorWidth;
};
// scaleMs > 0: that many ms span `width` instead (several charts on one scale).
std::vector<TimingBar> layoutTimingBars(const std::vector<PassTiming>& timings, double width, double scaleMs = 0);
// Each bar is marked data-check="bar:<checkPrefix><name>" (and "floor:..." for its floor).
std::string timingBarsSvg(const std::vector<PassTiming>& timings, double scaleMs = 0, const std::string& checkPrefix = "");

// The views a report shows: one row per view --view accepts, what it shows and the pass that must
// run in the report's frame for it to be there ("" : every frame has it). shadowmap's pass is the
// light --shadow-light picks (shadow_map_<N>).
struct ReportViewRule {
    DebugView view;
    std::string shows;  // "gbuffer", "ao_denoise", ...
    std::string needs;  // a pass that must run; empty: always
};
std::vector<ReportViewRule> reportViewRules(int shadowLight);
// The rules whose pass runs (`runs` asked of the frame's graph), in --view's order.
std::vector<ReportViewRule> reportViews(int shadowLight, const std::function<bool(const std::string&)>& runs);

struct ReportView {
    std::string name;   // the --view name
    std::string shows;  // the pass whose output it is
    Image8 image;       // already a thumbnail
};

struct ReportResource {
    std::string name, format;
    int width = 0, height = 0;
    size_t bytes = 0;
};

struct FrameReport {
    std::string source;  // the scene or model file
    std::string sceneCounts;  // sceneCountsText: models, instances, stored and drawn geometry
    std::string commandLine;
    std::string device;  // GL_RENDERER
    bool softwareRaster = false;
    std::string size;  // sizeLabel()
    std::string view;  // the frame's --view
    int frames = 0, warmup = 0;
    std::vector<ReportPass> passes;  // drawing order
    std::vector<PassTiming> timings;  // execution order, without the whole frame
    double frameMs = 0;
    std::string bandwidth;  // how the floors were measured
    std::vector<ReportView> views;
    std::vector<ReportResource> transients;
    size_t poolBytes = 0, persistentBytes = 0, graphTransientBytes = 0;
};
std::string frameReportHtml(const FrameReport& report);

// A `lightpass sweep` folder's sweep.csv, one row per knob value.
struct SweepRow {
    std::string knob, value, image;  // image: relative to the folder ("shadow-size/0.png")
    bool reference = false;
    double frameMs = 0, iblBakeMs = 0, rmse = 0, psnrDb = 0;
    // What the error is against (sweep --reference): "best" (the knob's last value) or "pathtraced"
    // with the path tracer's samples a pixel and RMS noise; "best" for a CSV without the columns.
    std::string referenceSource = "best";
    int referenceSpp = 0;
    double referenceNoiseRmse = 0;
    // Relative luminance error over the pixels that see a surface, of the frame and of the knob's light
    // term alone ("suns", "environment", "local-lights"; "frame": the frame's); empty term: a CSV
    // without the columns.
    std::string term;
    double surfaceRelativeError = 0, termRelativeError = 0;
};
// Throws lp::Error "<label>: line N: ..." for a missing column or a value that is not a number.
std::vector<SweepRow> parseSweepCsv(const std::string& text, const std::string& label);
// Indices of points not dominated in (ms, error): no other point is both no slower and no worse, and
// better in one (bench/sweep_report.py's rule).
std::vector<size_t> paretoFront(const std::vector<std::pair<double, double>>& points);
// The time a knob's values differ in: the frame's GPU ms, or where that is flat (within 3%) and every
// value baked its IBL, the bake's (bench/sweep_report.py's rule). True: the bake's.
bool sweepUsesBakeTime(const std::vector<SweepRow>& knobRows);

// The Pareto plot of one knob: x GPU ms (linear), y RMSE (log, floored at 1e-7), in pixels.
struct PlotPoint {
    double x = 0, y = 0;
    bool front = false;
};
std::vector<PlotPoint> layoutSweepPlot(const std::vector<SweepRow>& knobRows, double width, double height);

struct SweepImage {
    std::string png;  // the file's bytes
    int width = 0, height = 0;
};
struct SweepReport {
    std::string folder;
    std::string commandLine;
    std::vector<SweepRow> rows;
    std::vector<SweepImage> images;  // one per row
};
std::string sweepReportHtml(const SweepReport& report);

// A `lightpass bench` JSON (--timings-json): one run per variant.
struct BenchRun {
    std::string flags;
    int width = 0, height = 0, frames = 0;
    size_t transientBytes = 0;
    double frameMs = 0;
    std::vector<PassTiming> passes;  // most GPU time first (the JSON keeps no execution order)
};
struct BenchReport {
    std::string file, commandLine, device, scene, commonFlags, bandwidth;
    std::vector<BenchRun> runs;
};
// Throws lp::Error "<label>: ..." for text that is not JSON or not a bench's (no runs, a run without
// a frame time).
BenchReport parseBenchJson(const std::string& text, const std::string& label);
std::string benchReportHtml(const BenchReport& report);

}  // namespace lp::app
