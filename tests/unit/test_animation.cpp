// glTF node animation: the samplers against the specification (STEP holds, LINEAR and slerp,
// CUBICSPLINE's Hermite form), clip looping and choice, posed vertices from loaded files, and bad
// channels and samplers as one line naming the file and the element.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/error.hpp"
#include "engine/io/gltf_loader.hpp"
#include "engine/scene/animation.hpp"
#include "engine/scene/scene.hpp"
#include "engine/scene/scene_loader.hpp"
#include "tests/unit/gltf_test_files.hpp"

using namespace lp;
using lp::test::Doc;
using lp::test::loadError;
using lp::test::TempDir;

namespace {

AnimationSampler samplerOf(AnimationInterpolation interpolation, std::vector<float> times, std::vector<glm::vec4> values) {
    AnimationSampler s;
    s.interpolation = interpolation;
    s.times = std::move(times);
    s.values = std::move(values);
    return s;
}

glm::vec4 axisAngle(glm::vec3 axis, float radians) {
    axis = glm::normalize(axis);
    return glm::vec4(axis * std::sin(radians / 2), std::cos(radians / 2));
}

// A document with one quad drawn by node 0 (translation (5, 0, 0) at rest) and one animation whose
// sampler has `times` and `values` (VEC3 unless `type` says) on node 0's `path`.
struct AnimatedQuad {
    Doc doc;
    AnimatedQuad(const std::vector<float>& times, const std::vector<float>& values, const std::string& path = "translation",
                 const std::string& interpolation = "LINEAR", const char* type = "VEC3") {
        doc.node({{"mesh", doc.quad()}, {"translation", {5, 0, 0}}});
        const int in = doc.floatArray(times, "SCALAR", times.size());
        const int out = doc.floatArray(values, type, values.size() / (std::string(type) == "VEC4" ? 4 : 3));
        doc.j["animations"] = {{{"name", "Slide"},
                                {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", path}}}}}},
                                {"samplers", {{{"input", in}, {"output", out}, {"interpolation", interpolation}}}}}};
    }
};

}  // namespace

// STEP: each key's value holds until the next key, and the last from the last key on.
TEST(Animation, StepHoldsEachKeyUntilTheNext) {
    const AnimationSampler s = samplerOf(AnimationInterpolation::Step, {0, 1, 2}, {{1, 0, 0, 0}, {2, 0, 0, 0}, {3, 0, 0, 0}});
    EXPECT_EQ(sampleAnimation(s, AnimationPath::Translation, -1.0f).x, 1.0f);  // before the first key: the first
    EXPECT_EQ(sampleAnimation(s, AnimationPath::Translation, 0.0f).x, 1.0f);
    EXPECT_EQ(sampleAnimation(s, AnimationPath::Translation, 0.999f).x, 1.0f);
    EXPECT_EQ(sampleAnimation(s, AnimationPath::Translation, 1.0f).x, 2.0f);
    EXPECT_EQ(sampleAnimation(s, AnimationPath::Translation, 1.999f).x, 2.0f);
    EXPECT_EQ(sampleAnimation(s, AnimationPath::Translation, 2.0f).x, 3.0f);
    EXPECT_EQ(sampleAnimation(s, AnimationPath::Translation, 9.0f).x, 3.0f);  // after the last: the last
}

TEST(Animation, LinearInterpolatesTranslationAndScale) {
    const AnimationSampler s = samplerOf(AnimationInterpolation::Linear, {1, 3}, {{0, 2, 4, 0}, {4, 2, 0, 0}});
    const glm::vec4 v = sampleAnimation(s, AnimationPath::Scale, 1.5f);  // a quarter of the way
    EXPECT_NEAR(v.x, 1.0f, 1e-6f);
    EXPECT_NEAR(v.y, 2.0f, 1e-6f);
    EXPECT_NEAR(v.z, 3.0f, 1e-6f);
}

// LINEAR rotation is slerp: unit length everywhere, the angle linear in time, on the shorter arc
// (a key given as -q turns the same way as q).
TEST(Animation, SlerpStaysUnitWithAngleLinearInTime) {
    const glm::vec3 axis(1, 2, 3);
    const float end = glm::radians(170.0f);
    for (float sign : {1.0f, -1.0f}) {
        const AnimationSampler s = samplerOf(AnimationInterpolation::Linear, {0, 2}, {axisAngle(axis, 0.0f), sign * axisAngle(axis, end)});
        for (int i = 0; i <= 64; ++i) {
            const float t = 2.0f * float(i) / 64.0f;
            const glm::vec4 q = sampleAnimation(s, AnimationPath::Rotation, t);
            EXPECT_NEAR(glm::length(q), 1.0f, 1e-6f) << "t " << t;
            // The rotation angle between the first key and q: 2 acos |q . q0|.
            const float angle = 2.0f * std::acos(std::min(1.0f, std::abs(glm::dot(q, axisAngle(axis, 0.0f)))));
            EXPECT_NEAR(angle, end * t / 2.0f, 2e-3f) << "t " << t << " sign " << sign;
            // About the same axis, turning the positive way.
            const glm::vec3 v(q);
            if (glm::length(v) > 1e-3f) EXPECT_NEAR(glm::dot(glm::normalize(v) * (q.w < 0 ? -1.0f : 1.0f), glm::normalize(axis)), 1.0f, 1e-4f);
        }
    }
    // Unit results from keys that are not unit.
    const glm::vec4 q = slerpUnit(glm::vec4(0, 0, 0, 1), glm::normalize(glm::vec4(0, 1, 0, 1)), 0.3f);
    EXPECT_NEAR(glm::length(q), 1.0f, 1e-6f);
}

// CUBICSPLINE: the keys' values at the keys, the out-tangent (times the interval's length, as the
// spec scales it) as the derivative leaving a key and the in-tangent arriving at the next, and
// in between the spec's Hermite basis.
TEST(Animation, CubicSplineIsTheSpecsHermiteForm) {
    const std::vector<float> t = {0.5f, 1.25f, 3.0f};
    // in-tangent, value, out-tangent of each key
    const std::vector<glm::vec4> v = {{9, 9, 9, 0}, {1, -2, 0.5f, 0}, {3, 0, -1, 0},  //
                                      {-4, 2, 1, 0}, {2, 1, -1, 0},   {0.5f, -3, 2, 0},
                                      {1, 1, 1, 0},  {-1, 0, 4, 0},   {7, 7, 7, 0}};
    const AnimationSampler s = samplerOf(AnimationInterpolation::CubicSpline, t, v);
    for (size_t k = 0; k < t.size(); ++k)
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(sampleAnimation(s, AnimationPath::Translation, t[k])[c], v[3 * k + 1][c], 1e-5f);
    for (size_t k = 0; k + 1 < t.size(); ++k) {
        const double d = t[k + 1] - t[k];
        // The derivative leaving key k is its out-tangent b_k; arriving at k + 1, its in-tangent a_k+1.
        const double h = 1e-3;
        for (int c = 0; c < 3; ++c) {
            const double leaving = (sampleAnimation(s, AnimationPath::Translation, float(t[k] + h))[c] - v[3 * k + 1][c]) / h;
            const double arriving = (v[3 * (k + 1) + 1][c] - sampleAnimation(s, AnimationPath::Translation, float(t[k + 1] - h))[c]) / h;
            EXPECT_NEAR(leaving, v[3 * k + 2][c], 0.02 * (1 + std::abs(v[3 * k + 2][c])) + 2e-3 / d) << "key " << k;
            EXPECT_NEAR(arriving, v[3 * (k + 1)][c], 0.02 * (1 + std::abs(v[3 * (k + 1)][c])) + 2e-3 / d) << "key " << k;
        }
        for (double s01 : {0.2, 0.5, 0.9}) {
            const double s2 = s01 * s01, s3 = s2 * s01;
            for (int c = 0; c < 3; ++c) {
                const double expected = (2 * s3 - 3 * s2 + 1) * v[3 * k + 1][c] + (s3 - 2 * s2 + s01) * d * v[3 * k + 2][c] +
                                        (-2 * s3 + 3 * s2) * v[3 * (k + 1) + 1][c] + (s3 - s2) * d * v[3 * (k + 1)][c];
                EXPECT_NEAR(sampleAnimation(s, AnimationPath::Translation, float(t[k] + s01 * d))[c], expected, 1e-4) << "key " << k;
            }
        }
    }
    // A cubic rotation comes back unit.
    const AnimationSampler r = samplerOf(AnimationInterpolation::CubicSpline, {0, 1},
                                         {{0, 0, 0, 0}, {0, 0, 0, 1}, {1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0.7071f, 0, 0.7071f}, {0, 0, 0, 0}});
    EXPECT_NEAR(glm::length(sampleAnimation(r, AnimationPath::Rotation, 0.4f)), 1.0f, 1e-6f);
}

TEST(Animation, ClipsLoopOverTheirDuration) {
    AnimationClip clip;
    clip.duration = 2.0f;
    EXPECT_NEAR(clipTime(clip, 0.5), 0.5f, 1e-6f);
    EXPECT_NEAR(clipTime(clip, 3.5), 1.5f, 1e-6f);
    EXPECT_NEAR(clipTime(clip, -0.5), 1.5f, 1e-6f);
    EXPECT_LT(clipTime(clip, 2.0), 2.0f + 1e-6f);
    clip.duration = 0.0f;
    EXPECT_EQ(clipTime(clip, 7.0), 0.0f);
}

// A loaded file's animated node: the rest pose as before, the pose at t where its channel says,
// looping; its child follows, a still sibling has no posed range.
TEST(Animation, LoadedNodeAnimationPosesTheVertices) {
    TempDir dir;
    AnimatedQuad a({0, 1}, {0, 0, 0, 2, 4, 0});
    const int child = a.doc.node({{"mesh", a.doc.quad()}, {"translation", {0, 0, 1}}}, false);
    a.doc.j["nodes"][0]["children"] = {child};
    a.doc.node({{"mesh", 1}, {"translation", {-10, 0, 0}}});  // a still sibling
    const GltfContent g = loadGltf(dir.write("a.gltf", a.doc.text()));
    ASSERT_TRUE(g.animation);
    const NodeAnimation& anim = *g.animation;
    ASSERT_EQ(anim.clips.size(), 1u);
    EXPECT_EQ(anim.clips[0].name, "Slide");
    EXPECT_EQ(anim.clips[0].duration, 1.0f);
    ASSERT_EQ(anim.ranges.size(), 2u);  // node 0 and its child; not the sibling
    // Rest: node 0's quad around (5, 0, 0), the child's around (5, 0, 1).
    float restMinX = 1e9f;
    for (uint32_t i = 0; i < anim.ranges[0].vertexCount; ++i) restMinX = std::min(restMinX, g.mesh.vertices[anim.ranges[0].firstVertex + i].position.x);
    EXPECT_NEAR(restMinX, 4.0f, 1e-6f);
    for (double t : {0.25, 1.25, -0.75}) {  // 1.25 and -0.75: the loop
        std::vector<Vertex> posed = g.mesh.vertices;
        poseVertices(anim, animatedNodeWorlds(anim, {0}, t), posed);
        const glm::vec3 offset = glm::vec3(0.5f, 1.0f, 0.0f);  // a quarter of (2, 4, 0), replacing the rest (5, 0, 0)
        for (const NodeVertexRange& r : anim.ranges)
            for (uint32_t i = 0; i < r.vertexCount; ++i) {
                const glm::vec3 rest = g.mesh.vertices[r.firstVertex + i].position;
                const glm::vec3 p = posed[r.firstVertex + i].position;
                EXPECT_NEAR(p.x, rest.x - 5.0f + offset.x, 1e-5f) << "t " << t;
                EXPECT_NEAR(p.y, rest.y + offset.y, 1e-5f);
                EXPECT_NEAR(p.z, rest.z, 1e-5f);
            }
        // The sibling's vertices (not in a range) stay.
        for (size_t i = 0; i < posed.size(); ++i)
            if (g.mesh.vertices[i].position.x < -5.0f) EXPECT_EQ(posed[i].position, g.mesh.vertices[i].position);
    }
    // No clip playing: the rest pose.
    std::vector<Vertex> still = g.mesh.vertices;
    poseVertices(anim, animatedNodeWorlds(anim, {}, 0.6), still);
    for (size_t i = 0; i < still.size(); ++i) EXPECT_NEAR(glm::length(still[i].position - g.mesh.vertices[i].position), 0.0f, 1e-6f);
}

// A rotation channel turns the normals and tangents with the positions, and keeps them unit.
TEST(Animation, RotationTurnsNormalsAndTangents) {
    TempDir dir;
    const glm::vec4 q0 = axisAngle({0, 1, 0}, 0.0f), q1 = axisAngle({0, 1, 0}, glm::radians(120.0f));
    AnimatedQuad a({0, 2}, {q0.x, q0.y, q0.z, q0.w, q1.x, q1.y, q1.z, q1.w}, "rotation", "LINEAR", "VEC4");
    const GltfContent g = loadGltf(dir.write("r.gltf", a.doc.text()));
    ASSERT_TRUE(g.animation);
    std::vector<Vertex> posed = g.mesh.vertices;
    poseVertices(*g.animation, animatedNodeWorlds(*g.animation, {0}, 1.5), posed);  // 90 degrees about +Y
    for (size_t i = 0; i < posed.size(); ++i) {
        EXPECT_NEAR(posed[i].normal.x, 1.0f, 1e-5f);  // +Z turned to +X
        EXPECT_NEAR(glm::length(glm::vec3(posed[i].tangent)), 1.0f, 1e-5f);
        EXPECT_NEAR(glm::dot(glm::vec3(posed[i].tangent), posed[i].normal), 0.0f, 1e-5f);
        // Positions: local (x, y, 0) turned to (0, y, -x), then the rest translation (5, 0, 0).
        const glm::vec3 rest = g.mesh.vertices[i].position - glm::vec3(5, 0, 0);
        EXPECT_NEAR(glm::length(posed[i].position - (glm::vec3(0, rest.y, -rest.x) + glm::vec3(5, 0, 0))), 0.0f, 1e-5f);
    }
}

// --animation's choice: the first clip by default, none, all, an index, a name.
TEST(Animation, ChoosingClips) {
    NodeAnimation a;
    a.clips.resize(3);
    a.clips[0].name = "Idle";
    a.clips[1].name = "Walk";
    a.clips[2].name = "Walk";
    EXPECT_EQ(chooseClips(a, ""), std::vector<int>({0}));
    EXPECT_EQ(chooseClips(a, "none"), std::vector<int>());
    EXPECT_EQ(chooseClips(a, "all"), std::vector<int>({0, 1, 2}));
    EXPECT_EQ(chooseClips(a, "1"), std::vector<int>({1}));
    EXPECT_EQ(chooseClips(a, "7"), std::vector<int>());
    EXPECT_EQ(chooseClips(a, "Walk"), std::vector<int>({1, 2}));
    // In a scene: a name no model has is one line listing the clips there are.
    Scene scene;
    ModelInstance m;
    m.animation = std::make_shared<NodeAnimation>(a);
    scene.models.push_back(m);
    playAnimations(scene, "Walk");
    EXPECT_EQ(scene.models[0].playingClips, std::vector<int>({1, 2}));
    try {
        playAnimations(scene, "Run");
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "--animation Run: no model has an animation of that name (animations: 0 'Idle', 1 'Walk', 2 'Walk')");
    }
    playAnimations(scene, "none");
    EXPECT_TRUE(scene.models[0].playingClips.empty());
}

