#include "frame/knobs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <type_traits>

#include "engine/core/error.hpp"
#include "engine/post/post_config.hpp"
#include "engine/render/ibl_lights.hpp"
#include "engine/render/local_lights.hpp"
#include "engine/render/shadows.hpp"

namespace lp {

namespace {

template <class T> struct IsOptional : std::false_type {};
template <class T> struct IsOptional<std::optional<T>> : std::true_type {};

// Typed access to one RenderSettings member: `at` is [](auto& s) -> auto& { return s.shadows.size; }
// (one generic lambda serves the getter, on a const RenderSettings, and the setter).
template <class At>
KnobField member(At at) {
    using Member = std::decay_t<decltype(at(std::declval<RenderSettings&>()))>;
    KnobField f;
    if constexpr (IsOptional<Member>::value) {
        using T = typename Member::value_type;
        f.optional = true;
        f.get = [at](const RenderSettings& s) -> KnobValueOrUnset {
            const auto& v = at(s);
            return v ? KnobValueOrUnset(double(*v)) : std::nullopt;
        };
        f.set = [at](RenderSettings& s, KnobValueOrUnset v) { at(s) = v ? Member(T(*v)) : std::nullopt; };
    } else {
        f.get = [at](const RenderSettings& s) -> KnobValueOrUnset { return double(at(s)); };
        f.set = [at](RenderSettings& s, KnobValueOrUnset v) {
            if (v) at(s) = Member(*v);
        };
    }
    return f;
}

template <class At>
KnobEntry intKnob(const std::string& name, At at, int min, int max) {
    KnobEntry k;
    k.name = name;
    k.type = KnobType::Int;
    k.field = member(at);
    k.range = {double(min), double(max)};
    return k;
}

template <class At>
KnobEntry floatKnob(const std::string& name, At at, KnobRange range) {
    KnobEntry k;
    k.name = name;
    k.type = KnobType::Float;
    k.field = member(at);
    k.range = range;
    return k;
}

template <class At>
KnobEntry boolKnob(const std::string& name, At at) {
    KnobEntry k;
    k.name = name;
    k.type = KnobType::Bool;
    k.field = member(at);
    return k;
}

// An enum (or bool) member given by name: value i is options[i], named nameOf(options[i]).
template <class E, class At, class Name>
KnobEntry choiceKnob(const std::string& name, At at, const std::vector<E>& options, Name nameOf) {
    KnobEntry k;
    k.name = name;
    k.type = KnobType::Choice;
    for (E e : options) k.choices.push_back(nameOf(e));
    k.field.get = [at, options](const RenderSettings& s) -> KnobValueOrUnset {
        return double(std::find(options.begin(), options.end(), at(s)) - options.begin());
    };
    k.field.set = [at, options](RenderSettings& s, KnobValueOrUnset v) {
        if (v) at(s) = options.at(size_t(*v));
    };
    return k;
}

// A choice of every value of an enum's table (engine/core/enum_table.hpp), in the table's order.
template <typename At, typename E, std::size_t N>
KnobEntry choiceKnob(const std::string& name, At at, const EnumName<E> (&table)[N]) {
    return choiceKnob(name, at, enumValues(table), [&table](E e) { return enumName(table, e); });
}

KnobFlag valueFlag(const std::string& flag) { return {flag, std::nullopt}; }
KnobFlag setsFlag(const std::string& flag, double value) { return {flag, value}; }

// The froxel grid's sweeps (cluster-size, cluster-slices) time the kernel that uses the grid: the
// clustered method with its own kernel, whatever --clustered-kernel auto would pick.
void sweepClusteredKernel(RenderSettings& s, double) {
    s.localLights.method = LocalLightMethod::Clustered;
    s.localLights.clusteredKernel = ClusteredKernel::Froxels;
}

constexpr double kNoMax = std::numeric_limits<double>::infinity();
const KnobRange kNonNegative{0.0, kNoMax};

// Sweep side effects: a swept value switches on the feature it measures.
void shadowsOn(RenderSettings& s, double) { s.shadows.enabled = true; }
void iblOn(RenderSettings& s, double) { s.environment.ibl = true; }
void bloomOn(RenderSettings& s, double) { s.post.bloom = true; }
void aoOn(RenderSettings& s, double) { s.ao.enabled = true; }  // the method stays --bloom-method's

// The --aa choices a user is offered (each one implemented).
std::vector<KnobEntry> makeKnobTable() {
    std::vector<KnobEntry> t;
    // [knobs] one entry per user-facing setting, grouped by feature area. The order is --help's,
    // the panel's within a section, and the sweep's (allKnobs()). Defaults come from RenderSettings{}.
    // Sweep values are cheapest first, the last is the reference; monotone = false where a cheaper
    // value is not always further from it.

    // ---- G-buffer layout ----
    {
        KnobEntry k = choiceKnob("gbuffer-format", [](auto& s) -> auto& { return s.gbuffer.normal; },
                                 kGBufferNormalFormatNames);
        k.flags = {valueFlag("--gbuffer")};
        k.choiceNoun = "format";
        k.help = "G-buffer normal format, see docs/gbuffer.md (every format keeps the base colour in "
                 "8-bit sRGB: an sRGB texture's codes exactly)";
        k.sweep = {{"oct16", "oct24", "oct32", "seed-packed", "seed-packed-signed", "two-angle", "unpacked"},
                   false,
                   "G-buffer normal format (--gbuffer), fewest bytes first: octahedral 16/24/32 bits, seed 001's "
                   "packed xy (wrong where normals face away), its signed fix, seed 004's two angles, unpacked "
                   "RGBA32F (reference). Not monotone: seed-packed's failure is not a precision loss",
                   nullptr};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = choiceKnob("gbuffer-position", [](auto& s) -> auto& { return s.gbuffer.position; },
                                 kGBufferPositionModeNames);
        k.flags = {valueFlag("--gbuffer-position")};
        k.choiceNoun = "mode";
        k.help = "eye positions stored (RGBA32F) or rebuilt from standard or reversed-Z depth";
        k.sweep = {{"depth", "reversed-z", "stored"},
                   true,
                   "eye positions (--gbuffer-position): rebuilt from standard depth, from reversed-Z depth "
                   "(finer far away), stored RGBA32F (reference, 16 more bytes a pixel)",
                   nullptr};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = choiceKnob("gbuffer-mode", [](auto& s) -> auto& { return s.gbuffer.mode; },
                                 kGBufferModeNames);
        k.flags = {valueFlag("--gbuffer-mode")};
        k.choiceNoun = "mode";
        k.help = "classic: the G-buffer pass rasterises every target; visibility: depth and a triangle id are "
                 "rasterised and a compute pass rebuilds the same targets (docs/visibility-buffer.md); auto: "
                 "visibility on a GPU, classic on a software rasteriser or for a scene whose geometry exceeds the GPU's "
                 "storage blocks (lightpass info, graph --explain say which)";
        k.panel = {PanelSection::View, PanelWidget::Combo, "G-buffer mode", ""};
        k.sweep = {{"visibility", "classic"},
                   false,
                   "how the G-buffer is made (--gbuffer-mode): a visibility buffer resolved by compute, or the "
                   "classic raster (reference). The same targets by design: the error is ~0",
                   nullptr};
        t.push_back(std::move(k));
    }

    // ---- shadows ----
    {
        KnobEntry k = boolKnob("shadows", [](auto& s) -> auto& { return s.shadows.enabled; });
        k.flags = {setsFlag("--no-shadows", 0)};
        k.help = "no shadow maps (shadow-casting directional lights light everything)";
        k.panel = {PanelSection::Shadows, PanelWidget::Checkbox, "enabled", ""};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = intKnob("shadow-size", [](auto& s) -> auto& { return s.shadows.size; }, 16, 8192);
        k.flags = {valueFlag("--shadow-size")};
        k.help = "texels per side of each cascade's shadow map";
        k.panel = {PanelSection::Shadows, PanelWidget::PowersOfTwo, "map size", ""};
        k.sweep = {{"512", "1024", "2048", "4096"}, true,
                   "texels per side of each cascade's shadow map (--shadow-size); 4096 is the reference", shadowsOn};
        k.sweep.term = LightTerm::Suns;
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = choiceKnob("shadow-pcf", [](auto& s) -> auto& { return s.shadows.filter; },
                                 ShadowSettings::kFilterNames);
        k.flags = {valueFlag("--pcf")};
        k.choiceNoun = "filter";
        k.help = "shadow filter";
        k.panel = {PanelSection::Shadows, PanelWidget::Combo, "filter", ""};
        k.sweep = {{"off", "3x3", "5x5", "poisson"}, false,
                   "shadow filter (--pcf): off, 3x3, 5x5, poisson (reference). Not monotone: the filters "
                   "differ in penumbra shape, not only in sample count",
                   shadowsOn};
        k.sweep.term = LightTerm::Suns;
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = intKnob("shadow-cascades", [](auto& s) -> auto& { return s.shadows.cascades; }, 1, 4);
        k.flags = {valueFlag("--shadow-cascades")};
        k.help = "cascades per light, practical log/linear splits";
        k.panel = {PanelSection::Shadows, PanelWidget::Slider, "cascades", ""};
        k.sweep = {{"1", "2", "3", "4"}, false,
                   "cascades per shadowed light (--shadow-cascades), 4 is the reference. Not monotone: each "
                   "count splits the depth range differently",
                   shadowsOn};
        k.sweep.term = LightTerm::Suns;
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = floatKnob("shadow-split-lambda", [](auto& s) -> auto& { return s.shadows.splitLambda; }, {0.0, 1.0});
        k.flags = {valueFlag("--shadow-split-lambda")};
        k.help = "0 linear .. 1 logarithmic cascade splits";
        k.panel = {PanelSection::Shadows, PanelWidget::Slider, "split lambda", "%.2f"};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = floatKnob("shadow-depth-bias", [](auto& s) -> auto& { return s.shadows.depthBias; }, kNonNegative);
        k.flags = {valueFlag("--shadow-depth-bias")};
        k.help = "constant bias, shadow texels of depth";
        k.panel = {PanelSection::Shadows, PanelWidget::Slider, "depth bias", "%.2f texels"};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = floatKnob("shadow-slope-bias", [](auto& s) -> auto& { return s.shadows.slopeBias; }, kNonNegative);
        k.flags = {valueFlag("--shadow-slope-bias")};
        k.help = "slope-scaled bias of the depth pass, glPolygonOffset factor";
        k.panel = {PanelSection::Shadows, PanelWidget::Slider, "slope bias", "%.2f"};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = floatKnob("shadow-normal-bias", [](auto& s) -> auto& { return s.shadows.normalBias; }, kNonNegative);
        k.flags = {valueFlag("--shadow-normal-bias")};
        k.help = "receiver offset along its normal, texels x (1 - N.L)";
        k.panel = {PanelSection::Shadows, PanelWidget::Slider, "normal bias", "%.2f texels"};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = boolKnob("shadow-culling", [](auto& s) -> auto& { return s.shadows.cullCasters; });
        k.flags = {setsFlag("--shadow-culling", 1), setsFlag("--no-shadow-culling", 0)};
        k.help = "each sun cascade draws only the caster clusters whose bounds reach its tile";
        k.panel = {PanelSection::Shadows, PanelWidget::Checkbox, "cull casters", ""};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = choiceKnob("shadow-raster", [](auto& s) -> auto& { return s.shadows.raster; },
                                 ShadowSettings::kRasterNames);
        k.flags = {valueFlag("--shadow-raster")};
        k.choiceNoun = "raster";
        k.help = "sun cascades' caster raster: conservative (no crease leaks), plain (early-Z, leaks at creases), "
                 "split (faces towards the light plain, faces away conservative), compute (plain's depths from a "
                 "compute rasteriser, large triangles on the hardware) or auto (the fastest on this GPU, measured once "
                 "and cached)";
        k.panel = {PanelSection::Shadows, PanelWidget::Combo, "caster raster", ""};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = choiceKnob("shadow-cache", [](auto& s) -> auto& { return s.shadows.cache; }, std::vector<bool>{true, false},
                                 [](bool on) { return on ? "on" : "off"; });
        k.flags = {valueFlag("--shadow-cache")};
        k.help = "keep each sun's shadow atlas across frames and redraw a cascade only when its light matrix, the "
                 "casters, the caster raster (hardware or geometry-shader growth included) or the slope bias changed; "
                 "likewise each point light's shadow cube, redrawn only when the light or a caster within its range "
                 "moved or changed";
        k.choiceNoun = "setting";
        k.panel = {PanelSection::Shadows, PanelWidget::Combo, "cascade cache", ""};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = choiceKnob("shadow-scroll", [](auto& s) -> auto& { return s.shadows.scroll; }, std::vector<bool>{true, false},
                                 [](bool on) { return on ? "on" : "off"; });
        k.flags = {valueFlag("--shadow-scroll")};
        k.help = "with --shadow-cache: a cascade whose square moved by whole texels keeps the overlapping part of its tile, "
                 "moved by a GPU copy, and redraws only the newly covered strips (off: the whole tile is redrawn)";
        k.choiceNoun = "setting";
        k.panel = {PanelSection::Shadows, PanelWidget::Combo, "cascade scroll", ""};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = choiceKnob("shadow-size-hold", [](auto& s) -> auto& { return s.shadows.sizeHold; },
                                 std::vector<bool>{false, true}, [](bool on) { return on ? "on" : "off"; });
        k.flags = {valueFlag("--shadow-size-hold")};
        k.help = "each sun cascade's square keeps last frame's size while that still holds its slice and is at most "
                 "2^(1/4) larger than needed: a zooming or moving camera scrolls or keeps cached tiles instead of "
                 "redrawing them whole, at up to 19% less resolution while held";
        k.choiceNoun = "setting";
        k.panel = {PanelSection::Shadows, PanelWidget::Combo, "cascade size hold", ""};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = intKnob("shadow-redraw-budget", [](auto& s) -> auto& { return s.shadows.redrawBudget; }, 0, 64);
        k.flags = {valueFlag("--shadow-redraw-budget")};
        k.help = "with --shadow-cache: at most this many quarter tiles of resized sun cascade squares (a scroll counts "
                 "as one) are drawn per frame, all suns together (0: no limit, resized squares drawn whole at once); a "
                 "cascade whose new square is not drawn yet keeps its previous square, and the next cascade shades the "
                 "pixels it misses";
        k.panel = {PanelSection::Shadows, PanelWidget::Slider, "redraw budget (quarter tiles)", ""};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = floatKnob("shadow-origin-step", [](auto& s) -> auto& { return s.shadows.originStep; },
                                {0.0, double(kMaxShadowOriginStep)});
        k.flags = {valueFlag("--shadow-origin-step")};
        k.help = "each sun cascade's square is this fraction of its side larger than its slice needs, and its origin "
                 "moves in steps of that much (0: one texel): a moving camera redraws cached cascades less often, at "
                 "that fraction less shadow-map resolution";
        k.panel = {PanelSection::Shadows, PanelWidget::Slider, "origin step", "%.3f"};
        k.sweep = {{"0.25", "0.125", "0.0625", "0"},
                   true,
                   "room a sun cascade's square leaves for the camera (--shadow-origin-step), as a fraction of its side: "
                   "that much less resolution, fewer redraws with --shadow-cache on a moving camera; 0 (a one-texel grid) "
                   "is the reference",
                   shadowsOn};
        k.sweep.term = LightTerm::Suns;
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = choiceKnob("shadow-conservative", [](auto& s) -> auto& { return s.shadows.conservativeRaster; },
                                 ShadowSettings::kConservativeRasterNames);
        k.flags = {valueFlag("--shadow-conservative")};
        k.choiceNoun = "conservative raster";
        k.help = "how conservative and split grow casters: hardware (GL_NV_conservative_raster, no geometry shader), "
                 "geometry-shader, or auto (hardware where the GPU has GL_NV_conservative_raster and "
                 "GL_NV_fragment_shader_barycentric)";
        k.panel = {PanelSection::Shadows, PanelWidget::Combo, "conservative raster", ""};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = intKnob("shadow-light", [](auto& s) -> auto& { return s.shadows.debugLight; }, 0, 1000000);
        k.flags = {valueFlag("--shadow-light")};
        k.help = "--view shadowmap shows this directional light's shadow map";
        t.push_back(std::move(k));
    }

    // ---- lighting model, environment, image-based lighting, tone map ----
    {
        KnobEntry k = choiceKnob("render-path", [](auto& s) -> auto& { return s.renderPath; },
                                 kRenderPathNames);
        k.flags = {valueFlag("--render-path")};
        k.choiceNoun = "render path";
        k.help = "how opaque surfaces are lit: deferred (G-buffer, then light passes) or forward+ (depth pre-pass, "
                 "then one forward pass over the clustered light lists) or pathtraced (the reference path tracer, --spp samples a "
                 "pixel; docs/path-tracer.md)";
        k.panel = {PanelSection::Lighting, PanelWidget::Combo, "render path", ""};
        k.sweep = {{"forward+", "deferred"}, false,
                   "render path (--render-path): forward+ against deferred (reference). The same shading by design: "
                   "the error is the G-buffer's rounding and fp16 sums between the deferred passes, so not monotone",
                   nullptr};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = choiceKnob("skinning", [](auto& s) -> auto& { return s.skinning; }, kSkinningModeNames);
        k.flags = {valueFlag("--skinning")};
        k.choiceNoun = "skinning mode";
        k.help = "where animated glTF models are posed each frame (skins, morph targets, animated nodes): gpu, the "
                 "skinning compute pass; cpu, posed on the CPU and uploaded (the reference). docs/motion.md";
        k.panel = {PanelSection::View, PanelWidget::Combo, "skinning", ""};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = choiceKnob("brdf", [](auto& s) -> auto& { return s.brdf; },
                                 kBrdfNames);
        k.flags = {valueFlag("--brdf")};
        k.choiceNoun = "BRDF";
        k.help = "the BRDF of every light; ggx: glTF 2.0's metallic-roughness BRDF for every material (MTL: "
                 "F0 = Ks, roughness from Ns, Kd weighted by 1 - F); blinn-phong: the seeds' Kd/pi + normalised "
                 "Blinn-Phong for suns and local lights";
        k.panel = {PanelSection::Lighting, PanelWidget::Combo, "BRDF", ""};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = choiceKnob("specular-masking", [](auto& s) -> auto& { return s.specularMasking; },
                                 kSpecularMaskingNames);
        k.flags = {valueFlag("--specular-masking")};
        k.choiceNoun = "masking";
        k.help = "GGX's Smith masking-shadowing (lights, IBL, extracted lights): height-correlated, the glTF "
                 "specification's (Filament's, Unreal's), or separable G1(V) G1(L), as Mitsuba's built-in BSDFs";
        k.panel = {PanelSection::Lighting, PanelWidget::Combo, "specular masking", ""};
        k.sweep = {{"separable", "height-correlated"}, false,
                   "GGX masking model (--specular-masking, with --ibl): separable against height-correlated "
                   "(reference, the glTF specification's). A different model, not an approximation: not monotone",
                   iblOn};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = boolKnob("ibl", [](auto& s) -> auto& { return s.environment.ibl; });
        k.field.sceneValue = [](const Scene& scene) { return double(scene.environment.ibl); };
        k.flags = {setsFlag("--ibl", 1), setsFlag("--brdf-only", 0)};
        k.help = "image-based lighting from the scene's environment map (replaces the ambient), or analytic "
                 "lights + constant ambient only";
        k.panel = {PanelSection::Lighting, PanelWidget::Combo, "IBL", ""};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = choiceKnob("tonemap", [](auto& s) -> auto& { return s.environment.toneMap; },
                                 kToneMapNames);
        k.flags = {valueFlag("--tonemap")};
        k.choiceNoun = "operator";
        k.help = "tone map operator; lightpass: pow(c/(c+1),1.2); aces: Filament's ACES (RRT + ODT fit); aces-legacy: "
                 "the Narkowicz fit without its 0.6 input scale (+0.74 EV)";
        k.panel = {PanelSection::View, PanelWidget::Combo, "tone map", ""};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = intKnob("ibl-mip", [](auto& s) -> auto& { return s.environment.debugMip; }, 0, 16);
        k.flags = {valueFlag("--ibl-mip")};
        k.help = "mip the 'prefiltered' view shows, 0 = roughness 0";
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = intKnob("ibl-samples", [](auto& s) -> auto& { return s.environment.specularSamples; }, 1, 65536);
        k.flags = {valueFlag("--ibl-samples")};
        k.help = "GGX samples per prefiltered texel";
        k.sweep = {{"64", "256", "1024", "4096"}, true,
                   "GGX samples per prefiltered texel (--ibl-samples, with --ibl); 4096 is the reference", iblOn};
        k.sweep.term = LightTerm::Environment;
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = intKnob("ibl-face-size", [](auto& s) -> auto& { return s.environment.cubeSize; }, 4, 4096);
        k.flags = {valueFlag("--env-size")};
        k.help = "environment cube face size, a power of two";
        k.sweep = {{"64", "128", "256", "512"}, true,
                   "environment cube face size (--env-size, prefiltered cube half of it, with --ibl); 512 "
                   "is the reference",
                   [](RenderSettings& s, double v) {
                       s.environment.ibl = true;
                       s.environment.specularSize = int(v) / 2;
                   }};
        k.sweep.term = LightTerm::Environment;
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = choiceKnob("ibl-diffuse", [](auto& s) -> auto& { return s.environment.diffuse; },
                                 kIrradianceSourceNames);
        k.flags = {valueFlag("--ibl-diffuse")};
        k.help = "diffuse IBL from 9 SH coefficients or the irradiance cube";
        k.sweep = {{"sh", "cubemap"}, true,
                   "diffuse IBL (--ibl-diffuse, with --ibl): 9 SH coefficients, or the cosine-sampled "
                   "irradiance cube (reference)",
                   iblOn};
        k.sweep.term = LightTerm::Environment;
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = choiceKnob("ibl-specular", [](auto& s) -> auto& { return s.environment.specular; },
                                 kIblSpecularNames);
        k.flags = {valueFlag("--ibl-specular")};
        k.choiceNoun = "method";
        k.help = "specular IBL: split-sum (one prefiltered lookup x DFG LUT) or sampled (per-pixel GGX samples "
                 "of the prefiltered chain: the lobe's shape at grazing view)";
        k.panel = {PanelSection::Lighting, PanelWidget::Combo, "IBL specular", ""};
        k.sweep = {{"split-sum", "sampled"}, true,
                   "specular IBL (--ibl-specular, with --ibl): the split sum, or per-pixel GGX samples of the "
                   "prefiltered chain (reference)",
                   iblOn};
        k.sweep.term = LightTerm::Environment;
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = intKnob("ibl-specular-samples", [](auto& s) -> auto& { return s.environment.specularRuntimeSamples; },
                              1, 256);
        k.flags = {valueFlag("--ibl-specular-samples")};
        k.help = "GGX samples a pixel with --ibl-specular sampled";
        k.panel = {PanelSection::Lighting, PanelWidget::Slider, "IBL specular samples", ""};
        k.sweep = {{"4", "8", "16", "32", "64", "128"}, false,
                   "per-pixel GGX samples of the sampled specular IBL (--ibl-specular-samples, with "
                   "--ibl-specular sampled); 128 is the reference. Not monotone: one fixed point set a "
                   "count, whose pattern against a small lamp differs from count to count",
                   [](RenderSettings& s, double) {
                       s.environment.ibl = true;
                       s.environment.specular = IblSpecular::Sampled;
                   }};
        k.sweep.term = LightTerm::Environment;
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = intKnob("ibl-extract-lights", [](auto& s) -> auto& { return s.environment.extractLights; }, 0,
                              kMaxEnvironmentLights);
        k.flags = {valueFlag("--ibl-extract-lights")};
        k.help = "small, very bright sources of the map (a sun, a lamp) lit as directional lights with the BRDF "
                 "instead of through the prefiltered chain; 0 = off";
        k.panel = {PanelSection::Lighting, PanelWidget::Slider, "IBL lights extracted", ""};
        k.sweep = {{"0", "1", "4"}, true,
                   "sources taken out of the map and lit analytically (--ibl-extract-lights, with --ibl): "
                   "0 leaves a small lamp to the prefilter",
                   iblOn};
        k.sweep.term = LightTerm::Environment;
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = floatKnob("ibl-extract-threshold", [](auto& s) -> auto& { return s.environment.extractThreshold; },
                                {1.0});
        k.flags = {valueFlag("--ibl-extract-threshold")};
        k.help = "a source's texels are brighter than this many times the map's median luminance";
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = intKnob("ibl-specular-size", [](auto& s) -> auto& { return s.environment.specularSize; }, 4, 4096);
        k.flags = {valueFlag("--ibl-specular-size")};
        k.help = "prefiltered cube face size, cube size / 2^k";
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = intKnob("ibl-specular-levels", [](auto& s) -> auto& { return s.environment.specularLevels; }, 1, 13);
        k.flags = {valueFlag("--ibl-specular-levels")};
        k.help = "prefiltered mips; roughness r is read at mip (N-1) r (2-r)";
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = intKnob("ibl-irradiance-size", [](auto& s) -> auto& { return s.environment.irradianceSize; }, 1, 1024);
        k.flags = {valueFlag("--ibl-irradiance-size")};
        k.help = "irradiance cube face size";
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = intKnob("ibl-irradiance-samples", [](auto& s) -> auto& { return s.environment.irradianceSamples; },
                              1, 65536);
        k.flags = {valueFlag("--ibl-irradiance-samples")};
        k.help = "cosine-weighted samples per irradiance texel";
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = intKnob("dfg-size", [](auto& s) -> auto& { return s.environment.dfgSize; }, 2, 1024);
        k.flags = {valueFlag("--dfg-size")};
        k.help = "split-sum DFG LUT size";
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = intKnob("dfg-samples", [](auto& s) -> auto& { return s.environment.dfgSamples; }, 1, 65536);
        k.flags = {valueFlag("--dfg-samples")};
        k.help = "GGX samples per DFG LUT texel";
        t.push_back(std::move(k));
    }

    // ---- ambient occlusion (indirect light only; passes/ambient_occlusion_pass) ----
    {
        KnobEntry k = boolKnob("ao", [](auto& s) -> auto& { return s.ao.enabled; });
        k.flags = {setsFlag("--ao", 1), setsFlag("--no-ao", 0)};
        k.help = "screen-space ambient occlusion (GTAO) of the IBL and constant ambient, never of direct "
                 "light; runs only where the frame has indirect light";
        k.panel = {PanelSection::Lighting, PanelWidget::Checkbox, "ambient occlusion", ""};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = floatKnob("ao-radius", [](auto& s) -> auto& { return s.ao.radius; }, {0.0, 100.0, true});
        k.flags = {valueFlag("--ao-radius")};
        k.help = "AO search radius in view-space metres";
        k.panel = {PanelSection::Lighting, PanelWidget::LogSlider, "AO radius", "%.2f m"};
        k.sweep = {{"0.125", "0.25", "0.5", "1", "2"}, false,
                   "AO search radius in metres (--ao-radius, AO on): occluders further away are ignored; 2 m "
                   "is the reference. Not monotone: sampling gets sparser as the radius grows",
                   aoOn};
        k.sweep.term = LightTerm::Environment;
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = intKnob("ao-directions", [](auto& s) -> auto& { return s.ao.directions; }, 1, 16);
        k.flags = {valueFlag("--ao-directions")};
        k.help = "AO slice directions per AO texel (rotated and offset over an 8x8 tile of texels)";
        k.panel = {PanelSection::Lighting, PanelWidget::Slider, "AO directions", ""};
        k.sweep = {{"1", "2", "4", "8"}, true,
                   "AO slice directions per pixel (--ao-directions, AO on); 8 is the reference", aoOn};
        k.sweep.term = LightTerm::Environment;
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = intKnob("ao-steps", [](auto& s) -> auto& { return s.ao.steps; }, 1, 32);
        k.flags = {valueFlag("--ao-steps")};
        k.help = "AO depth samples per side of each slice";
        k.panel = {PanelSection::Lighting, PanelWidget::Slider, "AO steps", ""};
        k.sweep = {{"2", "4", "8", "16"}, true, "AO samples per side of a slice (--ao-steps, AO on); 16 is the reference",
                   aoOn};
        k.sweep.term = LightTerm::Environment;
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = choiceKnob("ao-resolution", [](auto& s) -> auto& { return s.ao.resolution; },
                                 kAoResolutionNames);
        k.flags = {valueFlag("--ao-resolution")};
        k.choiceNoun = "resolution";
        k.help = "AO computed at half size (depth-aware upsample) or at the full G-buffer size";
        k.panel = {PanelSection::Lighting, PanelWidget::Combo, "AO resolution", ""};
        k.sweep = {{"half", "full"}, true, "AO resolution (--ao-resolution, AO on): half size upsampled by depth, "
                                           "or full size (reference)",
                   aoOn};
        k.sweep.term = LightTerm::Environment;
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = floatKnob("ao-intensity", [](auto& s) -> auto& { return s.ao.intensity; }, {0.0, 8.0});
        k.flags = {valueFlag("--ao-intensity")};
        k.help = "exponent on the AO (1: the physical value, 0: no occlusion)";
        k.panel = {PanelSection::Lighting, PanelWidget::Slider, "AO intensity", "%.2f"};
        t.push_back(std::move(k));
    }

    // ---- bloom and toon (unset optional values take the scene's effects) ----
    {
        KnobEntry k = boolKnob("bloom", [](auto& s) -> auto& { return s.post.bloom; });
        k.field.sceneValue = [](const Scene& scene) { return double(scene.effects.bloom.enabled); };
        k.flags = {setsFlag("--bloom", 1), setsFlag("--no-bloom", 0)};
        k.help = "bloom on/off; the scene's is effects.bloom.enabled";
        k.panel = {PanelSection::Post, PanelWidget::Combo, "bloom", ""};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = intKnob("bloom-kernel", [](auto& s) -> auto& { return s.post.bloomKernel; }, 1, 101);
        k.field.sceneValue = [](const Scene& scene) { return double(scene.effects.bloom.kernelSize); };
        k.flags = {valueFlag("--bloom-kernel")};
        k.help = "blur width in pixels";
        k.panel = {PanelSection::Post, PanelWidget::Slider, "kernel (px)", ""};
        k.sweep = {{"5", "10", "25", "50", "100"}, true,
                   "bloom width in pixels (--bloom-kernel), with --bloom-method's blur (separable "
                   "unless given); 100 is the reference",
                   bloomOn};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = choiceKnob("bloom-method", [](auto& s) -> auto& { return s.post.bloomMethod; },
                                 PostSettings::kBloomMethodNames);
        k.flags = {valueFlag("--bloom-method")};
        k.help = "bloom blur; mip-chain: Jimenez 2014";
        k.panel = {PanelSection::Post, PanelWidget::Combo, "bloom method", ""};
        k.sweep = {{"mip-chain", "separable"}, true,
                   "bloom (--bloom-method) at the scene's kernel: the Jimenez mip chain, or the full-resolution "
                   "separable Gaussian (reference)",
                   bloomOn};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = floatKnob("bloom-threshold", [](auto& s) -> auto& { return s.post.bloomThreshold; }, kNonNegative);
        k.field.sceneValue = [](const Scene& scene) { return double(scene.effects.bloom.threshold); };
        k.flags = {valueFlag("--bloom-threshold")};
        k.help = "soft-knee bright pass: luminance where bloom starts";
        k.panel = {PanelSection::Post, PanelWidget::Slider, "threshold", "%.2f"};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = floatKnob("bloom-knee", [](auto& s) -> auto& { return s.post.bloomKnee; }, kNonNegative);
        k.field.sceneValue = [](const Scene& scene) { return double(scene.effects.bloom.knee); };
        k.flags = {valueFlag("--bloom-knee")};
        k.help = "soft-knee bright pass: width of the knee";
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = floatKnob("bloom-strength", [](auto& s) -> auto& { return s.post.bloomStrength; }, kNonNegative);
        k.field.sceneValue = [](const Scene& scene) { return double(scene.effects.bloom.strength); };
        k.flags = {valueFlag("--bloom-strength")};
        k.help = "how much bloom is mixed in";
        k.panel = {PanelSection::Post, PanelWidget::Slider, "strength", "%.3f"};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = floatKnob("bloom-clamp", [](auto& s) -> auto& { return s.post.bloomHighlight; },
                                {0.0, kNoMax, true});
        k.flags = {valueFlag("--bloom-clamp")};
        k.help = "per-channel ceiling of what enters the blur";
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = boolKnob("karis", [](auto& s) -> auto& { return s.post.bloomKaris; });
        k.flags = {setsFlag("--no-karis", 0)};
        k.help = "mip-chain: no Karis average on the first downsample";
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = choiceKnob("bloom-blur", [](auto& s) -> auto& { return s.post.bloomFragmentBlur; },
                                 std::vector<bool>{false, true},
                                 [](bool fragment) { return fragment ? "fragment" : "compute"; });
        k.flags = {valueFlag("--bloom-blur")};
        k.help = "the GLSL separable blur's stage";
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = boolKnob("bloom-only", [](auto& s) -> auto& { return s.post.bloomOnly; });
        k.flags = {setsFlag("--bloom-only", 1)};
        k.help = "display the bloom buffer alone (seed 001's bloom view)";
        k.panel = {PanelSection::Post, PanelWidget::Checkbox, "bloom buffer alone (8)", ""};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = boolKnob("toon", [](auto& s) -> auto& { return s.post.toon; });
        k.field.sceneValue = [](const Scene& scene) { return double(scene.effects.toon.enabled); };
        k.flags = {setsFlag("--toon", 1), setsFlag("--no-toon", 0)};
        k.help = "toon ramp and outlines on/off; the scene's is effects.toon.enabled";
        k.panel = {PanelSection::Post, PanelWidget::Combo, "toon (7)", ""};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = intKnob("toon-levels", [](auto& s) -> auto& { return s.post.toonLevels; }, 1, 64);
        k.field.sceneValue = [](const Scene& scene) { return double(scene.effects.toon.levels); };
        k.flags = {valueFlag("--toon-levels")};
        k.help = "toon ramp bands";
        k.panel = {PanelSection::Post, PanelWidget::Slider, "toon levels", ""};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = floatKnob("toon-edge", [](auto& s) -> auto& { return s.post.toonEdge; }, kNonNegative);
        k.field.sceneValue = [](const Scene& scene) { return double(scene.effects.toon.edgeThreshold); };
        k.flags = {valueFlag("--toon-edge")};
        k.help = "toon depth-edge threshold, a relative depth step";
        k.panel = {PanelSection::Post, PanelWidget::Slider, "depth edge", "%.2f"};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = floatKnob("toon-normal-edge", [](auto& s) -> auto& { return s.post.toonNormalEdge; }, kNonNegative);
        k.flags = {valueFlag("--toon-normal-edge")};
        k.help = "toon normal-edge threshold, sin of half the crease angle: 0.5 = 60 deg";
        k.panel = {PanelSection::Post, PanelWidget::Slider, "normal edge", "%.2f"};
        t.push_back(std::move(k));
    }
    // ---- motion blur (passes/motion_blur_pass) ----
    {
        KnobEntry k = boolKnob("motion-blur", [](auto& s) -> auto& { return s.motionBlur.enabled; });
        k.flags = {setsFlag("--motion-blur", 1)};
        k.help = "motion blur from the G-buffer's motion vectors (McGuire et al. 2012), before bloom; "
                 "skipped when nothing moves";
        k.panel = {PanelSection::Post, PanelWidget::Checkbox, "motion blur", ""};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = intKnob("motion-blur-samples", [](auto& s) -> auto& { return s.motionBlur.samples; }, 2, 64);
        k.flags = {valueFlag("--motion-blur-samples")};
        k.help = "motion blur: gather taps per pixel along the neighbourhood's blur";
        k.panel = {PanelSection::Post, PanelWidget::Slider, "blur samples", ""};
        // Needs a moving camera: sweep it on the clock, e.g. --scene cornell-flythrough --time 1 --fps 30.
        k.sweep = {{"4", "8", "16", "32"}, false,
                   "motion blur gather taps per pixel (--motion-blur-samples, motion blur on); 32 is the "
                   "reference. Not monotone: the taps' per-pixel noise differs between counts",
                   [](RenderSettings& s, double) { s.motionBlur.enabled = true; }};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = floatKnob("motion-blur-shutter", [](auto& s) -> auto& { return s.motionBlur.shutter; },
                                {0.0, 1.0, true});
        k.flags = {valueFlag("--motion-blur-shutter")};
        k.help = "motion blur: fraction of the frame interval the shutter is open (0.5: a 180-degree shutter)";
        k.panel = {PanelSection::Post, PanelWidget::Slider, "shutter", "%.2f"};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = choiceKnob("post-backend", [](auto& s) -> auto& { return s.post.backend; },
                                 PostSettings::kBackendNames);
        k.flags = {valueFlag("--post-backend")};
        k.help = "who runs bloom, the bloom composite and toon; auto: per effect, whichever of CUDA and GLSL "
                 "measured faster at start-up on this GPU at this size and kernel (cached, see --post-remeasure)";
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = choiceKnob("cuda-interop", [](auto& s) -> auto& { return s.post.cudaInterop; },
                                 PostSettings::kCudaInteropNames);
        k.flags = {valueFlag("--cuda-interop")};
        k.help = "how the CUDA post effects reach GL textures: external (GL memory objects on CUDA memory, shared "
                 "once, ordered on the GPU by Vulkan semaphores, else by host waits), map (map/unmap per use); "
                 "auto: external with semaphores where measured faster than map at start-up, else map";
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = boolKnob("post-remeasure", [](auto& s) -> auto& { return s.post.remeasure; });
        k.flags = {setsFlag("--post-remeasure", 1)};
        k.help = "--post-backend auto: time CUDA and GLSL again instead of reading the cache "
                 "(measured_choices.json in $LIGHTPASS_CACHE_DIR or ~/.cache/lightpass), and rewrite it";
        t.push_back(std::move(k));
    }

    // ---- local lights ----
    {
        KnobEntry k = boolKnob("local-lights", [](auto& s) -> auto& { return s.localLights.enabled; });
        k.flags = {setsFlag("--no-local-lights", 0)};
        k.help = "draw no local lights (the pass leaves the frame graph)";
        k.panel = {PanelSection::Lighting, PanelWidget::Checkbox, "local lights", ""};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = choiceKnob("local-light-method", [](auto& s) -> auto& { return s.localLights.method; },
                                 kLocalLightMethodNames);
        k.flags = {valueFlag("--local-lights")};
        k.choiceNoun = "method";
        k.help = "how local lights are drawn; all five give the same image";
        k.panel = {PanelSection::Lighting, PanelWidget::Combo, "method", ""};
        k.sweep = {{"tiled", "clustered", "volumes", "scissor", "fullscreen"}, false,
                   "local-light method (--local-lights): tiled, clustered, volumes, scissor, fullscreen (reference). The "
                   "same image by design: errors should be ~0 (fp16 sums in different orders), so not monotone",
                   nullptr};
        k.sweep.term = LightTerm::LocalLights;
        t.push_back(std::move(k));
    }
    {
        // lightCount -1 is "the scene's lights": an unset optional to the table.
        KnobEntry k;
        k.name = "light-count";
        k.type = KnobType::Int;
        k.range = {0, 1000000};
        k.field.optional = true;
        k.field.get = [](const RenderSettings& s) -> KnobValueOrUnset {
            return s.localLights.lightCount < 0 ? std::nullopt : KnobValueOrUnset(s.localLights.lightCount);
        };
        k.field.set = [](RenderSettings& s, KnobValueOrUnset v) { s.localLights.lightCount = v ? int(*v) : -1; };
        k.field.sceneValue = [](const Scene& scene) { return double(scene.pointLights.size()); };
        k.flags = {valueFlag("--light-count")};
        k.help = "draw the scene's first N point lights, plus generated demo lights up to N, deterministic and "
                 "spread through the scene's bounds; e.g. 4096";
        k.panel = {PanelSection::Lighting, PanelWidget::LogSlider, "light count", ""};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = boolKnob("scissor", [](auto& s) -> auto& { return s.localLights.scissor; });
        k.flags = {setsFlag("--no-scissor", 0)};
        k.help = "the scissor method draws every light full screen (the viewer's 'x')";
        k.panel = {PanelSection::Lighting, PanelWidget::Checkbox, "scissor (x, scissor method)", ""};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = boolKnob("globes", [](auto& s) -> auto& { return s.localLights.globes; });
        k.field.sceneValue = [](const Scene& scene) { return double(scene.lightGlobes); };
        k.flags = {setsFlag("--globes", 1), setsFlag("--no-globes", 0)};
        k.help = "draw each local light as a small flat-lit globe; the scene's is lightGlobes";
        k.panel = {PanelSection::Lighting, PanelWidget::Combo, "light globes", ""};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = boolKnob("local-specular", [](auto& s) -> auto& { return s.localLights.specular; });
        k.flags = {setsFlag("--no-local-specular", 0)};
        k.help = "local lights add diffuse only";
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = boolKnob("specular-outside-range", [](auto& s) -> auto& { return s.localLights.specularOutsideRange; });
        k.flags = {setsFlag("--specular-outside-range", 1)};
        k.help = "diffuse limited by the range, specular (1/d^2) not (seed 003)";
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = floatKnob("light-range-cutoff", [](auto& s) -> auto& { return s.localLights.rangeScale; }, {0.01, 1.0});
        k.flags = {valueFlag("--light-range-scale")};
        k.help = "each local light's range x this; < 1 cuts lights short, cheaper and darker";
        k.panel = {PanelSection::Lighting, PanelWidget::Slider, "light range scale", "%.2f"};
        k.sweep = {{"0.25", "0.5", "0.75", "1"}, true,
                   "each local light's range x this (--light-range-scale): lights stop sooner, fewer pixels per "
                   "light; 1 (the full range) is the reference",
                   nullptr};
        k.sweep.term = LightTerm::LocalLights;
        t.push_back(std::move(k));
    }

    {
        KnobEntry k = intKnob("cluster-size", [](auto& s) -> auto& { return s.localLights.clusterSize; }, 8, 256);
        k.flags = {valueFlag("--cluster-size")};
        k.help = "clustered method: froxel tile side in pixels";
        k.panel = {PanelSection::Lighting, PanelWidget::Slider, "cluster size (px)", ""};
        k.sweep = {{"16", "32", "64", "128"}, false,
                   "froxel tile side in pixels (--cluster-size, switches --local-lights clustered --clustered-kernel "
                   "froxels on): smaller tiles, shorter light lists, more froxels to build; the same image by design, "
                   "so not monotone",
                   sweepClusteredKernel};
        k.sweep.term = LightTerm::LocalLights;
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = intKnob("cluster-slices", [](auto& s) -> auto& { return s.localLights.clusterSlices; }, 1, 64);
        k.flags = {valueFlag("--cluster-slices")};
        k.help = "clustered method: exponential depth slices between the camera's near and far planes";
        k.panel = {PanelSection::Lighting, PanelWidget::Slider, "cluster slices", ""};
        k.sweep = {{"8", "16", "24", "32", "64"}, false,
                   "exponential depth slices of the froxel grid (--cluster-slices, switches --local-lights clustered "
                   "--clustered-kernel froxels on: the kernel that uses them, at any light count): the same image by "
                   "design, so not monotone",
                   sweepClusteredKernel};
        k.sweep.term = LightTerm::LocalLights;
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = choiceKnob("clustered-kernel", [](auto& s) -> auto& { return s.localLights.clusteredKernel; },
                                 kClusteredKernelNames);
        k.flags = {valueFlag("--clustered-kernel")};
        k.choiceNoun = "kernel";
        k.help = "clustered method, 16-pixel tiles: the kernel that shades (the same image). froxels: the clustered "
                 "kernel, each pixel the lights of its depth slice; tiles: the tiled kernel on the same tiles without "
                 "slices; auto: both timed on the GPU in turn for the view and the faster one kept, timed again "
                 "every 240 frames and when the lights, size or settings change (below 32 lights: tiles)";
        k.panel = {PanelSection::Lighting, PanelWidget::Combo, "clustered kernel", ""};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = intKnob("cluster-slice", [](auto& s) -> auto& { return s.localLights.clusterSlice; }, -1, 63);
        k.flags = {valueFlag("--cluster-slice")};
        k.help = "lights-per-cluster view: show this depth slice; -1 the most lights over all slices";
        k.panel = {PanelSection::Lighting, PanelWidget::Slider, "cluster slice shown", ""};
        t.push_back(std::move(k));
    }

    // ---- resolution, exposure, measuring ----
    {
        KnobEntry k = floatKnob("render-scale", [](auto& s) -> auto& { return s.renderScale; }, {kMinRenderScale, 1.0});
        k.flags = {valueFlag("--render-scale")};
        k.help = "G-buffer, lighting and post effects at this fraction of the output size, upsampled "
                 "bilinearly before the tone map";
        k.panel = {PanelSection::View, PanelWidget::Slider, "render scale", "%.2f"};
        k.sweep = {{"0.25", "0.5", "0.75", "1"}, true,
                   "G-buffer, lighting and post effects at this fraction of the output size (--render-scale), "
                   "upsampled bilinearly before the tone map, without anti-aliasing; 1 is the reference",
                   // Without AA at every value: at 1 the default SSAA would run, below 1 it cannot.
                   [](RenderSettings& s, double) { s.aa.method = AntiAliasing::Off; }};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = choiceKnob("aa", [](auto& s) -> auto& { return s.aa.method; }, kAntiAliasingNames);
        k.flags = {valueFlag("--aa")};
        k.choiceNoun = "anti-aliasing";
        k.help = "anti-aliasing: fxaa filters the tone-mapped image (FXAA 3.11); taa blends Halton-jittered frames "
                 "through the motion vectors; ssaa renders at --ssaa-scale x the size in each axis and box-filters "
                 "the HDR image down (not used at --render-scale below 1)";
        k.panel = {PanelSection::View, PanelWidget::Combo, "anti-aliasing", ""};
        k.sweep = {{"off", "fxaa", "taa"}, false,
                   "anti-aliasing (--aa): off, fxaa, taa (after the warm-up and timed frames), then ssaa at 2x2 and "
                   "3x3 samples a pixel, against ssaa 4x4 (reference). Not monotone: fxaa changes only the "
                   "tone-mapped image, so its HDR error is off's (FLIP from bench/sweep_report.py sees it)",
                   nullptr};
        for (int scale : {2, 3, kMaxSsaaScale})
            k.sweepExtraValues.push_back({"ssaa" + std::to_string(scale), [scale](RenderSettings& s) {
                                               s.aa.method = AntiAliasing::Ssaa;
                                               s.aa.ssaaScale = scale;
                                           }});
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = intKnob("ssaa-scale", [](auto& s) -> auto& { return s.aa.ssaaScale; }, 2, kMaxSsaaScale);
        k.flags = {valueFlag("--ssaa-scale")};
        k.help = "with --aa ssaa: render at S x the output size in each axis, S x S samples a pixel";
        k.sweep = {{"2", "3", "4"}, true,
                   "samples per axis of --aa ssaa (--ssaa-scale), box-filtered to the output; 4 (16 samples a "
                   "pixel) is the reference",
                   [](RenderSettings& s, double) { s.aa.method = AntiAliasing::Ssaa; }};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = floatKnob("taa-history-weight", [](auto& s) -> auto& { return s.aa.taaHistoryWeight; },
                                {0.01, 1.0});
        k.flags = {valueFlag("--taa-history-weight")};
        k.help = "with --aa taa: the current frame's weight in the blend with the history (smaller: smoother, "
                 "slower to converge and to follow changes)";
        k.sweep = {{"0.5", "0.25", "0.1", "0.05"}, false,
                   "the current frame's weight in TAA's blend (--taa-history-weight, switches --aa taa on), against "
                   "ssaa 4x4 (reference); not monotone (a smaller weight converges slower)",
                   [](RenderSettings& s, double) { s.aa.method = AntiAliasing::Taa; }};
        k.sweepExtraValues.push_back({"ssaa4", [](RenderSettings& s) {
                                           s.aa.method = AntiAliasing::Ssaa;
                                           s.aa.ssaaScale = kMaxSsaaScale;
                                       }});
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = boolKnob("dither", [](auto& s) -> auto& { return s.aa.dither; });
        k.flags = {setsFlag("--dither", 1), setsFlag("--no-dither", 0)};
        k.help = "triangular-PDF noise of +-1 LSB before the 8-bit quantisation of the displayed / saved image "
                 "(breaks up banding, keeps the mean)";
        k.panel = {PanelSection::View, PanelWidget::Checkbox, "dither", ""};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = floatKnob("exposure", [](auto& s) -> auto& { return s.exposureEV; }, {-16.0, 16.0});
        k.flags = {valueFlag("--exposure")};
        k.help = "stops added to the scene's exposure before the tone map: the compensation of auto exposure, or "
                 "a change of the scene's fixed \"exposure\"";
        k.panel = {PanelSection::View, PanelWidget::Slider, "exposure (EV)", "%+.1f"};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = boolKnob("auto-exposure", [](auto& s) -> auto& { return s.autoExposure; });
        k.field.sceneValue = [](const Scene& scene) { return double(!scene.exposure.has_value()); };
        k.flags = {setsFlag("--auto-exposure", 1), setsFlag("--no-auto-exposure", 0)};
        k.help = "expose each frame from a centre-weighted histogram of its luminance (the mean log luminance "
                 "of its 20%..70% part on middle grey); --exposure then adds to it. The scene's is on unless "
                 "its file sets \"exposure\"";
        k.panel = {PanelSection::View, PanelWidget::Combo, "auto exposure", ""};
        t.push_back(std::move(k));
    }
    {
        KnobEntry k = boolKnob("all-passes", [](auto& s) -> auto& { return s.allPasses; });
        k.flags = {setsFlag("--all-passes", 1)};
        k.help = "add every candidate pass even where the scene does not call for it (shadow maps for every "
                 "sun, local lights with none in view, colour sky, IBL, bloom at strength 0); for measuring "
                 "what the scene-driven graph saves, image may differ";
        t.push_back(std::move(k));
    }
    return t;
}

// 16, 0.25, 1e+06 as a person writes them: whole numbers in full, others shortest.
std::string number(double v) {
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    if (v == std::floor(v) && std::fabs(v) < 1e15) return std::to_string((long long)v);
    char b[32];
    std::snprintf(b, sizeof b, "%g", v);
    return b;
}

// "a or b", "a, b or c"
std::string alternatives(const std::vector<std::string>& names) {
    std::string s;
    for (size_t i = 0; i < names.size(); ++i)
        s += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
    return s;
}

std::string joined(const std::vector<std::string>& names, const char* separator) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : separator) + n;
    return s;
}

