#include "engine/render/settings.hpp"

namespace lp {

const char* viewName(DebugView v) {
    switch (v) {
        case DebugView::Final: return "final";
        case DebugView::Depth: return "depth";
        case DebugView::Normals: return "normals";
        case DebugView::Diffuse: return "diffuse";
        case DebugView::Position: return "position";
        case DebugView::Shininess: return "shininess";
        case DebugView::Specular: return "specular";
        case DebugView::Texcoords: return "texcoords";
        case DebugView::Lighting: return "lighting";
        case DebugView::Environment: return "environment";
        case DebugView::Irradiance: return "irradiance";
        case DebugView::Prefiltered: return "prefiltered";
        case DebugView::Dfg: return "dfg";
        case DebugView::ShadowMap: return "shadowmap";
        case DebugView::LightRanges: return "light-ranges";
        case DebugView::LightsPerTile: return "lights-per-tile";
        case DebugView::LightsPerCluster: return "lights-per-cluster";
        case DebugView::WorldPosition: return "world-position";
        case DebugView::EyeVector: return "eye-vector";
        case DebugView::DepthFitted: return "depth-fitted";
        case DebugView::Tangent: return "tangent";
        case DebugView::InvalidPixels: return "invalid-pixels";
        case DebugView::ExposureEv: return "exposure-ev";
        case DebugView::Velocity: return "velocity";
        case DebugView::Ao: return "ao";
        case DebugView::BaseColor: return "base-color";
        case DebugView::Metallic: return "metallic";
        case DebugView::Roughness: return "roughness";
        case DebugView::Occlusion: return "occlusion";
        case DebugView::Emissive: return "emissive";
        case DebugView::TermDiffuse: return "term-diffuse";
        case DebugView::TermSpecular: return "term-specular";
    }
    return "final";
}

std::vector<DebugView> allViews() {
    return {DebugView::Final,     DebugView::Depth,    DebugView::Normals,   DebugView::Diffuse, DebugView::Position,
            DebugView::Shininess, DebugView::Specular, DebugView::Texcoords, DebugView::Lighting,
            DebugView::Environment, DebugView::Irradiance, DebugView::Prefiltered, DebugView::Dfg,
            DebugView::WorldPosition, DebugView::EyeVector, DebugView::DepthFitted, DebugView::Tangent,
            DebugView::InvalidPixels, DebugView::ExposureEv, DebugView::Velocity, DebugView::Ao,
            DebugView::BaseColor, DebugView::Metallic, DebugView::Roughness, DebugView::Occlusion,
            DebugView::Emissive, DebugView::TermDiffuse, DebugView::TermSpecular};
}

std::vector<DebugView> materialInputViews() {
    return {DebugView::BaseColor, DebugView::Metallic, DebugView::Roughness, DebugView::Occlusion, DebugView::Emissive};
}

std::vector<DebugView> termViews() { return {DebugView::TermDiffuse, DebugView::TermSpecular}; }

DebugView nextViewInCycle(const std::vector<DebugView>& cycle, DebugView view) {
    for (size_t i = 0; i < cycle.size(); ++i)
        if (cycle[i] == view) return i + 1 < cycle.size() ? cycle[i + 1] : DebugView::Final;
    return cycle.empty() ? DebugView::Final : cycle.front();
}

int hiddenShadingTerms(DebugView view) {
    switch (view) {
        case DebugView::TermDiffuse: return kHideSpecular | kHideEmission;
        case DebugView::TermSpecular: return kHideDiffuse | kHideEmission;
        case DebugView::Emissive: return kHideDiffuse | kHideSpecular;
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

std::vector<DebugView> everyView() {
    std::vector<DebugView> views = allViews();
    views.push_back(DebugView::ShadowMap);
    for (DebugView v : localLightViews()) views.push_back(v);
    return views;
}

std::optional<DebugView> parseView(const std::string& name) {
    for (DebugView v : allViews())
        if (name == viewName(v)) return v;
    // Not in allViews(): it shows a light's shadow map, not the camera's image, and needs a
    // shadow-casting light (the camera views work on every scene).
    if (name == viewName(DebugView::ShadowMap)) return DebugView::ShadowMap;
    for (DebugView v : localLightViews())
        if (name == viewName(v)) return v;
    return std::nullopt;
}

std::vector<DebugView> localLightViews() {
    return {DebugView::LightRanges, DebugView::LightsPerTile, DebugView::LightsPerCluster};
}
bool isLocalLightView(DebugView v) {
    return v == DebugView::LightRanges || v == DebugView::LightsPerTile || v == DebugView::LightsPerCluster;
}

const char* renderPathName(RenderPath path) {
    switch (path) {
        case RenderPath::Deferred: return "deferred";
        case RenderPath::ForwardPlus: return "forward+";
        case RenderPath::PathTraced: return "pathtraced";
    }
    return "deferred";
}

std::optional<RenderPath> parseRenderPath(const std::string& name) {
    for (RenderPath p : {RenderPath::Deferred, RenderPath::ForwardPlus, RenderPath::PathTraced})
        if (name == renderPathName(p)) return p;
    return std::nullopt;
}

}  // namespace lp
