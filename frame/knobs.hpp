#pragma once
// Quality knobs: settings that trade accuracy for time, each with its values ordered from cheapest
// to best. `lightpass sweep` renders every value, measures GPU time and the error against the best
// value (the reference), so users see what accuracy costs.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "engine/render/settings.hpp"

namespace lp {

struct KnobValue {
    std::string label;
    std::function<void(RenderSettings&)> apply;
};

struct Knob {
    std::string name;
    std::string description;
    std::vector<KnobValue> values;  // cheapest first; the last is the reference
    bool monotone = true;           // error should fall as the value rises (tests check it)
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
