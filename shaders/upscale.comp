#version 450
// Render scale < 1: the small HDR buffer -> the output size, bilinear (before the tone map); with
// LP_UPSCALE_DEBUG, a debug view's RGBA8 image -> the output size, nearest.
#include "common/upscale.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D uSource;
#ifdef LP_UPSCALE_DEBUG
layout(rgba8, binding = 0) uniform writeonly image2D uTarget;
#else
layout(rgba16f, binding = 0) uniform writeonly image2D uTarget;
#endif

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uTarget);
    if (p.x >= size.x || p.y >= size.y) return;
#ifdef LP_UPSCALE_DEBUG
    imageStore(uTarget, p, upscaleNearest(uSource, p, size));
#else
    imageStore(uTarget, p, upscaleBilinear(uSource, p, size));
#endif
}