// What a float out of range should have been, in the words the CLI has always used.
std::string floatExpectation(const KnobRange& r) {
    if (r.bounded()) return "expected a number in [" + number(r.min) + ", " + number(r.max) + "]";
    if (r.min == 0.0) return r.minExclusive ? "expected a positive number" : "expected a non-negative number";
    return "expected a number " + std::string(r.minExclusive ? "> " : ">= ") + number(r.min);
}

// Sweep labels: floats with two decimals ("0.25", "1.00") so a column of them lines up.
std::string sweepLabel(const KnobEntry& k, double v) {
    if (k.type != KnobType::Float) return formatKnobValue(k, v);
    char b[16];
    std::snprintf(b, sizeof b, "%.2f", v);
    return b;
}

std::vector<Knob> makeSweepKnobs() {
    std::vector<Knob> knobs;
    for (const KnobEntry& e : knobTable()) {
        if (e.sweep.values.empty()) continue;
        Knob k{e.name, e.sweep.description, {}, e.sweep.monotone, e.sweep.term};
        const KnobEntry* entry = &e;  // the table is a function-local static: the address stays
        for (const std::string& text : e.sweep.values) {
            const double v = parseKnobValue(e, "sweep " + e.name, text);
            k.values.push_back({sweepLabel(e, v), [entry, v](RenderSettings& s) {
                                    entry->field.set(s, v);
                                    if (entry->sweep.alsoSet) entry->sweep.alsoSet(s, v);
                                }});
        }
        for (const KnobValue& extra : e.sweepExtraValues) k.values.push_back(extra);
        knobs.push_back(std::move(k));
    }
    return knobs;
}

}  // namespace

