// Camera paths: the spline through the keys (exact at keys, continuous with a continuous first
// derivative), clamping and looping, and one-line errors for each kind of bad path.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/error.hpp"
#include "engine/scene/camera_path.hpp"
#include "engine/scene/scene_loader.hpp"
#include "frame/frame_builder.hpp"

namespace lp {
namespace {

CameraPath fourKeys(bool loop) {
    CameraPath p;
    p.loop = loop;
    p.keys = {{0.0, {0, 1, 3}, {0, 0, 0}, 45.0f},
              {1.0, {2, 1.5f, 2}, {0.5f, 0, 0}, 50.0f},
              {2.5, {1, 2, -1}, {0, 0.5f, 0}, 40.0f},  // uneven spacing
              {3.0, {0, 1, 3}, {0, 0, 0}, 45.0f}};
    return p;
}

double distance(const CameraKey& a, const CameraKey& b) {
    return glm::length(glm::dvec3(a.position) - glm::dvec3(b.position)) +
           glm::length(glm::dvec3(a.target) - glm::dvec3(b.target)) + std::abs(double(a.fovYDegrees) - b.fovYDegrees);
}

TEST(CameraPath, HitsEveryKeyExactly) {
    for (bool loop : {false, true}) {
        const CameraPath p = fourKeys(loop);
        for (const CameraKey& k : p.keys) {
            if (loop && k.time == p.keys.back().time) continue;  // the wrap point stands for key 0
            const CameraKey at = cameraPathAt(p, k.time);
            EXPECT_EQ(at.position, k.position) << k.time;
            EXPECT_EQ(at.target, k.target) << k.time;
            EXPECT_EQ(at.fovYDegrees, k.fovYDegrees) << k.time;
        }
    }
}

// C0 and C1: across each key the value and the finite-difference derivative agree from both sides.
TEST(CameraPath, IsContinuousWithAContinuousDerivative) {
    const CameraPath p = fourKeys(false);
    const double h = 1e-5;
    for (size_t i = 1; i + 1 < p.keys.size(); ++i) {
        const double t = p.keys[i].time;
        const CameraKey before = cameraPathAt(p, t - h), at = cameraPathAt(p, t), after = cameraPathAt(p, t + h);
        EXPECT_LT(distance(before, at), 1e-3);
        EXPECT_LT(distance(after, at), 1e-3);
        const glm::dvec3 left = (glm::dvec3(at.position) - glm::dvec3(before.position)) / h;
        const glm::dvec3 right = (glm::dvec3(after.position) - glm::dvec3(at.position)) / h;
        EXPECT_LT(glm::length(left - right), 0.05 * (1.0 + glm::length(left))) << "kink at key " << i;
        // Catmull-Rom tangent for uneven times: (p[i+1] - p[i-1]) / (t[i+1] - t[i-1]).
        const glm::dvec3 expected = (glm::dvec3(p.keys[i + 1].position) - glm::dvec3(p.keys[i - 1].position)) /
                                    (p.keys[i + 1].time - p.keys[i - 1].time);
        EXPECT_LT(glm::length(0.5 * (left + right) - expected), 0.01);
    }
    // Fine steps never jump.
    CameraKey last = cameraPathAt(p, 0.0);
    for (double t = 0.001; t <= 3.0; t += 0.001) {
        const CameraKey now = cameraPathAt(p, t);
        EXPECT_LT(distance(now, last), 0.05) << t;
        last = now;
    }
}

TEST(CameraPath, ClampsOutsideTheKeysOrLoops) {
    const CameraPath open = fourKeys(false);
    EXPECT_EQ(cameraPathAt(open, -5.0).position, open.keys.front().position);
    EXPECT_EQ(cameraPathAt(open, 99.0).position, open.keys.back().position);
    const CameraPath loop = fourKeys(true);
    EXPECT_LT(distance(cameraPathAt(loop, 1.0 + 3.0), loop.keys[1]), 1e-4);
    EXPECT_LT(distance(cameraPathAt(loop, 0.7 - 6.0), cameraPathAt(loop, 0.7)), 1e-4);
    // Closed loop: smooth across the wrap too.
    const CameraKey a = cameraPathAt(loop, 3.0 - 1e-4), b = cameraPathAt(loop, 3.0 + 1e-4);
    EXPECT_LT(distance(a, b), 1e-2);
}

TEST(CameraPath, SceneFrameUsesThePathAndCameraOverrides) {
    Scene s = parseScene(R"({"camera": {"position": [0, 1, 5], "target": [0, 0, 0]},
        "cameraPath": {"keys": [{"time": 0, "position": [0, 1, 3], "target": [0, 0, 0], "fov": 45},
                                {"time": 2, "position": [2, 1, 3], "target": [0, 0, 0], "fov": 60}]}})",
                         "p.json", false);
    ASSERT_TRUE(s.cameraPath.has_value());
    EXPECT_EQ(s.cameraAt(2.0).position, glm::vec3(2, 1, 3));
    EXPECT_EQ(s.cameraAt(2.0).fovYDegrees, 60.0f);
    RenderSettings settings;
    const FrameData f = makeFrameData(s, settings, 2.0f);
    EXPECT_EQ(f.view, s.cameraAt(2.0).view());
    s.cameraPath.reset();  // what --camera does
    EXPECT_EQ(s.cameraAt(2.0).position, glm::vec3(0, 1, 5));
}

