#pragma once
// Quality knobs: settings that trade accuracy for time, each with its values ordered from cheapest
// to best. `lightpass sweep` renders every value, measures GPU time and the error against the best
// value (the reference), so users see what accuracy costs.
#include <functional>
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

}  // namespace lp
