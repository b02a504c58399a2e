#include "app/cli.hpp"

#include <cmath>
#include <filesystem>

#include "engine/core/error.hpp"

namespace lp::app {

std::string helpText() {
    return R"(lightpass - a multi-pass deferred renderer you can see, toggle and measure

usage:
  lightpass                         open the viewer on scenes/cornell.json (needs a display)
  lightpass view FILE               open the viewer on a scene (.json) or a model (.obj)
  lightpass render (--scene F | --model F.obj) --out F.png [options]
                                    render headless (EGL; NVIDIA if present, else Mesa llvmpipe)
                                    and print each pass's GPU time (median over the frames)
  lightpass graph (--scene F | --model F.obj) [--view V] [--dot F.dot]
                                    print the frame graph: passes that run, passes culled and
                                    why, what each reads and writes, transient textures
  lightpass sweep (--scene F | --model F.obj) --knob K [--knob K2 ...] [--out-dir D]
                                    render every value of each quality knob; GPU ms per pass
                                    and error against the knob's best value -> D/sweep.csv,
                                    D/sweep.md and images (bench/sweep_report.py adds FLIP
                                    and a Pareto plot)
  lightpass info                    print the OpenGL device headless rendering would use
  lightpass --help                  this text

options:
  --scene F         scene file (JSON, see README)
  --model F.obj     any OBJ, framed by the camera, with a key and a fill light
  --out F.png       tone-mapped image (written to a temporary name, then renamed)
  --exr F.exr       the linear HDR buffer before tone mapping (float32 EXR)
  --size WxH        render size (default 1280x720)
  --view V          final | depth | normals | diffuse | position | shininess | specular |
                    texcoords | lighting   (default final)
  --frames N        frames to render and time (default 1; the image is the last frame)
  --warmup N        untimed frames before timing (default 5 when --frames > 1, else 0)
  --exposure EV     exposure in stops before the tone map (default 0)
  --timings-json F  write the per-pass timings as JSON (for scripts and benchmarks)
  [shadows]
  [ibl]
  [local-lights]
  [post]
  --disable-pass P  switch pass P off (repeatable): in-place passes pass their input through,
                    passes that create textures clear them instead (see 'lightpass graph')
  --floors          also measure this GPU's compute and fragment bandwidth and print each pass's
                    floor (bytes it must move / bandwidth) and measured/floor
  --dot F           with graph: also write Graphviz DOT
  --no-vsync        viewer: don't wait for vertical sync (for measuring)
  --screenshot-dir D  viewer: where F12 writes lightpass-N.png (+ .exr of the HDR buffer)
  --hide-panel      viewer: start with the ImGui panel hidden (Tab toggles it)
  --screenshot-ui   viewer: F12 captures the whole window, panel included
  -v, --verbose     log debug messages (GL debug output included)
  -q, --quiet       log errors only

viewer keys (seed 001):
  1 depth  2 normals  3 diffuse  4 eye-space position  5 lighting  6 shininess  7 specular
  8 texcoords  0 final  r reset camera  x toggle scissor  W/S/A/D/Q/Z move  mouse drag: look
  +/- exposure  Tab panel  h help  F12 screenshot  Esc quit
)";
}

std::string defaultScenePath() {
#ifdef LIGHTPASS_SOURCE_DIR
    std::filesystem::path built = std::filesystem::path(LIGHTPASS_SOURCE_DIR) / "scenes" / "cornell.json";
    if (std::filesystem::exists(built)) return built.string();
#endif
    return "scenes/cornell.json";
}

