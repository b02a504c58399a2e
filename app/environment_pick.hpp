#pragma once
// The viewer's environment picker, apart from the window so that tests reach it: picking a map
// lights the scene with it, as model viewers do (Filament's, three.js's, Khronos's).
#include <filesystem>
#include <optional>

#include "engine/render/settings.hpp"
#include "engine/scene/scene.hpp"

namespace lp::app {

// What a pick replaced, to put back when the map does not load.
struct EnvironmentBefore {
    std::filesystem::path map;
    bool sceneIbl = false;
    std::optional<bool> iblKnob;
};

// `map` becomes the scene's environment map. A map turns IBL on: the scene's switch, and the IBL
// knob where it was switched off (--brdf-only, the panel). An empty path ("plain colour") leaves
// both as they are: without a map IBL lights nothing, and a bare model's key and fill take over.
EnvironmentBefore pickEnvironment(Scene& scene, RenderSettings& settings, const std::filesystem::path& map);
void restoreEnvironment(Scene& scene, RenderSettings& settings, const EnvironmentBefore& before);

}  // namespace lp::app
