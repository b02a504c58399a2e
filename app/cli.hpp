#pragma once
// Command-line parsing for the lightpass executable: flags are validated with one-line errors.
#include <optional>
#include <string>
#include <vector>

#include "engine/render/settings.hpp"

namespace lp::app {

struct Options {
    std::string command;  // "viewer", "render", "graph", "info", "help"
    std::string scene;
    std::string model;
    std::string out;
    std::string exr;
    std::string dot;
    std::string timingsJson;
    bool explain = false;  // graph: every candidate pass, whether it runs and why not
    int width = 1280, height = 720;
    bool sizeGiven = false;
    DebugView view = DebugView::Final;
    int frames = 1;
    int warmup = 5;
    float exposure = 0.0f;
    bool vsync = true;
    bool floors = false;
    std::string screenshotDir;  // viewer: where F12 writes
    bool hidePanel = false;
    bool screenshotUi = false;
    std::vector<std::string> knobs;  // sweep
    std::string outDir;              // sweep
    std::vector<std::string> varies; // bench: one axis of variants per --vary
    double maxSeconds = 0;           // bench: time cap per variant (0: none)
    int minFrames = 10;              // bench: timed frames a capped variant still gets
    RenderSettings base;  // feature flags (, , , ) set these
    bool verbose = false;
    bool quiet = false;
};

// Throws lp::Error("unknown flag ...") etc.
Options parseArgs(const std::vector<std::string>& args);
// The frame settings the options describe (size, view, exposure, feature flags).
RenderSettings renderSettings(const Options& options);
std::string helpText();
// "WxH", plus " (rendered at wxh, render scale S)" below render scale 1: for table headers.
std::string sizeLabel(const RenderSettings& settings);
std::string defaultScenePath();

}  // namespace lp::app
