#include "engine/render/frame_data.hpp"

namespace lp {

bool iblLightsFrame(const Scene& scene, const RenderSettings& settings) {
    return !scene.environment.map.empty() && settings.environment.ibl.value_or(scene.environment.ibl);
}

namespace {
const LightsWithoutIbl* substitute(const FrameData& frame) {
    if (!frame.scene || !frame.settings || !frame.scene->lightsWithoutIbl) return nullptr;
    return iblLightsFrame(*frame.scene, *frame.settings) ? nullptr : &*frame.scene->lightsWithoutIbl;
}
}  // namespace

std::vector<DirectionalLight> frameDirectionalLights(const FrameData& frame) {
    const LightsWithoutIbl* s = substitute(frame);
    std::vector<DirectionalLight> suns = s ? s->directionalLights : frame.scene->directionalLights;
    for (DirectionalLight& sun : suns) {
        sun.direction = sun.directionAt(frame.time);
        sun.turnSpeed = 0.0f;
    }
    return suns;
}

glm::vec3 frameAmbient(const FrameData& frame) {
    // The environment's irradiance is the indirect light the constant stands in for: under IBL the
    // constant would count it twice (docs/ibl-and-tonemapping.md).
    if (frame.scene && frame.settings && iblLightsFrame(*frame.scene, *frame.settings)) return glm::vec3(0.0f);
    const LightsWithoutIbl* s = substitute(frame);
    return s ? s->ambient : frame.scene->ambient;
}

}  // namespace lp
