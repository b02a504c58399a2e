#include "engine/render/motion.hpp"

#include "engine/render/frame_data.hpp"

namespace lp {

glm::mat4 jitteredProjection(const glm::mat4& projection, glm::vec2 jitterPixels, glm::ivec2 outputSize) {
    const glm::vec2 ndc = 2.0f * jitterPixels / glm::vec2(glm::max(outputSize, glm::ivec2(1)));
    glm::mat4 p = projection;
    for (int column = 0; column < 4; ++column) {  // row 0 += ndc.x row 3, row 1 += ndc.y row 3
        p[column][0] += ndc.x * projection[column][3];
        p[column][1] += ndc.y * projection[column][3];
    }
    return p;
}

void applyMotion(FrameData& frame, const MotionHistory& history, glm::vec2 jitterPixels) {
    frame.jitterPixels = jitterPixels;
    frame.projection = jitteredProjection(frame.unjitteredProjection, jitterPixels,
                                          {frame.outputWidth, frame.outputHeight});
    const bool continues = history.valid && history.outputSize == glm::ivec2(frame.outputWidth, frame.outputHeight) &&
                           frame.time >= history.time;
    frame.hasPrevious = continues;
    frame.previousViewProjection = continues ? history.viewProjection : frame.unjitteredProjection * frame.view;
    frame.previousTime = continues ? history.time : frame.time;
    frame.frameIndex = history.valid ? history.frameIndex + 1 : 0;
}

MotionHistory motionHistoryOf(const FrameData& frame) {
    MotionHistory h;
    h.valid = true;
    h.viewProjection = frame.unjitteredProjection * frame.view;
    h.time = frame.time;
    h.outputSize = {frame.outputWidth, frame.outputHeight};
    h.frameIndex = frame.frameIndex;
    return h;
}

glm::dvec2 velocityOfPoint(const glm::dmat4& viewProjection, const glm::dmat4& previousViewProjection, glm::dvec3 p) {
    const glm::dvec4 current = viewProjection * glm::dvec4(p, 1.0), previous = previousViewProjection * glm::dvec4(p, 1.0);
    if (current.w <= 1e-9 || previous.w <= 1e-9) return glm::dvec2(0.0);
    return 0.5 * (glm::dvec2(current) / current.w - glm::dvec2(previous) / previous.w);
}

}  // namespace lp