// A scene's glTF model plays its first clip; it moves between two times unless the clip holds still.
TEST(Animation, SceneModelsPlayTheFirstClipByDefault) {
    TempDir dir;
    AnimatedQuad a({0, 1}, {0, 0, 0, 2, 4, 0});
    const Scene scene = sceneForModel(dir.write("a.gltf", a.doc.text()), false);
    ASSERT_EQ(scene.models.size(), 1u);
    EXPECT_EQ(scene.models[0].playingClips, std::vector<int>({0}));
    EXPECT_TRUE(scene.models[0].movesBetween(0.1, 0.2));
    EXPECT_FALSE(scene.models[0].movesBetween(0.2, 0.2));
    EXPECT_FALSE(scene.models[0].movesBetween(1.0, 2.0));  // the same point of the loop
    AnimatedQuad still({0, 1}, {1, 0, 0, 1, 0, 0});
    EXPECT_FALSE(sceneForModel(dir.write("s.gltf", still.doc.text()), false).models[0].movesBetween(0.1, 0.7));
}

// Bad channels and samplers: one line naming the file and the animation's element.
TEST(Animation, BadChannelsAndSamplersNameTheElement) {
    TempDir dir;
    auto error = [&](AnimatedQuad& a) {
        const auto path = dir.write("bad.gltf", a.doc.text());
        const std::string e = loadError(path);
        EXPECT_EQ(e.rfind(path.string() + ": ", 0), 0u) << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
        return e.substr(path.string().size() + 2);
    };
    {
        AnimatedQuad a({0, 1}, {0, 0, 0, 1, 0, 0});
        a.doc.j["animations"][0]["channels"][0]["target"]["node"] = 7;
        EXPECT_EQ(error(a), "animations[0].channels[0].target.node: 7 does not exist (1 nodes)");
    }
    {
        AnimatedQuad a({0, 1}, {0, 0, 0, 1, 0, 0, 2, 0, 0});
        EXPECT_EQ(error(a), "animations[0].samplers[0].output (accessors[3]): 3 values for 2 key times: LINEAR needs 2 (one a key)");
    }
    {
        AnimatedQuad a({0, 1}, {0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0}, "translation", "CUBICSPLINE");
        EXPECT_EQ(error(a), "animations[0].samplers[0].output (accessors[3]): 4 values for 2 key times: CUBICSPLINE needs 6 "
                            "(in-tangent, value, out-tangent a key)");
    }
    {
        AnimatedQuad a({0, 1, 1}, {0, 0, 0, 1, 0, 0, 2, 0, 0});
        EXPECT_EQ(error(a), "animations[0].samplers[0].input (accessors[2]): key time 2 (1) is not after key time 1 (1): key times must increase");
    }
    {
        AnimatedQuad a({0, std::numeric_limits<float>::quiet_NaN()}, {0, 0, 0, 1, 0, 0});
        EXPECT_EQ(error(a), "animations[0].samplers[0].input (accessors[2]): key time 1 is not finite");
    }
    {
        AnimatedQuad a({0, 1}, {0, 0, 0, 1, std::numeric_limits<float>::infinity(), 0});
        EXPECT_EQ(error(a), "animations[0].samplers[0].output (accessors[3]): value 1 is not finite");
    }
    {
        AnimatedQuad a({0, 1}, {0, 0, 0, 1, 0, 0});
        a.doc.j["nodes"][0].erase("translation");
        a.doc.j["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
        EXPECT_EQ(error(a), "animations[0].channels[0].target.node: nodes[0] has a matrix; an animated node must have translation, "
                            "rotation and scale instead");
    }
    {
        AnimatedQuad a({0, 1}, {0, 0, 0, 1, 0, 0});
        a.doc.j["animations"][0]["channels"][0]["sampler"] = 3;
        EXPECT_EQ(error(a), "animations[0].channels[0].sampler: 3 does not exist (animations[0] has 1 samplers)");
    }
    {
        AnimatedQuad a({0, 1}, {0, 0, 0, 1, 0, 0});
        a.doc.j["animations"][0]["channels"].push_back(a.doc.j["animations"][0]["channels"][0]);
        EXPECT_EQ(error(a), "animations[0].channels[1].target: nodes[0] translation is already the target of another channel of animations[0]");
    }
    {
        AnimatedQuad a({0, 1}, {0, 0, 0, 0, 1, 0, 0, 0}, "rotation", "LINEAR", "VEC4");
        EXPECT_EQ(error(a), "animations[0].samplers[0].output (accessors[3]): value 0 is a rotation of length 0");
    }
    {
        AnimatedQuad a({0}, {0, 0, 0, 1, 0, 0, 2, 0, 0}, "translation", "CUBICSPLINE");
        EXPECT_EQ(error(a), "animations[0].samplers[0].input (accessors[2]): CUBICSPLINE needs at least 2 key times, this has 1");
    }
}
