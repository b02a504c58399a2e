#pragma once
// What the user chose for a frame (CLI flags, keys, later the UI): independent of the scene.
#include <optional>
#include <string>
#include <vector>

namespace lp {

enum class DebugView { Final, Depth, Normals, Diffuse, Position, Shininess, Specular, Texcoords, Lighting };

const char* viewName(DebugView view);
std::optional<DebugView> parseView(const std::string& name);
std::vector<DebugView> allViews();

struct RenderSettings {
    int width = 1280;
    int height = 720;
    DebugView view = DebugView::Final;
    float exposureEV = 0.0f;
    bool globalLighting = true;  // the directional-light pass
    bool keepHdr = false;        // keep the HDR buffer as an output (EXR dumps)
};

}  // namespace lp
