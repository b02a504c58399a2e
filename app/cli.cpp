#include "app/cli.hpp"

#include "engine/scene/scene_loader.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/core/paths.hpp"
#include "frame/frame_builder.hpp"
#include "frame/knobs.hpp"
#include "engine/scene/scene_loader.hpp"

namespace lp::app {

std::string helpText() {
    std::string text = R"(lightpass - a multi-pass deferred renderer you can see, toggle and measure

usage:
  lightpass                         open the viewer on scenes/cornell.json (needs a display)
  lightpass view FILE               open the viewer on a scene (.json) or a model (.obj, .gltf, .glb)
  lightpass render (--scene F | --model F) --out F.png [options]
                                    render headless (EGL; NVIDIA if present, else Mesa llvmpipe)
                                    and print each pass's GPU time (median over the frames)
  lightpass graph (--scene F | --model F) [--view V] [--dot F.dot] [--explain]
                                    print the frame graph: passes that run, passes culled and
                                    why, what each reads and writes, transient textures
  lightpass sweep (--scene F | --model F) --knob K [--knob K2 ...] [--out-dir D]
                                    render every value of each quality knob; GPU ms per pass
                                    and error against the knob's best value -> D/sweep.csv,
                                    D/sweep.md and images (bench/sweep_report.py adds FLIP
                                    and a Pareto plot); --knob A+B sweeps every combination
  lightpass bench (--scene F | --model F) --vary 'FLAG V1,V2,..' [--vary ...] [flags]
                                    one process renders every combination of the --vary axes
                                    (an axis is 'FLAG V1,V2' or 'FLAGS A|FLAGS B'), GPU ms per
                                    pass (median of --frames after --warmup, default 10) and
                                    floors with --floors -> --timings-json F (default bench.json);
                                    --max-seconds S caps a slow variant's frames and warm-up
                                    (never below --min-frames N, default 10)
  lightpass report (--scene F | --model F) --out DIR [render flags]
                                    one HTML page, DIR/index.html: the frame graph drawn, every
                                    view the frame has, GPU ms per pass against its floor (median
                                    of --frames, default 10, after --warmup), memory, device
  lightpass report (--sweep D | --bench F.json) --out DIR
                                    the same kind of page for a sweep folder (error against GPU
                                    ms per knob, Pareto front, each value's image) or a bench's
                                    --timings-json (GPU ms per variant and pass, floors)
  lightpass reference (--scene F | --model F) --spp N [--bounces B | --direct-only] --out F.png [--exr F.exr]
                                    the path tracer's image (docs/path-tracer.md): N samples a
                                    pixel, the tone map of render; the HDR mean in --exr; prints
                                    the noise (mean relative standard error)
  lightpass info                    print the OpenGL device headless rendering would use
  lightpass --help                  this text

)";
    text += "options:\n";
    for (const CommandFlag& f : commandFlags()) {
        std::string names;
        for (const auto& n : f.names) names += (names.empty() ? "" : ", ") + n;
        text += helpLine(names + (f.metavar.empty() ? "" : " " + f.metavar), f.help);
    }
    text += "\nknobs (frame/knobs.cpp's table; the viewer panel shows the same settings with the same ranges):\n";
    text += knobHelpText();
    text += R"(
viewer keys (seed 001):
  1 depth  2 normals  3 diffuse  4 eye-space position  5 lighting  6 shininess  7 toon on/off
  8 bloom buffer alone  9 velocity  0 standard view  r reset camera  x toggle scissor  W/S/A/D/Q/Z move
  m next material input (base-color, metallic, roughness, occlusion, emissive)
  t next term (term-diffuse, term-specular, clearcoat)  k the clearcoat layer alone (KHR_materials_clearcoat)
  c compare with the path tracer (raster | path tracer / heat map of the raster's error)
  mouse drag: look  p follow the camera path  +/- exposure  Tab panel  h help  F12 screenshot  Esc quit
  (the panel also picks scenes and environments, a picked map lighting the scene with IBL on,
  and shaders/ edits reload while it runs)
)";
    return text;
}

std::string sizeLabel(const RenderSettings& s) {
    std::string label = std::to_string(s.width) + "x" + std::to_string(s.height);
    const glm::ivec2 r = scaledRenderSize(s.width, s.height, internalRenderScale(s));
    if (r.x == s.width && r.y == s.height) return label;
    if (supersampled(s))
        return label + " (rendered at " + std::to_string(r.x) + "x" + std::to_string(r.y) + ", SSAA " +
               std::to_string(s.aa.ssaaScale) + "x" + std::to_string(s.aa.ssaaScale) + ")";
    char scale[16];
    std::snprintf(scale, sizeof scale, "%.2f", double(s.renderScale));
    return label + " (rendered at " + std::to_string(r.x) + "x" + std::to_string(r.y) + ", render scale " + scale + ")";
}

std::string defaultScenePath() { return (dataRoot() / "scenes" / "cornell.json").string(); }

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

// "px,py,pz,tx,ty,tz[,fov]": six or seven finite numbers, a target apart from the position, a fov in (0, 180).
void parseCamera(Options& o, const std::string& flag, const std::string& v) {
    std::vector<float> n;
    size_t start = 0;
    while (start <= v.size()) {
        const size_t comma = v.find(',', start);
        const std::string part = v.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        try {
            n.push_back(parseFloat(flag, part));
        } catch (const Error&) {
            throw Error(flag + " " + v + ": expected px,py,pz,tx,ty,tz[,fov] as finite numbers");
        }
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    if (n.size() != 6 && n.size() != 7) throw Error(flag + " " + v + ": expected px,py,pz,tx,ty,tz[,fov] (6 or 7 numbers)");
    // The scene file's camera limits: past +-1e7 m the shadow and culling matrices overflow a float,
    // and a fov outside (0.5, 179) degrees leaves a degenerate projection.
    for (size_t i = 0; i < 6; ++i)
        if (std::fabs(n[i]) > 1e7f) throw Error(flag + " " + v + ": coordinates must be within +-1e7 m");
    const glm::vec3 position(n[0], n[1], n[2]), target(n[3], n[4], n[5]);
    if (glm::length(target - position) <= 0.0f) throw Error(flag + " " + v + ": the target equals the position");
    if (n.size() == 7 && !(n[6] > 0.5f && n[6] < 179.0f)) throw Error(flag + " " + v + ": fov must be in (0.5, 179) degrees");
    o.cameraPosition = position;
    o.cameraTarget = target;
    if (n.size() == 7) o.cameraFov = n[6];
}

// --env: "none" (an empty path), or an .hdr / .exr map that exists (looked up in the data root as
// --scene is, so hdr/studio.exr works from anywhere).
std::filesystem::path parseEnvironmentFlag(const std::string& flag, const std::string& v) {
    if (v == "none") return {};
    const std::filesystem::path map = resolveDataPath(v);
    std::string ext = map.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext != ".hdr" && ext != ".exr") throw Error(flag + " " + v + ": expected an .hdr or .exr map, or none");
    std::error_code ec;
    if (!std::filesystem::is_regular_file(map, ec)) throw Error(flag + " " + v + ": file not found");
    return map;
}

std::string viewList(const std::vector<DebugView>& views, const std::string& separator = " | ") {
    std::string s;
    for (DebugView v : views) s += (s.empty() ? "" : separator) + std::string(viewName(v));
    return s;
}

std::vector<CommandFlag> makeCommandFlags() {
    using V = const std::string&;
    return {
        {{"-h", "--help"}, "", "this text", [](Options& o, V, V) { o.command = "help"; }},
        {{"--version"}, "", "the version, build (CUDA or not) and where shaders and scenes are read from",
         [](Options& o, V, V) { o.command = "version"; }},
        {{"--scene"}, "F", "scene file (JSON, see docs/scene-files.md); a bundled one by name from anywhere (cornell, gallery, ...)",
         [](Options& o, V, V v) { o.scene = resolveDataPath(v); }},
        {{"--model"}, "F",
         "any OBJ or glTF (.gltf, .glb), framed by the camera (or the glTF's first camera), lit by the bundled "
         "studio environment with IBL on (or by the glTF's own lights)",
         [](Options& o, V, V v) { o.model = v; }},
        {{"--env"}, "F|none",
         "the environment map (.hdr or .exr, equirectangular) of the scene or model instead of its own, "
         "sky and IBL, at intensity 1 and rotation 0; none: no map and no IBL (a bare model then gets a "
         "key and a fill light)",
         [](Options& o, V a, V v) { o.environment = parseEnvironmentFlag(a, v); }},
        {{"--up"}, "y|z", "the --model file's up axis: z turns a Z-up model (Blender, CAD, the Vulkan tutorial's viking room) to Y-up",
         [](Options& o, V a, V v) {
             if (v != "y" && v != "z") throw Error(a + " " + v + ": expected y or z");
             o.modelZUp = v == "z";
         }},
        {{"--out"}, "F.png", "tone-mapped image (written to a temporary name, then renamed); report: the folder of index.html",
         [](Options& o, V, V v) { o.out = v; }},
        {{"--exr"}, "F.exr", "the linear HDR buffer before tone mapping (float32 EXR)", [](Options& o, V, V v) { o.exr = v; }},
        {{"--size"}, "WxH", "render size (default 1280x720)",
         [](Options& o, V a, V v) {
             auto x = v.find('x');
             if (x == std::string::npos) throw Error("--size " + v + ": expected WxH, e.g. 1920x1080");
             o.width = parseInt(a + " " + v + ": width", v.substr(0, x), 1, 16384);
             o.height = parseInt(a + " " + v + ": height", v.substr(x + 1), 1, 16384);
             o.sizeGiven = true;
         }},
        {{"--view"}, "V",
         viewList(allViews()) + " (default final); shadowmap: light-space depth of directional light "
             "--shadow-light N's shadow map; " + viewList(localLightViews()) +
             ": overlay each light's rectangle/volume, or lights per 16x16 tile (docs/viewer.md)",
         [](Options& o, V, V v) {
             auto view = parseView(v);
             if (!view) throw Error("--view " + v + ": unknown view (" + viewList(everyView(), ", ") + ")");
             o.view = *view;
         }},
        {{"--time"}, "T", "render, bench, sweep: seconds on the scene's clock of the first timed frame (orbits and camera paths follow; default 0)",
         [](Options& o, V a, V v) {
             o.time = parseFloat(a, v);
             if (std::fabs(o.time) > 1e6) throw Error(a + " " + v + ": expected seconds in [-1e6, 1e6]");
         }},
        {{"--fps"}, "F", "render, bench, sweep: frame i is at --time + i / F, untimed frames at --time - 1 / F (default 0: every frame at --time)",
         [](Options& o, V a, V v) {
             o.fps = parseFloat(a, v);
             if (!(o.fps >= 0.0 && o.fps <= 1e4)) throw Error(a + " " + v + ": expected frames per second in [0, 10000]");
         }},
        {{"--camera"}, "P,T[,F]", "camera position px,py,pz, target tx,ty,tz and optionally vertical fov (degrees)",
         [](Options& o, V a, V v) { parseCamera(o, a, v); }},
        {{"--camera-path"}, "F",
         "JSON file of camera keyframes ({\"keys\": [{\"time\", \"position\", \"target\", \"fov\"}, ...], \"loop\"}; "
         "replaces the scene's cameraPath; --camera overrides it)",
         [](Options& o, V, V v) { o.cameraPath = v; }},
        {{"--reference"}, "R",
         "sweep: what each knob's error is measured against: best (its last value; the default) or pathtraced "
         "(the path tracer at the best value's settings, --spp samples a pixel, --bounces or --direct-only)",
         [](Options& o, V a, V v) {
             const std::optional<SweepReference> r = parseEnum(kSweepReferenceNames, v);
             if (!r) throw Error(a + " " + v + ": expected one of " + enumNameList(kSweepReferenceNames));
             o.sweepReference = *r;
             o.sweepReferenceGiven = true;
         }},
        {{"--spp"}, "N", "path tracer (--render-path pathtraced, reference): samples a pixel (default 64)",
         [](Options& o, V a, V v) { o.base.pathTrace.samples = parseInt(a, v, 1, 1 << 20); }},
        {{"--bounces"}, "B",
         "path tracer: surface interactions whose scattered light counts (default 8; Russian roulette from the 3rd)",
         [](Options& o, V a, V v) {
             o.base.pathTrace.bounces = parseInt(a, v, 1, 1024);
             o.bouncesGiven = true;
         }},
        {{"--direct-only"}, "", "path tracer: direct light only (one interaction: lights, environment and emitters seen from it)",
         [](Options& o, V, V) { o.base.pathTrace.directOnly = true; }},
        {{"--pixel-centre"}, "", "path tracer: every sample through the pixel's centre (default: jittered over the pixel)",
         [](Options& o, V, V) { o.base.pathTrace.pixelCentre = true; }},
        {{"--env-sampling"}, "S",
         "path tracer: how rays find an environment map's light: importance (by the map's luminance and the BRDF, "
         "combined by multiple importance sampling; the default) or brdf (the BRDF's samples alone)",
         [](Options& o, V a, V v) {
             if (v != "importance" && v != "brdf") throw Error(a + " " + v + ": expected importance or brdf");
             o.base.pathTrace.environmentSampling = v == "importance";
         }},
        {{"--material-variant"}, "NAME",
         "glTF models draw their KHR_materials_variants variant NAME (every model that has it; an error when none "
         "has); default: each file's own materials",
         [](Options& o, V, V v) { o.materialVariant = v; }},
        {{"--animation"}, "A",
         "the glTF animations models play on the scene's clock: a clip's NAME or INDEX, all, or none (the rest pose); "
         "default: each model's first clip",
         [](Options& o, V a, V v) {
             if (v.empty()) throw Error(a + ": expected a clip's name or index, all or none");
             o.animation = v;
         }},
        {{"--frames"}, "N", "frames to render and time (default 1, report: 10; the image is the last frame)",
         [](Options& o, V a, V v) {
             o.frames = parseInt(a, v, 1, 100000);
             o.framesGiven = true;
         }},
        {{"--warmup"}, "N", "untimed frames before timing (default 5 when --frames > 1, else 0; sweep and bench: 10)",
         [](Options& o, V a, V v) {
             o.warmup = parseInt(a, v, 0, 100000);
             o.warmupGiven = true;
         }},
        {{"--timings-json"}, "F", "write the per-pass timings as JSON (for scripts and benchmarks)",
         [](Options& o, V, V v) { o.timingsJson = v; }},
        {{"--disable-pass"}, "P",
         "switch pass P off (repeatable): in-place passes pass their input through, passes that create "
         "textures clear them instead (see 'lightpass graph')",
         [](Options& o, V, V v) { o.base.disabledPasses.insert(v); }},
        {{"--ibl-cache"}, "DIR", "also keep converted/baked environments on disk in DIR",
         [](Options& o, V, V v) { o.base.environment.cacheDir = v; }},
        {{"--floors"}, "",
         "also measure this GPU's compute and fragment bandwidth and print each pass's floor (bytes it "
         "must move / bandwidth) and measured/floor",
         [](Options& o, V, V) { o.floors = true; }},
        {{"--dot"}, "F", "with graph: also write Graphviz DOT", [](Options& o, V, V v) { o.dot = v; }},
        {{"--explain"}, "",
         "with graph: list every candidate pass, whether it runs, and why not (\"skipped: scene has no "
         "shadow-casting light\")",
         [](Options& o, V, V) { o.explain = true; }},
        {{"--knob"}, "K", "sweep: a knob to sweep (repeatable; A+B sweeps every combination)",
         [](Options& o, V, V v) { o.knobs.push_back(v); }},
        {{"--out-dir"}, "D", "sweep: where sweep.csv, sweep.md and the images go (default sweep)",
         [](Options& o, V, V v) { o.outDir = v; }},
        {{"--sweep"}, "D", "report: the page of a sweep output folder D (its sweep.csv and images) instead of a frame",
         [](Options& o, V, V v) { o.sweepDir = v; }},
        {{"--bench"}, "F.json", "report: the page of a bench --timings-json file instead of a frame",
         [](Options& o, V, V v) { o.benchJson = v; }},
        {{"--vary"}, "AXIS", "bench: 'FLAG V1,V2,..' or 'FLAGS A|FLAGS B' (repeatable)",
         [](Options& o, V, V v) { o.varies.push_back(v); }},
        {{"--max-seconds"}, "S", "bench: about S seconds of frames per variant at most",
         [](Options& o, V a, V v) {
             o.maxSeconds = parseFloat(a, v);
             if (o.maxSeconds <= 0) throw Error(a + " " + v + ": expected a positive number of seconds");
         }},
        {{"--min-frames"}, "N", "bench: timed frames a capped variant still gets (default 10)",
         [](Options& o, V a, V v) { o.minFrames = parseInt(a, v, 1, 100000); }},
        {{"--no-vsync"}, "", "viewer: don't wait for vertical sync (for measuring)", [](Options& o, V, V) { o.vsync = false; }},
        {{"--screenshot-dir"}, "D", "viewer: where F12 writes lightpass-N.png (+ .exr of the HDR buffer)",
         [](Options& o, V, V v) { o.screenshotDir = v; }},
        {{"--hide-panel"}, "", "viewer: start with the ImGui panel hidden (Tab toggles it)",
         [](Options& o, V, V) { o.hidePanel = true; }},
        {{"--screenshot-ui"}, "", "viewer: F12 captures the whole window, panel included",
         [](Options& o, V, V) { o.screenshotUi = true; }},
        {{"--panel-rows-out"}, "F",
         "viewer (for tests): whenever they change, write the panel's position and size and its pass "
         "rows (name, checkbox centre, state) to F",
         [](Options& o, V, V v) { o.panelRowsOut = v; }},
        {{"-v", "--verbose"}, "", "log debug messages (GL debug output included)", [](Options& o, V, V) { o.verbose = true; }},
        {{"-q", "--quiet"}, "", "log errors only (no progress either)", [](Options& o, V, V) { o.quiet = true; }},
        {{"--progress"}, "", "show progress (frames, IBL bake, bench, sweep) from the start, not only for work "
         "past 2 s", [](Options& o, V, V) { o.progress = true; }},
    };
}

const CommandFlag* findCommandFlag(const std::string& flag) {
    for (const CommandFlag& f : commandFlags())
        if (std::find(f.names.begin(), f.names.end(), flag) != f.names.end()) return &f;
    return nullptr;
}
}  // namespace

