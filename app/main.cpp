// lightpass: viewer and headless sub-commands. Every failure ends with one line on stderr and a
// non-zero exit code.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/bench.hpp"
#include "app/cli.hpp"
#include "app/frame_cost.hpp"
#include "app/render_checks.hpp"
#include "app/report.hpp"
#include "app/sweep.hpp"
#include "app/viewer.hpp"
#include "engine/core/error.hpp"
#include "engine/core/measured_cache.hpp"
#include "engine/core/paths.hpp"
#include "engine/core/progress.hpp"
#include "engine/post/backend_timings.hpp"
#include "engine/post/post_config.hpp"
#include "engine/scene/placements.hpp"
#include "passes/post_backend.hpp"
#include "passes/shadow_map_pass.hpp"
#include "engine/core/log.hpp"
#include "engine/gl/context.hpp"
#include "engine/gl/limits.hpp"
#include "engine/io/image_io.hpp"
#include "engine/render/floors.hpp"
#include "frame/renderer.hpp"
#include "engine/scene/scene_loader.hpp"
#ifdef LIGHTPASS_HAVE_CUDA
#include "cuda/device_info.hpp"
#include "cuda/post_cuda.hpp"
#endif

namespace lp::app {
namespace {

Scene loadFromOptions(const Options& o) { return sceneFromOptions(o); }

// The choices `--post-backend auto` cached (engine/post/backend_timings.hpp) whose key fields
// (gpu, driver, size, kernel, method, interop, effect) pass `keep`.
void printCachedPostChoices(const char* title, bool showGpu,
                            const std::function<bool(const std::vector<std::string>&)>& keep) {
    const std::filesystem::path file = measuredCachePath();
    if (file.empty()) {
        std::printf("%s: no cache folder ($LIGHTPASS_CACHE_DIR, $XDG_CACHE_HOME and $HOME unset)\n", title);
        return;
    }
    const post::CacheRead read = post::readTimingCache(file);
    std::printf("%s (%s):\n", title, file.string().c_str());
    if (!read.warning.empty()) std::printf("  %s\n", read.warning.c_str());
    int shown = 0;
    for (const auto& [text, t] : read.entries) {
        std::vector<std::string> key;
        std::stringstream in(text);
        for (std::string field; std::getline(in, field, '|');) key.push_back(field);
        if (key.size() != 7 || !keep(key)) continue;
        std::printf("  %-9s %s %s %s, %s interop: cuda %.3f ms, glsl %.3f ms -> %s%s\n", key[6].c_str(),
                    key[2].c_str(), key[3].c_str(), key[4].c_str(), key[5].c_str(), t.cudaMs, t.glslMs,
                    post::cudaWins(t) ? "cuda" : "glsl", showGpu ? (" (" + key[0] + ", " + key[1] + ")").c_str() : "");
        ++shown;
    }
    if (!shown) std::printf("  none yet: the first run with --post-backend auto measures (--post-remeasure again)\n");
}

RenderSettings settingsFromOptions(const Options& o) { return renderSettings(o); }

int commandInfo() {
    auto ctx = gl::createHeadlessContext();
    const auto& info = ctx->info();
    std::printf("platform: %s\nvendor:   %s\nrenderer: %s\nversion:  %s\n", info.platform.c_str(), info.vendor.c_str(),
                info.renderer.c_str(), info.version.c_str());
    if (ctx->isSoftware()) std::printf("note:     software rasteriser: GPU timings are not meaningful here\n");
#ifdef LIGHTPASS_HAVE_CUDA
    cuda::DeviceInfo cu = cuda::queryDevice();
    if (cu.available) {
        std::printf("cuda:     %s (compute %d.%d)\n", cu.name.c_str(), cu.computeMajor, cu.computeMinor);
        const std::string problem = PostBackend::cudaProblem();
        cuda::PostInterop interop;
        const std::string shared = problem.empty() ? interop.useSharedTextures() : problem;
        if (shared.empty()) {
            std::printf("interop:  external memory (GL memory objects on CUDA allocations, shared once; no "
                        "per-frame map/unmap; %s)\n", cuda::sharedTexturesLayoutName().c_str());
            if (interop.sharedSync() == cuda::SharedSync::Semaphores)
                std::printf("sync:     %s: GL and CUDA hand the textures over on the GPU, no host wait "
                            "(auto measures this against map/unmap at the frame's size)\n", interop.syncName().c_str());
            else
                std::printf("sync:     %s (Vulkan semaphores unavailable: %s; auto uses map/unmap)\n",
                            interop.syncName().c_str(), interop.semaphoreProblem().c_str());
        } else {
            std::printf("interop:  map/unmap per use (external memory unavailable: %s)\n", shared.c_str());
            std::printf("sync:     map/unmap (the driver orders GL and CUDA)\n");
        }
    } else {
        std::printf("cuda:     unavailable (%s): post effects use GLSL\n", cu.reason.c_str());
    }
#else
    std::printf("cuda:     not built (no CUDA toolkit at build time): post effects use GLSL\n");
#endif
    printCachedPostChoices("post backend auto, cached on this GPU", false, [&](const std::vector<std::string>& key) {
        return key[0] == info.renderer && key[1] == info.version;
    });
    // What the default --gbuffer-mode auto makes here (a scene too large for the visibility buffer's
    // storage blocks falls back to classic: lightpass graph --explain names it per scene).
    const GBufferModeChoice gbuffer = chooseGBufferMode(GBufferMode::Auto, ctx->isSoftware(), "");
    std::printf("G-buffer: %s, by the default %s; the visibility buffer reads a scene's geometry through storage "
                "blocks of up to %.0f MB here (a larger scene's G-buffer is classic)\n",
                gbufferModeName(gbuffer.mode), gbuffer.why.c_str(), double(gl::maxShaderStorageBlockBytes()) / (1024.0 * 1024.0));
    const ConservativeRasterSupport conservative = queryConservativeRasterSupport();
    if (conservative.hardware)
        std::printf("shadow casters: conservative raster in hardware (GL_NV_conservative_raster, "
                    "GL_NV_fragment_shader_barycentric; --shadow-conservative geometry-shader for the other)\n");
    else
        std::printf("shadow casters: conservative raster by geometry shader (%s)\n", conservative.reason.c_str());
    return 0;
}

int commandGraph(const Options& o) {
    if (!o.dot.empty()) requireWritableOutput(o.dot);
    Scene scene = loadFromOptions(o);
    RenderSettings settings = settingsFromOptions(o);
    FrameData frame = makeFrameData(scene, settings, float(o.time));
    if (settings.gbuffer.mode != GBufferMode::Classic) {
        // auto's G-buffer depends on the GPU's rasteriser and on whether the visibility buffer can
        // read the scene's geometry there: asked of a headless context where one can be made, else
        // the classic G-buffer, and the skip reasons say so.
        try {
            auto ctx = gl::createHeadlessContext();
            frame.softwareRaster = ctx->isSoftware();
            frame.maxStorageBlockBytes = gl::maxShaderStorageBlockBytes();
        } catch (const std::exception&) {
        }
    }
    fg::FrameGraph graph;
    PassStates passes;  // never executed: describing a graph needs no GPU
    if (o.explain) {
        // Which conservative raster the shadow passes would use is the GPU's to say: asked of a
        // headless context where one can be made, else the notes say what decides it.
        try {
            auto ctx = gl::createHeadlessContext();
            passes.shadowMaps.conservativeSupport = queryConservativeRasterSupport();
        } catch (const std::exception&) {
        }
    }
    buildFrameGraph(graph, passes, frame);
    graph.compile();
    checkDisabledPasses(graph, settings.disabledPasses);
    if (o.explain) noteEnvironmentLights(graph, scene, settings);
    std::printf("frame graph for %s, view '%s', %s\n", (o.model.empty() ? o.scene : o.model).c_str(),
                viewName(settings.view), sizeLabel(settings).c_str());
    if (o.explain) std::printf("scene: %s\n", sceneCountsText(sceneCounts(scene)).c_str());
    std::fputs((o.explain ? graph.explainText() : graph.describe()).c_str(), stdout);
    if (o.explain) {  // what auto would choose where it measured this size and kernel (any GPU)
        post::PostConfig config = post::resolvePostConfig(scene.effects, settings.post, frame.farPlane);
        const int kernel = post::bloomKernelAtRenderSize(config.bloomParams.kernel, frame.width, frame.outputWidth);
        const std::string size = std::to_string(frame.width) + "x" + std::to_string(frame.height);
        printCachedPostChoices("post backend auto, cached for this size and kernel", true, [&](const std::vector<std::string>& key) {
            return key[2] == size && key[3] == "kernel " + std::to_string(kernel) &&
                   key[4] == post::bloomMethodName(config.bloomParams.method);
        });
    }
    if (!o.dot.empty()) {
        OutputFiles outputs;
        outputs.add(o.dot, graph.toDot());
        outputs.commit();
        std::printf("wrote %s\n", o.dot.c_str());
    }
    return 0;
}

// Every output path checked before any work, and no two the same: a render that cannot save all its
// outputs should fail before it starts, not after writing some of them.
void requireOutputs(const std::vector<std::string>& paths) {
    std::vector<std::filesystem::path> seen;
    for (const auto& p : paths) {
        if (p.empty()) continue;
        requireWritableOutput(p);
        const auto absolute = std::filesystem::absolute(p).lexically_normal();
        if (std::find(seen.begin(), seen.end(), absolute) != seen.end()) throw Error(p + ": named twice as an output");
        seen.push_back(absolute);
    }
}

// lightpass reference: one path-traced frame (--spp samples a pixel), its tone-mapped PNG and HDR EXR.
int commandReference(const Options& o) {
    requireOutputs({o.out, o.exr});
    Scene scene = loadFromOptions(o);
    RenderSettings settings = settingsFromOptions(o);
    auto ctx = openHeadlessFor("tracing", scene, settings);
    Renderer renderer(scene);
    renderer.render(settings, float(o.time), false);
    checkDisabledPasses(renderer.graph(), settings.disabledPasses);
    glFinish();
    if (!o.quiet) std::printf("%s\n", describePathTraceNoise(settings, renderer.pathTraceNoise()).c_str());
    OutputFiles outputs;
    if (!o.out.empty()) outputs.addPng(o.out, renderer.readDisplay());
    if (!o.exr.empty()) outputs.addExr(o.exr, renderer.readHdr());
    outputs.commit();
    if (!o.quiet && !o.out.empty()) std::printf("wrote %s\n", o.out.c_str());
    if (!o.quiet && !o.exr.empty()) std::printf("wrote %s\n", o.exr.c_str());
    return 0;
}

int commandRender(const Options& o) {
    // -q: errors only, so no table either (the JSON still has every number).
    auto say = [&](const char* format, auto... args) {
        if (!o.quiet) std::printf(format, args...);
    };
    requireOutputs({o.out, o.exr, o.timingsJson});
    Scene scene = loadFromOptions(o);
    RenderSettings settings = settingsFromOptions(o);
    auto ctx = openHeadlessFor("rendering", scene, settings);
    Renderer renderer(scene);
    double wallMsPerFrame = 0.0;
    try {
        // With --fps the untimed frames are one frame step before --time: the first timed frame's
        // previous frame (motion vectors, motion blur) is then where the clock puts it.
        const int warmup = warmupFrames(o, o.warmup);
        ProgressReporter progress("render: frames", size_t(warmup + o.frames), std::cerr, stderrProgressStyle(), steadySeconds);
        for (int i = 0; i < warmup; ++i) {
            renderer.render(settings, float(warmupTime(o)), false);
            progress.step("warm-up " + std::to_string(i + 1) + "/" + std::to_string(warmup));
        }
        renderer.resetShadowCacheStats();  // the timed frames' cascade tiles only
        glFinish();  // the wall clock starts with the GPU idle
        const auto start = std::chrono::steady_clock::now();
        for (int i = 0; i < o.frames; ++i) {
            renderer.render(settings, float(frameTime(o, i)), true);
            progress.step("timed " + std::to_string(i + 1) + "/" + std::to_string(o.frames));
        }
        glFinish();  // the last frames' GPU work inside the progress and the wall time
        wallMsPerFrame = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / o.frames;
        progress.finish();
    } catch (const Error& e) {  // what the checks above could not foresee still names the size
        if (std::string(e.what()).rfind("GL out of memory", 0) != 0) throw;
        throw Error("--size " + std::to_string(settings.width) + "x" + std::to_string(settings.height) + ": " + e.what());
    }
    checkDisabledPasses(renderer.graph(), settings.disabledPasses);
    glFinish();
    renderer.timers().flush();

    // Per-pass GPU time table, with floors when asked.
    const auto& timers = renderer.timers();
    FloorBandwidths bandwidths;
    if (o.floors) {
        bandwidths = measureFloorBandwidths(gl::ShaderLibrary());
        say("bandwidth: compute copy %.1f GB/s, fragment fill %.1f GB/s (RGBA32F 3840x2160, median of 30)\n",
            bandwidths.compute.bytesPerSecond * 1e-9, bandwidths.fragment.bytesPerSecond * 1e-9);
    }
    say("%-16s %10s %10s %10s%s  (GPU ms over %d frames, %s%s)\n", "pass", "median", "min", "max",
                o.floors ? "   floor ms  meas/floor" : "", o.frames, sizeLabel(settings).c_str(),
                ctx->isSoftware() ? ", software rasteriser: not meaningful" : "");
    nlohmann::json j;
    if (o.floors) {
        j["bandwidth"] = {{"compute_GBps", bandwidths.compute.bytesPerSecond * 1e-9},
                          {"fragment_GBps", bandwidths.fragment.bytesPerSecond * 1e-9}};
    }
    j["device"] = ctx->info().renderer;
    j["width"] = settings.width;
    j["height"] = settings.height;
    j["render_scale"] = settings.renderScale;
    j["aa"] = antiAliasingName(settings.aa.method);
    if (supersampled(settings)) j["ssaa_scale"] = settings.aa.ssaaScale;
    j["frames"] = o.frames;
    j["view"] = viewName(settings.view);
    j["time_s"] = {{"first", frameTime(o, 0)}, {"last", frameTime(o, o.frames - 1)}, {"fps", o.fps}};
    for (const auto& name : timers.passOrder()) {
        const auto& s = timers.samples(name);
        double lo = *std::min_element(s.begin(), s.end()), hi = *std::max_element(s.begin(), s.end());
        say("%-16s %10.4f %10.4f %10.4f", name.c_str(), timers.median(name), lo, hi);
        j["passes"][name] = {{"median_ms", timers.median(name)}, {"min_ms", lo}, {"max_ms", hi}, {"samples", s.size()}};
        if (const std::optional<PassFloor> floor = o.floors ? passFloor(renderer.graph(), name, bandwidths) : std::nullopt) {
            say(" %11.4f %10.1fx", floor->ms, timers.median(name) / floor->ms);
            j["passes"][name]["bytes"] = floor->bytes;
            j["passes"][name]["floor_ms"] = floor->ms;
            j["passes"][name]["floor_basis"] = floor->basis;
        }
        say("\n");
    }
    const FrameCost cost = frameCost(renderer.cpuTimes().submitMs, renderer.cpuTimes().waitMs, wallMsPerFrame,
                                     timers.median("frame"));
    say("%s\n", frameCostLine(cost).c_str());
    j["cpu"] = frameCostJson(cost);
    for (const auto& r : renderer.graph().report())
        if (r.culled) j["culled"][r.name] = r.reason;
    for (const auto& d : renderer.graph().explain())
        if (!d.runs) j["not_run"][d.name] = d.reason;
    j["all_passes"] = settings.allPasses;
    // GPU memory of textures: the pool (every transient, shadow maps included, after reuse) and
    // what outlives frames outside it (environment cubes, IBL bakes).
    const size_t poolBytes = renderer.pool().totalBytes(), persistentBytes = renderer.persistentTextureBytes();
    say("texture memory: %.2f MiB pooled transients + %.2f MiB persistent (environment, IBL, kept shadow atlases)\n",
                poolBytes / 1048576.0, persistentBytes / 1048576.0);
    if (!renderer.poseMilliseconds().empty()) {  // animated glTF models: posing them is CPU work before the graph
        std::vector<double> ms = renderer.poseMilliseconds();
        std::sort(ms.begin(), ms.end());
        size_t vertices = 0;
        for (const ModelInstance& m : scene.models)
            if (m.animation && !m.playingClips.empty())
                for (const NodeVertexRange& r : m.animation->ranges) vertices += r.vertexCount;
        // --skinning gpu: the CPU evaluates the clips and uploads the matrices and weights; the
        // skinning pass (its own GPU row) poses the vertices.
        const bool onGpu = settings.skinning == SkinningMode::Gpu;
        say("animation pose: CPU median %.4f ms, min %.4f, max %.4f over %zu frames (%zu animated vertices; %s)\n",
            ms[ms.size() / 2], ms.front(), ms.back(), ms.size(), vertices,
            onGpu ? "--skinning gpu: evaluate, upload matrices and weights" : "--skinning cpu: evaluate, pose, upload");
        j["animation_pose_ms"] = {{"median_ms", ms[ms.size() / 2]}, {"min_ms", ms.front()}, {"max_ms", ms.back()},
                                  {"samples", ms.size()}, {"vertices", vertices}, {"skinning", skinningModeName(settings.skinning)}};
    }
    const ShadowCacheStats& cache = renderer.shadowCacheStats();
    if (cache.drawn + cache.kept + cache.scrolled + cache.completed > 0) {
        say("shadow cascades: %llu of %llu tiles kept from an earlier frame (%llu of them lagging behind a resized square), "
            "%llu scrolled (strips drawn), %llu drawn, %llu completed a quarter at a time (%llu quarters, at most %llu in a "
            "frame) (--shadow-cache %s, --shadow-scroll %s, --shadow-redraw-budget %d)\n",
            (unsigned long long)cache.kept, (unsigned long long)(cache.kept + cache.drawn + cache.scrolled + cache.completed),
            (unsigned long long)cache.lagging, (unsigned long long)cache.scrolled, (unsigned long long)cache.drawn,
            (unsigned long long)cache.completed, (unsigned long long)cache.quarters,
            (unsigned long long)cache.mostBudgetUnitsInAFrame, settings.shadows.cache ? "on" : "off",
            settings.shadows.scroll ? "on" : "off", settings.shadows.redrawBudget);
        j["shadow_cache"] = {{"tiles_drawn", cache.drawn}, {"tiles_kept", cache.kept}, {"tiles_scrolled", cache.scrolled},
                             {"hit_rate", double(cache.kept) / double(cache.kept + cache.drawn + cache.scrolled + cache.completed)},
                                   {"kept_per_cascade", std::vector<uint64_t>(std::begin(cache.keptPerCascade), std::end(cache.keptPerCascade))},
                                   {"drawn_per_cascade", std::vector<uint64_t>(std::begin(cache.drawnPerCascade), std::end(cache.drawnPerCascade))},
                                   {"scrolled_per_cascade", std::vector<uint64_t>(std::begin(cache.scrolledPerCascade), std::end(cache.scrolledPerCascade))},
                                   {"completed_per_cascade", std::vector<uint64_t>(std::begin(cache.completedPerCascade), std::end(cache.completedPerCascade))},
                                   {"lagging_per_cascade", std::vector<uint64_t>(std::begin(cache.laggingPerCascade), std::end(cache.laggingPerCascade))},
                                   {"tiles_lagging", cache.lagging}, {"tiles_completed", cache.completed},
                                   {"quarters_drawn", cache.quarters}, {"most_budget_units_in_a_frame", cache.mostBudgetUnitsInAFrame}};
    }
    const PointShadowStats& cubes = renderer.pointShadowStats();
    if (cubes.drawn + cubes.kept > 0) {
        say("point-light shadow cubes: %llu of %llu kept from an earlier frame, %llu drawn (--shadow-cache %s)\n",
            (unsigned long long)cubes.kept, (unsigned long long)(cubes.kept + cubes.drawn), (unsigned long long)cubes.drawn,
            settings.shadows.cache ? "on" : "off");
        j["point_shadow_cache"] = {{"cubes_drawn", cubes.drawn}, {"cubes_kept", cubes.kept}};
    }
    j["memory"] = {{"pool_bytes", poolBytes}, {"persistent_bytes", persistentBytes},
                   {"total_bytes", poolBytes + persistentBytes},
                   {"graph_transient_bytes", renderer.graph().liveTransientBytes()}};

    if (settings.renderPath == RenderPath::PathTraced) {
        const PathTraceNoise& noise = renderer.pathTraceNoise();
        say("%s\n", describePathTraceNoise(settings, noise).c_str());
        j["path_trace"] = {{"samples", noise.samples}, {"bounces", settings.pathTrace.interactions()},
                           {"mean_relative_standard_error", noise.meanRelativeStandardError},
                           {"lit_pixels", noise.pixels}, {"mean_luminance", noise.meanLuminance}};
    }
    // All or nothing: every output goes to a temporary name first; they are renamed only when all
    // were written.
    OutputFiles outputs;
    if (!o.out.empty()) outputs.addPng(o.out, renderer.readDisplay());
    if (!o.exr.empty()) outputs.addExr(o.exr, renderer.readHdr());
    if (!o.timingsJson.empty()) outputs.add(o.timingsJson, j.dump(2) + "\n");
    outputs.commit();
    if (!o.out.empty()) say("wrote %s\n", o.out.c_str());
    if (!o.exr.empty()) say("wrote %s\n", o.exr.c_str());
    return 0;
}

}  // namespace
}  // namespace lp::app