const std::vector<KnobEntry>& knobTable() {
    static const std::vector<KnobEntry> table = makeKnobTable();
    return table;
}

const KnobEntry* findKnobEntry(const std::string& name) {
    for (const auto& k : knobTable())
        if (k.name == name) return &k;
    return nullptr;
}

const KnobEntry* findKnobFlag(const std::string& flag, const KnobFlag** which) {
    for (const auto& k : knobTable())
        for (const auto& f : k.flags)
            if (f.flag == flag) {
                if (which) *which = &f;
                return &k;
            }
    return nullptr;
}

double parseKnobValue(const KnobEntry& k, const std::string& flag, const std::string& text) {
    auto error = [&](const std::string& what) { return Error(flag + " " + text + ": " + what); };
    switch (k.type) {
        case KnobType::Int:
            try {
                size_t used = 0;
                const long x = std::stol(text, &used);
                if (used != text.size() || !k.range.contains(double(x))) throw std::out_of_range("");
                return double(x);
            } catch (const std::exception&) {
                throw error("expected a whole number in [" + number(k.range.min) + ", " + number(k.range.max) + "]");
            }
        case KnobType::Float: {
            float x = 0.0f;  // parsed as float so that setting it back is exact
            try {
                size_t used = 0;
                x = std::stof(text, &used);
                if (used != text.size() || !std::isfinite(x)) throw std::out_of_range("");
            } catch (const std::exception&) {
                throw error("expected a finite number");
            }
            // Bounds as floats too: 0.01 must accept "0.01", which is 0.00999999977f.
            const KnobRange asFloat{double(float(k.range.min)), double(float(k.range.max)), k.range.minExclusive};
            if (!asFloat.contains(double(x))) throw error(floatExpectation(k.range));
            return double(x);
        }
        case KnobType::Bool:
            if (text == "on") return 1.0;
            if (text == "off") return 0.0;
            throw error("expected on or off");
        case KnobType::Choice:
            for (size_t i = 0; i < k.choices.size(); ++i)
                if (k.choices[i] == text) return double(i);
            throw error(k.choiceNoun.empty() ? "expected " + alternatives(k.choices)
                                             : "unknown " + k.choiceNoun + " (" + joined(k.choices, ", ") + ")");
    }
    throw error("unknown knob type");
}