const std::vector<CommandFlag>& commandFlags() {
    static const std::vector<CommandFlag> flags = makeCommandFlags();
    return flags;
}

Options parseArgs(const std::vector<std::string>& args) {
    Options o;
    size_t i = 0;
    o.command = "viewer";
    if (!args.empty() && args[0].rfind("-", 0) != 0) {
        o.command = args[0];
        i = 1;
        if (o.command != "render" && o.command != "graph" && o.command != "view" && o.command != "info" &&
            o.command != "sweep" && o.command != "bench" && o.command != "report" && o.command != "reference")
            throw Error("unknown command '" + o.command + "' (render, reference, graph, view, sweep, bench, report, info; see --help)");
        if (o.command == "view") {
            if (i >= args.size() || args[i].rfind("-", 0) == 0) throw Error("view: expected a .json scene or an .obj, .gltf or .glb model");
            std::string f = args[i++];
            (isModelPath(f) ? o.model : o.scene) = f;
            o.command = "viewer";
        }
    }
    auto value = [&](const std::string& flag) -> std::string {
        if (i + 1 >= args.size()) throw Error(flag + ": missing value");
        return args[++i];
    };
    for (; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (const CommandFlag* c = findCommandFlag(a)) {
            c->apply(o, a, c->metavar.empty() ? std::string() : value(a));
            continue;
        }
        const KnobFlag* knobFlag = nullptr;
        if (const KnobEntry* knob = findKnobFlag(a, &knobFlag)) {
            knob->field.set(o.base, knobFlag->fixedValue ? *knobFlag->fixedValue : parseKnobValue(*knob, a, value(a)));
            continue;
        }
        throw Error("unknown flag '" + a + "' (see --help)");
    }
    o.exposure = o.base.exposureEV;
    if (o.command == "report" && !o.framesGiven) o.frames = 10;  // a median needs several frames
    if (!o.warmupGiven) o.warmup = o.frames > 1 ? 5 : 0;
    if (o.command == "help" || o.command == "info" || o.command == "version") return o;
    if (!o.scene.empty() && !o.model.empty()) throw Error("give --scene or --model, not both");
    if ((o.command == "sweep" || o.command == "bench") && !o.warmupGiven) o.warmup = 10;
    if (o.bouncesGiven && o.base.pathTrace.directOnly) throw Error("--bounces and --direct-only: give one of them");
    if (o.command == "reference") o.base.renderPath = RenderPath::PathTraced;
    if (o.sweepReferenceGiven && o.command != "sweep") throw Error("--reference: only for sweep (lightpass sweep --reference pathtraced)");
    if (o.command == "render" || o.command == "graph" || o.command == "sweep" || o.command == "bench" ||
        o.command == "reference") {
        if (o.scene.empty() && o.model.empty()) throw Error(o.command + ": --scene F or --model F is required");
    }
    if (o.command == "report") {
        if (o.out.empty()) throw Error("report: --out DIR is required (the folder index.html is written to)");
        const int sources = int(!o.sweepDir.empty()) + int(!o.benchJson.empty()) + int(!o.scene.empty() || !o.model.empty());
        if (sources > 1) throw Error("report: give one of --scene F / --model F, --sweep D and --bench F.json");
        if (sources == 0) throw Error("report: --scene F, --model F, --sweep D or --bench F.json is required");
        if (!o.exr.empty()) throw Error("report: --exr is not used (the page shows the tone-mapped views)");
        return o;
    }
    if (!o.sweepDir.empty()) throw Error("--sweep: only for report (lightpass report --sweep D --out DIR)");
    if (!o.benchJson.empty()) throw Error("--bench: only for report (lightpass report --bench F.json --out DIR)");
    if ((o.command == "render" || o.command == "reference") && o.out.empty() && o.exr.empty())
        throw Error(o.command + ": --out F.png (or --exr F.exr) is required");
    if (!o.out.empty() && std::filesystem::path(o.out).extension() != ".png")
        throw Error("--out " + o.out + ": expected a .png file name");
    if (!o.exr.empty() && std::filesystem::path(o.exr).extension() != ".exr")
        throw Error("--exr " + o.exr + ": expected a .exr file name");
    if (!o.exr.empty() && o.view != DebugView::Final && o.view != DebugView::Lighting && !isShadingTermView(o.view))
        throw Error("--exr: the '" + std::string(viewName(o.view)) + "' view has no HDR buffer; use --view final, lighting, " +
                    viewList(termViews(), ", ") + " or emissive");
    if (o.command == "viewer" && o.scene.empty() && o.model.empty()) o.scene = defaultScenePath();
    return o;
}

