#pragma once
// What the user chose for a frame (CLI flags, keys, later the UI): independent of the scene.
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace lp {

enum class DebugView { Final, Depth, Normals, Diffuse, Position, Shininess, Specular, Texcoords, Lighting };

const char* viewName(DebugView view);
std::optional<DebugView> parseView(const std::string& name);
std::vector<DebugView> allViews();

// Each feature area owns one of these structs (and only its own fields).
struct ShadowSettings {         // [shadows] directional-light shadow maps
    bool enabled = true;
};
struct LocalLightSettings {     // [local-lights] ranged point lights
    bool enabled = true;
};
struct EnvironmentSettings {    // [ibl] environment, skybox, image-based lighting, tone map operator
    bool ibl = false;           // false: analytic lights + constant ambient; true: + IBL
};
struct PostSettings {           // [post] bloom and toon
    bool bloom = false;
    bool toon = false;
};

struct RenderSettings {
    int width = 1280;
    int height = 720;
    DebugView view = DebugView::Final;
    float exposureEV = 0.0f;
    bool globalLighting = true;  // the directional-light pass
    bool keepHdr = false;        // keep the HDR buffer as an output (EXR dumps)
    std::set<std::string> disabledPasses;  // switched off in the UI / --disable-pass
    ShadowSettings shadows;
    LocalLightSettings localLights;
    EnvironmentSettings environment;
    PostSettings post;
};

}  // namespace lp
