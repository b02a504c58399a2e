// Scene files: the bundled scenes load; every malformed field is an error naming file and field.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/scene/scene_loader.hpp"

using namespace lp;

namespace {
std::string errorFor(const std::string& json) {
    try {
        parseScene(json, "test.json", false);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}
}  // namespace

TEST(SceneLoader, DefaultSceneLoads) {
    Scene s = loadScene(std::string(LIGHTPASS_SOURCE_DIR) + "/scenes/cornell.json");
    EXPECT_EQ(s.models.size(), 3u);
    EXPECT_EQ(s.directionalLights.size(), 1u);
    EXPECT_GE(s.pointLights.size(), 2u);
    EXPECT_FALSE(s.models[0].mesh.vertices.empty());
    glm::vec3 lo, hi;
    s.bounds(lo, hi);
    EXPECT_NEAR(hi.x - lo.x, 0.556f, 0.01f);  // the published 556 mm width
    EXPECT_NEAR(hi.y - lo.y, 0.5488f, 0.01f);
}

TEST(SceneLoader, ParsesEveryField) {
    Scene s = parseScene(R"({
      "camera": {"position": [1, 2, 3], "target": [0, 0, 0], "fov": 60, "near": 0.5, "far": 50},
      "models": [{"primitive": "sphere", "translate": [1, 0, 0], "scale": [2, 2, 2], "rotate": [0, 90, 0],
                  "material": {"diffuse": [0.1, 0.2, 0.3], "shininess": 5}}],
      "lights": [{"type": "directional", "direction": [0, -2, 0], "intensity": 2, "shadows": false},
                 {"type": "point", "position": [0, 1, 0], "range": 3, "orbit": {"speed": 1}}],
      "environment": {"color": [0.1, 0.1, 0.1], "intensity": 2, "rotation": 45},
      "ambient": 0.05,
      "effects": {"bloom": {"kernel": 51}, "toon": {"enabled": false, "levels": 3}}
    })", "inline.json", true);
    EXPECT_FLOAT_EQ(s.camera.fovYDegrees, 60.0f);
    ASSERT_EQ(s.models.size(), 1u);
    EXPECT_EQ(s.models[0].mesh.materials[0].diffuse, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_FLOAT_EQ(s.models[0].mesh.materials[0].shininess, 5.0f);
    EXPECT_NEAR(glm::length(s.directionalLights[0].direction), 1.0f, 1e-6f);
    EXPECT_FALSE(s.directionalLights[0].castsShadows);
    EXPECT_FLOAT_EQ(s.pointLights[0].range, 3.0f);
    EXPECT_TRUE(s.effects.bloom.enabled);
    EXPECT_EQ(s.effects.bloom.kernelSize, 51);
    EXPECT_FALSE(s.effects.toon.enabled);
    EXPECT_EQ(s.ambient, glm::vec3(0.05f));
}

TEST(SceneLoader, ErrorsNameFileAndField) {
    EXPECT_NE(errorFor("{").find("test.json: invalid JSON"), std::string::npos);
    EXPECT_NE(errorFor(R"({"cameraa": {}})").find("test.json: cameraa: unknown field"), std::string::npos);
    EXPECT_NE(errorFor(R"({"models": [{"primitive": "cube", "scale": "big"}]})").find("models[0].scale: expected an array of 3 numbers"),
              std::string::npos);
    EXPECT_NE(errorFor(R"({"models": [{"primitive": "torus"}]})").find("unknown primitive 'torus'"), std::string::npos);
    EXPECT_NE(errorFor(R"({"models": [{}]})").find("exactly one of"), std::string::npos);
    EXPECT_NE(errorFor(R"({"lights": [{"type": "area"}]})").find("lights[0].type: unknown light type 'area' (directional, point, spot)"), std::string::npos);
    EXPECT_NE(errorFor(R"({"lights": [{"type": "point", "range": 0}]})").find("lights[0].range: must be > 0"), std::string::npos);
    EXPECT_NE(errorFor(R"({"lights": [{"type": "directional", "direction": [0, 0, 0]}]})").find("zero vector"), std::string::npos);
    EXPECT_NE(errorFor(R"({"lights": [{"type": "point", "color": [-1, 0, 0]}]})").find(">= 0"), std::string::npos);
    EXPECT_NE(errorFor(R"({"camera": {"near": 2, "far": 1}})").find("camera.far: must be greater than near"), std::string::npos);
    EXPECT_NE(errorFor(R"({"camera": {"fov": 1e39}})").find("camera.fov: not a finite number"), std::string::npos);
    EXPECT_NE(errorFor(R"({"effects": {"bloom": {"kernel": 500}}})").find("effects.bloom.kernel: must be in [1, 101]"), std::string::npos);
    EXPECT_NE(errorFor(R"({"models": [{"primitive": "cube", "material": {"shininess": 20000}}]})").find("[0, 10000]"),
              std::string::npos);
    // Reflectances above 1 give back more light than arrives; only a flat (unlit) colour may be brighter.
    EXPECT_NE(errorFor(R"({"models": [{"primitive": "cube", "material": {"diffuse": [1.5, 0.5, 0.5]}}]})")
                  .find("test.json: models[0].material.diffuse: reflectance components must be <= 1"),
              std::string::npos);
    EXPECT_NE(errorFor(R"({"models": [{"primitive": "cube", "material": {"specular": [0.5, 0.5, 2]}}]})")
                  .find("test.json: models[0].material.specular: reflectance components must be <= 1"),
              std::string::npos);
    EXPECT_NE(errorFor(R"({"models": [{"primitive": "cube", "material": {"flat": true, "specular": [0.5, 0.5, 2]}}]})")
                  .find("models[0].material.specular: reflectance"),
              std::string::npos);
    EXPECT_EQ(errorFor(R"({"models": [{"primitive": "cube", "material": {"flat": true, "diffuse": [4, 2, 1]}}]})"), "");
}

// environment.ibl turns image-based lighting on from the scene file; it needs a map to light with.
TEST(SceneLoader, EnvironmentIblNeedsAMap) {
    EXPECT_TRUE(parseScene(R"({"environment": {"map": "sky.exr", "ibl": true}})", "test.json", false).environment.ibl);
    EXPECT_FALSE(parseScene(R"({"environment": {"map": "sky.exr"}})", "test.json", false).environment.ibl);
    EXPECT_NE(errorFor(R"({"environment": {"ibl": true}})").find("test.json: environment.ibl: true needs environment.map"),
              std::string::npos);
}

TEST(SceneLoader, MissingObjNamesBothFiles) {
    try {
        parseScene(R"({"models": [{"obj": "nope.obj"}]})", "dir/s.json", true);
        FAIL() << "no error";
    } catch (const Error& e) {
        std::string m = e.what();
        EXPECT_NE(m.find("dir/s.json: models[0].obj:"), std::string::npos) << m;
        EXPECT_NE(m.find("nope.obj: file not found"), std::string::npos) << m;
    }
}

TEST(SceneLoader, WithoutCameraFramesTheBounds) {
    Scene s = parseScene(R"({"models": [{"primitive": "cube", "translate": [10, 0, 0], "scale": 2}]})", "x.json", true);
    EXPECT_NEAR(s.camera.target.x, 10.0f, 1e-4f);
    EXPECT_GT(glm::length(s.camera.position - s.camera.target), 2.0f);
    EXPECT_LT(s.camera.nearPlane, glm::length(s.camera.position - s.camera.target) - 1.8f);
}

TEST(SceneLoader, EveryBundledSceneParses) {
    const std::filesystem::path dir = std::filesystem::path(LIGHTPASS_SOURCE_DIR) / "scenes";
    int count = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        if (entry.path().extension() != ".json") continue;
        std::ifstream in(entry.path());
        std::stringstream text;
        text << in.rdbuf();
        EXPECT_NO_THROW(parseScene(text.str(), entry.path(), false)) << entry.path();
        ++count;
    }
    EXPECT_GE(count, 4);
}

