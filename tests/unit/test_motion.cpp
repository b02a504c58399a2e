// Jittered projections and the previous-frame bookkeeping (engine/render/motion.hpp), no GL.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/render/motion.hpp"
#include "frame/frame_builder.hpp"

namespace lp {
namespace {

// Window position (pixels, GL convention) of world point p under `viewProjection` on a w x h image.
glm::dvec2 windowOf(const glm::mat4& viewProjection, glm::vec3 p, glm::ivec2 size) {
    const glm::dvec4 c = glm::dmat4(viewProjection) * glm::dvec4(glm::dvec3(p), 1.0);
    return (glm::dvec2(c) / c.w * 0.5 + 0.5) * glm::dvec2(size);
}

TEST(MotionMath, JitteredProjectionShiftsEveryPointByTheJitterInPixels) {
    const glm::ivec2 size(1920, 1080);
    const glm::vec2 jitter(0.37f, -0.42f);
    const glm::mat4 view = glm::lookAt(glm::vec3(1, 2, 5), glm::vec3(0), glm::vec3(0, 1, 0));
    for (const glm::mat4& projection : {glm::perspective(0.9f, 16.0f / 9.0f, 0.05f, 100.0f),
                                        glm::ortho(-4.0f, 4.0f, -2.25f, 2.25f, 0.1f, 50.0f)}) {
        const glm::mat4 jittered = jitteredProjection(projection, jitter, size);
        for (glm::vec3 p : {glm::vec3(0), glm::vec3(1, 0.5f, -2), glm::vec3(-3, 1, 1), glm::vec3(0.2f, -1, -8)}) {
            const glm::dvec2 shift = windowOf(jittered * view, p, size) - windowOf(projection * view, p, size);
            EXPECT_NEAR(shift.x, jitter.x, 2e-3);
            EXPECT_NEAR(shift.y, jitter.y, 2e-3);
        }
        // Depth is untouched, and no jitter is the identity.
        EXPECT_EQ(jittered[2][2], projection[2][2]);
        EXPECT_EQ(jitteredProjection(projection, glm::vec2(0.0f), size), projection);
    }
}

TEST(MotionMath, FirstFrameResizeAndRewindHaveNoPreviousFrame) {
    Scene scene;
    RenderSettings settings;
    settings.width = 64;
    settings.height = 32;
    FrameData first = makeFrameData(scene, settings, 1.0f);
    applyMotion(first, MotionHistory{}, glm::vec2(0.25f, 0.0f));
    EXPECT_FALSE(first.hasPrevious);
    EXPECT_EQ(first.previousViewProjection, first.unjitteredProjection * first.view);
    EXPECT_EQ(first.previousTime, 1.0f);
    EXPECT_NE(first.projection, first.unjitteredProjection);  // jittered
    EXPECT_EQ(first.jitterPixels, glm::vec2(0.25f, 0.0f));

    scene.camera.position.x += 1.0f;
    FrameData second = makeFrameData(scene, settings, 1.5f);
    applyMotion(second, motionHistoryOf(first), glm::vec2(0.0f));
    EXPECT_TRUE(second.hasPrevious);
    EXPECT_EQ(second.previousViewProjection, first.unjitteredProjection * first.view);  // unjittered
    EXPECT_EQ(second.previousTime, 1.0f);
    EXPECT_EQ(second.frameIndex, first.frameIndex + 1);
    EXPECT_EQ(second.projection, second.unjitteredProjection);

    FrameData rewound = makeFrameData(scene, settings, 0.5f);  // a new run on the clock
    applyMotion(rewound, motionHistoryOf(second), glm::vec2(0.0f));
    EXPECT_FALSE(rewound.hasPrevious);

    settings.width = 65;  // a resize
    FrameData resized = makeFrameData(scene, settings, 2.0f);
    applyMotion(resized, motionHistoryOf(second), glm::vec2(0.0f));
    EXPECT_FALSE(resized.hasPrevious);
    EXPECT_EQ(resized.previousViewProjection, resized.unjitteredProjection * resized.view);
}

TEST(MotionMath, VelocityOfAPointIsItsUvChange) {
    const glm::dmat4 previous = glm::dmat4(glm::perspective(1.0f, 1.0f, 0.1f, 10.0f));
    const glm::dmat4 current = previous * glm::translate(glm::dmat4(1.0), glm::dvec3(-0.5, 0.0, 0.0));  // camera +x
    // A point straight ahead at 2 m: it was at the centre (uv 0.5) and is now left of it.
    const glm::dvec2 v = velocityOfPoint(current, previous, glm::dvec3(0, 0, -2));
    EXPECT_NEAR(v.x, 0.5 * (-0.5 / std::tan(0.5) / 2.0), 1e-6);  // the float perspective matrix
    EXPECT_NEAR(v.y, 0.0, 1e-9);
    EXPECT_EQ(velocityOfPoint(current, previous, glm::dvec3(0, 0, 2)), glm::dvec2(0.0));  // behind: unknown, 0
}

}  // namespace
}  // namespace lp
