#include "app/cli.hpp"

#include <cmath>
#include <filesystem>

#include "engine/core/error.hpp"
#include "frame/frame_builder.hpp"

namespace lp::app {

std::string helpText() {
    return R"(lightpass - a multi-pass deferred renderer you can see, toggle and measure

usage:
  lightpass                         open the viewer on scenes/cornell.json (needs a display)
  lightpass view FILE               open the viewer on a scene (.json) or a model (.obj)
  lightpass render (--scene F | --model F.obj) --out F.png [options]
                                    render headless (EGL; NVIDIA if present, else Mesa llvmpipe)
                                    and print each pass's GPU time (median over the frames)
  lightpass graph (--scene F | --model F.obj) [--view V] [--dot F.dot] [--explain]
                                    print the frame graph: passes that run, passes culled and
                                    why, what each reads and writes, transient textures
  lightpass sweep (--scene F | --model F.obj) --knob K [--knob K2 ...] [--out-dir D]
                                    render every value of each quality knob; GPU ms per pass
                                    and error against the knob's best value -> D/sweep.csv,
                                    D/sweep.md and images (bench/sweep_report.py adds FLIP
                                    and a Pareto plot); --knob A+B sweeps every combination
  lightpass bench (--scene F | --model F.obj) --vary 'FLAG V1,V2,..' [--vary ...] [flags]
                                    one process renders every combination of the --vary axes
                                    (an axis is 'FLAG V1,V2' or 'FLAGS A|FLAGS B'), GPU ms per
                                    pass (median of --frames after --warmup, default 10) and
                                    floors with --floors -> --timings-json F (default bench.json);
                                    --max-seconds S caps a slow variant's frames and warm-up
                                    (never below --min-frames N, default 10)
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
  --brdf B          blinn-phong | ggx: the analytic BRDF of the lights (default blinn-phong;
                    ggx: Cook-Torrance, roughness from MTL Ns, F0 = Ks)
  --no-shadows      no shadow maps (shadow-casting directional lights light everything)
  --shadow-size N   texels per side of each cascade's shadow map (16..8192, default 2048)
  --shadow-cascades N  cascades per light, 1..4 (default 4; practical log/linear splits)
  --shadow-split-lambda X  0 linear .. 1 logarithmic cascade splits (default 0.75)
  --pcf F           off | 3x3 | 5x5 | poisson: shadow filter (default 3x3)
  --shadow-depth-bias X   constant bias, shadow texels of depth (default 0.5)
  --shadow-slope-bias X   slope-scaled bias of the depth pass, glPolygonOffset factor (default 1)
  --shadow-normal-bias X  receiver offset along its normal, texels x (1 - N.L) (default 1)
  --view shadowmap  light-space depth of directional light --shadow-light N's shadow map (N = 0)
  --view environment | irradiance | prefiltered | dfg   environment debug views (README)
  --ibl             image-based lighting from the scene's environment map (replaces the ambient)
  --brdf-only       analytic lights + constant ambient only (the default)
  --tonemap T       lightpass | aces | pbr-neutral | agx   (default lightpass: pow(c/(c+1),1.2))
  --ibl-diffuse D   sh | cubemap: diffuse IBL from 9 SH coefficients or the irradiance cube (sh)
  --ibl-mip N       mip the 'prefiltered' view shows (0 = roughness 0)
  --ibl-cache DIR   also keep converted/baked environments on disk in DIR
  --env-size N      environment cube face size, a power of two (512)
  --ibl-specular-size N  prefiltered cube face size, cube size / 2^k (256)
  --ibl-specular-levels N  prefiltered mips, roughness m/(N-1) at mip m (6)
  --ibl-samples N   GGX samples per prefiltered texel (256)
  --ibl-irradiance-size N / --ibl-irradiance-samples N   irradiance cube (32, 512)
  --dfg-size N / --dfg-samples N   split-sum DFG LUT size and samples (128, 512)
  --local-lights M  local-light method: fullscreen | scissor | volumes | tiled (default tiled);
                    all four give the same image
  --no-local-lights draw no local lights (the pass leaves the frame graph)
  --light-count N   draw the scene's first N point lights, plus generated demo lights up to N
                    (deterministic, spread through the scene's bounds; e.g. 4096)
  --no-scissor      the scissor method draws every light full screen (the viewer's 'x')
  --globes          draw each local light as a small flat-lit globe
  --no-local-specular  local lights add diffuse only
  --specular-outside-range  diffuse limited by the range, specular (1/d^2) not (seed 003)
  --view light-ranges | lights-per-tile  overlay each light's rectangle/volume, or lights per 16x16 tile
  --light-range-scale S  each local light's range x S, 0.01..1 (default 1 = full range; < 1 cuts
                    lights short, cheaper and darker: a sweep knob)
  --render-scale S  G-buffer, lighting and post effects at S x the output size, 0.25..1, upsampled
                    bilinearly before the tone map (default 1; a sweep knob)
  --gbuffer F       G-buffer normal format: unpacked | seed-packed | seed-packed-signed | two-angle |
                    oct16 | oct24 | oct32   (default unpacked; README "G-buffer formats")
  --gbuffer-position P  stored | depth | reversed-z: eye positions stored (RGBA32F) or rebuilt
                    from standard or reversed-Z depth (default stored)
  --bloom, --no-bloom  bloom on/off (default: the scene's effects.bloom.enabled)
  --bloom-method M  separable | mip-chain   (default separable; mip-chain: Jimenez 2014)
  --bloom-kernel N  blur width in pixels, 1..101 (default: the scene's, else 25)
  --bloom-threshold X, --bloom-knee X, --bloom-strength X   soft-knee bright pass and mix
  --bloom-clamp X   per-channel ceiling of what enters the blur (default 1000)
  --no-karis        mip-chain: no Karis average on the first downsample
  --bloom-blur S    compute | fragment: the GLSL separable blur's stage (default compute)
  --bloom-only      display the bloom buffer alone (seed 001's bloom view)
  --toon, --no-toon  toon ramp and outlines on/off (default: the scene's effects.toon.enabled)
  --toon-levels N   ramp bands, 1..64; --toon-edge T depth-edge threshold (relative depth step)
  --toon-normal-edge T  normal-edge threshold, sin of half the crease angle (default 0.5 = 60 deg)
  --post-backend B  auto | cuda | glsl: who runs bloom and toon (auto: CUDA on an NVIDIA GPU)
  --disable-pass P  switch pass P off (repeatable): in-place passes pass their input through,
                    passes that create textures clear them instead (see 'lightpass graph')
  --floors          also measure this GPU's compute and fragment bandwidth and print each pass's
                    floor (bytes it must move / bandwidth) and measured/floor
  --dot F           with graph: also write Graphviz DOT
  --explain         with graph: list every candidate pass, whether it runs, and why not
                    ("skipped: scene has no shadow-casting light")
  --all-passes      add every candidate pass even where the scene does not call for it (shadow
                    maps for every sun, local lights with none in view, colour sky, IBL, bloom at
                    strength 0); for measuring what the scene-driven graph saves, image may differ
  --no-vsync        viewer: don't wait for vertical sync (for measuring)
  --screenshot-dir D  viewer: where F12 writes lightpass-N.png (+ .exr of the HDR buffer)
  --hide-panel      viewer: start with the ImGui panel hidden (Tab toggles it)
  --screenshot-ui   viewer: F12 captures the whole window, panel included
  -v, --verbose     log debug messages (GL debug output included)
  -q, --quiet       log errors only

viewer keys (seed 001):
  1 depth  2 normals  3 diffuse  4 eye-space position  5 lighting  6 shininess  7 toon on/off
  8 bloom buffer alone  0 standard view  r reset camera  x toggle scissor  W/S/A/D/Q/Z move
  mouse drag: look  +/- exposure  Tab panel  h help  F12 screenshot  Esc quit
  (the panel also picks scenes and environments, and shaders/ edits reload while it runs)
)";
}

std::string sizeLabel(const RenderSettings& s) {
    std::string label = std::to_string(s.width) + "x" + std::to_string(s.height);
    const glm::ivec2 r = scaledRenderSize(s.width, s.height, s.renderScale);
    if (r.x == s.width && r.y == s.height) return label;
    char scale[16];
    std::snprintf(scale, sizeof scale, "%.2f", double(s.renderScale));
    return label + " (rendered at " + std::to_string(r.x) + "x" + std::to_string(r.y) + ", render scale " + scale + ")";
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
            o.command != "sweep" && o.command != "bench")
            throw Error("unknown command '" + o.command + "' (render, graph, view, sweep, bench, info; see --help)");
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
        else if (a == "--explain") o.explain = true;
        else if (a == "--all-passes") o.base.allPasses = true;
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
        else if (a == "--vary") o.varies.push_back(value(a));
        else if (a == "--min-frames") o.minFrames = parseInt(a, value(a), 1, 100000);
        else if (a == "--max-seconds") {
            std::string v = value(a);
            o.maxSeconds = parseFloat(a, v);
            if (o.maxSeconds <= 0) throw Error(a + " " + v + ": expected a positive number of seconds");
        }
        else if (a == "--disable-pass") o.base.disabledPasses.insert(value(a));
        else if (a == "--brdf") {
            std::string v = value(a);
            auto brdf = parseBrdf(v);
            if (!brdf) throw Error("--brdf " + v + ": unknown BRDF (blinn-phong, ggx)");
            o.base.brdf = *brdf;
        } else if (a == "--no-shadows") o.base.shadows.enabled = false;
        else if (a == "--shadow-size") o.base.shadows.size = parseInt(a, value(a), 16, 8192);
        else if (a == "--shadow-cascades") o.base.shadows.cascades = parseInt(a, value(a), 1, 4);
        else if (a == "--shadow-light") o.base.shadows.debugLight = parseInt(a, value(a), 0, 1000000);
        else if (a == "--pcf") {
            std::string v = value(a);
            auto filter = ShadowSettings::parseFilter(v);
            if (!filter) throw Error("--pcf " + v + ": unknown filter (off, 3x3, 5x5, poisson)");
            o.base.shadows.filter = *filter;
        } else if (a == "--shadow-split-lambda" || a == "--shadow-depth-bias" || a == "--shadow-slope-bias" ||
                   a == "--shadow-normal-bias") {
            std::string v = value(a);
            float x = parseFloat(a, v);
            const bool lambda = a == "--shadow-split-lambda";
            if (x < 0.0f || (lambda && x > 1.0f)) throw Error(a + " " + v + (lambda ? ": expected a number in [0, 1]" : ": expected a number >= 0"));
            (lambda ? o.base.shadows.splitLambda : a == "--shadow-depth-bias" ? o.base.shadows.depthBias
                      : a == "--shadow-slope-bias" ? o.base.shadows.slopeBias : o.base.shadows.normalBias) = x;
        }
        else if (a == "--ibl") o.base.environment.ibl = true;
        else if (a == "--brdf-only") o.base.environment.ibl = false;
        else if (a == "--tonemap") {
            std::string v = value(a);
            auto op = parseToneMap(v);
            if (!op) throw Error("--tonemap " + v + ": unknown operator (lightpass, aces, pbr-neutral, agx)");
            o.base.environment.toneMap = *op;
        } else if (a == "--ibl-diffuse") {
            std::string v = value(a);
            if (v != "sh" && v != "cubemap") throw Error("--ibl-diffuse " + v + ": expected sh or cubemap");
            o.base.environment.diffuse = v == "sh" ? IrradianceSource::SphericalHarmonics : IrradianceSource::Cubemap;
        } else if (a == "--ibl-mip") o.base.environment.debugMip = parseInt(a, value(a), 0, 16);
        else if (a == "--ibl-cache") o.base.environment.cacheDir = value(a);
        else if (a == "--env-size") o.base.environment.cubeSize = parseInt(a, value(a), 4, 4096);
        else if (a == "--ibl-specular-size") o.base.environment.specularSize = parseInt(a, value(a), 4, 4096);
        else if (a == "--ibl-specular-levels") o.base.environment.specularLevels = parseInt(a, value(a), 1, 13);
        else if (a == "--ibl-samples") o.base.environment.specularSamples = parseInt(a, value(a), 1, 65536);
        else if (a == "--ibl-irradiance-size") o.base.environment.irradianceSize = parseInt(a, value(a), 1, 1024);
        else if (a == "--ibl-irradiance-samples") o.base.environment.irradianceSamples = parseInt(a, value(a), 1, 65536);
        else if (a == "--dfg-size") o.base.environment.dfgSize = parseInt(a, value(a), 2, 1024);
        else if (a == "--dfg-samples") o.base.environment.dfgSamples = parseInt(a, value(a), 1, 65536);
        else if (a == "--local-lights") {
            std::string v = value(a);
            auto m = parseLocalLightMethod(v);
            if (!m) throw Error("--local-lights " + v + ": unknown method (fullscreen, scissor, volumes, tiled)");
            o.base.localLights.method = *m;
        } else if (a == "--no-local-lights") o.base.localLights.enabled = false;
        else if (a == "--light-count") o.base.localLights.lightCount = parseInt(a, value(a), 0, 1000000);
        else if (a == "--no-scissor") o.base.localLights.scissor = false;
        else if (a == "--globes") o.base.localLights.globes = true;
        else if (a == "--no-local-specular") o.base.localLights.specular = false;
        else if (a == "--specular-outside-range") o.base.localLights.specularOutsideRange = true;
        else if (a == "--render-scale") {
            const std::string v = value(a);
            const float x = parseFloat(a, v);
            if (!(x >= kMinRenderScale && x <= 1.0f)) throw Error("--render-scale " + v + ": expected a number in [0.25, 1]");
            o.base.renderScale = x;
        } else if (a == "--light-range-scale") {
            const std::string v = value(a);
            const float x = parseFloat(a, v);
            if (x < 0.01f || x > 1.0f) throw Error("--light-range-scale " + v + ": expected a number in [0.01, 1]");
            o.base.localLights.rangeScale = x;
        } else if (a == "--gbuffer") {
            const std::string v = value(a);
            auto f = parseGBufferFormat(v);
            if (!f) throw Error("--gbuffer " + v + ": unknown format (" + gbufferFormatNames() + ")");
            o.base.gbuffer.normal = *f;
        } else if (a == "--gbuffer-position") {
            const std::string v = value(a);
            auto m = parseGBufferPosition(v);
            if (!m) throw Error("--gbuffer-position " + v + ": unknown mode (" + gbufferPositionNames() + ")");
            o.base.gbuffer.position = *m;
        }
        else if (a == "--bloom") o.base.post.bloom = true;  // flags
        else if (a == "--no-bloom") o.base.post.bloom = false;
        else if (a == "--bloom-method") {
            std::string v = value(a);
            if (v == "separable") o.base.post.bloomMethod = PostSettings::BloomMethod::Separable;
            else if (v == "mip-chain") o.base.post.bloomMethod = PostSettings::BloomMethod::MipChain;
            else throw Error("--bloom-method " + v + ": expected separable or mip-chain");
        } else if (a == "--bloom-kernel") o.base.post.bloomKernel = parseInt(a, value(a), 1, 101);
        else if (a == "--bloom-threshold" || a == "--bloom-knee" || a == "--bloom-strength" || a == "--bloom-clamp" ||
                 a == "--toon-edge" || a == "--toon-normal-edge") {
            std::string v = value(a);
            float x = parseFloat(a, v);
            if (x < 0.0f || (a == "--bloom-clamp" && x == 0.0f))
                throw Error(a + " " + v + ": expected a " + (a == "--bloom-clamp" ? "positive" : "non-negative") + " number");
            if (a == "--bloom-threshold") o.base.post.bloomThreshold = x;
            else if (a == "--bloom-knee") o.base.post.bloomKnee = x;
            else if (a == "--bloom-strength") o.base.post.bloomStrength = x;
            else if (a == "--bloom-clamp") o.base.post.bloomHighlight = x;
            else if (a == "--toon-edge") o.base.post.toonEdge = x;
            else o.base.post.toonNormalEdge = x;
        } else if (a == "--bloom-blur") {
            std::string v = value(a);
            if (v != "compute" && v != "fragment") throw Error("--bloom-blur " + v + ": expected compute or fragment");
            o.base.post.bloomFragmentBlur = v == "fragment";
        } else if (a == "--no-karis") o.base.post.bloomKaris = false;
        else if (a == "--bloom-only") o.base.post.bloomOnly = true;
        else if (a == "--toon") o.base.post.toon = true;
        else if (a == "--no-toon") o.base.post.toon = false;
        else if (a == "--toon-levels") o.base.post.toonLevels = parseInt(a, value(a), 1, 64);
        else if (a == "--post-backend") {
            std::string v = value(a);
            if (v == "auto") o.base.post.backend = PostSettings::Backend::Auto;
            else if (v == "cuda") o.base.post.backend = PostSettings::Backend::Cuda;
            else if (v == "glsl") o.base.post.backend = PostSettings::Backend::Glsl;
            else throw Error("--post-backend " + v + ": expected auto, cuda or glsl");
        }
        else if (a == "-v" || a == "--verbose") o.verbose = true;
        else if (a == "-q" || a == "--quiet") o.quiet = true;
        else throw Error("unknown flag '" + a + "' (see --help)");
    }
    if (!warmupGiven) o.warmup = o.frames > 1 ? 5 : 0;
    if (o.command == "help" || o.command == "info") return o;
    if (!o.scene.empty() && !o.model.empty()) throw Error("give --scene or --model, not both");
    if ((o.command == "sweep" || o.command == "bench") && !warmupGiven) o.warmup = 10;
    if (o.command == "render" || o.command == "graph" || o.command == "sweep" || o.command == "bench") {
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

RenderSettings renderSettings(const Options& o) {
    RenderSettings s = o.base;
    s.width = o.width;
    s.height = o.height;
    s.view = o.view;
    s.exposureEV = o.exposure;
    s.keepHdr = !o.exr.empty();
    return s;
}

}  // namespace lp::app
