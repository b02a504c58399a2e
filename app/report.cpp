#include "app/report.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "app/render_checks.hpp"
#include "app/report_html.hpp"
#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/gl/context.hpp"
#include "engine/gl/handles.hpp"
#include "engine/io/image_io.hpp"
#include "engine/render/floors.hpp"
#include "engine/scene/placements.hpp"
#include "frame/renderer.hpp"

namespace lp::app {
namespace fs = std::filesystem;

namespace {
constexpr int kThumbnailWidth = 320;

// The output folder, made if missing, and checked writable before any work.
fs::path prepareOutputFolder(const std::string& out) {
    const fs::path dir(out);
    std::error_code ec;
    if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) throw Error(out + ": not a folder (report --out names a folder)");
    fs::create_directories(dir, ec);
    if (ec) throw Error(out + ": cannot create the output folder: " + ec.message());
    requireWritableOutput(dir / "index.html");
    return dir / "index.html";
}

std::string readFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path.string() + ": cannot read");
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

int runSweepReport(const Options& o, const std::vector<std::string>& args) {
    const fs::path folder(o.sweepDir);
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) throw Error("--sweep " + o.sweepDir + ": no such folder");
    const fs::path csv = folder / "sweep.csv";
    if (!fs::is_regular_file(csv, ec)) throw Error(csv.string() + ": missing (not a lightpass sweep folder)");
    SweepReport report;
    report.folder = o.sweepDir;
    report.commandLine = commandLine(args);
    report.rows = parseSweepCsv(readFile(csv), csv.string());
    for (const SweepRow& row : report.rows) {
        const fs::path image = folder / row.image;
        if (!fs::is_regular_file(image, ec)) throw Error(image.string() + ": missing (sweep.csv names it)");
        SweepImage img;
        img.png = readFile(image);
        const Image8 decoded = decodeImage8(img.png, image);  // throws naming the file when it is no image
        img.width = decoded.width;
        img.height = decoded.height;
        report.images.push_back(std::move(img));
    }
    const fs::path page = prepareOutputFolder(o.out);
    OutputFiles outputs;
    outputs.add(page, sweepReportHtml(report));
    outputs.commit();
    if (!o.quiet) std::printf("wrote %s (%zu values)\n", page.c_str(), report.rows.size());
    return 0;
}

int runBenchReport(const Options& o, const std::vector<std::string>& args) {
    const fs::path file(o.benchJson);
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) throw Error("--bench " + o.benchJson + ": file not found");
    BenchReport report = parseBenchJson(readFile(file), o.benchJson);
    report.commandLine = commandLine(args);
    const fs::path page = prepareOutputFolder(o.out);
    OutputFiles outputs;
    outputs.add(page, benchReportHtml(report));
    outputs.commit();
    if (!o.quiet) std::printf("wrote %s (%zu variants)\n", page.c_str(), report.runs.size());
    return 0;
}

