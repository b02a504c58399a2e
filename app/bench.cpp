#include "app/bench.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/core/progress.hpp"
#include "app/frame_cost.hpp"
#include "app/render_checks.hpp"
#include "engine/gl/context.hpp"
#include "engine/io/image_io.hpp"
#include "engine/render/floors.hpp"
#include "frame/renderer.hpp"
#include "engine/scene/scene_loader.hpp"

namespace lp::app {
namespace {

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    std::string cur;
    std::istringstream in(s);
    while (std::getline(in, cur, sep)) out.push_back(cur);
    return out;
}

std::vector<std::string> words(const std::string& s) {
    std::vector<std::string> out;
    std::istringstream in(s);
    for (std::string w; in >> w;) out.push_back(w);
    return out;
}

std::string join(const std::vector<std::string>& v) {
    std::string s;
    for (const auto& w : v) s += (s.empty() ? "" : " ") + w;
    return s;
}

// The bench's own flags are removed from the flags every variant shares.
std::vector<std::string> commonFlags(const std::vector<std::string>& args) {
    std::vector<std::string> out;
    for (size_t i = 1; i < args.size(); ++i) {  // args[0] is "bench"
        if (args[i] == "--vary" || args[i] == "--max-seconds" || args[i] == "--min-frames" || args[i] == "--timings-json") {
            ++i;
            continue;
        }
        out.push_back(args[i]);
    }
    return out;
}

}  // namespace

std::vector<std::vector<std::string>> parseVaryAxis(const std::string& spec) {
    std::vector<std::vector<std::string>> axis;
    // An empty or blank axis would multiply the variants by zero: a bench of nothing that "succeeds".
    if (words(spec).empty()) throw Error("--vary " + quoteUserText(spec) + ": empty (expected 'FLAG V1,V2,...' or 'FLAGS|FLAGS')");
    auto alternatives = split(spec, '|');
    if (alternatives.size() == 1) {
        // "--flag v1,v2,v3": one alternative per value.
        auto w = words(spec);
        if (w.size() == 2 && w[1].find(',') != std::string::npos) {
            for (const auto& v : split(w[1], ',')) axis.push_back({w[0], v});
            return axis;
        }
    }
    for (const auto& alt : alternatives) {
        auto w = words(alt);
        if (w.empty()) throw Error("--vary " + quoteUserText(spec) + ": empty alternative");
        if (w[0].rfind("--", 0) != 0) throw Error("--vary " + quoteUserText(spec) + ": " + quoteUserText(w[0]) + " is not a flag");
        axis.push_back(w);
    }
    return axis;
}

std::vector<std::vector<std::string>> expandVariants(const std::vector<std::string>& specs) {
    std::vector<std::vector<std::string>> variants{{}};
    for (const auto& spec : specs) {
        std::vector<std::vector<std::string>> next;
        for (const auto& v : variants)
            for (const auto& alt : parseVaryAxis(spec)) {
                auto combined = v;
                combined.insert(combined.end(), alt.begin(), alt.end());
                next.push_back(combined);
            }
        variants = std::move(next);
    }
    return variants;
}

