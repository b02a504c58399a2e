#version 450
// --aa ssaa: the HDR image rendered at uScale x the output size -> the output size, a box over each
// pixel's uScale x uScale samples (before the tone map).
#include "common/downsample.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D uSource;
layout(rgba16f, binding = 0) uniform writeonly image2D uTarget;
uniform int uScale;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uTarget);
    if (p.x >= size.x || p.y >= size.y) return;
    imageStore(uTarget, p, downsampleBox(uSource, p, uScale));
}
