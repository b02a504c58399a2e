#version 450
// Depth-only: positions into one cascade's light clip space.
layout(location = 0) in vec3 inPosition;
uniform mat4 uModelToClip;
void main() { gl_Position = uModelToClip * vec4(inPosition, 1.0); }
