#pragma once
// What the viewer's keys and panel change, shared by app/viewer.cpp (window, keys, frame loop) and
// app/viewer_panel.cpp (the ImGui panel).
#include <deque>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/pass_rows.hpp"
#include "app/viewer_clock.hpp"
#include "app/viewer_compare.hpp"
#include "app/viewer_layout.hpp"
#include "engine/gl/context.hpp"
#include "engine/gl/shader_reload.hpp"
#include "frame/renderer.hpp"
#include "engine/scene/scene.hpp"

namespace lp::app {

// The panel's width until the user drags its right edge (ImGui's ini file then remembers theirs).
constexpr float kPanelDefaultWidth = 340.0f;

struct ViewerState {
    RenderSettings settings;
    // What '0' (and '8' off) go back to: the --toon/--bloom flags as given, else the scene's.
    std::optional<bool> startToon, startBloom;
    Camera home;
    bool showPanel = true;
    bool showHelp = false;
    bool screenshotRequested = false;
    bool screenshotWithPanel = false;  // --screenshot-ui: F12 captures the window, panel included
    bool resetCamera = false;
    // The scene's camera path (scene file or --camera-path) and whether the camera follows it on the
    // viewer's clock; moving the camera by hand stops following, 'p' / the panel's checkbox toggle it.
    std::optional<CameraPath> cameraPath;
    bool followPath = false;
    bool togglePath = false;  // 'p' or the checkbox asked; the frame loop applies it
    // The scene clock frames are rendered at: Space plays and pauses it, '[' and ']' halve and
    // double its speed, the panel's "animation" section also scrubs it. A scrub is a jump
    // (`clockJumped`: the frame loop cuts the motion vectors across it).
    ViewerClock clock;
    bool clockJumped = false;
    bool toonShown = false;         // toon as the last frame resolved it (scene or flag), for '7'
    bool dragging = false;
    double lastX = 0, lastY = 0;
    std::filesystem::path screenshotDir = ".";
    int screenshotCount = 0;
    std::string lastScreenshot;
    std::deque<float> frameMs;  // frame-time graph (CPU time between frames)
    std::vector<PassRow> passRows;  // the panel's pass list, in a stable order (app/pass_rows.hpp)
    // Where the panel was last drawn (window coordinates); the next frame's image goes beside it.
    float panelX = 0, panelY = 0, panelWidth = kPanelDefaultWidth, panelHeight = 0;
    ViewerViewport viewport;  // where this frame's image goes (app/viewer_layout.hpp)
    // 'c' / the panel: the raster frame beside the path tracer's and a heat map of its error.
    bool compareWithTruth = false;
    TruthComparison comparison;

    // Scene and environment pickers: the panel asks, the frame loop loads between frames.
    std::filesystem::path sceneFile;  // the scene (.json) or model (.obj) on screen
    std::optional<std::filesystem::path> sceneRequest;
    std::optional<std::filesystem::path> environmentRequest;  // empty path: the scene's plain colour
    std::optional<std::string> materialVariantRequest;          // KHR_materials_variants; "": the files' own
    std::string sceneError;        // the one-line error of the last failed load
    std::string shaderError;       // the first compile error of the last shader reload, file:line
    std::string shaderStatus;      // "reloaded 3 programs (common/post.glsl)"
    gl::ShaderFileWatcher shaderWatcher;
    double nextShaderPoll = 0.0;
};

// Files the pickers offer: scenes (*.json, and *.obj models shown as `lightpass view model.obj` does) and environments (*.exr, *.hdr) under scenes/, hdr/ and,
// when present, ../shared/assets, searched from the repository the shaders come from.
struct PickerFiles {
    std::vector<std::filesystem::path> scenes;
    std::vector<std::filesystem::path> environments;
};
PickerFiles findPickerFiles(const std::filesystem::path& repositoryRoot);

void drawViewerPanel(ViewerState& state, Renderer& renderer, const Scene& scene, const gl::GpuContext& context,
                     const PickerFiles& files);

// Every key binding, one per line (the 'h' overlay and the README's table say the same).
extern const char* const kViewerHelp;

}  // namespace lp::app
