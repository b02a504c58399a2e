#version 450
// After additive blending of many lights into the RGBA16F buffer: a sum past the
// largest half float becomes +Inf in the blender, so clamp it back (sanitizeHdr) like every pass.
#include "common/tonemap.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba16f, binding = 0) uniform image2D uHdr;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uHdr);
    if (p.x >= size.x || p.y >= size.y) return;
    vec4 c = imageLoad(uHdr, p);
    imageStore(uHdr, p, vec4(sanitizeHdr(c.rgb), c.a));
}
