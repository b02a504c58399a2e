#pragma once
// Command-line parsing for the lightpass executable: flags are validated with one-line errors.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/core/enum_table.hpp"
#include "engine/render/settings.hpp"
#include "engine/scene/scene.hpp"

namespace lp::app {

// What `sweep` measures each knob's error against (--reference).
enum class SweepReference {
    BestValue,   // the knob's last (most accurate) value
    PathTraced,  // the path tracer (--spp, --bounces / --direct-only) at the best value's settings
};
inline constexpr EnumName<SweepReference> kSweepReferenceNames[] = {
    {SweepReference::BestValue, "best"}, {SweepReference::PathTraced, "pathtraced"}};

struct Options {
    std::string command;  // "viewer", "render", "reference", "graph", "sweep", "bench", "report", "info", "help"
    std::string scene;
    std::string model;
    bool modelZUp = false;  // --up z: the --model file is Z-up (turned to Y-up on load)
    // --env FILE|none: replaces the scene's or model's environment; an empty path: none.
    std::optional<std::filesystem::path> environment;
    std::string out;
    std::string exr;
    std::string dot;
    std::string timingsJson;
    bool explain = false;  // graph: every candidate pass, whether it runs and why not
    int width = 1280, height = 720;
    bool sizeGiven = false;
    DebugView view = DebugView::Final;
    int frames = 1;
    bool framesGiven = false;
    int warmup = 5;
    // --time T, --fps F: timed frame i is at T + i / F seconds (F 0: every frame at T); warm-up at T.
    double time = 0.0;
    double fps = 0.0;
    // --camera px,py,pz,tx,ty,tz[,fov]: replaces the scene's camera position, target (and fov).
    std::optional<glm::vec3> cameraPosition, cameraTarget;
    std::optional<float> cameraFov;
    std::string cameraPath;  // --camera-path F: a JSON file holding a "cameraPath" object (--camera wins)
    std::optional<std::string> materialVariant;  // --material-variant NAME: the KHR_materials_variants variant glTF models draw
    std::optional<std::string> animation;  // --animation NAME|INDEX|all|none: the clips glTF models play (default: the first)
    float exposure = 0.0f;  // = base.exposureEV (the --exposure knob), for the viewer's start
    bool vsync = true;
    bool floors = false;
    std::string screenshotDir;  // viewer: where F12 writes
    bool hidePanel = false;
    bool screenshotUi = false;
    std::string panelRowsOut;  // viewer: where the panel's pass rows go when they change (for tests)
    std::vector<std::string> knobs;  // sweep
    std::string outDir;              // sweep
    SweepReference sweepReference = SweepReference::BestValue;  // sweep --reference
    bool sweepReferenceGiven = false;
    std::string sweepDir;            // report --sweep: a sweep output folder to draw
    std::string benchJson;           // report --bench: a bench --timings-json file to draw
    std::vector<std::string> varies; // bench: one axis of variants per --vary
    double maxSeconds = 0;           // bench: time cap per variant (0: none)
    int minFrames = 10;              // bench: timed frames a capped variant still gets
    bool warmupGiven = false;
    bool bouncesGiven = false;       // --bounces (not with --direct-only)
    RenderSettings base;  // the knob flags (frame/knobs.cpp's table) set these
    bool verbose = false;
    bool quiet = false;
    bool progress = false;  // progress from the first step (engine/core/progress.hpp), not after 2 s
};

// A flag that is not a knob (commands' inputs and outputs, size, view, timing, viewer options): the
// knob flags come from frame/knobs.cpp's table, these from commandFlags(). The parser accepts
// exactly the flags of the two lists, and --help prints both.
struct CommandFlag {
    std::vector<std::string> names;  // {"-v", "--verbose"}
    std::string metavar;             // "F" for a flag that takes a value; empty: it takes none
    std::string help;
    std::function<void(Options&, const std::string& flag, const std::string& value)> apply;
};
const std::vector<CommandFlag>& commandFlags();

// Throws lp::Error("unknown flag ...") etc.
Options parseArgs(const std::vector<std::string>& args);
// The frame settings the options describe (size, view, exposure, feature flags).
RenderSettings renderSettings(const Options& options);

// The scene the options name (--scene or --model), with --env's environment, --camera-path's path
// and --camera's camera applied (--camera removes any path: it fixes the camera).
Scene sceneFromOptions(const Options& options);
// --time / --fps: when timed frame i is on the scene's clock (T + i / F; T without --fps).
double frameTime(const Options& options, int i);
// When the untimed frames before the timed ones are: T - 1 / F with --fps (so the first timed frame
// has a previous frame one step earlier: its motion vectors), else T.
double warmupTime(const Options& options);
// Untimed frames before the timed ones: --warmup, at least one with --fps (the previous frame).
int warmupFrames(const Options& options, int warmup);
std::string helpText();
// "WxH", plus " (rendered at wxh, render scale S)" below render scale 1: for table headers.
std::string sizeLabel(const RenderSettings& settings);
std::string defaultScenePath();

}  // namespace lp::app
