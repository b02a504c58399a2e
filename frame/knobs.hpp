#pragma once
// The knob table: every user-facing setting in one place. Each entry names its RenderSettings field,
// CLI flag(s), value type, range, help text, viewer panel widget and, for quality knobs, the values
// `lightpass sweep` renders. The CLI parser and --help (app/cli.cpp), the panel
// (app/viewer_panel.cpp) and the sweep (allKnobs()) are generated from it, so they cannot disagree.
// Adding a knob: its field in engine/render/settings.hpp (the default lives there) and one entry in
// knobTable() (frame/knobs.cpp).
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "engine/render/settings.hpp"
#include "engine/scene/scene.hpp"
#include "frame/light_terms.hpp"

namespace lp {

enum class KnobType { Int, Float, Bool, Choice };

// A knob's value as the table moves it: ints and floats exactly, bools as 0/1, a choice as its index
// in `choices`. nullopt: unset, the scene's value applies (optional settings only).
using KnobValueOrUnset = std::optional<double>;

struct KnobField {
    std::function<KnobValueOrUnset(const RenderSettings&)> get;
    std::function<void(RenderSettings&, KnobValueOrUnset)> set;
    bool optional = false;                          // may be unset: the scene's value applies
    std::function<double(const Scene&)> sceneValue;  // optional fields: the value unset stands for
};

// Inclusive unless minExclusive; an infinite bound is no bound.
struct KnobRange {
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    bool minExclusive = false;
    bool contains(double v) const { return (minExclusive ? v > min : v >= min) && v <= max; }
    bool bounded() const { return min > -std::numeric_limits<double>::infinity() && max < std::numeric_limits<double>::infinity(); }
};

struct KnobFlag {
    std::string flag;               // "--shadow-size", "--no-shadows"
    KnobValueOrUnset fixedValue;    // set: the flag takes no argument and sets this ("--no-shadows": 0)
};

enum class PanelSection { None, View, Lighting, Shadows, Post };
enum class PanelWidget {
    None,
    Slider,         // Int/Float over the knob's range (a drag box where the range is open-ended)
    LogSlider,      // the same, logarithmic
    PowersOfTwo,    // Int: a combo of the powers of two in the range
    Checkbox,       // Bool
    Combo,          // Choice; an optional Bool: scene (on|off) / off / on
};
struct KnobPanel {
    PanelSection section = PanelSection::None;
    PanelWidget widget = PanelWidget::None;
    std::string label;   // the panel's words ("map size"); the knob's name where empty
    std::string format;  // slider printf format; "%d" / "%.2f" where empty
};

// One swept setting: its label in the tables and what it sets.
struct KnobValue {
    std::string label;
    std::function<void(RenderSettings&)> apply;
};

struct KnobSweep {
    std::vector<std::string> values;  // in the flag's syntax, cheapest first; the last is the reference
    bool monotone = true;             // error should fall as the value rises (tests check it)
    std::string description;
    // What a swept value switches on besides the field (shadows, IBL, bloom), given the value.
    std::function<void(RenderSettings&, double)> alsoSet;
    // The light the knob changes: the sweep also measures it alone (frame/light_terms.hpp).
    LightTerm term = LightTerm::Frame;
};

struct KnobEntry {
    std::string name;                  // "shadow-size": the sweep's --knob name and the test's handle
    KnobType type = KnobType::Int;
    KnobField field;
    std::vector<KnobFlag> flags;
    std::vector<std::string> choices;  // Choice: value i is choices[i]
    std::string choiceNoun;            // a bad choice: "unknown NOUN (a, b)"; empty: "expected a or b"
    KnobRange range;                   // Int/Float
    std::string help;                  // --help's words; range and default are appended
    KnobPanel panel;
    KnobSweep sweep;                   // no values: not a sweep knob
    // Points swept after sweep.values that set more than this knob's field (aa: "ssaa2" is --aa ssaa
    // --ssaa-scale 2); when there are any, the last of them is the reference.
    std::vector<KnobValue> sweepExtraValues;
};

const std::vector<KnobEntry>& knobTable();
const KnobEntry* findKnobEntry(const std::string& name);
// The entry that owns a flag, and which of its flags it is; nullptr for a flag of no knob.
const KnobEntry* findKnobFlag(const std::string& flag, const KnobFlag** which = nullptr);

// A flag's value parsed and range-checked as the table says; throws lp::Error with one line
// ("--shadow-size 9: expected a whole number in [16, 8192]").
double parseKnobValue(const KnobEntry& knob, const std::string& flag, const std::string& text);
// "2048", "0.75", "3x3", "on"; "scene's" for unset.
std::string formatKnobValue(const KnobEntry& knob, KnobValueOrUnset value);
std::string knobDefault(const KnobEntry& knob);  // formatKnobValue of RenderSettings{}'s value
std::string knobRangeText(const KnobEntry& knob);  // "16..8192", ">= 0", "off | 3x3 | ..."; "" for Bool

// --help's lines for every knob flag, and one line's layout (shared with the non-knob flags).
std::string knobHelpText();
std::string helpLine(const std::string& flags, const std::string& text);

// ---- the sweep: the table's entries that have sweep values ----

struct Knob {
    std::string name;
    std::string description;
    std::vector<KnobValue> values;  // cheapest first; the last is the reference
    bool monotone = true;           // error should fall as the value rises (tests check it)
    LightTerm term = LightTerm::Frame;  // the light it changes; a product of knobs of two terms: Frame
};

const std::vector<Knob>& allKnobs();
const Knob* findKnob(const std::string& name);
std::string knobNames();

// A knob by name, or the product of several ("shadow-size+shadow-pcf"): every combination of their
// values, the first knob's value varying slowest, labelled "512/off"; the reference is every
// knob's reference together. A product is never monotone (no order of pairs is cheapest first).
// Empty when a part is unknown or repeated.
std::optional<Knob> knobByName(const std::string& spec);

}  // namespace lp