std::string formatKnobValue(const KnobEntry& k, KnobValueOrUnset v) {
    if (!v) return "the scene's";
    switch (k.type) {
        case KnobType::Int:
        case KnobType::Float: return number(*v);
        case KnobType::Bool: return *v != 0.0 ? "on" : "off";
        case KnobType::Choice: return size_t(*v) < k.choices.size() ? k.choices[size_t(*v)] : "?";
    }
    return "?";
}

std::string knobDefault(const KnobEntry& k) { return formatKnobValue(k, k.field.get(RenderSettings{})); }

std::string knobRangeText(const KnobEntry& k) {
    switch (k.type) {
        case KnobType::Choice: return joined(k.choices, " | ");
        case KnobType::Bool: return "";
        case KnobType::Int:
        case KnobType::Float:
            if (k.range.bounded()) return number(k.range.min) + ".." + number(k.range.max);
            if (k.range.min > -kNoMax) return (k.range.minExclusive ? "> " : ">= ") + number(k.range.min);
            return "";
    }
    return "";
}

std::string helpLine(const std::string& flags, const std::string& text) {
    const size_t column = 20, width = 104;  // text starts in column 20, lines stop by 104
    std::string line = "  " + flags;
    line += line.size() + 2 <= column ? std::string(column - line.size(), ' ') : "  ";
    std::string out;
    size_t start = 0;
    while (start < text.size()) {
        // Break at the last space that fits; a word longer than the line goes on whole.
        size_t end = text.size();
        if (line.size() + (end - start) > width) {
            const size_t room = width > line.size() ? width - line.size() : 0;
            const size_t space = text.rfind(' ', start + room);
            end = space != std::string::npos && space > start ? space : text.find(' ', start + room);
            if (end == std::string::npos) end = text.size();
        }
        out += line + text.substr(start, end - start) + "\n";
        start = text.find_first_not_of(' ', end);
        if (start == std::string::npos) break;
        line = std::string(column, ' ');
    }
    return out;
}

