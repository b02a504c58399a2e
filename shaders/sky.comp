#version 450
// Fills the pixels no geometry covered (depth at the far plane) with the background.
#include "common/tonemap.glsl"
#include "common/gbuffer_layout.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = LP_BIND_DEPTH) uniform sampler2D uDepth;
layout(rgba16f, binding = 0) uniform image2D uHdr;
uniform vec3 uColor;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uHdr);
    if (p.x >= size.x || p.y >= size.y) return;
    if (texelFetch(uDepth, p, 0).r < 1.0) return;
    imageStore(uHdr, p, vec4(sanitizeHdr(uColor), 1.0));
}
