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
    vec4 e = uInverseRotationProjection * vec4(vNdc - uJitterNdc, 1.0, 1.0);
    vec4 direction = vec4(e.xyz / e.w, 0.0);
    outVelocity = velocityFromClip(uViewProjection * direction, uPreviousViewProjection * direction);
}
