#include "app/sweep.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/core/progress.hpp"
#include "app/render_checks.hpp"
#include "engine/gl/context.hpp"
#include "engine/io/image_io.hpp"
#include "engine/render/image_metrics.hpp"
#include "engine/render/surface_mask.hpp"
#include "frame/knobs.hpp"
#include "passes/path_trace_pass.hpp"
#include "frame/renderer.hpp"
#include "engine/scene/scene_loader.hpp"

namespace lp::app {
namespace fs = std::filesystem;

namespace {

struct Row {
    std::string knob, value;
    std::map<std::string, double> passMs;
    std::vector<std::string> passOrder;
    ImageError error;
    ImageError surface;  // the same frame over the pixels that see a surface
    ImageError term;     // the knob's light term alone (frame/light_terms.hpp), over those pixels
    LightTerm termOf = LightTerm::Frame;  // which term that is
    bool reference = false;
};

std::string csvEscape(const std::string& s) { return s.find(',') == std::string::npos ? s : "\"" + s + "\""; }


}  // namespace

int runSweep(const Options& o) {
    if (o.knobs.empty()) throw Error("sweep: --knob NAME is required (knobs: " + knobNames() + ")");
    std::vector<Knob> knobs;
    for (const auto& name : o.knobs) {
        std::optional<Knob> k = knobByName(name);
        if (!k)
            throw Error("sweep: unknown knob " + quoteUserText(name) + " (knobs: " + knobNames() +
                        "; A+B sweeps every combination of two different knobs)");
        knobs.push_back(std::move(*k));
    }
    const fs::path outDir = o.outDir.empty() ? fs::path("sweep") : fs::path(o.outDir);
    Scene scene = sceneFromOptions(o);
    // The folders (each knob's images go in its own), made and checked writable before any rendering;
    // after the scene loaded, so a bad scene leaves no empty folders behind.
    std::error_code ec;
    for (const Knob& knob : knobs) {
        fs::create_directories(outDir / knob.name, ec);
        if (ec) throw Error((outDir / knob.name).string() + ": cannot create the output folder: " + ec.message());
        requireWritableOutput(outDir / knob.name / "reference.png");
    }
    requireWritableOutput(outDir / "sweep.csv");
    requireWritableOutput(outDir / "sweep.md");
    auto settingsFor = [&](const KnobValue& v) {
        RenderSettings s = o.base;
        s.width = o.width;
        s.height = o.height;
        s.view = DebugView::Final;
        s.keepHdr = true;
        v.apply(s);
        return s;
    };
    auto ctx = gl::createHeadlessContext();
    logInfo("sweeping on " + ctx->info().renderer + (ctx->isSoftware() ? " (software: times are not meaningful)" : ""));
    // Every value's settings against the GPU before the first frame: no reference image is rendered
    // for a sweep that cannot finish.
    for (const Knob& knob : knobs)
        for (const KnobValue& v : knob.values) requireFrameFitsGpu(*ctx, scene, settingsFor(v));
    Renderer renderer(scene);
    // The pixels that see a surface, at the camera of the last timed frame (the one every error is
    // taken on): the errors over surfaces leave the background out.
    const double lastFrameTime = frameTime(o, o.frames - 1);
    const std::vector<uint8_t> mask = surfaceMask(scene, scene.cameraAt(lastFrameTime), o.width, o.height, lastFrameTime);
    // Per light term a knob isolates: the scene lit by it alone and a renderer of its own (made when
    // a knob first asks).
    struct TermRenderer {
        std::unique_ptr<Scene> scene;
        std::unique_ptr<Renderer> renderer;
    };
    std::map<LightTerm, TermRenderer> termRenderers;
    auto termRendererFor = [&](LightTerm term, const RenderSettings& settings) -> Renderer& {
        TermRenderer& t = termRenderers[term];
        if (!t.renderer) {
            t.scene = std::make_unique<Scene>(sceneLitBy(scene, settings, term));
            t.renderer = std::make_unique<Renderer>(*t.scene, renderer.shaders());
        }
        return *t.renderer;
    };
    // A frame of `s` on `r` as a value's timed frames end (warm-up, then the timed frames untimed).
    auto renderUntimed = [&](Renderer& r, const RenderSettings& s) {
        for (int i = 0; i < std::max(o.warmup, 1); ++i) r.render(s, float(warmupTime(o)), false);
        for (int i = 0; i < o.frames; ++i) r.render(s, float(frameTime(o, i)), false);
    };
    // --time T / --fps F as for render: warm-up frames at T - 1 / F (at T without --fps), timed frame
    // i at T + i / F (a moving camera or orbit moves through the timed frames; temporal methods carry
    // their history along).
    // Every image, the CSV and the Markdown are renamed into place together at the end.
    OutputFiles outputs;

    const bool pathTraced = o.sweepReference == SweepReference::PathTraced;
    // Per knob: the path tracer's samples and noise where it is the reference (sweep.csv and .md record them).
    std::map<std::string, PathTraceNoise> referenceNoise;
    std::vector<Row> rows;
    std::vector<std::string> allPasses;  // the CSV's time columns, in order of first appearance
    auto addColumn = [&](const std::string& name) {
        if (std::find(allPasses.begin(), allPasses.end(), name) == allPasses.end()) allPasses.push_back(name);
    };
    size_t valueCount = 0;
    for (const Knob& knob : knobs) valueCount += knob.values.size();
    ProgressStyle progressStyle = stderrProgressStyle();
    progressStyle.plainLinePerStep = true;  // a line per knob value in a log
    ProgressReporter progress("sweep", valueCount, std::cerr, progressStyle, steadySeconds);
    for (size_t ki = 0; ki < knobs.size(); ++ki) {
        const Knob& knob = knobs[ki];
        const fs::path dir = outDir / knob.name;
        // The reference: the knob's best value, or the path tracer at its settings (one frame holds
        // every --spp sample), at the time of the last timed frame.
        RenderSettings refSettings = settingsFor(knob.values.back());
        if (pathTraced) {
            refSettings.renderPath = RenderPath::PathTraced;
            renderer.render(refSettings, float(frameTime(o, o.frames - 1)), false);
            glFinish();
            referenceNoise[knob.name] = renderer.pathTraceNoise();
            logInfo(knob.name + ": reference " + describePathTraceNoise(refSettings, renderer.pathTraceNoise()));
        } else {
            // On the scene's clock as render puts it (--time, --fps): the reference and every value end
            // on the same frame, with the same previous frame (motion blur, camera paths).
            for (int i = 0; i < warmupFrames(o, o.warmup + 1); ++i) renderer.render(refSettings, float(warmupTime(o)), false);
            for (int i = 0; o.fps > 0.0 && i < o.frames; ++i) renderer.render(refSettings, float(frameTime(o, i)), false);
        }
        const ImageF reference = renderer.readHdr();
        outputs.addPng(dir / "reference.png", renderer.readDisplay());
        outputs.addExr(dir / "reference.exr", reference);
        // The same reference in the scene lit by the knob's term alone.
        Renderer* termRenderer = knob.term == LightTerm::Frame ? nullptr : &termRendererFor(knob.term, refSettings);
        ImageF termReference;
        if (termRenderer) {
            if (pathTraced) {
                termRenderer->render(refSettings, float(frameTime(o, o.frames - 1)), false);
                glFinish();
            } else {
                renderUntimed(*termRenderer, refSettings);
            }
            termReference = termRenderer->readHdr();
            outputs.addExr(dir / "reference_term.exr", termReference);
        }

        const size_t steps = knob.values.size();
        for (size_t vi = 0; vi < steps; ++vi) {
            const KnobValue& value = knob.values[vi];
            RenderSettings s = settingsFor(value);
            // Each value bakes its IBL afresh in its first (untimed) frame: the bake is a one-off cost,
            // not part of frame_ms, reported as ibl_bake_gpu_ms where a bake ran.
            renderer.environments().forgetBakes();
            for (int i = 0; i < std::max(o.warmup, 1); ++i) renderer.render(s, float(warmupTime(o)), false);
            const double bakeMs = renderer.environments().lastBakeGpuMs();
            renderer.timers().clear();
            for (int i = 0; i < o.frames; ++i) renderer.render(s, float(frameTime(o, i)), true);
            glFinish();
            renderer.timers().flush();
            Row row;
            row.knob = knob.name;
            row.termOf = knob.term;
            row.value = value.label;
            row.reference = !pathTraced && vi + 1 == steps;
            for (const auto& name : renderer.timers().passOrder()) {
                row.passMs[name] = renderer.timers().median(name);
                row.passOrder.push_back(name);
                addColumn(name);
            }
            if (bakeMs > 0.0) {
                row.passMs["ibl_bake_gpu"] = bakeMs;
                addColumn("ibl_bake_gpu");
            }
            const ImageF image = renderer.readHdr();
            row.error = compareHdr(image, reference);
            row.surface = compareHdr(image, reference, &mask);
            row.term = row.surface;
            if (termRenderer) {
                renderUntimed(*termRenderer, s);
                row.term = compareHdr(termRenderer->readHdr(), termReference, &mask);
            }
            std::string file = std::to_string(vi) + ".png";
            outputs.addPng(dir / file, renderer.readDisplay());
            rows.push_back(row);
            progress.step(knob.name + " " + value.label);
        }
    }
    progress.finish();

    // CSV: one row per knob value; pass times in columns.
    {
        std::ostringstream f;
        f << "knob,value,index,reference,frame_ms";
        for (const auto& p : allPasses)
            if (p != "frame") f << "," << p << "_ms";
        f << ",rmse,psnr_db,max_abs,non_finite,image,reference_source,reference_spp,reference_noise_rmse"
          << ",surface_pixels,surface_rmse,surface_relative_error,term,term_rmse,term_relative_error\n";
        std::map<std::string, int> index;
        for (const auto& r : rows) {
            int i = index[r.knob]++;
            f << csvEscape(r.knob) << "," << csvEscape(r.value) << "," << i << "," << (r.reference ? 1 : 0) << ","
              << (r.passMs.count("frame") ? r.passMs.at("frame") : 0.0);
            for (const auto& p : allPasses)
                if (p != "frame") f << "," << (r.passMs.count(p) ? r.passMs.at(p) : 0.0);
            f << "," << r.error.rmse << "," << (std::isinf(r.error.psnr) ? 999.0 : r.error.psnr) << "," << r.error.maxAbs
              << "," << r.error.nonFinite << "," << r.knob << "/" << i << ".png";
            // The reference: best (0 samples, no noise) or pathtraced with its samples and RMS noise.
            const auto noise = referenceNoise.find(r.knob);
            f << "," << enumName(kSweepReferenceNames, o.sweepReference) << ","
              << (noise == referenceNoise.end() ? 0 : noise->second.samples) << ","
              << (noise == referenceNoise.end() ? 0.0 : noise->second.rmsStandardError);
            // Over the surfaces, and the knob's term alone over them (the frame's figures for a Frame knob).
            f << "," << r.surface.pixels << "," << r.surface.rmse << "," << r.surface.relativeError << ","
              << enumName(kLightTermNames, r.termOf) << "," << r.term.rmse << ","
              << r.term.relativeError << "\n";
        }
        outputs.add(outDir / "sweep.csv", f.str());
    }
    // Markdown: one table per knob.
    std::ostringstream md;
    md << "# Sweep: " << (o.model.empty() ? o.scene : o.model) << ", " << o.width << "x" << o.height << ", "
       << ctx->info().renderer << "\n\nGPU ms are medians of " << o.frames << " frames after " << o.warmup
       << " warm-up frames; errors are against "
       << (pathTraced ? "the path tracer at each knob's best value's settings" : "each knob's best value")
       << ", on the linear HDR buffer (PSNR peak 1). `surface` is the error over the pixels that see a surface "
          "(Σ|ΔY| / ΣY of the reference's luminance Y); `term` the same with the scene lit by the knob's light "
          "term alone (suns, environment or local lights; the frame for a knob of every light).\n";
    for (const Knob& k : knobs) {
        md << "\n## " << k.name << "\n\n" << k.description << "\n\n";
        if (const auto noise = referenceNoise.find(k.name); noise != referenceNoise.end()) {
            char line[256];
            std::snprintf(line, sizeof line,
                          "Reference: the path tracer, %d samples a pixel; its own noise adds about %.3g RMSE "
                          "(mean relative standard error %.3f%%).\n\n",
                          noise->second.samples, noise->second.rmsStandardError, 100.0 * noise->second.meanRelativeStandardError);
            md << line;
        }
        md << "Term: " << enumName(kLightTermNames, k.term) << ".\n\n";
        md << "| value | frame ms | RMSE | PSNR dB | surface rel. error | term rel. error |\n| --- | --- | --- | --- | --- | --- |\n";
        for (const auto& r : rows) {
            if (r.knob != k.name) continue;
            char line[256];
            std::snprintf(line, sizeof line, "| %s%s | %.4f | %.3g | %s | %.2f%% | %.2f%% |\n", r.value.c_str(),
                          r.reference ? " (reference)" : "", r.passMs.count("frame") ? r.passMs.at("frame") : 0.0,
                          r.error.rmse, std::isinf(r.error.psnr) ? "inf" : std::to_string(r.error.psnr).substr(0, 6).c_str(),
                          100.0 * r.surface.relativeError, 100.0 * r.term.relativeError);
            md << line;
        }
    }
    outputs.add(outDir / "sweep.md", md.str());
    outputs.commit();
    std::fputs(md.str().c_str(), stdout);
    std::printf("\nwrote %s and %s\n", (outDir / "sweep.csv").c_str(), (outDir / "sweep.md").c_str());
    return 0;
}

}  // namespace lp::app
