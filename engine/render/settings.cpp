#include "engine/render/settings.hpp"

namespace lp {

std::vector<DebugView> allViews() {
    std::vector<DebugView> views;
    for (const auto& e : kViewNames)
        if (e.value != DebugView::ShadowMap && !isLocalLightView(e.value)) views.push_back(e.value);
    return views;
}

std::vector<DebugView> materialInputViews() {
    return {DebugView::BaseColor, DebugView::Metallic, DebugView::Roughness, DebugView::Occlusion, DebugView::Emissive};
}

std::vector<DebugView> termViews() { return {DebugView::TermDiffuse, DebugView::TermSpecular, DebugView::TermClearcoat}; }

DebugView nextViewInCycle(const std::vector<DebugView>& cycle, DebugView view) {
    for (size_t i = 0; i < cycle.size(); ++i)
        if (cycle[i] == view) return i + 1 < cycle.size() ? cycle[i + 1] : DebugView::Final;
    return cycle.empty() ? DebugView::Final : cycle.front();
}

int hiddenShadingTerms(DebugView view) {
    switch (view) {
        case DebugView::TermDiffuse: return kHideSpecular | kHideEmission | kHideClearcoat;
        case DebugView::TermSpecular: return kHideDiffuse | kHideEmission | kHideClearcoat;
        case DebugView::TermClearcoat: return kHideDiffuse | kHideSpecular | kHideEmission;
        case DebugView::Emissive: return kHideDiffuse | kHideSpecular | kHideClearcoat;
        default: return 0;
    }
}

int materialInputShown(DebugView view) {
    switch (view) {  // = LP_MATERIAL_INPUT_* (shaders/common/material.glsl)
        case DebugView::BaseColor: return 1;
        case DebugView::Metallic: return 2;
        case DebugView::Roughness: return 3;
        case DebugView::Occlusion: return 4;
        default: return 0;
    }
}

bool isShadingTermView(DebugView view) { return hiddenShadingTerms(view) != 0; }

std::vector<DebugView> localLightViews() {
    return {DebugView::LightRanges, DebugView::LightsPerTile, DebugView::LightsPerCluster};
}
bool isLocalLightView(DebugView v) {
    return v == DebugView::LightRanges || v == DebugView::LightsPerTile || v == DebugView::LightsPerCluster;
}

}  // namespace lp