TEST(SceneLoader, GalleryLoadsTheStanfordModels) {
    if (!std::filesystem::exists(LIGHTPASS_SHARED_ASSETS)) GTEST_SKIP() << "no ../shared/assets here";
    Scene s = loadScene(std::string(LIGHTPASS_SOURCE_DIR) + "/scenes/gallery.json");
    EXPECT_EQ(s.pointLights.size(), 256u);
    EXPECT_EQ(s.directionalLights.size(), 2u);
    size_t triangles = 0;
    for (const auto& m : s.models) triangles += m.mesh.indices.size() / 3;
    EXPECT_GT(triangles, 250000u);  // bunny 69k + dragon 100k + buddha 113k
}

// models[].material.flat: every material of the model flat-lit (seed 003); a bool, nothing else.
TEST(SceneLoader, MaterialFlatMarksTheModelsMaterials) {
    Scene s = parseScene(R"({"models": [{"primitive": "cube", "material": {"flat": true}},
                                       {"primitive": "plane"}]})", "test.json", false);
    ASSERT_EQ(s.models.size(), 2u);
    for (const Material& m : s.models[0].mesh.materials) EXPECT_TRUE(m.flat);
    for (const Material& m : s.models[1].mesh.materials) EXPECT_FALSE(m.flat);
    const std::string e = errorFor(R"({"models": [{"primitive": "cube", "material": {"flat": "yes"}}]})");
    EXPECT_NE(e.find("test.json: models[0].material.flat"), std::string::npos) << e;
}