RenderSettings renderSettings(const Options& o) {
    RenderSettings s = o.base;
    s.width = o.width;
    s.height = o.height;
    s.view = o.view;
    s.keepHdr = !o.exr.empty();
    if (s.aa.method == AntiAliasing::Ssaa && s.renderScale < 1.0f)
        logInfo("--render-scale below 1 renders below the output size: --aa ssaa (the default) is not used");
    return s;
}

Scene sceneFromOptions(const Options& o) {
    Scene scene = o.model.empty() ? loadScene(o.scene) : sceneForModel(o.model, o.modelZUp);
    if (o.environment) replaceEnvironment(scene, *o.environment);
    if (!o.cameraPath.empty()) scene.cameraPath = loadCameraPath(o.cameraPath);
    if (o.materialVariant) chooseMaterialVariant(scene, *o.materialVariant);
    if (o.animation) playAnimations(scene, *o.animation);
    if (o.cameraPosition) scene.cameraPath.reset();  // --camera fixes the camera
    if (o.cameraPosition) scene.camera.position = *o.cameraPosition;
    if (o.cameraTarget) scene.camera.target = *o.cameraTarget;
    if (o.cameraFov) scene.camera.fovYDegrees = *o.cameraFov;
    return scene;
}

double frameTime(const Options& o, int i) { return o.fps > 0.0 ? o.time + double(i) / o.fps : o.time; }
double warmupTime(const Options& o) { return o.fps > 0.0 ? o.time - 1.0 / o.fps : o.time; }
int warmupFrames(const Options& o, int warmup) { return o.fps > 0.0 ? std::max(warmup, 1) : warmup; }

}  // namespace lp::app
