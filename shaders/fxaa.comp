#version 450
// --aa fxaa: FXAA 3.11 quality (common/fxaa.glsl) on the tone map's sRGB-encoded RGBA16F image, then
// the display's one 8-bit quantisation, dithered unless uDither is off.
#include "common/fxaa.glsl"
#include "common/dither.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D uSource;
layout(rgba8, binding = 0) uniform writeonly image2D uTarget;
uniform bool uDither;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uTarget);
    if (p.x >= size.x || p.y >= size.y) return;
    imageStore(uTarget, p, vec4(quantize8(fxaaQuality(uSource, p), p, uDither), 1.0));
}
