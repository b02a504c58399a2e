#include "app/environment_pick.hpp"

namespace lp::app {

EnvironmentBefore pickEnvironment(Scene& scene, RenderSettings& settings, const std::filesystem::path& map) {
    EnvironmentBefore before{scene.environment.map, scene.environment.ibl, settings.environment.ibl};
    scene.environment.map = map;
    if (!map.empty()) {
        scene.environment.ibl = true;
        if (settings.environment.ibl == false) settings.environment.ibl = true;
    }
    return before;
}

void restoreEnvironment(Scene& scene, RenderSettings& settings, const EnvironmentBefore& before) {
    scene.environment.map = before.map;
    scene.environment.ibl = before.sceneIbl;
    settings.environment.ibl = before.iblKnob;
}

}  // namespace lp::app
