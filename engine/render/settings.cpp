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
    }
    return "final";
}

std::vector<DebugView> allViews() {
    return {DebugView::Final,     DebugView::Depth,    DebugView::Normals,   DebugView::Diffuse, DebugView::Position,
            DebugView::Shininess, DebugView::Specular, DebugView::Texcoords, DebugView::Lighting};
}

std::optional<DebugView> parseView(const std::string& name) {
    for (DebugView v : allViews())
        if (name == viewName(v)) return v;
    return std::nullopt;
}

}  // namespace lp
