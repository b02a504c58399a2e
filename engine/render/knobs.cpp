#include "engine/render/knobs.hpp"

namespace lp {

namespace {
std::vector<Knob> makeKnobs() {
    std::vector<Knob> knobs;
    // [knobs] each feature area registers its quality knobs here.
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

std::string knobNames() {
    std::string s;
    for (const auto& k : allKnobs()) s += (s.empty() ? "" : ", ") + k.name;
    return s.empty() ? "(none)" : s;
}

}  // namespace lp