TEST(SceneLoader, LightGlobesIsABool) {
    EXPECT_TRUE(parseScene(R"({"lightGlobes": true})", "test.json", false).lightGlobes);
    EXPECT_FALSE(parseScene(R"({})", "test.json", false).lightGlobes);
    EXPECT_NE(errorFor(R"({"lightGlobes": 1})").find("lightGlobes: expected true or false"), std::string::npos)
        << errorFor(R"({"lightGlobes": 1})");
}

// material.roughness: perceptual GGX roughness in [0.02, 1], stored as the Blinn-Phong exponent of
// the same width (alpha = r^2 = sqrt(2 / (n + 2))); exclusive with shininess; one-line errors.
TEST(SceneLoader, MaterialRoughnessSetsTheEquivalentShininess) {
    for (float r : {1.0f, 0.5f, 0.119f, 0.02f}) {
        const std::string json = R"({"models": [{"primitive": "cube", "material": {"roughness": )" + std::to_string(r) + "}}]}";
        Scene s = parseScene(json, "test.json", false);
        for (const Material& m : s.models[0].mesh.materials) {
            const double alpha = std::sqrt(2.0 / (double(m.shininess) + 2.0));
            EXPECT_NEAR(std::sqrt(alpha), r, 1e-4 * r) << r;
        }
    }
    EXPECT_FLOAT_EQ(shininessFromRoughness(1.0f), 0.0f);
    EXPECT_NEAR(shininessFromRoughness(kMinRoughness), 1.25e7f, 10.0f);
    const std::string both = errorFor(R"({"models": [{"primitive": "cube", "material": {"roughness": 0.5, "shininess": 8}}]})");
    EXPECT_NE(both.find("test.json: models[0].material.roughness: give either roughness or shininess, not both"), std::string::npos) << both;
    EXPECT_EQ(both.find('\n'), std::string::npos);
    for (const char* bad : {"0.01", "1.5", "-0.2", "0"}) {
        const std::string e = errorFor(std::string(R"({"models": [{"primitive": "cube", "material": {"roughness": )") + bad + "}}]}");
        EXPECT_NE(e.find("models[0].material.roughness"), std::string::npos) << bad << ": " << e;
        EXPECT_NE(e.find("must be in [0.02, 1]"), std::string::npos) << bad << ": " << e;
    }
    EXPECT_NE(errorFor(R"({"models": [{"primitive": "cube", "material": {"roughness": "smooth"}}]})").find("material.roughness"),
              std::string::npos);
}

