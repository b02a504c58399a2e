#version 450
// Vertex stage of the fragment methods. Mode 0: a full-screen triangle for light
// uFirstLight + instance (the fullscreen and scissor methods, and every method when specular is not
// limited by range). Mode 1: the circumscribing icosphere of light `instance`'s bounding sphere (its
// range sphere; a spot's cone sphere), the volumes method.
#include "common/local_light.glsl"

layout(std430, binding = 0) readonly buffer LocalLights { LpLocalLight uLights[]; };
layout(location = 0) in vec3 aPosition;  // unit circumscribing icosphere
uniform int uMode;
uniform int uFirstLight;
uniform mat4 uProjection;
flat out int vLight;

void main() {
    vLight = uFirstLight + gl_InstanceID;
    if (uMode == 0) {
        vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
        gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
    } else {
        vec4 pr = uLights[vLight].bound;
        gl_Position = uProjection * vec4(pr.xyz + aPosition * pr.w, 1.0);
    }
}
