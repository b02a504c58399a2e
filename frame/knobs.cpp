#include "frame/knobs.hpp"

#include <algorithm>
#include <cstdio>

namespace lp {

namespace {

// One value per entry of `values`, labelled by `label(v)`, applied by `set(settings, v)`.
template <class T, class Label, class Set>
std::vector<KnobValue> valuesOf(const std::vector<T>& values, Label label, Set set) {
    std::vector<KnobValue> out;
    for (const T& v : values) out.push_back({label(v), [v, set](RenderSettings& s) { set(s, v); }});
    return out;
}

std::string str(int v) { return std::to_string(v); }
std::string str2(float v) {
    char b[16];
    std::snprintf(b, sizeof b, "%.2f", double(v));
    return b;
}

std::vector<Knob> makeKnobs() {
    std::vector<Knob> knobs;
    // [knobs] each feature area registers its quality knobs here; values cheapest first, the last
    // is the reference. `monotone` = false where a cheaper value is not always further from it.

    // ---- G-buffer layout ----
    knobs.push_back({"gbuffer-format",
                     "G-buffer normal format (--gbuffer), fewest bytes first: octahedral 16/24/32 bits, seed 001's "
                     "packed xy (wrong where normals face away), its signed fix, seed 004's two angles, unpacked "
                     "RGBA32F (reference). Not monotone: seed-packed's failure is not a precision loss",
                     valuesOf<GBufferNormalFormat>(
                         {GBufferNormalFormat::Oct16, GBufferNormalFormat::Oct24, GBufferNormalFormat::Oct32,
                          GBufferNormalFormat::SeedPacked, GBufferNormalFormat::SeedPackedSigned,
                          GBufferNormalFormat::TwoAngle, GBufferNormalFormat::Unpacked},
                         [](GBufferNormalFormat f) { return std::string(gbufferFormatName(f)); },
                         [](RenderSettings& s, GBufferNormalFormat f) { s.gbuffer.normal = f; }),
                     false});
    knobs.push_back({"gbuffer-position",
                     "eye positions (--gbuffer-position): rebuilt from standard depth, from reversed-Z depth "
                     "(finer far away), stored RGBA32F (reference, 16 more bytes a pixel)",
                     valuesOf<GBufferPositionMode>(
                         {GBufferPositionMode::Depth, GBufferPositionMode::ReversedZ, GBufferPositionMode::Stored},
                         [](GBufferPositionMode m) { return std::string(gbufferPositionName(m)); },
                         [](RenderSettings& s, GBufferPositionMode m) { s.gbuffer.position = m; }),
                     true});

    // ---- shadows ----
    knobs.push_back({"shadow-size", "texels per side of each cascade's shadow map (--shadow-size); 4096 is the reference",
                     valuesOf<int>({512, 1024, 2048, 4096}, str,
                                   [](RenderSettings& s, int v) {
                                       s.shadows.enabled = true;
                                       s.shadows.size = v;
                                   }),
                     true});
    knobs.push_back({"shadow-pcf",
                     "shadow filter (--pcf): off, 3x3, 5x5, poisson (reference). Not monotone: the filters "
                     "differ in penumbra shape, not only in sample count",
                     valuesOf<ShadowSettings::Filter>(
                         {ShadowSettings::Filter::Off, ShadowSettings::Filter::Pcf3x3, ShadowSettings::Filter::Pcf5x5,
                          ShadowSettings::Filter::Poisson},
                         [](ShadowSettings::Filter f) { return std::string(ShadowSettings::filterName(f)); },
                         [](RenderSettings& s, ShadowSettings::Filter f) {
                             s.shadows.enabled = true;
                             s.shadows.filter = f;
                         }),
                     false});
    knobs.push_back({"shadow-cascades",
                     "cascades per shadowed light (--shadow-cascades), 4 is the reference. Not monotone: each "
                     "count splits the depth range differently",
                     valuesOf<int>({1, 2, 3, 4}, str,
                                   [](RenderSettings& s, int v) {
                                       s.shadows.enabled = true;
                                       s.shadows.cascades = v;
                                   }),
                     false});

    // ---- image-based lighting (switches --ibl on; needs a scene with an environment map) ----
    knobs.push_back({"ibl-samples", "GGX samples per prefiltered texel (--ibl-samples, with --ibl); 1024 is the reference",
                     valuesOf<int>({16, 64, 256, 1024}, str,
                                   [](RenderSettings& s, int v) {
                                       s.environment.ibl = true;
                                       s.environment.specularSamples = v;
                                   }),
                     true});
    knobs.push_back({"ibl-face-size",
                     "environment cube face size (--env-size, prefiltered cube half of it, with --ibl); 512 "
                     "is the reference",
                     valuesOf<int>({64, 128, 256, 512}, str,
                                   [](RenderSettings& s, int v) {
                                       s.environment.ibl = true;
                                       s.environment.cubeSize = v;
                                       s.environment.specularSize = v / 2;
                                   }),
                     true});
    knobs.push_back({"ibl-diffuse",
                     "diffuse IBL (--ibl-diffuse, with --ibl): 9 SH coefficients, or the cosine-sampled "
                     "irradiance cube (reference)",
                     valuesOf<IrradianceSource>(
                         {IrradianceSource::SphericalHarmonics, IrradianceSource::Cubemap},
                         [](IrradianceSource d) { return std::string(d == IrradianceSource::Cubemap ? "cubemap" : "sh"); },
                         [](RenderSettings& s, IrradianceSource d) {
                             s.environment.ibl = true;
                             s.environment.diffuse = d;
                         }),
                     true});

    // ---- bloom (switches --bloom on) ----
    knobs.push_back({"bloom-kernel", "bloom width in pixels (--bloom-kernel), with --bloom-method's blur (separable "
                                     "unless given); 100 is the reference",
                     valuesOf<int>({5, 10, 25, 50, 100}, str,
                                   [](RenderSettings& s, int v) {
                                       s.post.bloom = true;  // the method is --bloom-method's (separable)
                                       s.post.bloomKernel = v;
                                   }),
                     true});
    knobs.push_back({"bloom-method",
                     "bloom (--bloom-method) at the scene's kernel: the Jimenez mip chain, or the full-resolution "
                     "separable Gaussian (reference)",
                     valuesOf<PostSettings::BloomMethod>(
                         {PostSettings::BloomMethod::MipChain, PostSettings::BloomMethod::Separable},
                         [](PostSettings::BloomMethod m) {
                             return std::string(m == PostSettings::BloomMethod::MipChain ? "mip-chain" : "separable");
                         },
                         [](RenderSettings& s, PostSettings::BloomMethod m) {
                             s.post.bloom = true;
                             s.post.bloomMethod = m;
                         }),
                     true});

    // ---- local lights ----
    knobs.push_back({"local-light-method",
                     "local-light method (--local-lights): tiled, volumes, scissor, fullscreen (reference). The "
                     "same image by design: errors should be ~0 (fp16 sums in different orders), so not monotone",
                     valuesOf<LocalLightMethod>(
                         {LocalLightMethod::Tiled, LocalLightMethod::Volumes, LocalLightMethod::Scissor,
                          LocalLightMethod::Fullscreen},
                         [](LocalLightMethod m) { return std::string(localLightMethodName(m)); },
                         [](RenderSettings& s, LocalLightMethod m) { s.localLights.method = m; }),
                     false});
    knobs.push_back({"light-range-cutoff",
                     "each local light's range x this (--light-range-scale): lights stop sooner, fewer pixels per "
                     "light; 1 (the full range) is the reference",
                     valuesOf<float>({0.25f, 0.5f, 0.75f, 1.0f},
                                     str2,
                                     [](RenderSettings& s, float v) { s.localLights.rangeScale = v; }),
                     true});

    // ---- resolution ----
    knobs.push_back({"render-scale",
                     "G-buffer, lighting and post effects at this fraction of the output size (--render-scale), "
                     "upsampled bilinearly before the tone map; 1 is the reference",
                     valuesOf<float>({0.25f, 0.5f, 0.75f, 1.0f},
                                     str2,
                                     [](RenderSettings& s, float v) { s.renderScale = v; }),
                     true});
    return knobs;
}
}  // namespace

const std::vector<Knob>& allKnobs() {
    static const std::vector<Knob> knobs = makeKnobs();
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
    Knob product{spec, "every combination of", {KnobValue{"", [](RenderSettings&) {}}}, false};
    for (const Knob* k : parts) {
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
