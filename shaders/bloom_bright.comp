#version 450
// Bloom bright pass (separable method): soft-knee threshold of the HDR buffer.
#include "common/tonemap.glsl"
#include "common/post.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D uHdr;
layout(rgba16f, binding = 0) uniform writeonly image2D uBright;
uniform float uThreshold;
uniform float uKnee;
uniform float uHighlight;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uBright);
    if (p.x >= size.x || p.y >= size.y) return;
    vec3 c = texelFetch(uHdr, p, 0).rgb;
    imageStore(uBright, p, vec4(bloomBright(c, uThreshold, uKnee, uHighlight), 1.0));
}
