#version 450
// engine/gl/gradient_probe.cpp, the compute case (the visibility resolve's): every invocation samples
// the same point with the same explicit gradients, so the level read depends on nothing but whether
// textureGrad uses them.
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D uLevels;  // level k: red k / 4
layout(std430, binding = 0) writeonly buffer Result { float levels[]; };
uniform vec2 uDx;
uniform vec2 uDy;

void main() { levels[gl_LocalInvocationIndex] = 4.0 * textureGrad(uLevels, vec2(0.37, 0.61), uDx, uDy).r; }
