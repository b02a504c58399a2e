#version 450
// hdr = sanitize(sanitize(hdr) + strength * bloom), in place: a NaN texel becomes its glow.
#include "common/tonemap.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D uBloom;
layout(rgba16f, binding = 0) uniform image2D uHdr;
uniform float uStrength;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uHdr);
    if (p.x >= size.x || p.y >= size.y) return;
    vec3 h = imageLoad(uHdr, p).rgb;
    vec3 b = texelFetch(uBloom, p, 0).rgb;
    imageStore(uHdr, p, vec4(sanitizeHdr(sanitizeHdr(h) + b * uStrength), 1.0));
}
