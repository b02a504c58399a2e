#version 450
// Velocity of the background (directions at infinity: the camera's rotation alone moves them).
#include "common/velocity.glsl"
in vec2 vNdc;
uniform vec2 uJitterNdc;                     // the jitter in NDC, removed so velocity is unjittered
uniform mat4 uInverseRotationProjection;     // inverse(unjittered projection x view's rotation)
uniform mat4 uViewProjection;                // unjittered, current
uniform mat4 uPreviousViewProjection;        // unjittered, previous frame
layout(location = 6) out vec2 outVelocity;
void main() {
    outVelocity = backgroundVelocity(vNdc, uJitterNdc, uInverseRotationProjection, uViewProjection, uPreviousViewProjection);
}