int runBench(const Options& o, const std::vector<std::string>& args) {
    if (o.varies.empty()) throw Error("bench: --vary 'FLAG V1,V2,...' is required (see --help)");
    const auto common = commonFlags(args);
    const auto variants = expandVariants(o.varies);
    // Validate every variant's flags before any GPU work, so a typo fails at once.
    std::vector<RenderSettings> settings;
    for (const auto& v : variants) {
        std::vector<std::string> a{"graph"};
        a.insert(a.end(), common.begin(), common.end());
        a.insert(a.end(), v.begin(), v.end());
        Options vo = parseArgs(a);
        settings.push_back(renderSettings(vo));
    }

    if (variants.empty()) throw Error("bench: --vary gives no variants");
    const std::string out = o.timingsJson.empty() ? "bench.json" : o.timingsJson;
    requireWritableOutput(out);

    Scene scene = sceneFromOptions(o);
    auto ctx = gl::createHeadlessContext();
    logInfo("bench on " + ctx->info().renderer + (ctx->isSoftware() ? " (software rasteriser: times are not meaningful)" : ""));
    for (const auto& s : settings) requireFrameFitsGpu(*ctx, scene, s);
    Renderer renderer(scene);
    nlohmann::json j;
    j["device"] = ctx->info().renderer;
    j["scene"] = o.model.empty() ? o.scene : o.model;
    j["common_flags"] = join(common);
    FloorBandwidths bandwidths;
    if (o.floors) {
        bandwidths = measureFloorBandwidths(gl::ShaderLibrary());
        j["bandwidth"] = {{"compute_GBps", bandwidths.compute.bytesPerSecond * 1e-9},
                          {"fragment_GBps", bandwidths.fragment.bytesPerSecond * 1e-9}};
    }
    ProgressStyle progressStyle = stderrProgressStyle();
    progressStyle.plainLinePerStep = true;  // each variant's frame time, in a log too
    ProgressReporter progress("bench", variants.size(), std::cerr, progressStyle, steadySeconds);
    for (size_t vi = 0; vi < variants.size(); ++vi) {
        const RenderSettings& s = settings[vi];
        renderer.timers().clear();
        // Slow variants (e.g. 4096 full-screen light passes at 4K) get fewer frames: about
        // --max-seconds per variant (a quarter of it for warm-up), never fewer than --min-frames.
        int frames = o.frames, warmup = o.warmup;
        if (o.maxSeconds > 0) {
            renderer.render(s, float(warmupTime(o)), false);  // first frame of a setting compiles programs, fills caches
            glFinish();
            auto t0 = std::chrono::steady_clock::now();
            renderer.render(s, float(warmupTime(o)), false);
            glFinish();
            const double secs = std::max(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 1e-6);
            frames = std::min(o.frames, std::max(o.minFrames, int(o.maxSeconds / secs)));
            warmup = std::min(o.warmup, std::max(1, int(0.25 * o.maxSeconds / secs)));
        }
        // --time / --fps as render takes them (a camera path then moves between timed frames).
        renderer.cutMotion();  // a new variant: no motion from the last one's frames
        for (int i = 0; i < warmupFrames(o, warmup); ++i) renderer.render(s, float(warmupTime(o)), false);
        renderer.resetShadowCacheStats();  // the timed frames' cascade tiles only
        renderer.clearCpuTimes();
        glFinish();  // the wall clock starts with the GPU idle
        const auto start = std::chrono::steady_clock::now();
        for (int i = 0; i < frames; ++i) renderer.render(s, float(frameTime(o, i)), true);
        glFinish();
        const double wallMsPerFrame =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / frames;
        renderer.timers().flush();
        nlohmann::json run;
        run["flags"] = join(variants[vi]);
        run["width"] = s.width;
        run["height"] = s.height;
        run["render_scale"] = s.renderScale;
        run["frames"] = frames;
        run["transient_texture_bytes"] = renderer.pool().totalBytes();
        const ShadowCacheStats& cache = renderer.shadowCacheStats();
        if (cache.drawn + cache.kept + cache.scrolled + cache.completed > 0)
            run["shadow_cache"] = {{"tiles_drawn", cache.drawn}, {"tiles_kept", cache.kept}, {"tiles_scrolled", cache.scrolled},
                                   {"hit_rate", double(cache.kept) / double(cache.kept + cache.drawn + cache.scrolled + cache.completed)},
                                   {"kept_per_cascade", std::vector<uint64_t>(std::begin(cache.keptPerCascade), std::end(cache.keptPerCascade))},
                                   {"drawn_per_cascade", std::vector<uint64_t>(std::begin(cache.drawnPerCascade), std::end(cache.drawnPerCascade))},
                                   {"scrolled_per_cascade", std::vector<uint64_t>(std::begin(cache.scrolledPerCascade), std::end(cache.scrolledPerCascade))},
                                   {"completed_per_cascade", std::vector<uint64_t>(std::begin(cache.completedPerCascade), std::end(cache.completedPerCascade))},
                                   {"lagging_per_cascade", std::vector<uint64_t>(std::begin(cache.laggingPerCascade), std::end(cache.laggingPerCascade))},
                                   {"tiles_lagging", cache.lagging}, {"tiles_completed", cache.completed},
                                   {"quarters_drawn", cache.quarters}, {"most_budget_units_in_a_frame", cache.mostBudgetUnitsInAFrame}};
        const PointShadowStats& cubes = renderer.pointShadowStats();
        if (cubes.drawn + cubes.kept > 0) run["point_shadow_cache"] = {{"cubes_drawn", cubes.drawn}, {"cubes_kept", cubes.kept}};
        const LocalLightStats& lights = renderer.localLightStats();
        if (lights.froxelKernelMs >= 0.0)  // --clustered-kernel auto raced its two kernels: what it found
            run["clustered_kernel"] = {{"shading", lights.slicesShaded ? "froxels" : "tiles"},
                                       {"froxels_ms", lights.froxelKernelMs}, {"tiles_ms", lights.tileKernelMs}};
        const auto& timers = renderer.timers();
        const FrameCost cost = frameCost(renderer.cpuTimes().submitMs, renderer.cpuTimes().waitMs, wallMsPerFrame,
                                         timers.median("frame"));
        run["cpu"] = frameCostJson(cost);
        char result[64];
        std::snprintf(result, sizeof result, ": frame %.4f ms (%d frames)", timers.median("frame"), frames);
        progress.step(join(variants[vi]) + result);
        logInfo(join(variants[vi]) + ": " + frameCostLine(cost));
        for (const auto& name : timers.passOrder()) {
            if (timers.samples(name).empty()) continue;
            run["passes"][name]["median_ms"] = timers.median(name);
            // Mean and max too: a cached pass (--shadow-cache) is cheap most frames and costly on a few.
            const auto& samples = timers.samples(name);
            double sum = 0.0, most = 0.0;
            for (double ms : samples) sum += ms, most = std::max(most, ms);
            run["passes"][name]["mean_ms"] = sum / double(samples.size());
            run["passes"][name]["max_ms"] = most;
            // Per frame, in frame order (every pass of these frames is timed every frame): what
            // percentiles of a sum of passes (e.g. the suns' shadow maps) need.
            std::vector<double> sorted = samples;
            std::sort(sorted.begin(), sorted.end());
            run["passes"][name]["p99_ms"] = sorted[std::min(sorted.size() - 1, size_t(std::ceil(0.99 * double(sorted.size()))) - 1)];
            run["passes"][name]["samples_ms"] = samples;
            if (const std::optional<PassFloor> floor = o.floors ? passFloor(renderer.graph(), name, bandwidths) : std::nullopt) {
                run["passes"][name]["bytes"] = floor->bytes;
                run["passes"][name]["floor_ms"] = floor->ms;
                run["passes"][name]["floor_basis"] = floor->basis;
            }
        }
        j["runs"].push_back(run);
    }
    progress.finish();
    OutputFiles outputs;
    outputs.add(out, j.dump(1) + "\n");
    outputs.commit();
    std::printf("wrote %s (%zu variants)\n", out.c_str(), variants.size());
    return 0;
}

}  // namespace lp::app