namespace {
int run(int argc, char** argv) {
    using namespace lp;
    std::vector<std::string> args(argv + 1, argv + argc);
    app::Options o = app::parseArgs(args);
    if (o.verbose) setLogLevel(LogLevel::Debug);
    if (o.quiet) setLogLevel(LogLevel::Error);
    setProgressFromStart(o.progress);
    if (o.command == "help") {
        std::fputs(app::helpText().c_str(), stdout);
        return 0;
    }
    if (o.command == "info") return app::commandInfo();
    if (o.command == "version") {
        std::printf("lightpass %s (%s, %s)\ndata: %s\n", LIGHTPASS_VERSION, LIGHTPASS_BUILD_TYPE,
                    PostBackend::compiledWithCuda() ? "CUDA post effects" : "no CUDA: GLSL post effects",
                    dataRoot().string().c_str());
        return 0;
    }
    if (o.command == "graph") return app::commandGraph(o);
    if (o.command == "render") return app::commandRender(o);
    if (o.command == "reference") return app::commandReference(o);
    if (o.command == "sweep") return app::runSweep(o);
    if (o.command == "bench") return app::runBench(o, args);
    if (o.command == "report") return app::runReport(o, args);
    return app::runViewer(o);
}
}  // namespace

int main(int argc, char** argv) {
    // Before any output is written: a temporary left by SIGINT, SIGTERM or SIGHUP is removed.
    lp::installTemporaryFileCleanup();
    std::string error;
    int code = 1;
    try {
        code = run(argc, argv);
    } catch (const std::bad_alloc&) {
        error = "out of memory";
    } catch (const std::exception& e) {  // lp::Error, and anything a library throws
        error = *e.what() ? e.what() : "unexpected error";
    }
    lp::flushRepeatedWarnings();  // counts of repeated warnings, before the error so it stays last
    if (!error.empty()) {
        // One clean line, whatever a library or a file put in the message.
        std::fprintf(stderr, "lightpass: error: %s\n", lp::oneLineMessage(error).c_str());
        return 1;
    }
    return code;
}