TEST(SceneLoader, SpotLightFields) {
    Scene s = parseScene(R"({"lights": [
      {"type": "spot", "position": [0, 2, 0], "direction": [0, -2, 0], "color": [1, 0.5, 0.25], "intensity": 3,
       "range": 4, "innerAngle": 10, "outerAngle": 25, "castsShadow": true},
      {"type": "spot", "position": [1, 2, 0]},
      {"type": "point", "position": [0, 1, 0]}]})",
                         "test.json", false);
    ASSERT_EQ(s.pointLights.size(), 3u);
    ASSERT_TRUE(s.pointLights[0].spot.has_value());
    const SpotCone& c = *s.pointLights[0].spot;
    EXPECT_EQ(c.direction, glm::vec3(0.0f, -1.0f, 0.0f));  // normalised
    EXPECT_EQ(c.innerDegrees, 10.0f);
    EXPECT_EQ(c.outerDegrees, 25.0f);
    EXPECT_TRUE(s.pointLights[0].castsShadow);
    EXPECT_EQ(s.pointLights[0].range, 4.0f);
    ASSERT_TRUE(s.pointLights[1].spot.has_value());  // defaults: straight down, 20 / 30 degrees, no shadow
    EXPECT_EQ(s.pointLights[1].spot->outerDegrees, 30.0f);
    EXPECT_FALSE(s.pointLights[1].castsShadow);
    EXPECT_FALSE(s.pointLights[2].spot.has_value());
}

// "castsShadow" on a point light: a cube shadow map (passes/point_shadow_pass); off by default.
TEST(SceneLoader, PointLightCastsShadow) {
    Scene s = parseScene(R"({"lights": [
      {"type": "point", "position": [0, 1, 0], "castsShadow": true},
      {"type": "point", "position": [1, 1, 0]},
      {"type": "point", "position": [2, 1, 0], "castsShadow": false}]})",
                         "test.json", false);
    ASSERT_EQ(s.pointLights.size(), 3u);
    EXPECT_TRUE(s.pointLights[0].castsShadow);
    EXPECT_FALSE(s.pointLights[0].spot.has_value());
    EXPECT_FALSE(s.pointLights[1].castsShadow);
    EXPECT_FALSE(s.pointLights[2].castsShadow);
    EXPECT_EQ(errorFor(R"({"lights": [{"type": "point", "castsShadow": "yes"}]})"),
              "test.json: lights[0].castsShadow: expected true or false");
    EXPECT_NE(errorFor(R"({"lights": [{"type": "point", "castShadow": true}]})").find("test.json: lights[0].castShadow: unknown field"),
              std::string::npos);
}

TEST(SceneLoader, SpotLightErrorsNameFileAndLight) {
    auto spot = [](const std::string& fields) {
        return errorFor(R"({"lights": [{"type": "point"}, {"type": "spot", )" + fields + "}]}");
    };
    EXPECT_EQ(spot(R"("direction": [0, 0, 0])"), "test.json: lights[1].direction: is the zero vector");
    EXPECT_EQ(spot(R"("innerAngle": 30, "outerAngle": 20)"),
              "test.json: lights[1].outerAngle: 20 degrees is less than innerAngle 30");
    EXPECT_EQ(spot(R"("outerAngle": 90)"), "test.json: lights[1].outerAngle: 90 degrees: must be in (0, 90)");
    EXPECT_EQ(spot(R"("outerAngle": 0, "innerAngle": 0)"), "test.json: lights[1].outerAngle: 0 degrees: must be in (0, 90)");
    EXPECT_EQ(spot(R"("innerAngle": -5)"), "test.json: lights[1].innerAngle: -5 degrees: must be >= 0");
    EXPECT_EQ(spot(R"("innerAngle": "wide")"), "test.json: lights[1].innerAngle: expected a number");
    EXPECT_EQ(spot(R"("castsShadow": 1)"), "test.json: lights[1].castsShadow: expected true or false");
    EXPECT_NE(spot(R"("cone": 3)").find("test.json: lights[1].cone: unknown field"), std::string::npos);
    // A point light takes no spot fields.
    EXPECT_NE(errorFor(R"({"lights": [{"type": "point", "direction": [0, -1, 0]}]})").find("lights[0].direction: unknown field"),
              std::string::npos);
    // NaN cannot be written in JSON; a huge number is the non-finite case a file can hold.
    EXPECT_EQ(spot(R"("outerAngle": 1e400)").find("test.json: invalid JSON"), 0u);
}