// Each error is one line naming the file and the key.
void expectError(const std::string& json, const std::string& expected) {
    try {
        parseCameraPathFile(json, "path.json");
        ADD_FAILURE() << "no error for " << json;
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(expected), std::string::npos) << what;
        EXPECT_EQ(what.rfind("path.json: ", 0), 0u) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
}

const char* kKey0 = R"({"time": 0, "position": [0, 1, 3], "target": [0, 0, 0], "fov": 45})";

TEST(CameraPath, BadPathsAreOneLineErrorsNamingTheKey) {
    const std::string k0 = kKey0;
    expectError(R"({"keys": [)" + k0 + "]}", "cameraPath.keys: has 1 key(s); a path needs at least two");
    expectError(R"({"keys": []})", "cameraPath.keys: has 0 key(s)");
    expectError(R"({"loop": true})", "cameraPath.keys: missing");
    expectError(R"({"keys": [)" + k0 + R"(, {"time": 1, "position": [0, 1e39, 3], "target": [0, 0, 0], "fov": 45}]})",
                "cameraPath.keys[1].position[1]: not a finite number");
    expectError(R"({"keys": [)" + k0 + R"(, {"time": 1e39, "position": [0, 1, 3], "target": [0, 0, 0], "fov": 45}]})",
                "cameraPath.keys[1].time: not a finite number");
    expectError(R"({"keys": [)" + k0 + R"(, {"time": NaN, "position": [0, 1, 3], "target": [0, 0, 0], "fov": 45}]})",
                "invalid JSON");
    expectError(R"({"keys": [)" + k0 + R"(, {"time": 0, "position": [1, 1, 3], "target": [0, 0, 0], "fov": 45}]})",
                "cameraPath.keys[1].time: 0 is not after keys[0].time (0): key times must increase");
    expectError(R"({"keys": [)" + k0 + R"(, {"time": -1, "position": [1, 1, 3], "target": [0, 0, 0], "fov": 45}]})",
                "cameraPath.keys[1].time: -1 is not after");
    expectError(R"({"keys": [)" + k0 + R"(, {"time": 1, "position": [1, 1, 3], "fov": 45}]})",
                "cameraPath.keys[1].target: missing");
    expectError(R"({"keys": [)" + k0 + R"(, {"time": 1, "target": [1, 1, 3], "position": [0, 0, 0]}]})",
                "cameraPath.keys[1].fov: missing");
    expectError(R"({"keys": [)" + k0 + R"(, {"time": 1, "position": [1, 1, 3], "target": [0, 0, 0], "fov": 180}]})",
                "cameraPath.keys[1].fov: 180 is outside (0, 180) degrees");
    expectError(R"({"keys": [)" + k0 + R"(, {"time": 1, "position": [1, 1, 3], "target": [0, 0, 0], "fov": 0}]})",
                "cameraPath.keys[1].fov: 0 is outside (0, 180) degrees");
    expectError(R"({"keys": [)" + k0 + R"(, {"time": 1, "position": [1, 1, 3], "target": [1, 1, 3], "fov": 45}]})",
                "cameraPath.keys[1].target: equals the position");
    expectError(R"({"keys": [)" + k0 + R"(, {"time": 1, "position": [1, 1, 3], "target": [0, 0, 0], "fov": 45, "roll": 2}]})",
                "cameraPath.keys[1].roll: unknown field");
    expectError(R"({"keys": [)" + k0 + "," + k0 + R"(], "loop": 1})", "cameraPath.loop: expected true or false");
}

TEST(CameraPath, SceneFileErrorsNameTheSceneFile) {
    try {
        parseScene(R"({"cameraPath": {"keys": [{"time": 0, "position": [0, 1, 3], "target": [0, 0, 0], "fov": 45}]}})",
                   "scene.json", false);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "scene.json: cameraPath.keys: has 1 key(s); a path needs at least two");
    }
}

}  // namespace
}  // namespace lp