int runFrameReport(const Options& o, const std::vector<std::string>& args) {
    Scene scene = sceneFromOptions(o);  // a bad scene fails before any folder is made
    const RenderSettings settings = renderSettings(o);
    const fs::path page = prepareOutputFolder(o.out);
    auto ctx = openHeadlessFor("report", scene, settings);
    Renderer renderer(scene);
    for (int i = 0; i < warmupFrames(o, o.warmup); ++i) renderer.render(settings, float(warmupTime(o)), false);
    for (int i = 0; i < o.frames; ++i) renderer.render(settings, float(frameTime(o, i)), true);
    checkDisabledPasses(renderer.graph(), settings.disabledPasses);
    glFinish();
    renderer.timers().flush();

    FrameReport report;
    report.source = o.model.empty() ? o.scene : o.model;
    report.sceneCounts = sceneCountsText(sceneCounts(scene));
    report.commandLine = commandLine(args);
    report.device = ctx->info().renderer;
    report.softwareRaster = ctx->isSoftware();
    report.size = sizeLabel(settings);
    report.view = viewName(settings.view);
    report.frames = o.frames;
    report.warmup = warmupFrames(o, o.warmup);

    // The graph as the timed frames ran it (read before the views below rebuild it).
    const fg::FrameGraph& graph = renderer.graph();
    std::vector<ReportPass> candidates;
    for (const fg::PassDecision& d : graph.explain()) {
        ReportPass p;
        p.name = d.name;
        p.runs = d.runs;
        p.reason = d.reason;
        candidates.push_back(p);
    }
    for (const fg::PassReport& pr : graph.report())
        for (ReportPass& p : candidates)
            if (p.name == pr.name) {
                p.kind = fg::passKindName(pr.kind);
                p.reads = pr.reads;
                p.writes = pr.writes;
            }
    report.passes = passesInDrawingOrder(candidates, graph.executionOrder());
    for (ReportPass& p : report.passes)  // passes that run but are no candidate (none today) get their kind too
        if (p.runs && p.kind.empty()) p.kind = fg::passKindName(graph.passKind(p.name));
    for (const fg::ResourceReport& res : graph.resources())
        if (res.live && !res.imported && !res.buffer)
            report.transients.push_back({res.name, gl::formatName(res.desc.format), res.desc.width, res.desc.height, res.desc.bytes()});
    report.poolBytes = renderer.pool().totalBytes();
    report.persistentBytes = renderer.persistentTextureBytes();
    report.graphTransientBytes = graph.liveTransientBytes();

    // Floors: this GPU's bandwidth as `render --floors` measures it. A software rasteriser's times mean
    // nothing, so there a smaller copy, measured fewer times, keeps the report quick.
    gl::ShaderLibrary shaders;
    const int bw = ctx->isSoftware() ? 960 : 3840, bh = ctx->isSoftware() ? 540 : 2160, repeats = ctx->isSoftware() ? 5 : 30;
    const FloorBandwidths bandwidths = measureFloorBandwidths(shaders, bw, bh, repeats);
    report.bandwidth = "compute copy bandwidth (" + std::to_string(int(bandwidths.compute.bytesPerSecond * 1e-9 + 0.5)) +
                       " GB/s) or fragment fill rate (" + std::to_string(int(bandwidths.fragment.bytesPerSecond * 1e-9 + 0.5)) +
                       " GB/s), RGBA32F " + std::to_string(bw) + "x" + std::to_string(bh) + ", median of " +
                       std::to_string(repeats);
    const auto& timers = renderer.timers();
    for (const auto& name : timers.passOrder()) {
        if (name == "frame") {
            report.frameMs = timers.median(name);
            continue;
        }
        PassTiming t;
        t.name = name;
        t.medianMs = timers.median(name);
        if (const std::optional<PassFloor> floor = passFloor(graph, name, bandwidths)) {
            t.floorMs = floor->ms;
            t.floorBasis = floor->basis;
        } else {
            t.noFloorReason = "moves no texture bytes";
        }
        report.timings.push_back(t);
    }

    // Each view the frame has, rendered with the same flags (the graph's live passes decide which).
    std::set<std::string> live;
    for (const auto& name : graph.executionOrder()) live.insert(name);
    for (const ReportViewRule& rule :
         reportViews(settings.shadows.debugLight, [&](const std::string& pass) { return live.count(pass) > 0; })) {
        RenderSettings s = settings;
        s.view = rule.view;
        s.keepHdr = false;
        renderer.render(s, float(frameTime(o, o.frames - 1)), false);
        report.views.push_back({viewName(rule.view), rule.shows, shrinkToWidth(renderer.readDisplay(), kThumbnailWidth)});
    }

    OutputFiles outputs;
    outputs.add(page, frameReportHtml(report));
    outputs.commit();
    if (!o.quiet)
        std::printf("wrote %s (%zu passes, %zu views, %.3f GPU ms per frame on %s)\n", page.c_str(), report.passes.size(),
                    report.views.size(), report.frameMs, report.device.c_str());
    return 0;
}
}  // namespace

int runReport(const Options& o, const std::vector<std::string>& args) {
    if (!o.sweepDir.empty()) return runSweepReport(o, args);
    if (!o.benchJson.empty()) return runBenchReport(o, args);
    return runFrameReport(o, args);
}

}  // namespace lp::app