std::string knobHelpText() {
    std::string out;
    for (const KnobEntry& k : knobTable()) {
        if (k.flags.empty()) continue;
        std::string flags;
        for (const KnobFlag& f : k.flags)
            flags += (flags.empty() ? "" : ", ") + f.flag + (f.fixedValue ? "" : k.type == KnobType::Int ? " N"
                                                                               : k.type == KnobType::Float ? " X"
                                                                                                           : " NAME");
        std::string facts = knobRangeText(k);
        const bool takesValue = std::any_of(k.flags.begin(), k.flags.end(), [](const KnobFlag& f) { return !f.fixedValue; });
        if (k.field.optional) facts += (facts.empty() ? "" : "; ") + std::string("default: the scene's");
        else if (takesValue) facts += (facts.empty() ? "" : k.type == KnobType::Choice ? "; " : ", ") + ("default " + knobDefault(k));
        if (!k.sweep.values.empty()) facts += "; sweep knob " + k.name;
        out += helpLine(flags, k.help + (facts.empty() ? "" : " (" + facts + ")"));
    }
    return out;
}

const std::vector<Knob>& allKnobs() {
    static const std::vector<Knob> knobs = makeSweepKnobs();
    return knobs;
}

const Knob* findKnob(const std::string& name) {
    for (const auto& k : allKnobs())
        if (k.name == name) return &k;
    return nullptr;
}

