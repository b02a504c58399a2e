#include "engine/render/exposure.hpp"

namespace lp {

bool autoExposureOn(const RenderSettings& settings, const Scene& scene) {
    return settings.autoExposure.value_or(!scene.exposure.has_value());
}

float exposureEvBase(const RenderSettings& settings, const Scene& scene) {
    return settings.exposureEV + (autoExposureOn(settings, scene) ? 0.0f : scene.exposure.value_or(0.0f));
}

}  // namespace lp