namespace {
int parseInt(const std::string& flag, const std::string& v, int lo, int hi) {
    try {
        size_t used = 0;
        long x = std::stol(v, &used);
        if (used != v.size() || x < lo || x > hi) throw std::out_of_range("");
        return int(x);
    } catch (const std::exception&) {
        throw Error(flag + " " + v + ": expected a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    }
}
float parseFloat(const std::string& flag, const std::string& v) {
    try {
        size_t used = 0;
        float x = std::stof(v, &used);
        if (used != v.size() || !std::isfinite(x)) throw std::out_of_range("");
        return x;
    } catch (const std::exception&) {
        throw Error(flag + " " + v + ": expected a finite number");
    }
}
}  // namespace

Options parseArgs(const std::vector<std::string>& args) {
    Options o;
    size_t i = 0;
    o.command = "viewer";
    if (!args.empty() && args[0].rfind("-", 0) != 0) {
        o.command = args[0];
        i = 1;
        if (o.command != "render" && o.command != "graph" && o.command != "view" && o.command != "info" &&
            o.command != "sweep")
            throw Error("unknown command '" + o.command + "' (render, graph, view, sweep, info; see --help)");
        if (o.command == "view") {
            if (i >= args.size() || args[i].rfind("-", 0) == 0) throw Error("view: expected a .json scene or .obj model");
            std::string f = args[i++];
            (std::filesystem::path(f).extension() == ".obj" ? o.model : o.scene) = f;
            o.command = "viewer";
        }
    }
    bool warmupGiven = false;
    auto value = [&](const std::string& flag) -> std::string {
        if (i + 1 >= args.size()) throw Error(flag + ": missing value");
        return args[++i];
    };
    for (; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "--help" || a == "-h") o.command = "help";
        else if (a == "--scene") o.scene = value(a);
        else if (a == "--model") o.model = value(a);
        else if (a == "--out") o.out = value(a);
        else if (a == "--exr") o.exr = value(a);
        else if (a == "--dot") o.dot = value(a);
        else if (a == "--timings-json") o.timingsJson = value(a);
        else if (a == "--size") {
            std::string v = value(a);
            auto x = v.find('x');
            if (x == std::string::npos) throw Error("--size " + v + ": expected WxH, e.g. 1920x1080");
            o.width = parseInt(a + " " + v + ": width", v.substr(0, x), 1, 16384);
            o.height = parseInt(a + " " + v + ": height", v.substr(x + 1), 1, 16384);
            o.sizeGiven = true;
        } else if (a == "--view") {
            std::string v = value(a);
            auto view = parseView(v);
            if (!view) throw Error("--view " + v + ": unknown view (final, depth, normals, diffuse, position, shininess, specular, texcoords, lighting)");
            o.view = *view;
        } else if (a == "--frames") o.frames = parseInt(a, value(a), 1, 100000);
        else if (a == "--warmup") {
            o.warmup = parseInt(a, value(a), 0, 100000);
            warmupGiven = true;
        } else if (a == "--exposure") o.exposure = parseFloat(a, value(a));
        else if (a == "--no-vsync") o.vsync = false;
        else if (a == "--floors") o.floors = true;
        else if (a == "--screenshot-dir") o.screenshotDir = value(a);
        else if (a == "--hide-panel") o.hidePanel = true;
        else if (a == "--screenshot-ui") o.screenshotUi = true;
        else if (a == "--knob") o.knobs.push_back(value(a));
        else if (a == "--out-dir") o.outDir = value(a);
        else if (a == "--disable-pass") o.base.disabledPasses.insert(value(a));
        // [shadows] flags here.
        // [ibl] flags here.
        // [local-lights] flags here.
        // [post] flags here.
        else if (a == "-v" || a == "--verbose") o.verbose = true;
        else if (a == "-q" || a == "--quiet") o.quiet = true;
        else throw Error("unknown flag '" + a + "' (see --help)");
    }
    if (!warmupGiven) o.warmup = o.frames > 1 ? 5 : 0;
    if (o.command == "help" || o.command == "info") return o;
    if (!o.scene.empty() && !o.model.empty()) throw Error("give --scene or --model, not both");
    if (o.command == "sweep" && !warmupGiven) o.warmup = 10;
    if (o.command == "render" || o.command == "graph" || o.command == "sweep") {
        if (o.scene.empty() && o.model.empty()) throw Error(o.command + ": --scene F or --model F.obj is required");
    }
    if (o.command == "render" && o.out.empty() && o.exr.empty()) throw Error("render: --out F.png (or --exr F.exr) is required");
    if (!o.out.empty() && std::filesystem::path(o.out).extension() != ".png")
        throw Error("--out " + o.out + ": expected a .png file name");
    if (!o.exr.empty() && std::filesystem::path(o.exr).extension() != ".exr")
        throw Error("--exr " + o.exr + ": expected a .exr file name");
    if (!o.exr.empty() && o.view != DebugView::Final && o.view != DebugView::Lighting)
        throw Error("--exr: the '" + std::string(viewName(o.view)) + "' view has no HDR buffer; use --view final or lighting");
    if (o.command == "viewer" && o.scene.empty() && o.model.empty()) o.scene = defaultScenePath();
    return o;
}

}  // namespace lp::app