std::optional<Knob> knobByName(const std::string& spec) {
    std::vector<const Knob*> parts;
    for (size_t start = 0;;) {
        const size_t plus = spec.find('+', start);
        const Knob* k = findKnob(spec.substr(start, plus == std::string::npos ? std::string::npos : plus - start));
        if (!k || std::find(parts.begin(), parts.end(), k) != parts.end()) return std::nullopt;
        parts.push_back(k);
        if (plus == std::string::npos) break;
        start = plus + 1;
    }
    if (parts.size() == 1) return *parts[0];
    Knob product{spec, "every combination of", {KnobValue{"", [](RenderSettings&) {}}}, false, parts.front()->term};
    for (const Knob* k : parts) {
        if (k->term != product.term) product.term = LightTerm::Frame;  // two terms: the frame holds both
        product.description += (k == parts.front() ? " " : " x ") + k->name;
        std::vector<KnobValue> combined;
        for (const KnobValue& a : product.values)
            for (const KnobValue& b : k->values)
                combined.push_back({a.label.empty() ? b.label : a.label + "/" + b.label,
                                    [first = a.apply, second = b.apply](RenderSettings& s) {
                                        first(s);
                                        second(s);
                                    }});
        product.values = std::move(combined);
    }
    return product;
}

std::string knobNames() {
    std::string s;
    for (const auto& k : allKnobs()) s += (s.empty() ? "" : ", ") + k.name;
    return s.empty() ? "(none)" : s;
}

}  // namespace lp
