// The knob table (frame/knobs.cpp) is the one place a user-facing setting is described: these tests
// fail when a flag, a panel widget or a sweep knob exists outside it, when the CLI and the panel could
// disagree on a range, or when a table entry is incomplete.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "engine/core/paths.hpp"
#include "app/cli.hpp"
#include "engine/core/error.hpp"
#include "engine/scene/scene.hpp"
#include "frame/knobs.hpp"

using namespace lp;

namespace {

std::string errorOf(const std::vector<std::string>& args) {
    try {
        app::parseArgs(args);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

std::set<std::string> commandFlagNames() {
    std::set<std::string> names;
    for (const auto& f : app::commandFlags())
        for (const auto& n : f.names) names.insert(n);
    return names;
}

std::set<std::string> knobFlagNames() {
    std::set<std::string> names;
    for (const auto& k : knobTable())
        for (const auto& f : k.flags) names.insert(f.flag);
    return names;
}

bool takesValue(const KnobEntry& k) {
    for (const auto& f : k.flags)
        if (!f.fixedValue) return true;
    return false;
}
const KnobFlag* valueFlagOf(const KnobEntry& k) {
    for (const auto& f : k.flags)
        if (!f.fixedValue) return &f;
    return nullptr;
}

// The repository the tests were built from (not __FILE__, which a compiler cache may make relative to
// the build directory, so the test failed when run from anywhere but ctest's working directory).
std::filesystem::path sourceRoot() { return lp::dataRoot(); }

std::string readFile(const std::filesystem::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

TEST(KnobTable, EveryEntryIsComplete) {
    std::set<std::string> names;
    std::set<std::string> flags;
    const std::set<std::string> commandNames = commandFlagNames();
    const RenderSettings defaults;
    for (const KnobEntry& k : knobTable()) {
        SCOPED_TRACE(k.name);
        EXPECT_FALSE(k.name.empty());
        EXPECT_TRUE(names.insert(k.name).second) << "duplicate knob";
        EXPECT_FALSE(k.help.empty());
        EXPECT_TRUE(k.field.get && k.field.set);
        EXPECT_TRUE(!k.flags.empty() || k.panel.widget != PanelWidget::None) << "neither a flag nor a widget shows it";
        for (const KnobFlag& f : k.flags) {
            EXPECT_EQ(f.flag.rfind("--", 0), 0u) << f.flag;
            EXPECT_TRUE(flags.insert(f.flag).second) << "flag of two knobs: " << f.flag;
            EXPECT_FALSE(commandNames.count(f.flag)) << "flag is a knob and a command flag: " << f.flag;
        }
        const KnobValueOrUnset def = k.field.get(defaults);
        EXPECT_EQ(def.has_value(), !k.field.optional) << "optional knobs default to the scene's value";
        if (k.field.optional) EXPECT_TRUE(bool(k.field.sceneValue)) << "an optional knob needs the scene's value";
        switch (k.type) {
            case KnobType::Int:
                EXPECT_TRUE(k.range.bounded()) << "int ranges are bounded (the panel's sliders need both ends)";
                EXPECT_EQ(k.range.min, std::floor(k.range.min));
                EXPECT_EQ(k.range.max, std::floor(k.range.max));
                [[fallthrough]];
            case KnobType::Float:
                EXPECT_LT(k.range.min, k.range.max);
                if (def) EXPECT_TRUE(k.range.contains(*def)) << "default " << *def << " outside " << knobRangeText(k);
                break;
            case KnobType::Bool:
                if (def) EXPECT_TRUE(*def == 0.0 || *def == 1.0);
                for (const KnobFlag& f : k.flags) EXPECT_TRUE(f.fixedValue.has_value()) << "bool flags take no value";
                break;
            case KnobType::Choice: {
                EXPECT_GE(k.choices.size(), 2u);
                EXPECT_EQ(std::set<std::string>(k.choices.begin(), k.choices.end()).size(), k.choices.size());
                ASSERT_TRUE(def.has_value());
                EXPECT_LT(size_t(*def), k.choices.size()) << "the default is not one of the choices";
                break;
            }
        }
        // The widget suits the value; a widget is in a section and a section has a widget.
        EXPECT_EQ(k.panel.section == PanelSection::None, k.panel.widget == PanelWidget::None);
        switch (k.panel.widget) {
            case PanelWidget::None: break;
            case PanelWidget::Checkbox: EXPECT_TRUE(k.type == KnobType::Bool && !k.field.optional); break;
            case PanelWidget::Combo:
                EXPECT_TRUE(k.type == KnobType::Choice || (k.type == KnobType::Bool && k.field.optional));
                break;
            case PanelWidget::Slider:
            case PanelWidget::LogSlider: EXPECT_TRUE(k.type == KnobType::Int || k.type == KnobType::Float); break;
            case PanelWidget::PowersOfTwo:
                EXPECT_EQ(k.type, KnobType::Int);
                EXPECT_LE(std::exp2(std::ceil(std::log2(k.range.min))), k.range.max) << "no power of two in range";
                break;
        }
    }
}

// Every value flag stores what it parses in its own field and nowhere else; a fixed flag stores its value.
TEST(KnobTable, EachFlagSetsItsFieldAndNoOther) {
    const RenderSettings defaults;
    for (const KnobEntry& k : knobTable()) {
        for (const KnobFlag& f : k.flags) {
            SCOPED_TRACE(f.flag);
            std::vector<std::string> args = {"render", "--scene", "x.json", "--out", "x.png", f.flag};
            double expected = 0.0;
            if (f.fixedValue) {
                expected = *f.fixedValue;
            } else {
                // A value unlike the default: the range's top, or the last choice unless that is the default.
                std::string text;
                if (k.type == KnobType::Choice) {
                    const size_t def = size_t(*k.field.get(defaults));
                    expected = double(def + 1 == k.choices.size() ? 0 : k.choices.size() - 1);
                    text = k.choices[size_t(expected)];
                } else {
                    expected = k.range.bounded() ? k.range.max : k.field.get(defaults).value_or(0.0) + 2.0;
                    text = formatKnobValue(k, expected);
                }
                args.push_back(text);
            }
            const app::Options o = app::parseArgs(args);
            const KnobValueOrUnset got = k.field.get(o.base);
            ASSERT_TRUE(got.has_value());
            EXPECT_EQ(*got, expected);
            for (const KnobEntry& other : knobTable())
                if (&other != &k) EXPECT_EQ(other.field.get(o.base), other.field.get(defaults)) << other.name << " changed too";
        }
    }
    // No flag: the settings are RenderSettings{}'s, knob by knob.
    const app::Options o = app::parseArgs({"render", "--scene", "x.json", "--out", "x.png"});
    for (const KnobEntry& k : knobTable()) EXPECT_EQ(k.field.get(o.base), k.field.get(defaults)) << k.name;
}

// What lightpass computes by default is glTF 2.0's BRDF: with no flag the CLI's settings are GGX with
// the height-correlated Smith masking (the specification's V_SmithGGXCorrelated), --help says so, and
// --specular-masking separable / --brdf blinn-phong still reach the other models.
TEST(KnobTable, BrdfDefaultsAreTheGltfSpecifications) {
    const app::Options o = app::parseArgs({"render", "--scene", "x.json", "--out", "x.png"});
    EXPECT_EQ(o.base.brdf, Brdf::Ggx);
    EXPECT_EQ(o.base.specularMasking, SpecularMasking::HeightCorrelated);
    const std::string help = std::regex_replace(app::helpText(), std::regex("\\s+"), " ");  // lines unwrapped
    EXPECT_NE(help.find("(ggx | blinn-phong; default ggx)"), std::string::npos);
    EXPECT_NE(help.find("(height-correlated | separable; default height-correlated;"), std::string::npos);
    EXPECT_EQ(app::parseArgs({"render", "--scene", "x.json", "--out", "x.png", "--specular-masking", "separable"})
                  .base.specularMasking,
              SpecularMasking::Separable);
    EXPECT_EQ(app::parseArgs({"render", "--scene", "x.json", "--out", "x.png", "--brdf", "blinn-phong"}).base.brdf,
              Brdf::BlinnPhong);
}

// The CLI checks the table's range and the panel's widgets are drawn over that same range
// (app/viewer_panel.cpp's knobWidget reads KnobEntry::range): both ends are accepted, just outside
// is refused.
TEST(KnobTable, CliRangeIsTheTableRangeThePanelUses) {
    for (const KnobEntry& k : knobTable()) {
        const KnobFlag* flag = valueFlagOf(k);
        if (!flag || (k.type != KnobType::Int && k.type != KnobType::Float)) continue;
        SCOPED_TRACE(k.name);
        const std::vector<std::string> base = {"render", "--scene", "x.json", "--out", "x.png", flag->flag};
        auto with = [&](const std::string& v) {
            auto a = base;
            a.push_back(v);
            return a;
        };
        const double step = k.type == KnobType::Int ? 1.0 : (k.range.bounded() ? (k.range.max - k.range.min) / 100 : 1.0);
        if (k.range.min > -std::numeric_limits<double>::infinity()) {
            if (!k.range.minExclusive) EXPECT_EQ(errorOf(with(formatKnobValue(k, k.range.min))), "");
            EXPECT_NE(errorOf(with(formatKnobValue(k, k.range.min - step))), "");
        }
        if (k.range.max < std::numeric_limits<double>::infinity()) {
            EXPECT_EQ(errorOf(with(formatKnobValue(k, k.range.max))), "");
            EXPECT_NE(errorOf(with(formatKnobValue(k, k.range.max + step))), "");
        }
    }
    // The two known disagreements are one range now, and the panel shows both knobs.
    const KnobEntry* size = findKnobEntry("shadow-size");
    ASSERT_NE(size, nullptr);
    EXPECT_EQ(size->range.min, 16);
    EXPECT_EQ(size->range.max, 8192);
    EXPECT_NE(size->panel.widget, PanelWidget::None);
    EXPECT_EQ(errorOf({"render", "--shadow-size", "8193"}), "--shadow-size 8193: expected a whole number in [16, 8192]");
    const KnobEntry* levels = findKnobEntry("toon-levels");
    ASSERT_NE(levels, nullptr);
    EXPECT_EQ(levels->range.min, 1);
    EXPECT_EQ(levels->range.max, 64);
    EXPECT_NE(levels->panel.widget, PanelWidget::None);
    EXPECT_EQ(errorOf({"render", "--toon-levels", "65"}), "--toon-levels 65: expected a whole number in [1, 64]");
}

// Error wording scripts and tests/cli rely on stays as it was.
TEST(KnobTable, ErrorsKeepTheirWording) {
    const std::map<std::vector<std::string>, std::string> expected = {
        {{"render", "--bloom-kernel", "102"}, "--bloom-kernel 102: expected a whole number in [1, 101]"},
        {{"render", "--post-backend", "vulkan"}, "--post-backend vulkan: expected auto, cuda or glsl"},
        {{"render", "--bloom-method", "box"}, "--bloom-method box: expected separable or mip-chain"},
        {{"render", "--ibl-diffuse", "x"}, "--ibl-diffuse x: expected sh or cubemap"},
        {{"render", "--bloom-blur", "x"}, "--bloom-blur x: expected compute or fragment"},
        {{"render", "--pcf", "7x7"}, "--pcf 7x7: unknown filter (off, 3x3, 5x5, poisson)"},
        {{"render", "--brdf", "x"}, "--brdf x: unknown BRDF (ggx, blinn-phong)"},
        {{"render", "--tonemap", "x"}, "--tonemap x: unknown operator (lightpass, aces, aces-legacy, pbr-neutral, agx)"},
        {{"render", "--local-lights", "x"}, "--local-lights x: unknown method (fullscreen, scissor, volumes, tiled, clustered)"},
        {{"render", "--gbuffer", "oct12"},
         "--gbuffer oct12: unknown format (unpacked, seed-packed, seed-packed-signed, two-angle, oct16, oct24, oct32)"},
        {{"render", "--gbuffer-position", "far"}, "--gbuffer-position far: unknown mode (stored, depth, reversed-z)"},
        {{"render", "--render-scale", "0.1"}, "--render-scale 0.1: expected a number in [0.25, 1]"},
        {{"render", "--render-scale", "nan"}, "--render-scale nan: expected a finite number"},
        {{"render", "--aa", "msaa"}, "--aa msaa: unknown anti-aliasing (off, fxaa, taa, ssaa)"},
        {{"render", "--ssaa-scale", "5"}, "--ssaa-scale 5: expected a whole number in [2, 4]"},
        {{"render", "--ssaa-scale", "1"}, "--ssaa-scale 1: expected a whole number in [2, 4]"},
        {{"render", "--light-range-scale", "2"}, "--light-range-scale 2: expected a number in [0.01, 1]"},
        {{"render", "--shadow-split-lambda", "2"}, "--shadow-split-lambda 2: expected a number in [0, 1]"},
        {{"render", "--bloom-clamp", "0"}, "--bloom-clamp 0: expected a positive number"},
        {{"render", "--bloom-threshold", "-1"}, "--bloom-threshold -1: expected a non-negative number"},
        {{"render", "--shadow-size"}, "--shadow-size: missing value"},
        {{"render", "--frobnicate"}, "unknown flag '--frobnicate' (see --help)"},
    };
    for (const auto& [args, message] : expected) EXPECT_EQ(errorOf(args), message);
    // The smallest value the message names is accepted (0.01 is not exactly a float).
    EXPECT_EQ(errorOf({"render", "--scene", "x.json", "--out", "x.png", "--light-range-scale", "0.01"}), "");
}

// --camera takes what the scene file's camera takes: coordinates beyond +-1e7 m failed later in the
// shadow pass ("light matrix is not finite") without naming the flag; fov 1e-30 was accepted.
TEST(KnobTable, CameraFlagHasTheSceneCameraLimits) {
    const std::vector<std::string> base = {"render", "--scene", "x.json", "--out", "x.png", "--camera"};
    auto with = [&](const std::string& v) {
        std::vector<std::string> a = base;
        a.push_back(v);
        return a;
    };
    EXPECT_EQ(errorOf(with("1e30,0,0,0,0,0")), "--camera 1e30,0,0,0,0,0: coordinates must be within +-1e7 m");
    EXPECT_EQ(errorOf(with("0,0,0,0,0,-2e7")), "--camera 0,0,0,0,0,-2e7: coordinates must be within +-1e7 m");
    EXPECT_EQ(errorOf(with("1e7,0,0,-1e7,0,0,90")), "");
    EXPECT_EQ(errorOf(with("0,0,0,1,0,0,1e-30")), "--camera 0,0,0,1,0,0,1e-30: fov must be in (0.5, 179) degrees");
    EXPECT_EQ(errorOf(with("0,0,0,1,0,0,179.5")), "--camera 0,0,0,1,0,0,179.5: fov must be in (0.5, 179) degrees");
    EXPECT_EQ(errorOf(with("0,0,0,1,0,0,178.9")), "");
}

TEST(KnobTable, SweepKnobsAreTableEntries) {
    std::vector<std::string> sweepEntries;
    for (const KnobEntry& k : knobTable())
        if (!k.sweep.values.empty()) sweepEntries.push_back(k.name);
    std::vector<std::string> sweepKnobs;
    for (const Knob& k : allKnobs()) sweepKnobs.push_back(k.name);
    EXPECT_EQ(sweepKnobs, sweepEntries);

    for (const Knob& knob : allKnobs()) {
        const KnobEntry* entry = findKnobEntry(knob.name);
        ASSERT_NE(entry, nullptr) << knob.name;
        SCOPED_TRACE(knob.name);
        EXPECT_EQ(knob.description, entry->sweep.description);
        EXPECT_EQ(knob.monotone, entry->sweep.monotone);
        ASSERT_EQ(knob.values.size(), entry->sweep.values.size() + entry->sweepExtraValues.size());
        for (size_t i = 0; i < entry->sweep.values.size(); ++i) {
            // In range (the CLI would take it), and applying it sets the knob's field to it.
            const double v = parseKnobValue(*entry, "--" + entry->name, entry->sweep.values[i]);
            if (entry->type == KnobType::Int || entry->type == KnobType::Float) EXPECT_TRUE(entry->range.contains(v));
            RenderSettings s;
            knob.values[i].apply(s);
            EXPECT_EQ(entry->field.get(s), KnobValueOrUnset(v)) << knob.values[i].label;
        }
    }
    // Labels as the sweep has always written them (CSV and plots key on them).
    auto labels = [](const std::string& name) {
        std::vector<std::string> out;
        for (const KnobValue& v : findKnob(name)->values) out.push_back(v.label);
        return out;
    };
    EXPECT_EQ(labels("render-scale"), (std::vector<std::string>{"0.25", "0.50", "0.75", "1.00"}));
    EXPECT_EQ(labels("light-range-cutoff"), (std::vector<std::string>{"0.25", "0.50", "0.75", "1.00"}));
    EXPECT_EQ(labels("shadow-size"), (std::vector<std::string>{"512", "1024", "2048", "4096"}));
    EXPECT_EQ(labels("bloom-kernel"), (std::vector<std::string>{"5", "10", "25", "50", "100"}));
    EXPECT_EQ(labels("bloom-method"), (std::vector<std::string>{"mip-chain", "separable"}));
    EXPECT_EQ(labels("ibl-diffuse"), (std::vector<std::string>{"sh", "cubemap"}));
    EXPECT_EQ(labels("local-light-method"), (std::vector<std::string>{"tiled", "clustered", "volumes", "scissor", "fullscreen"}));
    EXPECT_EQ(labels("gbuffer-format"), (std::vector<std::string>{"oct16", "oct24", "oct32", "seed-packed",
                                                                  "seed-packed-signed", "two-angle", "unpacked"}));
    // ibl-face-size also halves the prefiltered cube, as --env-size with --ibl-specular-size would.
    RenderSettings s;
    findKnob("ibl-face-size")->values.front().apply(s);
    EXPECT_EQ(s.environment.cubeSize, 64);
    EXPECT_EQ(s.environment.specularSize, 32);
    EXPECT_EQ(s.environment.ibl, true);    // The froxel grid's sweeps time the clustered method's own kernel, not whichever auto would race to.
    for (const char* grid : {"cluster-size", "cluster-slices"}) {
        RenderSettings g;
        findKnob(grid)->values.front().apply(g);
        EXPECT_EQ(g.localLights.method, LocalLightMethod::Clustered) << grid;
        EXPECT_EQ(g.localLights.clusteredKernel, ClusteredKernel::Froxels) << grid;
    }
}

// Every flag --help names is a knob flag or a command flag, and every one of those is in --help.
TEST(CliFlags, HelpListsExactlyTheTableAndCommandFlags) {
    const std::string help = app::helpText();
    std::set<std::string> listed = commandFlagNames();
    for (const auto& f : knobFlagNames()) listed.insert(f);
    std::set<std::string> inHelp;
    const std::regex flag("(^|[^A-Za-z0-9_-])(--?[a-z][a-z0-9-]*)");
    for (auto it = std::sregex_iterator(help.begin(), help.end(), flag); it != std::sregex_iterator(); ++it)
        inHelp.insert((*it)[2]);
    for (const auto& f : inHelp) EXPECT_TRUE(listed.count(f)) << f << " is in --help but neither a knob nor a command flag";
    for (const auto& f : listed) EXPECT_TRUE(inHelp.count(f)) << f << " is missing from --help";
    // Each knob and command flag has its own line, at the start of it.
    auto startsALine = [&](const std::string& f) {
        for (size_t at = help.find("\n  " + f); at != std::string::npos; at = help.find("\n  " + f, at + 1)) {
            const char next = help[at + 3 + f.size()];
            if (next == ' ' || next == ',') return true;
        }
        return false;
    };
    for (const auto& f : app::commandFlags()) EXPECT_TRUE(startsALine(f.names[0])) << f.names[0];
    for (const KnobEntry& k : knobTable())
        if (!k.flags.empty()) EXPECT_TRUE(startsALine(k.flags[0].flag)) << k.flags[0].flag;
    // Ranges and defaults in --help are the table's.
    EXPECT_NE(help.find("--shadow-size N   texels per side of each cascade's shadow map (16..8192, default 2048"),
              std::string::npos);
}

// The parser takes exactly the listed flags: each of them parses (or fails on its value, not as unknown).
TEST(CliFlags, ParserAcceptsTheListedFlagsAndNoOther) {
    std::set<std::string> listed = commandFlagNames();
    for (const auto& f : knobFlagNames()) listed.insert(f);
    for (const auto& f : listed) {
        const std::string error = errorOf({"render", f, "1"});  // "1" is itself an unknown flag after a bare flag
        EXPECT_EQ(error.find("unknown flag '" + f + "'"), std::string::npos) << error;
    }
    for (const std::string bogus : {"--frobnicate", "--directional-lights", "--global-lighting", "--shadows", "-x"})
        EXPECT_EQ(errorOf({"render", bogus}), "unknown flag '" + bogus + "' (see --help)");
    // Every knob flag really is the knob's (findKnobFlag is what the parser asks).
    for (const KnobEntry& k : knobTable())
        for (const KnobFlag& f : k.flags) EXPECT_EQ(findKnobFlag(f.flag), &k) << f.flag;
}

// The viewer panel draws knob widgets only through knobWidget(), from the table. Any other ImGui
// input widget in app/ must be one of the few that are not knobs (each says why). A new slider or
// checkbox written by hand fails here: add a table entry instead.
TEST(ViewerPanel, KnobWidgetsComeOnlyFromTheTable) {
    const std::map<std::string, std::string> nonKnobWidgets = {
        {"knobLabel", "knobWidget(): the table-driven widget itself"},
        {"p.name.c_str()", "the passes table's switches (--disable-pass)"},
        {"m.name.c_str()", "the materials' flat-lit switches (scene field models[].material.flat)"},
        {"pickerLabel", "the scene and environment file pickers (files, not settings)"},
        {"\"material variant\"", "a glTF's KHR_materials_variants variant (scene content: models[].materialVariant)"},
        {"\"debug view\"", "--view, a command flag"},
        {"\"with panel\"", "--screenshot-ui, a viewer option"},
        {"\"follow camera path (p)\"", "whether the viewer's camera follows the scene's cameraPath (viewer state, 'p')"},
        {"\"time (s)\"", "the viewer's scene clock, scrubbed (viewer state, not a render setting: app/viewer_clock.hpp)"},
        {"\"speed ([ ])\"", "the viewer's scene clock speed (viewer state, '[' and ']')"},
        {"\"compare with the path tracer (c)\"", "the viewer's side-by-side with the path tracer (viewer state, 'c')"},
    };
    const std::regex widget(
        R"(ImGui::(Checkbox\w*|RadioButton|Combo|BeginCombo|ListBox|BeginListBox|Slider\w*|VSlider\w*|Drag\w*|Input\w*|ColorEdit\w*|ColorPicker\w*)\s*\()");
    const std::filesystem::path app = sourceRoot() / "app";
    ASSERT_TRUE(std::filesystem::exists(app / "viewer_panel.cpp")) << app;
    int knobWidgetCalls = 0, files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(app)) {
        if (entry.path().extension() != ".cpp") continue;
        ++files;
        const std::string source = readFile(entry.path());
        for (auto it = std::sregex_iterator(source.begin(), source.end(), widget); it != std::sregex_iterator(); ++it) {
            // The first argument, up to the comma at this call's own nesting level.
            size_t end = size_t(it->position() + it->length());
            for (int depth = 0; end < source.size() && !(depth == 0 && (source[end] == ',' || source[end] == ')')); ++end)
                depth += source[end] == '(' ? 1 : source[end] == ')' ? -1 : 0;
            std::string label = source.substr(size_t(it->position() + it->length()), end - size_t(it->position() + it->length()));
            label.erase(0, label.find_first_not_of(" \n"));
            label.erase(label.find_last_not_of(" \n") + 1);
            EXPECT_TRUE(nonKnobWidgets.count(label))
                << entry.path().filename().string() << ": ImGui::" << (*it)[1] << "(" << label
                << ", ...) is drawn outside the knob table (frame/knobs.cpp)";
            if (label == "knobLabel") {
                ++knobWidgetCalls;
                const size_t at = size_t(it->position());
                const size_t fn = source.rfind("void knobWidget(", at);
                EXPECT_TRUE(fn != std::string::npos && source.find("\n}\n", fn) > at)
                    << "a knobLabel widget outside knobWidget()";
            }
        }
    }
    EXPECT_GE(files, 3);
    EXPECT_GE(knobWidgetCalls, 4) << "the regex no longer finds knobWidget()'s widgets";
    // The dead "directional lights" checkbox is gone (the passes table switches global_lights).
    EXPECT_EQ(readFile(app / "viewer_panel.cpp").find("\"directional lights\""), std::string::npos);
}

// The defaults of the first frame (issue "the default frame is right"): anti-aliasing on (SSAA 2x2:
// bench/results/aa), the exposure metered unless the scene fixes it, and --help says so.
TEST(KnobTable, DefaultFrameIsAntiAliasedAndExposed) {
    const app::Options o = app::parseArgs({"render", "--scene", "x.json", "--out", "x.png"});
    EXPECT_EQ(o.base.aa.method, AntiAliasing::Ssaa);
    EXPECT_EQ(o.base.aa.ssaaScale, 2);
    EXPECT_FALSE(o.base.autoExposure.has_value());
    Scene withoutExposure, withExposure;
    withExposure.exposure = -1.0f;
    const KnobEntry* autoExposure = nullptr;
    for (const KnobEntry& k : knobTable())
        if (k.name == "auto-exposure") autoExposure = &k;
    ASSERT_NE(autoExposure, nullptr);
    EXPECT_EQ(autoExposure->field.sceneValue(withoutExposure), 1.0);
    EXPECT_EQ(autoExposure->field.sceneValue(withExposure), 0.0);
    EXPECT_FALSE(app::parseArgs({"render", "--scene", "x.json", "--out", "x.png", "--no-auto-exposure"})
                     .base.autoExposure.value_or(true));
    const std::string help = app::helpText();
    EXPECT_NE(help.find("default ssaa"), std::string::npos);
}