// A file several models name is parsed once: the same OBJ three times gives three equal meshes and
// its warning (a missing material library) once, not three times.
TEST(SceneLoader, AModelFileNamedTwiceIsParsedOnce) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / ("lp_scene_parsed_once_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "tri.obj") << "mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::ofstream(dir / "scene.json") << R"({"models": [
        {"obj": "tri.obj"}, {"obj": "./tri.obj", "translate": [2, 0, 0]}, {"obj": "tri.obj", "translate": [4, 0, 0]}]})";
    resetWarningCount();
    const Scene s = loadScene((dir / "scene.json").string());
    const int warnings = warningCount();
    fs::remove_all(dir);
    ASSERT_EQ(s.models.size(), 3u);
    for (const ModelInstance& m : s.models) {
        ASSERT_EQ(m.mesh.vertices.size(), 3u);
        EXPECT_EQ(m.mesh.indices, s.models[0].mesh.indices);
        EXPECT_EQ(m.mesh.vertices[1].position, s.models[0].mesh.vertices[1].position);
    }
    EXPECT_EQ(warnings, 1) << "the missing material library is said once";
}

// "turn": a sun whose direction turns about an axis with the scene's clock; bad values name the field.
TEST(SceneLoader, TurningSunRotatesItsDirectionAboutItsAxis) {
    Scene s = parseScene(R"({"lights": [{"type": "directional", "direction": [1, -1, 0],
                                         "turn": {"axis": [0, 2, 0], "speed": 0.5}}]})", "sun.json", false);
    const DirectionalLight& sun = s.directionalLights[0];
    EXPECT_FLOAT_EQ(sun.turnSpeed, 0.5f);
    EXPECT_NEAR(glm::length(sun.turnAxis - glm::vec3(0, 1, 0)), 0.0f, 1e-6f);
    const glm::vec3 d0 = glm::normalize(glm::vec3(1, -1, 0));
    EXPECT_NEAR(glm::length(sun.directionAt(0.0f) - d0), 0.0f, 1e-6f);
    // A quarter turn (pi/2 radians at 0.5 rad/s) about +Y takes +X to -Z; the height stays.
    const glm::vec3 quarter = sun.directionAt(float(M_PI));
    EXPECT_NEAR(glm::length(quarter - glm::vec3(0.0f, d0.y, -d0.x)), 0.0f, 1e-5f) << quarter.x << " " << quarter.z;
    EXPECT_NEAR(glm::length(quarter), 1.0f, 1e-6f);
    // Without "turn" the sun stays still at any time.
    Scene still = parseScene(R"({"lights": [{"type": "directional", "direction": [0, -1, 0]}]})", "still.json", false);
    EXPECT_EQ(still.directionalLights[0].directionAt(123.0f), still.directionalLights[0].direction);

    EXPECT_NE(errorFor(R"({"lights": [{"type": "directional", "turn": {"axis": [0, 0, 0]}}]})").find("lights[0].turn.axis"),
              std::string::npos);
    EXPECT_NE(errorFor(R"({"lights": [{"type": "directional", "turn": {"sped": 1}}]})").find("sped"), std::string::npos);
    EXPECT_NE(errorFor(R"({"lights": [{"type": "directional", "turn": {"speed": "fast"}}]})").find("lights[0].turn"),
              std::string::npos);
}
