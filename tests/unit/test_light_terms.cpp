// A sweep knob's light term (frame/light_terms.hpp) and the surface mask its errors are taken over
// (engine/render/surface_mask.hpp).
#include <gtest/gtest.h>

#include "engine/render/surface_mask.hpp"
#include "engine/scene/primitives.hpp"
#include "frame/knobs.hpp"
#include "frame/light_terms.hpp"

using namespace lp;

namespace {

Scene litScene() {
    Scene s;
    ModelInstance plane;
    plane.name = "plane";
    plane.primitive = "plane";
    plane.mesh = makePlane(100.0f);
    plane.mesh.materials.at(0).emission = glm::vec3(2.0f);
    s.models.push_back(plane);
    DirectionalLight sun;
    sun.intensity = 3.0f;
    s.directionalLights.push_back(sun);
    PointLight point;
    point.position = glm::vec3(0.0f, 1.0f, 0.0f);
    s.pointLights.push_back(point);
    s.environment.map = "sky.hdr";
    s.environment.color = glm::vec3(0.5f);
    s.environment.ibl = true;
    s.ambient = glm::vec3(0.1f);
    return s;
}

}  // namespace

TEST(LightTerms, EachTermKeepsItsOwnLightsAndNothingElse) {
    const Scene scene = litScene();
    const RenderSettings settings;

    const Scene frame = sceneLitBy(scene, settings, LightTerm::Frame);
    EXPECT_EQ(frame.directionalLights.size(), 1u);
    EXPECT_EQ(frame.pointLights.size(), 1u);
    EXPECT_EQ(frame.models[0].mesh.materials[0].emission, glm::vec3(2.0f));

    const Scene suns = sceneLitBy(scene, settings, LightTerm::Suns);
    EXPECT_EQ(suns.directionalLights.size(), 1u);
    EXPECT_TRUE(suns.pointLights.empty());
    EXPECT_TRUE(suns.environment.map.empty());
    EXPECT_EQ(suns.environment.color, glm::vec3(0.0f));
    EXPECT_EQ(suns.ambient, glm::vec3(0.0f));
    EXPECT_EQ(suns.models[0].mesh.materials[0].emission, glm::vec3(0.0f));

    const Scene environment = sceneLitBy(scene, settings, LightTerm::Environment);
    EXPECT_TRUE(environment.directionalLights.empty());
    EXPECT_TRUE(environment.pointLights.empty());
    EXPECT_EQ(environment.environment.map, scene.environment.map);
    EXPECT_TRUE(environment.environment.ibl);
    EXPECT_EQ(environment.ambient, scene.ambient);  // the stand-in for the environment's light
    EXPECT_EQ(environment.models[0].mesh.materials[0].emission, glm::vec3(0.0f));

    const Scene locals = sceneLitBy(scene, settings, LightTerm::LocalLights);
    EXPECT_TRUE(locals.directionalLights.empty());
    EXPECT_EQ(locals.pointLights.size(), 1u);
    EXPECT_TRUE(locals.environment.map.empty());
    EXPECT_EQ(locals.ambient, glm::vec3(0.0f));
}

TEST(LightTerms, TheSunsOfAFrameWithoutIblAreItsStandIns) {
    // A bare model: lit by its map, or by a key light when IBL is off. The suns term follows the frame.
    Scene scene = litScene();
    scene.directionalLights.clear();
    LightsWithoutIbl rig;
    rig.directionalLights.push_back(DirectionalLight{});
    rig.ambient = glm::vec3(0.2f);
    scene.lightsWithoutIbl = rig;
    RenderSettings ibl;
    EXPECT_TRUE(sceneLitBy(scene, ibl, LightTerm::Suns).directionalLights.empty());
    RenderSettings noIbl;
    noIbl.environment.ibl = false;
    const Scene suns = sceneLitBy(scene, noIbl, LightTerm::Suns);
    EXPECT_EQ(suns.directionalLights.size(), 1u);
    EXPECT_FALSE(suns.lightsWithoutIbl.has_value());
    // The environment term keeps the stand-in ambient, not its key light.
    const Scene environment = sceneLitBy(scene, noIbl, LightTerm::Environment);
    ASSERT_TRUE(environment.lightsWithoutIbl.has_value());
    EXPECT_TRUE(environment.lightsWithoutIbl->directionalLights.empty());
    EXPECT_EQ(environment.lightsWithoutIbl->ambient, glm::vec3(0.2f));
}

TEST(LightTerms, KnobsNameTheLightTheyChange) {
    EXPECT_EQ(findKnob("shadow-size")->term, LightTerm::Suns);
    EXPECT_EQ(findKnob("ibl-specular")->term, LightTerm::Environment);
    EXPECT_EQ(findKnob("ao-directions")->term, LightTerm::Environment);
    EXPECT_EQ(findKnob("local-light-method")->term, LightTerm::LocalLights);
    EXPECT_EQ(findKnob("aa")->term, LightTerm::Frame);
    EXPECT_EQ(knobByName("shadow-size+shadow-pcf")->term, LightTerm::Suns);
    EXPECT_EQ(knobByName("shadow-size+ibl-specular")->term, LightTerm::Frame);
}

TEST(SurfaceMask, AGroundPlaneFillsTheRowsBelowTheHorizon) {
    // Camera 1 above an endless (100 m) ground looking level: a pixel centre sees the ground iff its
    // ray points down, i.e. in the bottom half of the rows (rows top first).
    Scene scene = litScene();
    Camera camera;
    camera.position = glm::vec3(0.0f, 1.0f, 0.0f);
    camera.target = glm::vec3(0.0f, 1.0f, -1.0f);
    camera.fovYDegrees = 60.0f;
    camera.nearPlane = 0.1f;
    camera.farPlane = 1000.0f;
    const int w = 8, h = 6;
    const std::vector<uint8_t> mask = surfaceMask(scene, camera, w, h);
    ASSERT_EQ(mask.size(), size_t(w * h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) EXPECT_EQ(mask[size_t(y * w + x)], y >= h / 2 ? 1 : 0) << "pixel " << x << "," << y;
    // Beyond the far plane nothing counts: the ground 10 below, the far plane at 0.5.
    camera.farPlane = 0.5f;
    camera.position.y = 10.0f;
    camera.target.y = 10.0f;
    for (uint8_t m : surfaceMask(scene, camera, w, h)) EXPECT_EQ(m, 0);
    // No models: nothing.
    scene.models.clear();
    for (uint8_t m : surfaceMask(scene, camera, w, h)) EXPECT_EQ(m, 0);
}
