// A scene file's "spin": a one-clip animation that turns the whole mesh about an axis at a constant
// speed, posed by the same code as glTF animation.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/error.hpp"
#include "engine/scene/primitives.hpp"
#include "engine/scene/scene.hpp"
#include "engine/scene/scene_loader.hpp"
#include "engine/scene/spin.hpp"

using namespace lp;

namespace {
// The cube's vertices posed at `time` against the rest vertices turned by `radians` about `axis`:
// the largest position and normal error.
float largestSpinError(const MeshData& cube, const NodeAnimation& spin, double time, glm::vec3 axis, float radians) {
    std::vector<Vertex> posed = cube.vertices;
    poseVertices(spin, animatedPose(spin, {0}, time), posed);
    const glm::mat3 turn(glm::rotate(glm::mat4(1.0f), radians, axis));
    float worst = 0.0f;
    for (size_t i = 0; i < posed.size(); ++i) {
        worst = std::max(worst, glm::length(posed[i].position - turn * cube.vertices[i].position));
        worst = std::max(worst, glm::length(posed[i].normal - turn * cube.vertices[i].normal));
    }
    return worst;
}
}  // namespace

TEST(Spin, TurnsEveryVertexBySpeedTimesTime) {
    const MeshData cube = makeCube(1.0f);
    const glm::vec3 axis = glm::normalize(glm::vec3(1.0f, 2.0f, 0.5f));
    const float speed = 0.8f;
    const NodeAnimation spin = spinAnimation(cube, axis, speed);
    ASSERT_EQ(spin.clips.size(), 1u);
    EXPECT_NEAR(spin.clips[0].duration, 2.0f * float(M_PI) / speed, 1e-5f);
    // At keys and between them (slerp about one axis is exact), across a whole turn and past it.
    for (double t : {0.0, 0.3, 1.0, 1.9634954, 2.5, 5.0, 7.853982, 9.0})
        EXPECT_LT(largestSpinError(cube, spin, t, axis, speed * float(t)), 2e-5f) << "t = " << t;
    // A negative speed turns the other way.
    const NodeAnimation back = spinAnimation(cube, axis, -speed);
    EXPECT_LT(largestSpinError(cube, back, 1.0, axis, -speed), 2e-5f);
}

TEST(Spin, SceneFieldMakesAMovingModelAndBadValuesNameTheField) {
    const Scene s = parseScene(R"({"models": [{"primitive": "cube", "spin": {"axis": [0, 3, 0], "speed": 1.5}},
                                              {"primitive": "sphere", "spin": {"speed": 0}},
                                              {"primitive": "plane"}]})", "spin.json", true);
    ASSERT_TRUE(s.models[0].animation);
    EXPECT_EQ(s.models[0].playingClips, std::vector<int>{0});
    EXPECT_TRUE(s.models[0].movesBetween(0.0, 0.25));
    EXPECT_FALSE(s.models[1].animation) << "speed 0 stands still";
    EXPECT_FALSE(s.models[2].movesBetween(0.0, 1.0));

    auto error = [](const std::string& text) {
        try {
            parseScene(text, "spin.json", true);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_NE(error(R"({"models": [{"primitive": "cube", "spin": {"axis": [0, 0, 0]}}]})").find("models[0].spin.axis"),
              std::string::npos);
    EXPECT_NE(error(R"({"models": [{"primitive": "cube", "spin": {"rate": 1}}]})").find("rate"), std::string::npos);
    EXPECT_NE(error(R"({"models": [{"primitive": "cube", "spin": 3}]})").find("models[0].spin"), std::string::npos);
    const std::string animated = error(R"({"models": [{"gltf": ")" + std::string(LIGHTPASS_SOURCE_DIR) +
                                       R"(/tests/data/gltf/animated_grid.gltf", "spin": {"speed": 1}}]})");
    EXPECT_NE(animated.find("models[0].spin"), std::string::npos) << animated;
    EXPECT_NE(animated.find("animations of its own"), std::string::npos) << animated;
}
