#pragma once
// Which exposure a frame gets. A scene file's "exposure" (EV) fixes it; a scene without one is
// metered each frame (the auto_exposure pass, passes/auto_exposure_pass.hpp). --auto-exposure /
// --no-auto-exposure override that choice, and --exposure is always added on top: the compensation
// of the metered exposure, or a change of the fixed one.
#include "engine/render/settings.hpp"
#include "engine/scene/scene.hpp"

namespace lp {

// Whether the frame meters its exposure: settings.autoExposure, else on unless the scene fixes one.
bool autoExposureOn(const RenderSettings& settings, const Scene& scene);

// The EV the tone map and the HDR views apply besides the metered one: --exposure, plus the scene's
// fixed "exposure" when the frame is not metered.
float exposureEvBase(const RenderSettings& settings, const Scene& scene);

}  // namespace lp
