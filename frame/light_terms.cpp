#include "frame/light_terms.hpp"

#include "engine/render/frame_data.hpp"

namespace lp {

Scene sceneLitBy(const Scene& scene, const RenderSettings& settings, LightTerm term) {
    Scene lit = scene;
    if (term == LightTerm::Frame) return lit;
    for (ModelInstance& model : lit.models)
        for (Material& m : model.mesh.materials) m.emission = glm::vec3(0.0f);
    // The suns this scene's frames use: its own, or the stand-ins a frame without IBL takes.
    const bool ibl = iblLightsFrame(scene, settings);
    const std::vector<DirectionalLight> suns =
        ibl || !scene.lightsWithoutIbl ? scene.directionalLights : scene.lightsWithoutIbl->directionalLights;
    auto noEnvironment = [&] {
        lit.environment.map.clear();
        lit.environment.color = glm::vec3(0.0f);
        lit.environment.ibl = false;
        lit.ambient = glm::vec3(0.0f);
        lit.lightsWithoutIbl.reset();
    };
    switch (term) {
    case LightTerm::Suns:
        noEnvironment();
        lit.directionalLights = suns;
        lit.pointLights.clear();
        break;
    case LightTerm::Environment:
        lit.directionalLights.clear();
        if (lit.lightsWithoutIbl) lit.lightsWithoutIbl->directionalLights.clear();  // its ambient stays
        lit.pointLights.clear();
        break;
    case LightTerm::LocalLights:
        noEnvironment();
        lit.directionalLights.clear();
        break;
    case LightTerm::Frame:
        break;
    }
    return lit;
}

}  // namespace lp
