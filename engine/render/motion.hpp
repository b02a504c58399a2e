#pragma once
// Sub-pixel jitter and the previous frame's camera: what motion vectors (gbuffer.velocity) and the
// passes that read them (velocity view, motion blur, temporal anti-aliasing) need.
//
// Conventions (docs/motion.md):
// - jitterPixels is in OUTPUT pixels, +x right, +y up (GL window coordinates): a point the
//   unjittered projection puts at window position w is rasterised at w + jitterPixels (at a render
//   scale below 1 that is jitterPixels x renderScale render pixels: the same fraction of the image).
// - velocity = uv_current - uv_previous, uv in [0, 1] over the image (u right, v up), both from the
//   UNJITTERED projections: a static scene has velocity 0 whatever the jitter. The previous position
//   of the pixel at uv is uv - velocity.
#include <cstdint>

#include <glm/glm.hpp>

namespace lp {

struct FrameData;

// `projection` with its image shifted by `jitterPixels` output pixels on an outputSize image: clip x
// and y gain (2 jitter / size) x w, so a point's NDC moves by 2 jitter / size (perspective or ortho).
glm::mat4 jitteredProjection(const glm::mat4& projection, glm::vec2 jitterPixels, glm::ivec2 outputSize);

// What a frame leaves for the next one to compute its motion against.
struct MotionHistory {
    bool valid = false;
    glm::mat4 viewProjection{1.0f};  // unjittered
    float time = 0.0f;
    glm::ivec2 outputSize{0};
    uint64_t frameIndex = 0;
};

// Fills frame's jitter fields (projection becomes the jittered one, unjitteredProjection keeps the
// camera's) and its previous-frame fields from `history`. No previous frame: `history` invalid (the
// first frame, a camera cut), a different output size (a resize) or a time earlier than the history's
// (a new run on the clock); previous = current then, and every velocity is 0.
void applyMotion(FrameData& frame, const MotionHistory& history, glm::vec2 jitterPixels);
// What `frame` leaves for the next.
MotionHistory motionHistoryOf(const FrameData& frame);

// Screen-space motion of the world-space point p between the previous and current frame, in the
// velocity target's units (uv_current - uv_previous); 0 where either position is behind its camera.
// The CPU reference the tests check the G-buffer against.
glm::dvec2 velocityOfPoint(const glm::dmat4& viewProjection, const glm::dmat4& previousViewProjection, glm::dvec3 p);

}  // namespace lp
